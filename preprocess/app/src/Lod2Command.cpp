// quakeview-prep lod2 --city DIR --input FILE [--place LON,LAT[,ROT]] [--lod L] [OBJ placement options]
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>

#include "CityFiles.h"
#include "Commands.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/Lod2CityModel.h"
#include "qv/prep/Lod2Import.h"
#include "qv/prep/Tiler.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep lod2 --city DIR --input FILE [options]\n"
    "  Adds detailed LOD2 building models (CityJSON .json/.city.json, OBJ .obj) to a city directory:\n"
    "  each model replaces the building it belongs to (by id or footprint overlap) or is added as a new\n"
    "  building; models are re-meshed at every floor and skinned to one bone per floor level, and the\n"
    "  city's tiles are written again with their MESH sections (the manifest last). Run `response`\n"
    "  afterwards: the city's response is out of date until then.\n"
    "  --place LON,LAT[,ROT]  put the models' footprint centre at LON,LAT (degrees), turned ROT degrees\n"
    "                         clockwise (required for OBJ and for CityJSON without a usable CRS)\n"
    "  --lod L                CityJSON LOD to take (e.g. 2.2; default: the highest present)\n"
    "  --obj-unit m|cm|mm|ft  OBJ file unit (default m)      --obj-scale S   scale after the unit\n"
    "  --obj-up y|z           OBJ up axis (default y)        --obj-centre    the footprint centre, not\n"
    "                                                                        the origin, goes to --place\n";

// A city's buildings as the tiles store them: the leaves hold every building at full detail.
Result<CityModel> readCityFromTiles(const std::string& dir, const Tileset& tileset) {
  CityModel city;
  city.originLon = tileset.originLon;
  city.originLat = tileset.originLat;
  city.projection = tileset.projection;
  city.sources = tileset.sources;
  city.excluded = tileset.excluded;
  for (const TileNode& node : tileset.nodes) {
    if (node.coarse) continue;
    auto tile = loadCityTile(dir, node);
    if (!tile.ok()) return Error{tile.error()};
    std::vector<const TileMesh*> meshOf(tile->buildings.size(), nullptr);
    for (const TileMesh& m : tile->meshes) meshOf[m.building] = &m;
    for (std::size_t bi = 0; bi < tile->buildings.size(); ++bi) {
      const TileBuilding& tb = tile->buildings[bi];
      Building b;
      b.attributes = tb.attributes;
      b.attributes.centroidX += tile->originX;
      b.attributes.centroidY += tile->originY;
      for (std::uint32_t pi = tb.firstPart; pi < tb.firstPart + tb.partCount; ++pi) {
        const TilePart& tp = tile->parts[pi];
        BuildingPart part;
        part.minHeightM = tp.minHeightM;
        part.heightM = tp.heightM;
        part.roofHeightM = tp.roofHeightM;
        part.roofShape = tp.roofShape == RoofShape::Flat ? std::string() : std::string(roofShapeName(tp.roofShape));
        for (std::uint32_t v = tp.firstVertex; v < tp.firstVertex + tp.vertexCount; ++v) {
          part.points.emplace_back(tile->vertices[v].x + tile->originX, tile->vertices[v].y + tile->originY);
        }
        std::uint32_t end = 0;
        for (std::uint32_t r = tp.firstRing; r < tp.firstRing + tp.ringCount; ++r) {
          end += tile->ringVertexCounts[r];
          part.ringEnds.push_back(end);
        }
        b.parts.push_back(std::move(part));
      }
      if (const TileMesh* m = meshOf[bi]) {
        BuildingMesh mesh;
        mesh.source = m->source;
        mesh.verticesBefore = m->verticesBefore;
        for (const glm::vec3& p : m->positions)
          mesh.positions.emplace_back(p.x + tile->originX, p.y + tile->originY, p.z);
        mesh.triangles = m->triangles;
        mesh.trianglesPerKind = m->trianglesPerKind;
        for (const glm::vec3& p : m->farPositions) {
          mesh.farPositions.emplace_back(p.x + tile->originX, p.y + tile->originY, p.z);
        }
        mesh.farTriangles = m->farTriangles;
        b.mesh = std::move(mesh);
      }
      city.buildings.push_back(std::move(b));
    }
  }
  return city;
}

}  // namespace

int runLod2(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv,
                                {{"city"},
                                 {"input"},
                                 {"place"},
                                 {"lod"},
                                 {"obj-unit"},
                                 {"obj-scale"},
                                 {"obj-up"},
                                 {"obj-centre", false},
                                 {"help", false}},
                                error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "lod2: %s\n", error.c_str());
    std::fputs(kUsage, args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "lod2: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
  };
  if (!args->positional().empty()) return usage("unexpected argument '" + args->positional()[0] + "'");
  const auto dir = args->value("city");
  if (!dir || dir->empty()) return usage("--city DIR is required");
  const auto input = args->value("input");
  if (!input || input->empty()) return usage("--input FILE is required");

  Lod2ImportOptions options;
  if (const auto place = args->value("place")) {
    options.placement = parsePlacement(*place);
    if (!options.placement) return usage("--place must be LON,LAT or LON,LAT,ROTATION_DEG in degrees");
  }
  if (const auto lod = args->value("lod")) {
    if (!parseDouble(*lod)) return usage("--lod must be a number such as 2 or 2.2");
    options.lod = *lod;
  }
  if (const auto unit = args->value("obj-unit")) {
    const auto u = parseModelUnit(*unit);
    if (!u) return usage("--obj-unit must be m, cm, mm or ft");
    options.objUnit = *u;
  }
  if (const auto scale = args->value("obj-scale")) {
    const auto s = parseDouble(*scale);
    if (!s || !(*s > 0.0) || *s > 1.0e6) return usage("--obj-scale must be a number above 0");
    options.objScale = *s;
  }
  if (const auto up = args->value("obj-up")) {
    const auto axis = parseUpAxis(*up);
    if (!axis) return usage("--obj-up must be y or z");
    options.objUp = *axis;
  }
  options.objCentreOnAnchor = args->has("obj-centre");

  installInterruptHandler();
  const auto start = std::chrono::steady_clock::now();
  const auto tileset = loadTileset(*dir);
  if (!tileset.ok()) {
    std::fprintf(stderr, "lod2: %s\n", tileset.error().c_str());
    return kExitDataError;
  }
  auto city = readCityFromTiles(*dir, *tileset);
  if (!city.ok()) {
    std::fprintf(stderr, "lod2: %s\n", city.error().c_str());
    return kExitDataError;
  }
  const std::vector<ExistingBuilding> existing = existingBuildings(*city);
  options.originLon = tileset->originLon;
  options.originLat = tileset->originLat;
  options.extent = tileset->bounds;
  options.existing = &existing;
  auto imported = importModels(*input, options);
  if (!imported.ok()) {
    std::fprintf(stderr, "lod2: %s\n", imported.error().c_str());
    return kExitDataError;
  }
  if (interrupted()) {
    std::fprintf(stderr, "lod2: interrupted; nothing was written\n");
    return kExitDataError;
  }

  // Replace or add, by id.
  std::unordered_map<std::string, std::size_t> byId;
  for (std::size_t i = 0; i < city->buildings.size(); ++i) byId.emplace(city->buildings[i].attributes.id, i);
  Lod2ImportReport& report = imported->report;
  std::uint64_t replaced = 0, added = 0;
  for (const Lod2Model& model : imported->models) {
    auto building = buildingFromModel(model);
    if (!building.ok()) {
      report.skipped["cannot-store"] += 1;
      report.warnings.push_back(building.error());
      continue;
    }
    const auto found = byId.find(model.id);
    if (found != byId.end()) {
      city->buildings[found->second] = std::move(*building);
      ++replaced;
    } else {
      byId.emplace(model.id, city->buildings.size());
      city->buildings.push_back(std::move(*building));
      ++added;
    }
  }
  if (replaced + added == 0) {
    std::fprintf(stderr, "lod2: %s: no model could be imported; the city is unchanged\n", input->c_str());
    for (const std::string& w : report.warnings) std::fprintf(stderr, "  warning: %s\n", w.c_str());
    return kExitDataError;
  }
  city->sources.push_back(*input);

  TilerOptions tiler;
  tiler.generator = "quakeview-prep lod2";
  tiler.name = tileset->name;
  tiler.buildingsRevision = tileset->buildingsRevision + 1;
  tiler.response = tileset->response;  // kept, now older than the buildings: out of date
  // The map under the city is not in the tiles the city is read back from: its files and layer go
  // into the new city as they were (none when it was made with --no-ground).
  tiler.ground = tileset->ground.has_value();
  tiler.keptGround = tileset->ground;
  tiler.keptGroundDir = *dir;
  tiler.keptDistricts = tileset->districts;
  const auto written = writeCityTiles(*city, *dir, tiler);
  if (!written.ok()) {
    std::fprintf(stderr, "lod2: %s\n", written.error().c_str());
    return kExitDataError;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("LOD2 models from %s (%s%s%s) written to %s\n", input->c_str(), report.format.c_str(),
              report.crs.empty() ? "" : ", ", report.crs.c_str(), dir->c_str());
  std::printf("imported    %llu models (%llu vertices before re-meshing, %llu after)\n",
              static_cast<unsigned long long>(replaced + added), static_cast<unsigned long long>(report.verticesBefore),
              static_cast<unsigned long long>(report.verticesAfter));
  std::printf("replaced    %llu buildings\n", static_cast<unsigned long long>(replaced));
  std::printf("added       %llu new buildings\n", static_cast<unsigned long long>(added));
  std::uint64_t skipped = 0;
  for (const auto& [kind, n] : report.skipped) skipped += n;
  std::printf("skipped     %llu\n", static_cast<unsigned long long>(skipped));
  for (const auto& [kind, n] : report.skipped) {
    std::printf("            %-24s %llu\n", kind.c_str(), static_cast<unsigned long long>(n));
  }
  for (const std::string& w : report.warnings) std::fprintf(stderr, "lod2: warning: %s\n", w.c_str());
  std::printf("city        %llu buildings in %llu tiles, buildings revision %llu\n",
              static_cast<unsigned long long>(written->buildings), static_cast<unsigned long long>(written->tiles),
              static_cast<unsigned long long>(tiler.buildingsRevision));
  if (tileset->response) std::printf("note        the response is now out of date: run `quakeview-prep response`\n");
  std::printf("            (%.2f s)\n", seconds);
  return kExitOk;
}

}  // namespace qv::prep
