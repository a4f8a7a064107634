#include "qv/prep/Lod2OsmParts.h"

#include <string>

#include "qv/prep/Lod2Geometry.h"

namespace qv::prep {

Result<Lod2Model> modelFromOsmParts(const Building& building) {
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
  model.source = "osm-parts";
  model.attributes = building.attributes;
  model.attributes.lod = 2;
  model.footprint = unionOuterRing(outerRings);
  model.verticesBefore = static_cast<std::uint32_t>(mesh.positions.size());
  model.skinned.mesh = std::move(mesh);
  return model;
}

}  // namespace qv::prep
