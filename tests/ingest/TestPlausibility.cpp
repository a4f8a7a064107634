// Underground buildings and the plausibility rules of docs/attributes.md ("Underground buildings",
// "Plausibility rules"), one building per rule in the hand-written tests/ingest/data/plausibility.osm
// (tags copied from Pennsylvania Station, Saint Patrick's Cathedral, The Grand Hotel, w265302074 and
// w265042577), and the rule functions themselves.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <string>

#include "IngestTestData.h"
#include "qv/prep/Attributes.h"

using namespace qv;
using namespace qv::prep;
using namespace qv::prep::test;

namespace {

const BuildingAttributes& attributesOf(const CityModel& model, const std::string& id) {
  const Building* b = findBuilding(model, id);
  INFO(id);
  REQUIRE(b != nullptr);
  return b->attributes;
}

}  // namespace

TEST_CASE("Underground buildings are left out and counted, and height=0 above ground is told",
          "[ingest][plausibility]") {
  const Ingested in = ingest({fixture("plausibility.osm")});
  REQUIRE(in.model.ok());
  const CityModel& model = *in.model;
  CHECK(model.buildings.size() == 11);
  CHECK(model.excluded == std::map<std::string, std::uint64_t>{{"underground", 2}});
  // Pennsylvania Station: location=underground, layer=-2, height=0 (was a 6 m slab in Midtown).
  CHECK(findBuilding(model, "w812714851") == nullptr);
  CHECK(hasWarning(model, "w812714851: location=underground: underground, neither drawn nor analysed"));
  // A negative layer with no height above ground.
  CHECK(findBuilding(model, "w2") == nullptr);
  CHECK(hasWarning(model, "w2: layer=-1 with no height above ground: underground, neither drawn nor analysed"));
  // A negative layer under a tagged height above 0 stands (a building under a deck).
  CHECK(attributesOf(model, "w3").heightM == Approx(8.0f));
  // height=0 on a building above ground: inferred, warned and noted; never silently.
  const BuildingAttributes& zero = attributesOf(model, "w4");
  CHECK(zero.heightSource == ValueSource::Inferred);
  CHECK(zero.heightM == Approx(defaultHeightForUse("unknown")));
  CHECK((zero.notes & ~kNoteTypeFromUse) == kNoteZeroHeight);  // its type is a guess too
  CHECK(hasWarning(model, "w4: height=0 is not above the ground; inferred instead"));
  CHECK(model.warningCounts.at("underground") == 2);
}

TEST_CASE("A cathedral's storeys come from its nave, and it is masonry", "[ingest][plausibility]") {
  const Ingested in = ingest({fixture("plausibility.osm")});
  REQUIRE(in.model.ok());
  // Saint Patrick's (1878): outline (also the nave part, 42 m) with two spire parts of 100.5 m.
  // Was "S1H, 17 storeys, 100.5 m": the spires' height made storeys and a steel frame.
  const Building* cathedral = findBuilding(*in.model, "w266010379");
  REQUIRE(cathedral != nullptr);
  const BuildingAttributes& a = cathedral->attributes;
  REQUIRE(cathedral->parts.size() == 3);
  CHECK(cathedral->parts[0].sourceId == "w266010379");  // the nave is drawn
  CHECK(cathedral->parts[0].heightM == Approx(42.0f));
  CHECK(a.heightM == Approx(100.5f));  // drawn to the spires' tips
  CHECK(a.minHeightM == 0.0f);
  CHECK(a.storeys == 7);  // 42 m / 6 m (religious storey height)
  CHECK(a.storeysSource == ValueSource::Inferred);
  CHECK(a.structuralType == StructuralType::URMM);
  CHECK(a.notes == (kNoteStoreysFromNave | kNotePreFrameMasonry));
  // An undated church without parts: height − roof:height is the main body (30 − 12 = 18 m).
  const BuildingAttributes& church = attributesOf(*in.model, "w7");
  CHECK(church.storeys == 3);
  CHECK(church.structuralType == StructuralType::URMM);
  CHECK(church.notes == (kNoteStoreysFromNave | kNoteTraditionalMasonry));
  // A chimney is a tower: undated, so masonry.
  const BuildingAttributes& chimney = attributesOf(*in.model, "w15");
  CHECK(chimney.use == "tower");
  CHECK(chimney.structuralType == StructuralType::URMM);
  CHECK(chimney.notes == kNoteTraditionalMasonry);
}

TEST_CASE("Tagged height and levels in conflict: the height wins, storeys inferred with the reason",
          "[ingest][plausibility]") {
  const Ingested in = ingest({fixture("plausibility.osm")});
  REQUIRE(in.model.ok());
  const CityModel& model = *in.model;
  // 21 m with building:levels=1 (w265042577's numbers): 21 m a storey.
  const BuildingAttributes& tall = attributesOf(model, "w8");
  CHECK(tall.storeys == 5);  // 21 m / 3.9 m (office)
  CHECK(tall.storeysSource == ValueSource::Inferred);
  CHECK(tall.heightSource == ValueSource::Tagged);
  CHECK((tall.notes & ~kNoteTypeFromUse) == kNoteLevelsConflict);
  CHECK(hasWarning(model,
                   "w8: height 21.0 m with 1 tagged storeys gives 21.0 m storeys (over 7 m); 5 storeys "
                   "inferred from the height"));
  // 10 m with 8 levels: 1.25 m a storey.
  const BuildingAttributes& squat = attributesOf(model, "w9");
  CHECK(squat.storeys == 3);  // 10 m / 3.1 m (residential)
  CHECK(squat.storeysSource == ValueSource::Inferred);
  CHECK((squat.notes & ~kNoteTypeFromUse) == kNoteLevelsConflict);
  // 30 m with 8 levels (3.75 m): both tags kept.
  const BuildingAttributes& fine = attributesOf(model, "w10");
  CHECK(fine.storeys == 8);
  CHECK(fine.storeysSource == ValueSource::Tagged);
  CHECK((fine.notes & ~kNoteTypeFromUse) == kNoteNone);
  CHECK(model.warningCounts.at("height and levels in conflict") == 2);
}

TEST_CASE("A building of 1868 is masonry with 19th-century storeys", "[ingest][plausibility]") {
  const Ingested in = ingest({fixture("plausibility.osm")});
  REQUIRE(in.model.ok());
  // The Grand Hotel: height=45.9, building:material=marble, start_date=1868. Was "S1H, 15 storeys".
  const BuildingAttributes& hotel = attributesOf(*in.model, "r3564791");
  CHECK(hotel.storeys == 10);  // 45.9 m / 4.5 m
  CHECK(hotel.storeysSource == ValueSource::Inferred);
  CHECK(hotel.structuralType == StructuralType::URMM);
  CHECK(hotel.notes == (kNoteOldStoreyHeight | kNotePreFrameMasonry));
}

TEST_CASE("An outline tagged building:part stands under its rooftop part and a lone rooftop part keeps its base",
          "[ingest][plausibility]") {
  const Ingested in = ingest({fixture("plausibility.osm")});
  REQUIRE(in.model.ok());
  // w265302074's tags: the outline (42 m, building:part=yes) and a rooftop part 42-50 m. Was drawn
  // as the rooftop alone: "base 42 m, 50 m, 2 storeys".
  const Building* b = findBuilding(*in.model, "w13");
  REQUIRE(b != nullptr);
  REQUIRE(b->parts.size() == 2);
  CHECK(b->parts[0].minHeightM == 0.0f);
  CHECK(b->parts[0].heightM == Approx(42.0f));
  CHECK(b->parts[1].minHeightM == Approx(42.0f));
  CHECK(b->attributes.minHeightM == 0.0f);
  CHECK(b->attributes.heightM == Approx(50.0f));
  CHECK(b->attributes.storeys == 11);  // 50 m / 4.5 m (retail)
  // A part without an outline keeps its min_height as the building's base.
  const BuildingAttributes& roof = attributesOf(*in.model, "w16");
  CHECK(roof.minHeightM == Approx(20.0f));
  CHECK(roof.heightM == Approx(26.0f));
}

TEST_CASE("undergroundReason and applyStoreyRules, case by case", "[ingest][plausibility]") {
  CHECK(undergroundReason("underground", "", std::nullopt, std::nullopt) == "location=underground");
  CHECK(undergroundReason(" Underground ", "", 30.0, 5.0) == "location=underground");
  CHECK(undergroundReason("", "-2", std::nullopt, std::nullopt) == "layer=-2 with no height above ground");
  CHECK(undergroundReason("", "-1", std::nullopt, 0.0) == "layer=-1 with no height above ground");
  CHECK(undergroundReason("", "-1", 8.0, std::nullopt).empty());
  CHECK(undergroundReason("", "-1", std::nullopt, 2.0).empty());
  CHECK(undergroundReason("", "1", std::nullopt, std::nullopt).empty());
  CHECK(undergroundReason("roof", "", std::nullopt, std::nullopt).empty());
  CHECK(undergroundReason("", "garbage", std::nullopt, std::nullopt).empty());

  struct Case {
    const char* use;
    float heightM, minHeightM;
    int storeys;
    bool heightTagged, storeysTagged;
    int year;
    std::optional<double> mainBodyM;
    int wantStoreys;
    bool wantTagged;
    unsigned wantNotes;
  };
  const Case cases[] = {
      {"office", 50, 0, 2, true, true, 0, {}, 13, false, kNoteLevelsConflict},   // 25 m a storey
      {"office", 14, 0, 2, true, true, 0, {}, 2, true, kNoteNone},               // 7 m: the limit is kept
      {"office", 4.4f, 0, 2, true, true, 0, {}, 2, true, kNoteNone},             // 2.2 m: kept
      {"office", 4.3f, 0, 2, true, true, 0, {}, 1, false, kNoteLevelsConflict},  // 2.15 m
      {"office", 50, 42, 2, true, true, 0, {}, 2, true, kNoteNone},              // 4 m above its base
      {"office", 50, 0, 2, false, true, 0, {}, 2, true, kNoteNone},              // height inferred: no conflict
      {"religious", 100, 0, 17, true, false, 0, 42.0, 7, false, kNoteStoreysFromNave},
      {"religious", 100, 0, 3, true, true, 0, 42.0, 3, true, kNoteNone},          // levels tagged win
      {"religious", 30, 0, 5, true, false, 0, 30.0, 5, false, kNoteNone},         // no lower main body
      {"office", 341, 0, 48, true, true, 0, {}, 49, false, kNoteLevelsConflict},  // w86121620: a spire
      {"office", 70, 0, 7, true, true, 0, {}, 18, false, kNoteLevelsConflict},    // 10 m: not a high-rise
      {"office", 30, 0, 8, true, true, 0, {}, 8, true, kNoteNone},
      {"tower", 60, 0, 3, true, true, 0, {}, 3, true, kNoteNone},  // towers keep their levels
      {"hotel", 45.9f, 0, 15, true, false, 1868, {}, 10, false, kNoteOldStoreyHeight},
      {"hotel", 45.9f, 0, 15, true, false, 1890, {}, 15, false, kNoteNone},
      {"retail", 9, 0, 2, true, false, 1850, {}, 2, false, kNoteNone},  // 4.5 m already
  };
  for (const Case& c : cases) {
    CAPTURE(c.use, c.heightM, c.minHeightM, c.storeys, c.year);
    BuildingAttributes a;
    a.use = c.use;
    a.heightM = c.heightM;
    a.minHeightM = c.minHeightM;
    a.storeys = static_cast<std::uint16_t>(c.storeys);
    a.heightSource = c.heightTagged ? ValueSource::Tagged : ValueSource::Inferred;
    a.storeysSource = c.storeysTagged ? ValueSource::Tagged : ValueSource::Inferred;
    a.startYear = static_cast<std::int16_t>(c.year);
    StoreyEvidence evidence;
    evidence.mainBodyHeightM = c.mainBodyM;
    const std::vector<std::string> messages = applyStoreyRules(a, evidence);
    CHECK(a.storeys == c.wantStoreys);
    CHECK((a.storeysSource == ValueSource::Tagged) == c.wantTagged);
    CHECK(a.notes == c.wantNotes);
    CHECK(messages.size() == ((c.wantNotes & kNoteLevelsConflict) != 0 ? 1u : 0u));
  }
}

TEST_CASE("Masonry eras: before 1890 and old religious buildings, towers and chimneys", "[ingest][plausibility]") {
  using T = StructuralType;
  CHECK(inferStructuralType("hotel", 45.9f, 15, "marble", "", 1868) == T::URMM);
  CHECK(inferStructuralType("hotel", 45.9f, 15, "marble", "", 1900) == T::S1H);     // cladding of a frame
  CHECK(inferStructuralType("office", 40, 10, "", "steel_frame", 1885) == T::S1H);  // structure tagged wins
  CHECK(inferStructuralType("house", 9, 3, "wood", "", 1850) == T::W1);
  CHECK(inferStructuralType("religious", 100.5f, 17, "", "", 1878) == T::URMM);
  CHECK(inferStructuralType("religious", 30, 5, "stone", "", 0) == T::URMM);
  CHECK(inferStructuralType("religious", 12, 2, "", "", 0) == T::URML);
  // Only use, height and era deciding: a guess (kNoteTypeFromUse, the damage is a type mixture).
  bool fromUse = false;
  inferStructuralType("office", 40, 10, "", "", 0, &fromUse);
  CHECK(fromUse);
  inferStructuralType("office", 40, 10, "brick", "", 0, &fromUse);  // masonry at 8+ storeys: cladding
  CHECK(fromUse);
  inferStructuralType("office", 40, 10, "glass", "", 0, &fromUse);  // curtain walls: a steel frame, by rule
  CHECK_FALSE(fromUse);
  inferStructuralType("office", 40, 10, "", "steel_frame", 0, &fromUse);
  CHECK_FALSE(fromUse);
  inferStructuralType("house", 9, 3, "wood", "", 0, &fromUse);
  CHECK_FALSE(fromUse);
  inferStructuralType("residential", 20, 5, "", "", 1868, &fromUse);  // pre-frame masonry: the era says
  CHECK_FALSE(fromUse);
  CHECK(inferStructuralType("religious", 30, 5, "concrete", "", 1965) == T::C1M);
  CHECK(inferStructuralType("tower", 60, 15, "", "", 1920) == T::URMM);
  CHECK(normalizeUse("chimney", "") == "tower");
  CHECK(normalizeUse("bell_tower", "") == "tower");
  CHECK(storeyHeightForUse("tower") == 4.0f);
  BuildingAttributes a;
  a.use = "religious";
  a.storeys = 2;
  a.heightM = 12;
  inferSeismicAttributes(a, false);
  CHECK(a.notes == kNoteTraditionalMasonry);
  a.startYear = 1878;
  inferSeismicAttributes(a, false);
  CHECK(a.notes == kNotePreFrameMasonry);
  a.startYear = 1990;
  inferSeismicAttributes(a, false);
  CHECK(a.notes == kNoteTypeFromUse);  // no masonry era: the type is a guess from use
}

TEST_CASE("A spire, mast or antenna part is drawn but is not structure: height and storeys stop at the roof",
          "[ingest][plausibility]") {
  const Ingested in = ingest({fixture("appendage.osm")});
  REQUIRE(in.model.ok());
  // A pyramidal part that is all roof, raised on the body (the Empire State Building's mast).
  const Building* mast = findBuilding(*in.model, "w100");
  REQUIRE(mast != nullptr);
  CHECK(mast->attributes.heightM == Approx(40.0f));
  CHECK(mast->attributes.storeys == 10);  // the outline's tagged levels
  CHECK((mast->attributes.notes & kNoteRoofAppendage) != 0);
  REQUIRE(mast->parts.size() == 2);  // the mast is still drawn, to its tip
  CHECK(std::max(mast->parts[0].heightM, mast->parts[1].heightM) == Approx(60.0f));
  // man_made=tower, tower:type=communication (One World Trade Center's spire).
  const BuildingAttributes& spire = attributesOf(*in.model, "w200");
  CHECK(spire.heightM == Approx(80.0f));
  CHECK(spire.storeys == 20);
  CHECK((spire.notes & kNoteRoofAppendage) != 0);
  // A pointed part standing on the ground is the building; a bell tower is structure.
  const BuildingAttributes& pavilion = attributesOf(*in.model, "w300");
  CHECK(pavilion.heightM == Approx(10.0f));
  CHECK((pavilion.notes & kNoteRoofAppendage) == 0);
  const BuildingAttributes& church = attributesOf(*in.model, "w400");
  CHECK(church.heightM == Approx(35.0f));
  CHECK((church.notes & kNoteRoofAppendage) == 0);
}

TEST_CASE("The Empire State Building and One World Trade Center stand at their roofs, not their antenna and spire",
          "[ingest][plausibility]") {
  const Ingested& in = manhattanSouth();
  REQUIRE(in.model.ok());
  // OSM: ESB height=443.2 to the antenna tip, its mast two pyramidal parts from 330 m; One WTC's
  // outline height=417, its spire a communication tower part to 541 m.
  const BuildingAttributes& esb = attributesOf(*in.model, "w34633854");
  CHECK(esb.heightM == Approx(330.0f));
  CHECK(esb.storeys == 102);
  const BuildingAttributes& wtc = attributesOf(*in.model, "w713565776");
  CHECK(wtc.heightM < 425.0f);
  CHECK(wtc.heightM >= 417.0f);
  CHECK(wtc.storeys == 94);
}
