// CityJSON import: the shared files (counts checked against the files with a script: Buildings,
// BuildingParts, geometries, the vertices their faces use, triangles = sum over faces of
// corners + 2 x holes - 2), LOD choice, geometry types, CRS transformation with PROJ.
#include <set>

#include <catch2/catch.hpp>

#include "Lod2TestData.h"
#include "qv/prep/Lod2CityJson.h"
#include "qv/prep/Lod2Georeference.h"
#include "qv/prep/Projection.h"

namespace qv::prep::test {
namespace {

using Counts = std::map<std::string, std::uint64_t>;

std::map<SurfaceKind, std::size_t> kindCounts(const Lod2Mesh& mesh) {
  std::map<SurfaceKind, std::size_t> counts;
  for (SurfaceKind kind : mesh.kinds) ++counts[kind];
  return counts;
}

}  // namespace

TEST_CASE("lod2: DH_01_subs: 4 Buildings with 8 BuildingParts, 9 LOD2 Solids, 92 vertices", "[lod2][cityjson][data]") {
  const Result<Lod2Import>& imported = placedImport("DH_01_subs.city.json");
  REQUIRE(imported.ok());
  const Lod2ImportReport& report = imported->report;
  CHECK(report.format == "cityjson 1.1");
  CHECK(report.imported == 4);
  CHECK(report.partsMerged == 8);
  CHECK(report.geometries == Counts{{"Solid", 9}});
  CHECK(report.lods == Counts{{"2", 4}});
  CHECK(report.verticesBefore == 92);
  CHECK(report.originalTriangles == 148);  // 70 faces (quads to heptagons), none skipped
  CHECK(report.facesSkipped == 0);
  CHECK(report.skipped.empty());
  CHECK(report.crs.empty());  // no CRS in the file: placed
  CHECK(report.verticesAfter > 10 * report.verticesBefore);
  CHECK(report.replaced == 0);  // not matched (no existing buildings given)

  std::uint32_t vertices = 0;
  std::set<std::string> ids;
  for (const Lod2Model& model : imported->models) {
    ids.insert(model.id);
    CHECK(model.id.rfind("cj:GUID_", 0) == 0);
    CHECK(model.source == "cityjson:DH_01_subs.city.json");
    CHECK_FALSE(model.replacesExisting);
    CHECK(model.attributes.lod == 2);
    CHECK(model.attributes.id == model.id);
    // Heights about 9.4 m (the file's RelativeRidgeHeight goes up to 9.508 m); ground at the lowest vertex.
    CHECK(model.attributes.heightM > 5.0f);
    CHECK(model.attributes.heightM < 11.5f);
    CHECK(heightRange(model.skinned.mesh).minZ == 0.0);
    CHECK(model.footprint.size() >= 4);
    CHECK(model.attributes.footprintAreaM2 > 20.0f);
    // Semantics kept: every model has walls, roofs and ground surfaces.
    const auto kinds = kindCounts(model.skinned.mesh);
    CHECK(kinds.count(SurfaceKind::Wall) == 1);
    CHECK(kinds.count(SurfaceKind::Roof) == 1);
    CHECK(kinds.count(SurfaceKind::Ground) == 1);
    CHECK(model.skinned.mesh.kinds.size() == model.skinned.mesh.triangleCount());
    CHECK(model.farMesh.triangleCount() > 0);
    CHECK(model.farMesh.triangleCount() <= 148);
    vertices += model.verticesBefore;
  }
  CHECK(ids.size() == 4);
  CHECK(vertices == 92);
  // Buildings with parts are complex (two with 3 parts, one with 2, one with its own Solid).
  std::size_t complex = 0;
  for (const Lod2Model& model : imported->models) {
    if ((model.attributes.importanceReasons & kReasonComplex) != 0) ++complex;
  }
  CHECK(complex == 3);
}

TEST_CASE("lod2: zurich_subset_lod2: 49 Buildings with their 161 BuildingParts merged", "[lod2][cityjson][data]") {
  const Result<Lod2Import>& imported = placedImport("zurich_subset_lod2.json");
  REQUIRE(imported.ok());
  const Lod2ImportReport& report = imported->report;
  CHECK(report.format == "cityjson 1.1");
  CHECK(report.imported == 49);
  CHECK(report.partsMerged == 161);
  CHECK(report.geometries == Counts{{"MultiSurface", 161}});
  CHECK(report.verticesBefore == 3670);
  CHECK(report.originalTriangles == 5142);  // includes 4 roof faces with a hole each
  CHECK(report.facesSkipped == 0);
  CHECK(report.skipped.empty());
  float tallest = 0.0f;
  for (const Lod2Model& model : imported->models) {
    tallest = std::max(tallest, model.attributes.heightM);
    // The far mesh: collapsed where the 2 % error bound allows, the building's top kept.
    CHECK(model.farMesh.triangleCount() > 0);
    CHECK(model.farMesh.kinds.size() == model.farMesh.triangleCount());
    CHECK(heightRange(model.farMesh).maxZ == Approx(heightRange(model.skinned.mesh).maxZ).epsilon(0.05));
    if (model.farMesh.triangleCount() < model.skinned.mesh.triangleCount()) {
      // Collapsed: kinds from the normals; every building keeps roofs.
      CHECK(std::count(model.farMesh.kinds.begin(), model.farMesh.kinds.end(), SurfaceKind::Roof) > 0);
    }
  }
  INFO("far " << report.farTriangles << " of " << report.originalTriangles);
  CHECK(report.farTriangles < report.originalTriangles * 7 / 10);
  CHECK(report.farTriangles > report.originalTriangles / 10);
  // Heights relative to each building's lowest vertex: the tallest is about 31 m (the README: up to 31.4 m).
  CHECK(tallest > 25.0f);
  CHECK(tallest < 32.0f);
}

TEST_CASE("lod2: delft: 160 Buildings imported, roads, vegetation, land use, water and bridges skipped by type",
          "[lod2][cityjson][data]") {
  const Result<Lod2Import>& imported = placedImport("delft.json");
  REQUIRE(imported.ok());
  const Lod2ImportReport& report = imported->report;
  CHECK(report.format == "cityjson 2.0");
  CHECK(report.imported == 160);
  CHECK(report.skipped == Counts{{"Bridge", 3},
                                 {"GenericCityObject", 54},
                                 {"LandUse", 81},
                                 {"PlantCover", 126},
                                 {"Road", 143},
                                 {"WaterBody", 3}});
  CHECK(report.geometries == Counts{{"Solid", 160}});
  CHECK(report.lods == Counts{{"1", 160}});
  CHECK(report.verticesBefore == 3741);  // 603 vertices are shared between neighbours: copied per building
  CHECK(report.originalTriangles == 5563);
  // No semantics in delft.json: kinds come from the normals.
  std::map<SurfaceKind, std::size_t> kinds;
  for (const Lod2Model& model : imported->models) {
    for (const auto& [kind, n] : kindCounts(model.skinned.mesh)) kinds[kind] += n;
  }
  CHECK(kinds[SurfaceKind::Wall] > 0);
  CHECK(kinds[SurfaceKind::Roof] > 0);
  CHECK(kinds[SurfaceKind::Ground] == 0);  // delft.json's LOD1 solids have no ground faces (open at the base)
}

TEST_CASE("lod2: multi_lod: LOD 2.2 by default, 1.2 when asked", "[lod2][cityjson][data]") {
  SECTION("default: the highest LOD") {
    const Result<Lod2Import>& imported = placedImport("multi_lod.json");
    REQUIRE(imported.ok());
    CHECK(imported->report.imported == 10);
    CHECK(imported->report.lods == Counts{{"2.2", 10}});
    CHECK(imported->report.verticesBefore == 194);
    CHECK(imported->report.originalTriangles == 348);
  }
  SECTION("--lod 1.2") {
    Lod2ImportOptions options = placedInSyntheticCity();
    options.lod = "1.2";
    const Result<Lod2Import> imported = importModels(sharedData("cityjson/multi_lod.json"), options);
    REQUIRE(imported.ok());
    CHECK(imported->report.imported == 10);
    CHECK(imported->report.lods == Counts{{"1.2", 10}});
    CHECK(imported->report.verticesBefore == 110);
    CHECK(imported->report.originalTriangles == 180);
  }
  SECTION("a LOD the file does not have") {
    Lod2ImportOptions options = placedInSyntheticCity();
    options.lod = "3.0";
    const Result<Lod2Import> imported = importModels(sharedData("cityjson/multi_lod.json"), options);
    REQUIRE(imported.ok());
    CHECK(imported->report.imported == 0);
    CHECK(imported->report.skipped == Counts{{"no LOD 3.0", 10}});
  }
}

TEST_CASE("lod2: CityJSON 1.0 with CompositeSolid, MultiSolid, MultiSurface with holes, numeric LODs",
          "[lod2][cityjson]") {
  const Result<CityJsonFile> file = readCityJson(fixture("geometry_types.city.json"));
  REQUIRE(file.ok());
  CHECK(file->version == "1.0");
  CHECK(file->referenceSystem == "urn:ogc:def:crs:EPSG::7415");
  CHECK(file->crs == "EPSG:7415");
  REQUIRE(file->buildings.size() == 2);
  CHECK(file->partsMerged == 1);
  CHECK(file->geometries == Counts{{"CompositeSolid", 1}, {"MultiSolid", 1}, {"MultiSurface", 1}});
  CHECK(file->lods == Counts{{"2", 2}});
  CHECK(file->skipped == Counts{{"BuildingInstallation", 1}, {"Road", 1}});

  const CityJsonBuilding& hospital = file->buildings[0];
  CHECK(hospital.objectId == "b1");
  CHECK(hospital.parts == 1);
  CHECK(hospital.geometries == 2);
  CHECK(hospital.name == "Test Hospital");
  CHECK(hospital.function == "hospital");
  CHECK(hospital.storeysAboveGround == Approx(3.0));
  CHECK(hospital.startYear == 1998);
  CHECK(hospital.positions.size() == 24);  // three boxes of 8 corners
  CHECK(hospital.triangles.size() == 3 * 36);
  // Two boxes of the CompositeSolid (10 x 10 x 3 and 6 x 10 x 3) and the part's box (10 x 10 x 6).
  Lod2Mesh mesh{hospital.positions, hospital.triangles, hospital.kinds};
  CHECK(enclosedVolumeM3(mesh) == Approx(300.0 + 180.0 + 600.0).epsilon(1e-9));
  // The part has no semantics: its kinds come from the normals (2 roof, 2 ground, 8 wall triangles).
  const auto kinds = kindCounts(mesh);
  CHECK(kinds.at(SurfaceKind::Roof) == 6);
  CHECK(kinds.at(SurfaceKind::Ground) == 4);  // the part's bottom is at 3 m: Other, not ground
  CHECK(kinds.at(SurfaceKind::Other) == 2);
  CHECK(kinds.at(SurfaceKind::Wall) == 24);

  // The courtyard building: roof and ground with a hole, triangulated in their plane.
  const CityJsonBuilding& courtyard = file->buildings[1];
  CHECK(courtyard.objectId == "b2");
  Lod2Mesh court{courtyard.positions, courtyard.triangles, courtyard.kinds};
  CHECK(enclosedVolumeM3(court) == Approx((20.0 * 20.0 - 8.0 * 8.0) * 6.0).epsilon(1e-9));
  CHECK(surfaceAreaM2(court) == Approx(2 * 336.0 + 6.0 * (80.0 + 32.0)).epsilon(1e-9));
  CHECK(kindCounts(court).at(SurfaceKind::Roof) == 8);  // 4 + 4 corners + 2 for the hole - 2

  SECTION("an LOD present in one building only") {
    const Result<CityJsonFile> lod1 = readCityJson(fixture("geometry_types.city.json"), CityJsonOptions{"1"});
    REQUIRE(lod1.ok());
    REQUIRE(lod1->buildings.size() == 1);
    CHECK(lod1->buildings[0].objectId == "b1");
    CHECK(lod1->buildings[0].lod == "1");
    CHECK(lod1->skipped.at("no LOD 1") == 1);
  }
  SECTION("imported: a hospital of 3 storeys built in 1998 is critical") {
    Lod2ImportOptions options;
    // A city around the fixture's own place in Delft, so its CRS is used (no placement).
    const auto toLonLat = CrsToLonLat::create("EPSG:7415");
    REQUIRE(toLonLat.ok());
    const auto origin = toLonLat->toLonLat(85030.0, 447510.0);
    REQUIRE(origin.has_value());
    options.originLon = origin->x;
    options.originLat = origin->y;
    options.extent = Rect{-500.0f, -500.0f, 500.0f, 500.0f};
    const Result<Lod2Import> imported = importModels(fixture("geometry_types.city.json"), options);
    REQUIRE(imported.ok());
    CHECK(imported->report.crs == "EPSG:7415");
    REQUIRE(imported->models.size() == 2);
    const BuildingAttributes& a = imported->models[0].attributes;
    CHECK(a.id == "cj:b1");
    CHECK(a.use == "hospital");
    CHECK(a.storeys == 3);
    CHECK(a.storeysSource == ValueSource::Tagged);
    CHECK(a.heightM == Approx(9.0f));
    CHECK(a.startYear == 1998);
    CHECK(a.codeEra == CodeEra::HighCode);
    CHECK(a.importance == Importance::Critical);
    CHECK((a.importanceReasons & kReasonHospital) != 0);
    // The footprint: the union of the ground projections, 16 x 10 m, about 30 m west of the origin.
    CHECK(a.footprintAreaM2 == Approx(160.0f).epsilon(0.001));
    CHECK(a.centroidX == Approx(-22.0).margin(0.5));
    CHECK(a.centroidY == Approx(-5.0).margin(0.5));
    const BuildingAttributes& b = imported->models[1].attributes;
    CHECK(b.use == "unknown");
    CHECK(b.storeys == 2);  // 6 m at 3.5 m a storey (the mixed-use value for unknown uses)
    CHECK(b.storeysSource == ValueSource::Inferred);
    CHECK(b.footprintAreaM2 == Approx(400.0f).epsilon(0.001));  // the outer ring: the courtyard is inside
  }
}

TEST_CASE("lod2: PROJ transforms the CRSs of CityJSON files to WGS84", "[lod2][crs]") {
  CHECK(epsgFromReferenceSystem("https://www.opengis.net/def/crs/EPSG/0/7415") == "EPSG:7415");
  CHECK(epsgFromReferenceSystem("http://www.opengis.net/def/crs/EPSG/0/2056") == "EPSG:2056");
  CHECK(epsgFromReferenceSystem("urn:ogc:def:crs:EPSG::28992") == "EPSG:28992");
  CHECK(epsgFromReferenceSystem("urn:ogc:def:crs:EPSG:6.18:3:7415") == "EPSG:7415");
  CHECK(epsgFromReferenceSystem("EPSG:2056") == "EPSG:2056");
  CHECK(epsgFromReferenceSystem("urn:ogc:def:crs:OGC:1.3:CRS84").empty());
  CHECK(epsgFromReferenceSystem("").empty());

  struct Case {
    const char* crs;
    double x, y;
    double lon, lat;
  };
  // The RD origin in Amersfoort (WGS84 52.15517440 N, 5.38720621 E) and the LV95 origin at Bern's old
  // observatory (swisstopo's approximate formulas: 46.95108 N, 7.43863 E); within about 10 m.
  const Case cases[] = {{"EPSG:28992", 155000.0, 463000.0, 5.38720621, 52.15517440},
                        {"EPSG:7415", 155000.0, 463000.0, 5.38720621, 52.15517440},
                        {"EPSG:2056", 2600000.0, 1200000.0, 7.43863, 46.95108}};
  for (const Case& c : cases) {
    INFO(c.crs);
    const auto transform = CrsToLonLat::create(c.crs);
    REQUIRE(transform.ok());
    CHECK_FALSE(transform->geographic());
    CHECK(transform->horizontalMetresPerUnit() == 1.0);
    CHECK(transform->verticalMetresPerUnit() == 1.0);
    const auto lonLat = transform->toLonLat(c.x, c.y);
    REQUIRE(lonLat.has_value());
    CHECK(lonLat->x == Approx(c.lon).margin(1e-4));
    CHECK(lonLat->y == Approx(c.lat).margin(1e-4));
  }
  const auto feet = CrsToLonLat::create("EPSG:2263");  // NAD83 / New York Long Island (ftUS)
  REQUIRE(feet.ok());
  CHECK(feet->horizontalMetresPerUnit() == Approx(1200.0 / 3937.0));
  const auto unknown = CrsToLonLat::create("EPSG:999999");
  REQUIRE_FALSE(unknown.ok());
  CHECK(unknown.error().find("unknown coordinate reference system \"EPSG:999999\"") != std::string::npos);
}

TEST_CASE("lod2: delft.json in a city around Delft: georeferenced by its CRS, true metres", "[lod2][crs][data]") {
  const Result<CityJsonFile> file = readCityJson(sharedData("cityjson/delft.json"));
  REQUIRE(file.ok());
  CHECK(file->crs == "EPSG:7415");
  const auto rd = CrsToLonLat::create(file->crs);
  REQUIRE(rd.ok());
  const auto centre = rd->toLonLat(84878.0, 447587.0);  // the middle of the file's extent
  REQUIRE(centre.has_value());
  CHECK(centre->x == Approx(4.36).margin(0.02));  // Delft
  CHECK(centre->y == Approx(52.01).margin(0.02));
  Lod2ImportOptions options;
  options.originLon = centre->x;
  options.originLat = centre->y;
  options.extent = Rect{-1000.0f, -1000.0f, 1000.0f, 1000.0f};
  Lod2ImportReport report;
  const Result<std::vector<Lod2Model>> models = georeferenceCityJson(*file, "delft.json", options, &report);
  REQUIRE(models.ok());
  REQUIRE(models->size() == 160);
  CHECK(report.crs == "EPSG:7415");
  // Horizontal distances: RD New is scaled by about 0.99992 here, the city frame is true to scale.
  const CityJsonBuilding& first = file->buildings.front();
  const Lod2Mesh& mesh = models->front().skinned.mesh;
  double longestRd = 0.0;
  double longestCity = 0.0;
  for (std::size_t i = 1; i < first.positions.size(); ++i) {
    const glm::dvec2 d(first.positions[i] - first.positions[0]);
    const glm::dvec2 e(mesh.positions[i] - mesh.positions[0]);
    if (std::hypot(d.x, d.y) > longestRd) {
      longestRd = std::hypot(d.x, d.y);
      longestCity = std::hypot(e.x, e.y);
    }
  }
  REQUIRE(longestRd > 5.0);
  CHECK(longestCity / longestRd == Approx(1.0).margin(3e-4));
  CHECK(longestCity / longestRd > 1.0);
  // Every building lies in the extent, within 400 m of the origin.
  for (const Lod2Model& model : *models) {
    CHECK(std::abs(model.attributes.centroidX) < 400.0);
    CHECK(std::abs(model.attributes.centroidY) < 400.0);
  }
}

TEST_CASE("lod2: A placement moves the model set's footprint centre and turns it clockwise", "[lod2][crs][data]") {
  const Result<CityJsonFile> file = readCityJson(sharedData("cityjson/DH_01_subs.city.json"));
  REQUIRE(file.ok());
  CHECK(file->crs.empty());
  glm::dvec2 lo(1e300);
  glm::dvec2 hi(-1e300);
  for (const CityJsonBuilding& b : file->buildings) {
    for (const glm::dvec3& p : b.positions) {
      lo = glm::min(lo, glm::dvec2(p));
      hi = glm::max(hi, glm::dvec2(p));
    }
  }
  const glm::dvec2 size = hi - lo;  // RD New metres (the file does not say so)
  for (const double rotation : {0.0, 90.0}) {
    INFO("rotation " << rotation);
    const Lod2ImportOptions options = placedInSyntheticCity(rotation);
    const Result<std::vector<Lod2Model>> models = georeferenceCityJson(*file, "DH_01_subs", options, nullptr);
    REQUIRE(models.ok());
    glm::dvec2 placedLo(1e300);
    glm::dvec2 placedHi(-1e300);
    for (const Lod2Model& model : *models) {
      for (const glm::dvec3& p : model.skinned.mesh.positions) {
        placedLo = glm::min(placedLo, glm::dvec2(p));
        placedHi = glm::max(placedHi, glm::dvec2(p));
      }
    }
    const CityProjection projection(options.originLon, options.originLat);
    const glm::dvec2 target = projection.forward(kPlaceLon, kPlaceLat);
    const glm::dvec2 centre = 0.5 * (placedLo + placedHi);
    CHECK(centre.x == Approx(target.x).margin(1e-6));
    CHECK(centre.y == Approx(target.y).margin(1e-6));
    const glm::dvec2 placedSize = placedHi - placedLo;
    const glm::dvec2 expected = rotation == 0.0 ? size : glm::dvec2(size.y, size.x);
    CHECK(placedSize.x == Approx(expected.x).epsilon(1e-9));
    CHECK(placedSize.y == Approx(expected.y).epsilon(1e-9));
  }
  CHECK(glm::length(rotateClockwise({0.0, 1.0}, 90.0) - glm::dvec2(1.0, 0.0)) < 1e-12);
  CHECK(glm::length(rotateClockwise({1.0, 0.0}, 90.0) - glm::dvec2(0.0, -1.0)) < 1e-12);
}

}  // namespace qv::prep::test
