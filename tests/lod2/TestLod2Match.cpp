// Matching models to the LOD1 buildings of a city: by id, by footprint overlap >= 0.5, each
// building replaced once; replacements keep the existing attributes unless the model is taller.
#include <set>

#include <catch2/catch.hpp>

#include "Lod2TestData.h"
#include "qv/prep/Lod2Attributes.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Match.h"

namespace qv::prep::test {
namespace {

std::vector<glm::dvec2> square(double x, double y, double size) {
  return {{x, y}, {x + size, y}, {x + size, y + size}, {x, y + size}};
}

/// A closed box model over a square footprint.
Lod2Model boxModel(const std::string& id, double x, double y, double size, double height) {
  Lod2Model model;
  model.id = id;
  Lod2Mesh& mesh = model.skinned.mesh;
  for (const double z : {0.0, height}) {
    for (const glm::dvec2& p : square(x, y, size)) mesh.positions.emplace_back(p, z);
  }
  const std::uint32_t faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& f : faces) {
    mesh.triangles.insert(mesh.triangles.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    mesh.kinds.insert(mesh.kinds.end(), 2, SurfaceKind::Wall);
  }
  model.footprint = square(x, y, size);
  NewModelFacts facts;
  facts.id = id;
  model.attributes = newModelAttributes(facts, mesh, model.footprint);
  model.verticesBefore = 8;
  return model;
}

ExistingBuilding existing(const std::string& id, double x, double y, double size, float height, std::uint16_t storeys,
                          ValueSource storeysSource) {
  ExistingBuilding b;
  b.id = id;
  b.footprint = square(x, y, size);
  b.attributes.id = id;
  b.attributes.use = "office";
  b.attributes.heightM = height;
  b.attributes.storeys = storeys;
  b.attributes.storeysSource = storeysSource;
  b.attributes.heightSource = ValueSource::Tagged;
  b.attributes.name = "Existing " + id;
  return b;
}

}  // namespace

TEST_CASE("lod2: Footprint overlap: intersection over the smaller footprint", "[lod2][match]") {
  CHECK(footprintOverlap(square(0, 0, 10), square(0, 0, 10)) == Approx(1.0));
  CHECK(footprintOverlap(square(0, 0, 10), square(5, 0, 10)) == Approx(0.5));
  CHECK(footprintOverlap(square(0, 0, 10), square(2, 2, 4)) == Approx(1.0));  // inside: all of the smaller one
  CHECK(footprintOverlap(square(0, 0, 10), square(20, 0, 10)) == 0.0);
  // Orientation does not matter.
  std::vector<glm::dvec2> clockwise = square(5, 5, 10);
  std::reverse(clockwise.begin(), clockwise.end());
  CHECK(footprintOverlap(square(0, 0, 10), clockwise) == Approx(0.25));
}

TEST_CASE("lod2: Models replace buildings by id or by overlap, the rest are new", "[lod2][match]") {
  const std::vector<ExistingBuilding> city = {
      existing("w1", 0, 0, 20, 30.0f, 8, ValueSource::Tagged),      // matched by overlap, model shorter
      existing("w2", 100, 0, 20, 12.0f, 3, ValueSource::Inferred),  // matched by overlap, model taller
      existing("w3", 200, 0, 20, 30.0f, 8, ValueSource::Tagged),    // matched by id (model elsewhere)
      existing("w4", 300, 0, 20, 30.0f, 8, ValueSource::Tagged),    // overlapped 40 % only: not matched
      existing("w5", 400, 0, 20, 9.0f, 3, ValueSource::Tagged),     // two candidates: the better one wins
  };
  std::vector<Lod2Model> models;
  models.push_back(boxModel("cj:a", 1, 1, 19, 25.0));       // w1
  models.push_back(boxModel("cj:b", 100, 0, 20, 40.0));     // w2, taller
  models.push_back(boxModel("obj:w3", 1000, 0, 10, 10.0));  // w3 by its bare id
  models.push_back(boxModel("cj:d", 312, 0, 20, 30.0));     // w4: 8 x 20 of 20 x 20 = 0.4
  models.push_back(boxModel("cj:e1", 405, 0, 20, 9.0));     // w5: 0.75
  models.push_back(boxModel("cj:e2", 401, 0, 20, 9.0));     // w5: 0.95, wins
  models.push_back(boxModel("cj:f", 5000, 0, 20, 9.0));     // nothing there

  const Result<MatchResult> result = matchModels(models, city);
  REQUIRE(result.ok());
  CHECK(result->byId == 1);
  CHECK(result->byOverlap == 3);
  CHECK(result->added == 3);
  CHECK(result->replaced() == 4);

  CHECK(models[0].id == "w1");
  CHECK(models[0].replacesExisting);
  CHECK(models[0].attributes.name == "Existing w1");
  CHECK(models[0].attributes.heightM == Approx(30.0f));  // model shorter: the existing height stays
  CHECK(models[0].attributes.storeys == 8);
  CHECK(models[0].attributes.lod == 2);

  CHECK(models[1].id == "w2");
  CHECK(models[1].attributes.heightM == Approx(40.0f));  // model taller: its top
  CHECK(models[1].attributes.storeys == 10);             // 40 m / 3.9 m (office), storeys were inferred
  CHECK(models[1].attributes.use == "office");

  CHECK(models[2].id == "w3");
  CHECK(models[2].replacesExisting);
  // What is drawn, picked and flown to is the model: its footprint's centre and area, not the
  // replaced building's (w3 stood at x = 200; its model stands at x = 1000).
  CHECK(models[2].attributes.centroidX == Approx(1005.0));
  CHECK(models[2].attributes.centroidY == Approx(5.0));
  CHECK(models[2].attributes.footprintAreaM2 == Approx(100.0f));

  CHECK(models[3].id == "cj:d");
  CHECK_FALSE(models[3].replacesExisting);
  CHECK(models[4].id == "cj:e1");
  CHECK_FALSE(models[4].replacesExisting);
  CHECK(models[5].id == "w5");
  CHECK(models[6].id == "cj:f");
}

TEST_CASE("lod2: A tagged storey count survives a taller model, finished models are re-skinned", "[lod2][match]") {
  const std::vector<ExistingBuilding> city = {existing("w7", 0, 0, 20, 20.0f, 5, ValueSource::Tagged)};
  std::vector<Lod2Model> models{boxModel("cj:t", 0, 0, 20, 24.0)};
  REQUIRE(finishModel(models[0]).ok());
  CHECK(models[0].attributes.storeys == 7);  // new building: 24 m / 3.5 m
  const Result<MatchResult> result = matchModels(models, city);
  REQUIRE(result.ok());
  const Lod2Model& model = models[0];
  CHECK(model.id == "w7");
  CHECK(model.attributes.heightM == Approx(24.0f));
  CHECK(model.attributes.storeys == 5);
  const FloorLevels floors = floorLevels(model.attributes);
  CHECK(floors.storeyHeightM == Approx(4.8));
  requireWithinStoreyBands(model.skinned.mesh, floors);
  requireSkinningRule(model.skinned, floors);
  CHECK(heightRange(model.skinned.mesh).maxZ == Approx(floors.levelM(5)));  // the top follows the roof
}

TEST_CASE("lod2: Models that already replace a building (OSM parts) keep it only when it is in the city",
          "[lod2][match]") {
  const std::vector<ExistingBuilding> city = {existing("w1", 0, 0, 20, 30.0f, 8, ValueSource::Tagged),
                                              existing("w2", 100, 0, 20, 30.0f, 8, ValueSource::Tagged)};
  std::vector<Lod2Model> models;
  models.push_back(boxModel("w1", 0, 0, 20, 30.0));     // its own building
  models.push_back(boxModel("w99", 100, 0, 20, 30.0));  // not in this city, standing on w2
  models.push_back(boxModel("cj:x", 1, 1, 18, 30.0));   // on w1, which is taken
  for (Lod2Model& model : models) model.replacesExisting = model.id.rfind("w", 0) == 0;
  const Result<MatchResult> result = matchModels(models, city);
  REQUIRE(result.ok());
  CHECK(result->byId == 1);
  CHECK(result->byOverlap == 0);  // w99 is settled as new: it does not take w2 by overlap
  CHECK(result->added == 2);
  CHECK(models[0].id == "w1");
  CHECK(models[0].replacesExisting);
  CHECK(models[1].id == "w99");
  CHECK_FALSE(models[1].replacesExisting);
  CHECK(models[2].id == "cj:x");
  CHECK_FALSE(models[2].replacesExisting);
}

TEST_CASE("lod2: Den Haag's models placed in the synthetic city replace the blocks they stand on",
          "[lod2][match][data]") {
  const SyntheticCity& city = syntheticCity();
  Lod2ImportOptions options = placedInSyntheticCity();
  options.existing = &city.existing;
  const Result<Lod2Import> imported = importModels(sharedData("cityjson/DH_01_subs.city.json"), options);
  REQUIRE(imported.ok());
  REQUIRE(imported->models.size() == 4);
  std::set<std::string> cityIds;
  for (const ExistingBuilding& b : city.existing) cityIds.insert(b.id);
  std::set<std::string> replaced;
  for (const Lod2Model& model : imported->models) {
    if (!model.replacesExisting) {
      CHECK(model.id.rfind("cj:", 0) == 0);
      continue;
    }
    CHECK(cityIds.count(model.id) == 1);
    CHECK(replaced.insert(model.id).second);  // each building at most once
    CHECK(model.attributes.lod == 2);
    // The model stands mostly on the building it replaces.
    for (const ExistingBuilding& b : city.existing) {
      if (b.id == model.id) CHECK(footprintOverlap(model.footprint, b.footprint) >= 0.5);
    }
    requireSkinningRule(model.skinned, floorLevels(model.attributes));
  }
  INFO(replaced.size() << " of 4 models replaced a block");
  CHECK(replaced.size() >= 1);
  CHECK(imported->report.replaced == replaced.size());
  CHECK(imported->report.imported == 4);
}

}  // namespace qv::prep::test
