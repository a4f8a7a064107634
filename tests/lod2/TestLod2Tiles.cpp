// LOD2 models as city buildings and in the tiles the tiler writes (MESH sections): the footprint as
// the LOD1 fallback, triangles grouped by kind, skinned meshes in leaves and far meshes in inner
// tiles, positions within a quantization step.
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "Lod2TestData.h"
#include "qv/format/CityTile.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Files.h"
#include "qv/prep/Ingest.h"
#include "qv/prep/Lod2CityModel.h"
#include "qv/prep/Tiler.h"

namespace qv::prep::test {

TEST_CASE("lod2: a finished model becomes a building with its footprint and grouped triangles", "[lod2][tiles]") {
  const Result<Lod2Import>& imported = placedImport("DH_01_subs.city.json");
  REQUIRE(imported.ok());
  for (const Lod2Model& model : imported->models) {
    INFO(model.id);
    const Result<Building> b = buildingFromModel(model);
    REQUIRE(b.ok());
    CHECK(b->attributes.lod == 2);
    CHECK(b->attributes.id == model.id);
    REQUIRE(b->parts.size() == 1);
    CHECK(b->parts[0].points.size() == model.footprint.size());
    double twiceArea = 0.0;
    const auto& ring = b->parts[0].points;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      twiceArea += ring[i].x * ring[(i + 1) % ring.size()].y - ring[(i + 1) % ring.size()].x * ring[i].y;
    }
    CHECK(twiceArea > 0.0);  // counter-clockwise
    REQUIRE(b->mesh.has_value());
    const BuildingMesh& m = *b->mesh;
    CHECK(m.source == MeshSource::CityJson);
    CHECK(m.positions.size() == model.skinned.mesh.positions.size());
    CHECK(m.triangles.size() == model.skinned.mesh.triangles.size());
    std::array<std::uint32_t, kMeshSurfaceKinds> perKind{};
    for (SurfaceKind k : model.skinned.mesh.kinds) ++perKind[static_cast<std::size_t>(k)];
    CHECK(m.trianglesPerKind == perKind);
    CHECK(m.farTriangles.size() == model.farMesh.triangles.size());
  }

  Lod2Model unfinished = imported->models[0];
  unfinished.skinned.finished = false;
  const Result<Building> refused = buildingFromModel(unfinished);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().find("not finished") != std::string::npos);
}

TEST_CASE("lod2: the tiler writes skinned meshes to leaves and far meshes to inner tiles", "[lod2][tiles]") {
  const Result<Lod2Import>& imported = placedImport("DH_01_subs.city.json");
  REQUIRE(imported.ok());
  CityModel city = syntheticCity().model;
  std::map<std::string, const Lod2Model*> models;
  for (const Lod2Model& model : imported->models) {
    Result<Building> b = buildingFromModel(model);
    REQUIRE(b.ok());
    city.buildings.push_back(std::move(*b));
    models[model.id] = &model;
  }
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("qv-lod2-tiles-" + std::to_string(::getpid()))).string();
  TilerOptions options;
  options.maxBuildingsPerLeaf = 8;  // several leaves and an inner tile
  options.threads = 1;
  options.showProgress = false;
  const Result<TilerReport> report = writeCityTiles(city, dir, options);
  REQUIRE(report.ok());
  REQUIRE(report->tiles > report->leaves);

  std::size_t leafMeshes = 0, innerMeshes = 0;
  for (const TileNode& node : report->tileset.nodes) {
    const auto bytes = readFile(dir + "/" + node.file);
    REQUIRE(bytes.ok());
    const Result<CityTile> tile = decodeCityTile(*bytes, node.file);
    REQUIRE(tile.ok());
    const float stepXY = tile->extent / 65535.0f;
    for (const TileMesh& m : tile->meshes) {
      const BuildingAttributes& a = tile->buildings[m.building].attributes;
      INFO(node.file << " " << a.id);
      REQUIRE(models.count(a.id) == 1);
      const Lod2Model& model = *models[a.id];
      CHECK(a.lod == 2);
      CHECK(m.storeys == a.storeys);
      CHECK(m.farPositions.size() == model.farMesh.positions.size());
      if (node.coarse) {
        ++innerMeshes;
        CHECK(m.positions.empty());
        CHECK(m.triangles.empty());
        continue;
      }
      ++leafMeshes;
      REQUIRE(m.positions.size() == model.skinned.mesh.positions.size());
      double worstXY = 0.0, worstZ = 0.0;
      for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const glm::dvec3& p = model.skinned.mesh.positions[i];
        worstXY = std::max({worstXY, std::abs(m.positions[i].x + tile->originX - p.x),
                            std::abs(m.positions[i].y + tile->originY - p.y)});
        worstZ = std::max(worstZ, std::abs(m.positions[i].z - p.z));
      }
      CHECK(worstXY <= stepXY * 0.51 + 1e-4);
      CHECK(worstZ <= m.topM / 65535.0 * 0.51 + 1e-4);
    }
  }
  CHECK(leafMeshes == imported->models.size());
  CHECK(innerMeshes >= imported->models.size());  // the root and any inner tile on the way
  removeTree(dir);
}

TEST_CASE("tiler: coarse tiles carry every attribute of the leaf except the descriptive strings", "[lod2][tiles]") {
  CityModel city = syntheticCity().model;
  for (std::size_t i = 0; i < city.buildings.size(); ++i) {
    BuildingAttributes& a = city.buildings[i].attributes;
    a.name = "A building with a name longer than the small-string buffer " + std::to_string(i);
    a.address = std::to_string(i) + " Fifth Avenue, 10118 New York";
    a.material = "brick";
    a.structure = "frame";
    a.amenity = "school";
    a.startYear = static_cast<std::int16_t>(1900 + i % 120);
    a.importanceReasons = static_cast<std::uint8_t>(i % 64);
  }
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("qv-coarse-attributes-" + std::to_string(::getpid()))).string();
  city.sources = {"/home/someone/private/inputs/manhattan.osm.pbf", "parts.geojson"};
  TilerOptions options;
  options.maxBuildingsPerLeaf = 16;
  options.threads = 1;
  options.showProgress = false;
  const Result<TilerReport> report = writeCityTiles(city, dir, options);
  REQUIRE(report.ok());
  REQUIRE(report->tiles > report->leaves);
  // The manifest names its inputs by file name, not by the preparing machine's directories.
  CHECK(report->tileset.sources == std::vector<std::string>{"manhattan.osm.pbf", "parts.geojson"});
  const auto manifest = readFile(dir + "/tileset.json");
  REQUIRE(manifest.ok());
  CHECK(std::string(manifest->begin(), manifest->end()).find("/home/someone") == std::string::npos);

  // Centroids are stored relative to each tile's origin: compare them in city coordinates.
  const auto inCity = [](BuildingAttributes a, const CityTile& tile) {
    a.centroidX += tile.originX;
    a.centroidY += tile.originY;
    return a;
  };
  std::map<std::string, BuildingAttributes> leaf;
  std::vector<BuildingAttributes> coarse;
  for (const TileNode& node : report->tileset.nodes) {
    const auto bytes = readFile(dir + "/" + node.file);
    REQUIRE(bytes.ok());
    const Result<CityTile> tile = decodeCityTile(*bytes, node.file);
    REQUIRE(tile.ok());
    for (const TileBuilding& b : tile->buildings) {
      if (node.coarse) {
        coarse.push_back(inCity(b.attributes, *tile));
      } else {
        leaf.emplace(b.attributes.id, inCity(b.attributes, *tile));
      }
    }
  }
  CHECK(leaf.size() == city.buildings.size());
  REQUIRE(coarse.size() >= city.buildings.size());  // the root holds every building, coarser
  for (const BuildingAttributes& c : coarse) {
    INFO(c.id);
    REQUIRE(leaf.count(c.id) == 1);
    BuildingAttributes expected = leaf.at(c.id);
    CHECK_FALSE(expected.name.empty());  // the leaf keeps the strings...
    CHECK_FALSE(expected.address.empty());
    CHECK(c.name.empty());  // ...the coarse tile drops them
    CHECK(c.address.empty());
    CHECK(c.material.empty());
    CHECK(c.structure.empty());
    CHECK(c.amenity.empty());
    // Everything else is the same (centroids within the float precision of the tile offsets).
    CHECK(std::abs(c.centroidX - expected.centroidX) < 0.01);
    CHECK(std::abs(c.centroidY - expected.centroidY) < 0.01);
    expected.name.clear();
    expected.address.clear();
    expected.material.clear();
    expected.structure.clear();
    expected.amenity.clear();
    expected.centroidX = c.centroidX;
    expected.centroidY = c.centroidY;
    CHECK(c == expected);
  }
  removeTree(dir);
}

}  // namespace qv::prep::test

namespace qv::prep::test {

TEST_CASE("tiler: far away the Empire State Building keeps its setbacks: a prism per part, not one 443 m box",
          "[lod2][tiles][data]") {
  Result<CityModel> city = readCity({sharedData("osm/fixture-midtown-empire-state.osm")}, {});
  REQUIRE(city.ok());
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("qv-coarse-parts-" + std::to_string(::getpid()))).string();
  TilerOptions options;
  options.maxBuildingsPerLeaf = 64;  // inner tiles above the leaves
  options.threads = 1;
  options.showProgress = false;
  const Result<TilerReport> report = writeCityTiles(*city, dir, options);
  REQUIRE(report.ok());
  int seen = 0;
  for (const TileNode& node : report->tileset.nodes) {
    if (!node.coarse) continue;
    const auto bytes = readFile(dir + "/" + node.file);
    REQUIRE(bytes.ok());
    const Result<CityTile> tile = decodeCityTile(*bytes, node.file);
    REQUIRE(tile.ok());
    for (const TileBuilding& b : tile->buildings) {
      if (b.attributes.id != "w34633854") continue;
      INFO(node.file);
      ++seen;
      // Several prisms at several heights, the highest the spire's top, the lowest on the ground.
      std::set<long> tops;
      float highest = 0.0f, lowestBase = 1e9f;
      for (std::uint32_t p = b.firstPart; p < b.firstPart + b.partCount; ++p) {
        tops.insert(std::lround(tile->parts[p].heightM));
        highest = std::max(highest, tile->parts[p].heightM);
        lowestBase = std::min(lowestBase, tile->parts[p].minHeightM);
      }
      CHECK(b.partCount >= 4);
      CHECK(tops.size() >= 4);
      CHECK(highest == Approx(443.2f).margin(0.5f));
      CHECK(lowestBase == 0.0f);
    }
  }
  CHECK(seen >= 1);
  removeTree(dir);
}

}  // namespace qv::prep::test
