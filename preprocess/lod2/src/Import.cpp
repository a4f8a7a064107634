#include "qv/prep/Lod2Import.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <glm/common.hpp>

#include "qv/core/NumberFormat.h"
#include "qv/prep/Lod2Attributes.h"
#include "qv/prep/Lod2CityJson.h"
#include "qv/prep/Lod2Geometry.h"
#include "qv/prep/Projection.h"

namespace qv::prep {
namespace {

constexpr const char* kPlaceHint = "give a placement (--place LON,LAT[,ROTATION_DEG]) to put the models into the city";

bool endsWith(const std::string& text, std::string_view suffix) {
  if (text.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i) {
    const char a = static_cast<char>(std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])));
    if (a != suffix[i]) return false;
  }
  return true;
}

std::string number(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

struct Box2 {
  glm::dvec2 min{std::numeric_limits<double>::max()};
  glm::dvec2 max{std::numeric_limits<double>::lowest()};
  void expand(const glm::dvec2& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  [[nodiscard]] glm::dvec2 centre() const { return 0.5 * (min + max); }
};

}  // namespace

Result<std::vector<Lod2Model>> georeferenceCityJson(const CityJsonFile& file, const std::string& fileName,
                                                    const Lod2ImportOptions& options, Lod2ImportReport* report) {
  Lod2ImportReport scratch;
  Lod2ImportReport& out = report != nullptr ? *report : scratch;
  const CityProjection projection(options.originLon, options.originLat);
  std::optional<CrsToLonLat> crs;
  if (!file.crs.empty()) {
    Result<CrsToLonLat> created = CrsToLonLat::create(file.crs);
    if (created.ok()) {
      crs = std::move(*created);
    } else if (!options.placement) {
      return Error{fileName + ": " + created.error() + "; " + kPlaceHint};
    } else {
      out.warnings.push_back(fileName + ": " + created.error() + "; placed as metres");
    }
  } else if (!options.placement) {
    return Error{fileName + ": no coordinate reference system (metadata.referenceSystem " +
                 (file.referenceSystem.empty() ? std::string("is missing")
                                               : "\"" + file.referenceSystem + "\" names no EPSG code") +
                 "): the models cannot be georeferenced; " + kPlaceHint};
  }
  const double verticalFactor = crs ? crs->verticalMetresPerUnit() : 1.0;

  // Horizontal positions of every building in the city frame.
  std::vector<std::vector<glm::dvec2>> placed(file.buildings.size());
  std::vector<Box2> lonLatBounds(file.buildings.size());
  const auto toLonLat = [&](const CityJsonBuilding& b, const glm::dvec3& p) -> Result<glm::dvec2> {
    const auto lonLat = crs->toLonLat(p.x, p.y);
    if (!lonLat)
      return Error{fileName + ": cj:" + b.objectId + ": vertex (" + number(p.x, 3) + ", " + number(p.y, 3) +
                   ") cannot be transformed from " + file.crs + " to WGS84 (outside the CRS's domain?)"};
    return *lonLat;
  };
  if (options.placement) {
    // A local metric frame: the CRS's own units in metres, or a transverse Mercator about the
    // models for a geographic CRS; then centred, rotated and moved to the placement.
    std::optional<CityProjection> localTm;
    if (crs && crs->geographic()) {
      Box2 all;
      for (const CityJsonBuilding& b : file.buildings) {
        for (const glm::dvec3& p : b.positions) {
          Result<glm::dvec2> lonLat = toLonLat(b, p);
          if (!lonLat.ok()) return Error{lonLat.error()};
          all.expand(*lonLat);
        }
      }
      localTm.emplace(all.centre().x, all.centre().y);
    }
    const double horizontalFactor = crs ? crs->horizontalMetresPerUnit() : 1.0;
    Box2 all;
    for (std::size_t i = 0; i < file.buildings.size(); ++i) {
      const CityJsonBuilding& b = file.buildings[i];
      placed[i].reserve(b.positions.size());
      for (const glm::dvec3& p : b.positions) {
        glm::dvec2 xy(p.x * horizontalFactor, p.y * horizontalFactor);
        if (localTm) {
          Result<glm::dvec2> lonLat = toLonLat(b, p);
          if (!lonLat.ok()) return Error{lonLat.error()};
          xy = localTm->forward(lonLat->x, lonLat->y);
        }
        placed[i].push_back(xy);
        all.expand(xy);
      }
    }
    const glm::dvec2 centre = all.centre();
    const glm::dvec2 target = projection.forward(options.placement->lon, options.placement->lat);
    for (std::vector<glm::dvec2>& building : placed) {
      for (glm::dvec2& xy : building) xy = rotateClockwise(xy - centre, options.placement->rotationDeg) + target;
    }
  } else {
    for (std::size_t i = 0; i < file.buildings.size(); ++i) {
      const CityJsonBuilding& b = file.buildings[i];
      placed[i].reserve(b.positions.size());
      for (const glm::dvec3& p : b.positions) {
        Result<glm::dvec2> lonLat = toLonLat(b, p);
        if (!lonLat.ok()) return Error{lonLat.error()};
        lonLatBounds[i].expand(*lonLat);
        placed[i].push_back(projection.forward(lonLat->x, lonLat->y));
      }
    }
    out.crs = file.crs;
  }

  const std::string source = "cityjson:" + std::filesystem::path(fileName).filename().string();
  std::vector<Lod2Model> models;
  models.reserve(file.buildings.size());
  for (std::size_t i = 0; i < file.buildings.size(); ++i) {
    const CityJsonBuilding& b = file.buildings[i];
    const std::string id = "cj:" + b.objectId;
    if (!options.placement && !options.extent.empty()) {
      Box2 box;
      for (const glm::dvec2& xy : placed[i]) box.expand(xy);
      const glm::dvec2 c = box.centre();
      const Rect& e = options.extent;
      if (!e.contains(static_cast<float>(c.x), static_cast<float>(c.y))) {
        if (options.skipOutsideExtent) {
          ++out.skipped["outside-extent"];
          continue;
        }
        const glm::dvec2 lonLat = lonLatBounds[i].centre();
        return Error{fileName + ": " + id + " lies at lon " + number(lonLat.x, 5) + ", lat " + number(lonLat.y, 5) +
                     " (" + file.crs + "), outside the city's extent (x " + number(e.minX, 0) + " .. " +
                     number(e.maxX, 0) + " m, y " + number(e.minY, 0) + " .. " + number(e.maxY, 0) + " m about lon " +
                     number(options.originLon, 5) + ", lat " + number(options.originLat, 5) + "); " + kPlaceHint};
      }
    }
    double minZ = std::numeric_limits<double>::max();
    for (const glm::dvec3& p : b.positions) minZ = std::min(minZ, p.z);
    Lod2Mesh mesh;
    mesh.positions.reserve(b.positions.size());
    for (std::size_t v = 0; v < b.positions.size(); ++v) {
      mesh.positions.emplace_back(placed[i][v], (b.positions[v].z - minZ) * verticalFactor);
    }
    mesh.triangles = b.triangles;
    mesh.kinds = b.kinds;
    const double top = heightRange(mesh).maxZ;
    if (!(top > 0.0)) {
      ++out.skipped["flat-model"];
      continue;
    }
    Box2 extent;
    for (const glm::dvec3& p : mesh.positions) extent.expand(glm::dvec2(p));
    const glm::dvec2 size = extent.max - extent.min;
    if (!(top <= kMaxModelHeightM) || !(size.x <= kMaxModelExtentM) || !(size.y <= kMaxModelExtentM)) {
      const bool tall = !(top <= kMaxModelHeightM);
      ++out.skipped[tall ? "too-tall" : "too-large"];
      out.warnings.push_back(fileName + ": " + id + " skipped: " +
                             (tall ? formatDouble(top) + " m tall (more than " + formatDouble(kMaxModelHeightM) + " m)"
                                   : formatDouble(std::max(size.x, size.y)) + " m wide (more than " +
                                         formatDouble(kMaxModelExtentM) + " m)") +
                             ": broken coordinates or a wrong unit?");
      continue;
    }
    Lod2Model model;
    model.id = id;
    model.source = source;
    model.footprint = groundFootprint(mesh);
    NewModelFacts facts;
    facts.id = id;
    facts.name = b.name;
    facts.function = b.function;
    facts.storeys = b.storeysAboveGround;
    facts.startYear = b.startYear;
    facts.parts = std::max<std::uint32_t>(b.parts, 1);
    model.attributes = newModelAttributes(facts, mesh, model.footprint);
    model.verticesBefore = static_cast<std::uint32_t>(b.positions.size());
    model.skinned.mesh = std::move(mesh);
    models.push_back(std::move(model));
  }
  out.partsMerged += file.partsMerged;
  out.facesSkipped += file.facesSkipped;
  for (const auto& [key, n] : file.geometries) out.geometries[key] += n;
  for (const auto& [key, n] : file.lods) out.lods[key] += n;
  for (const auto& [key, n] : file.skipped) out.skipped[key] += n;
  out.warnings.insert(out.warnings.end(), file.warnings.begin(), file.warnings.end());
  return models;
}

Result<Lod2Import> importModels(const std::string& path, const Lod2ImportOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!validLonLat(options.originLon, options.originLat) || std::abs(options.originLat) >= 89.0)
    return Error{path + ": invalid city origin lon " + number(options.originLon, 6) + ", lat " +
                 number(options.originLat, 6)};
  if (options.placement && !validLonLat(options.placement->lon, options.placement->lat))
    return Error{path + ": invalid placement lon " + number(options.placement->lon, 6) + ", lat " +
                 number(options.placement->lat, 6)};
  Lod2Import result;
  Lod2ImportReport& report = result.report;
  if (endsWith(path, ".obj")) {
    if (!options.placement) return Error{path + ": OBJ models carry no georeference; " + std::string(kPlaceHint)};
    ObjPlacement placement;
    placement.lon = options.placement->lon;
    placement.lat = options.placement->lat;
    placement.rotationDeg = options.placement->rotationDeg;
    placement.scale = options.objScale;
    placement.unit = options.objUnit;
    placement.up = options.objUp;
    placement.centreOnAnchor = options.objCentreOnAnchor;
    Result<Lod2Model> model = readObjModel(path, placement, CityProjection(options.originLon, options.originLat));
    if (!model.ok()) return Error{model.error()};
    report.format = "obj";
    result.models.push_back(std::move(*model));
  } else if (endsWith(path, ".json")) {
    CityJsonOptions cityJsonOptions;
    cityJsonOptions.lod = options.lod;
    Result<CityJsonFile> file = readCityJson(path, cityJsonOptions);
    if (!file.ok()) return Error{file.error()};
    report.format = "cityjson " + file->version;
    Result<std::vector<Lod2Model>> models = georeferenceCityJson(*file, path, options, &report);
    if (!models.ok()) return Error{models.error()};
    result.models = std::move(*models);
  } else {
    return Error{path + ": unknown model format (expected .json or .city.json for CityJSON, .obj for OBJ)"};
  }

  if (options.existing != nullptr) {
    Result<MatchResult> matched = matchModels(result.models, *options.existing, options.match);
    if (!matched.ok()) return Error{path + ": " + matched.error()};
    report.replaced = matched->replaced();
  }
  // A model that cannot be finished (too many vertices for the target, more storeys than bones)
  // is left out with a warning; the others are imported.
  std::vector<Lod2Model> finished;
  finished.reserve(result.models.size());
  for (Lod2Model& model : result.models) {
    const std::size_t originalTriangles = model.skinned.mesh.triangleCount();
    if (Status s = finishModel(model, options.finish); !s) {
      ++report.skipped["cannot-finish"];
      report.warnings.push_back(path + ": " + s.error() + "; the model is left out");
      if (model.replacesExisting) --report.replaced;
      continue;
    }
    report.originalTriangles += originalTriangles;
    report.verticesBefore += model.verticesBefore;
    report.verticesAfter += model.verticesAfter;
    report.trianglesAfter += model.skinned.mesh.triangleCount();
    report.farTriangles += model.farMesh.triangleCount();
    finished.push_back(std::move(model));
  }
  result.models = std::move(finished);
  report.imported = result.models.size();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace qv::prep
