// The Empire State Building (w34633854) as one LOD2 mesh from its OSM building:part set, read by
// prep::ingest's readCity like the city step does.
#include <set>

#include <catch2/catch.hpp>

#include "Lod2TestData.h"
#include "qv/prep/Cleaning.h"
#include "qv/prep/Ingest.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2OsmParts.h"
#include "qv/prep/SynthCity.h"

namespace qv::prep::test {
namespace {

const Building* empireStateBuilding() {
  static const Result<CityModel> city = readCity({sharedData("osm/fixture-midtown-empire-state.osm")}, {});
  if (!city.ok()) return nullptr;
  for (const Building& b : city->buildings) {
    if (b.attributes.id == "w34633854") return &b;
  }
  return nullptr;
}

}  // namespace

TEST_CASE(
    "lod2: The Empire State Building from its OSM parts: setbacks, a 330 m structure under a mast drawn to 443.2 m",
    "[lod2][osm][data]") {
  const Building* esb = empireStateBuilding();
  REQUIRE(esb != nullptr);
  REQUIRE(esb->parts.size() == 11);
  Result<Lod2Model> model = modelFromOsmParts(*esb);
  REQUIRE(model.ok());
  CHECK(model->id == "w34633854");
  CHECK(model->replacesExisting);
  CHECK(model->source == "osm-parts");
  CHECK(model->attributes.lod == 2);
  CHECK(model->attributes.name == "Empire State Building");
  CHECK(model->attributes.storeys == 102);
  const HeightRange range = heightRange(model->skinned.mesh);
  CHECK(range.minZ == 0.0);
  CHECK(range.maxZ == Approx(443.2).margin(1e-4));     // drawn to the antenna's tip
  CHECK(model->attributes.heightM == Approx(330.0f));  // the structure's roof, under the mast

  // Setbacks: above the lobby (a ring-shaped part up to 17 m around the core) the horizontal
  // cross-section shrinks stepwise with height: 6,204 m2 at 30 m, ... 55 m2 on the spire.
  std::vector<double> areas;
  for (const double z : {30.0, 80.0, 100.0, 200.0, 280.0, 300.0, 350.0, 400.0, 440.0}) {
    areas.push_back(crossSectionAreaM2(model->skinned.mesh, z));
    INFO("z " << z << " m: " << areas.back() << " m2");
    CHECK(areas.back() > 0.0);
  }
  std::set<long> distinct;
  for (std::size_t i = 0; i < areas.size(); ++i) {
    distinct.insert(std::lround(areas[i]));
    if (i > 0) CHECK(areas[i] <= areas[i - 1] + 1e-6);
  }
  CHECK(distinct.size() >= 6);
  CHECK(areas.front() > 6000.0);
  CHECK(areas.front() > 100.0 * areas.back());
  // The footprint (union of the parts' outlines) is the lot, about 424 ft x 187 ft.
  REQUIRE(model->footprint.size() >= 4);
  CHECK(std::abs(signedRingArea(model->footprint.data(), model->footprint.size())) == Approx(7700.0).epsilon(0.03));

  // Finished: one bone per floor level, cut at all 103 levels.
  const double area = surfaceAreaM2(model->skinned.mesh);
  const double volume = enclosedVolumeM3(model->skinned.mesh);
  REQUIRE(finishModel(*model).ok());
  const FloorLevels floors = floorLevels(model->attributes);
  CHECK(floors.storeys == 102);
  CHECK(floors.storeyHeightM == Approx(330.0 / 102.0).epsilon(1e-6));
  requireWithinStoreyBands(model->skinned.mesh, floors);
  const std::size_t onFloors = requireSkinningRule(model->skinned, floors);
  CHECK(onFloors > 4 * 103);
  // The mast stands above the top floor level (330 m), on the roof's bone (requireSkinningRule).
  CHECK(floors.levelM(102) == Approx(330.0));
  CHECK(heightRange(model->skinned.mesh).maxZ == Approx(443.2).margin(1e-3));
  CHECK(surfaceAreaM2(model->skinned.mesh) == Approx(area).epsilon(1e-3));
  CHECK(enclosedVolumeM3(model->skinned.mesh) == Approx(volume).epsilon(1e-3));
  INFO("vertices " << model->verticesBefore << " -> " << model->verticesAfter << ", far triangles "
                   << model->farMesh.triangleCount());
  CHECK(model->verticesBefore == 354);
  CHECK(model->verticesAfter > 100 * model->verticesBefore);
  CHECK(model->farMesh.triangleCount() > 12);
  CHECK(model->farMesh.triangleCount() < model->skinned.mesh.triangleCount() / 100);
}

TEST_CASE("lod2: A part standing on another gets a bottom face, a building without parts fails", "[lod2][osm]") {
  Building building;
  building.attributes.id = "w1";
  building.attributes.heightM = 20.0f;
  building.attributes.storeys = 5;
  BuildingPart podium;
  podium.points = {{0, 0}, {30, 0}, {30, 20}, {0, 20}};
  podium.ringEnds = {4};
  podium.heightM = 8.0f;
  BuildingPart tower;  // a 10 x 10 tower with a 4 x 4 light well, from 8 m to 20 m
  tower.points = {{5, 5}, {15, 5}, {15, 15}, {5, 15}, {8, 8}, {8, 12}, {12, 12}, {12, 8}};
  tower.ringEnds = {4, 8};
  tower.minHeightM = 8.0f;
  tower.heightM = 20.0f;
  building.parts = {podium, tower};
  const Result<Lod2Model> model = modelFromOsmParts(building);
  REQUIRE(model.ok());
  std::map<SurfaceKind, std::size_t> kinds;
  for (SurfaceKind k : model->skinned.mesh.kinds) ++kinds[k];
  CHECK(kinds[SurfaceKind::Roof] == 2 + 8);
  CHECK(kinds[SurfaceKind::Other] == 8);   // the tower's underside, light well included
  CHECK(kinds[SurfaceKind::Ground] == 0);  // ground-level parts have no bottom face
  CHECK(kinds[SurfaceKind::Wall] == 2 * 4 + 2 * 8);
  // Volumes: the podium (open at z = 0, which adds nothing) and the closed tower.
  CHECK(enclosedVolumeM3(model->skinned.mesh) == Approx(30.0 * 20.0 * 8.0 + (100.0 - 16.0) * 12.0));
  CHECK(crossSectionAreaM2(model->skinned.mesh, 15.0) == Approx(84.0));
  CHECK(std::abs(signedRingArea(model->footprint.data(), model->footprint.size())) == Approx(600.0));

  Building empty;
  empty.attributes.id = "w2";
  const Result<Lod2Model> none = modelFromOsmParts(empty);
  REQUIRE_FALSE(none.ok());
  CHECK(none.error() == "w2: no building:part with a polygon and a height above its base");
}

TEST_CASE("lod2: synth-city's detailed towers: setbacks on floor levels, assembled like OSM parts", "[lod2][synth]") {
  SynthCityOptions options;
  options.buildings = 600;
  options.seed = 4;
  options.detailedTowers = 25;
  CityModel city = generateSynthCity(options);
  REQUIRE(city.buildings.size() == 600);
  // Exactly the 25 tallest eligible buildings (rectangles and L-shapes of 3 storeys or more).
  std::vector<float> towerHeights, otherHeights;
  for (const Building& b : city.buildings) {
    if (!hasOsmParts(b)) {
      const bool eligible = b.attributes.storeys >= kMinTowerStoreys && b.parts.size() == 1 &&
                            b.parts[0].ringEnds.size() == 1 &&
                            (b.parts[0].points.size() == 4 || b.parts[0].points.size() == 6);
      if (eligible) otherHeights.push_back(b.attributes.heightM);
      continue;
    }
    towerHeights.push_back(b.attributes.heightM);
    const BuildingAttributes& a = b.attributes;
    INFO(a.id);
    REQUIRE(b.parts.size() == 3);
    CHECK(b.parts[0].sourceId == a.id + "/podium");
    CHECK(b.parts[2].sourceId == a.id + "/crown");
    CHECK(b.parts[0].minHeightM == 0.0f);
    CHECK(b.parts[2].heightM == a.heightM);
    const double storeyM = static_cast<double>(a.heightM) / a.storeys;
    for (std::size_t i = 0; i < 3; ++i) {
      const BuildingPart& part = b.parts[i];
      CHECK(part.heightM > part.minHeightM);
      const double level = part.minHeightM / storeyM;  // each part starts on a floor level
      CHECK(level == Approx(std::round(level)).margin(1e-3));
      if (i > 0) {
        CHECK(part.minHeightM == b.parts[i - 1].heightM);  // stacked without a gap
        // Set back: strictly inside the part below.
        const double below = std::abs(signedRingArea(b.parts[i - 1].points.data(), 4));
        CHECK(std::abs(signedRingArea(part.points.data(), 4)) < below);
      }
    }
  }
  REQUIRE(towerHeights.size() == 25);
  CHECK(*std::min_element(towerHeights.begin(), towerHeights.end()) >=
        *std::max_element(otherHeights.begin(), otherHeights.end()));

  // Made models as the city step makes them from OSM parts, the same with one thread or two.
  CityModel again = city;
  FinishOptions finish;
  finish.remesh.maxEdgeM = kPartModelMaxEdgeM;
  const OsmPartsReport one = assembleOsmPartModels(city, finish, 1, "synthetic");
  const OsmPartsReport two = assembleOsmPartModels(again, finish, 2, "synthetic");
  CHECK(one.candidates == 25);
  CHECK(one.assembled == 25);
  CHECK(one.warnings.empty());
  CHECK(one.verticesAfter > one.verticesBefore);
  CHECK(two.verticesAfter == one.verticesAfter);
  std::size_t models = 0;
  for (std::size_t i = 0; i < city.buildings.size(); ++i) {
    const Building& b = city.buildings[i];
    if (!b.mesh) continue;
    ++models;
    INFO(b.attributes.id);
    CHECK(b.attributes.lod == 2);
    CHECK(b.mesh->source == MeshSource::Synthetic);
    CHECK(b.parts.size() == 3);  // the LOD1 fallback keeps the setbacks
    CHECK(again.buildings[i].mesh->positions == b.mesh->positions);
    // The setbacks show in the mesh: the cross-section shrinks from podium to crown.
    Lod2Mesh mesh;
    mesh.positions = b.mesh->positions;
    mesh.triangles = b.mesh->triangles;
    mesh.kinds.assign(mesh.triangles.size() / 3, SurfaceKind::Wall);
    const double low = crossSectionAreaM2(mesh, b.parts[0].heightM * 0.5);
    const double high = crossSectionAreaM2(mesh, (b.parts[2].minHeightM + b.parts[2].heightM) * 0.5);
    CHECK(low > high);
    CHECK(high > 0.0);
  }
  CHECK(models == 25);
}

}  // namespace qv::prep::test
