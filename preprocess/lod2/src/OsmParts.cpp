#include "qv/prep/Lod2OsmParts.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "qv/prep/Files.h"
#include "qv/prep/Lod2CityModel.h"
#include "qv/prep/Lod2Geometry.h"

namespace qv::prep {

Result<Lod2Model> modelFromOsmParts(const Building& building, const std::string& source) {
  Lod2Mesh mesh;
  std::vector<std::vector<glm::dvec2>> outerRings;
  std::vector<glm::dvec3> top;
  std::vector<std::uint32_t> roof;
  for (const BuildingPart& part : building.parts) {
    const double bottomM = static_cast<double>(part.minHeightM);
    const double topM = static_cast<double>(part.heightM);
    if (!(topM > bottomM) || part.ringEnds.empty() || part.ringEnds.back() != part.points.size()) continue;
    top.clear();
    for (const glm::dvec2& p : part.points) top.emplace_back(p.x, p.y, topM);
    roof.clear();
    if (!triangulateFace(top, part.ringEnds, roof)) continue;  // cleaning keeps such parts out; be safe
    const auto n = static_cast<std::uint32_t>(part.points.size());
    const auto bottom = static_cast<std::uint32_t>(mesh.positions.size());  // bottom ring vertex i: bottom + i
    const std::uint32_t upper = bottom + n;                                 // top ring vertex i: upper + i
    for (const glm::dvec2& p : part.points) mesh.positions.emplace_back(p.x, p.y, bottomM);
    mesh.positions.insert(mesh.positions.end(), top.begin(), top.end());
    for (std::size_t t = 0; t + 2 < roof.size(); t += 3) {
      mesh.triangles.insert(mesh.triangles.end(), {upper + roof[t], upper + roof[t + 1], upper + roof[t + 2]});
      mesh.kinds.push_back(SurfaceKind::Roof);
    }
    if (bottomM > 0.0) {  // the underside of a part standing on another one (or overhanging)
      for (std::size_t t = 0; t + 2 < roof.size(); t += 3) {
        mesh.triangles.insert(mesh.triangles.end(), {bottom + roof[t], bottom + roof[t + 2], bottom + roof[t + 1]});
        mesh.kinds.push_back(SurfaceKind::Other);
      }
    }
    // Walls along every ring: outer rings run counter-clockwise and holes clockwise, so the right
    // side of each edge is outside the part.
    std::uint32_t begin = 0;
    for (const std::uint32_t end : part.ringEnds) {
      const std::uint32_t count = end - begin;
      for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t a = begin + i;
        const std::uint32_t c = begin + (i + 1) % count;
        mesh.triangles.insert(mesh.triangles.end(), {bottom + a, bottom + c, upper + c});
        mesh.triangles.insert(mesh.triangles.end(), {bottom + a, upper + c, upper + a});
        mesh.kinds.insert(mesh.kinds.end(), 2, SurfaceKind::Wall);
      }
      begin = end;
    }
    outerRings.emplace_back(part.points.begin(), part.points.begin() + part.ringEnds.front());
  }
  if (mesh.triangles.empty())
    return Error{building.attributes.id + ": no building:part with a polygon and a height above its base"};

  Lod2Model model;
  model.id = building.attributes.id;
  model.replacesExisting = true;
  model.source = source;
  model.attributes = building.attributes;
  model.attributes.lod = 2;
  model.footprint = unionOuterRing(outerRings);
  model.verticesBefore = static_cast<std::uint32_t>(mesh.positions.size());
  model.skinned.mesh = std::move(mesh);
  return model;
}

bool hasOsmParts(const Building& building) {
  return std::any_of(building.parts.begin(), building.parts.end(), [&building](const BuildingPart& part) {
    return !part.sourceId.empty() && part.sourceId != building.attributes.id;
  });
}

OsmPartsReport assembleOsmPartModels(CityModel& city, const FinishOptions& options, unsigned threads,
                                     const std::string& source) {
  const auto start = std::chrono::steady_clock::now();
  OsmPartsReport report;
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < city.buildings.size(); ++i) {
    if (hasOsmParts(city.buildings[i])) candidates.push_back(i);
  }
  report.candidates = candidates.size();
  struct Outcome {
    std::optional<Building> building;
    std::uint64_t verticesBefore = 0, verticesAfter = 0, farTriangles = 0;
    std::string problem;
  };
  std::vector<Outcome> outcomes(candidates.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < candidates.size(); k = next++) {
      const Building& original = city.buildings[candidates[k]];
      Outcome& out = outcomes[k];
      auto model = modelFromOsmParts(original, source);
      if (!model.ok()) {
        out.problem = model.error();
        continue;
      }
      if (const Status finished = finishModel(*model, options); !finished.ok()) {
        out.problem = finished.error();
        continue;
      }
      auto building = buildingFromModel(*model);
      if (!building.ok()) {
        out.problem = building.error();
        continue;
      }
      building->parts = original.parts;  // the LOD1 fallback keeps the setbacks
      out.verticesBefore = model->verticesBefore;
      out.verticesAfter = model->verticesAfter;
      out.farTriangles = model->farMesh.triangleCount();
      out.building = std::move(*building);
    }
  };
  const unsigned hardware = usableCores();
  const auto workers = static_cast<unsigned>(
      std::min<std::size_t>(threads == 0 ? hardware : threads, std::max<std::size_t>(candidates.size(), 1)));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();

  for (std::size_t k = 0; k < candidates.size(); ++k) {
    Outcome& out = outcomes[k];
    if (!out.building) {
      report.warnings.push_back(city.buildings[candidates[k]].attributes.id +
                                " stays LOD1 (its building:parts could not make a model): " + out.problem);
      continue;
    }
    city.buildings[candidates[k]] = std::move(*out.building);
    ++report.assembled;
    report.verticesBefore += out.verticesBefore;
    report.verticesAfter += out.verticesAfter;
    report.farTriangles += out.farTriangles;
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace qv::prep
