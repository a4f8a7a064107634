// The attribute rules of docs/attributes.md, table by table.
#include <catch2/catch.hpp>

#include <optional>
#include <string>

#include "qv/format/FacilityCategory.h"
#include "qv/prep/Attributes.h"

using namespace qv;
using namespace qv::prep;

TEST_CASE("OSM lengths parse to metres with their units", "[ingest][attributes]") {
  struct Row {
    const char* text;
    std::optional<double> meters;
  };
  const Row rows[] = {
      {"30", 30.0},
      {"30.5", 30.5},
      {"30 m", 30.0},
      {"30m", 30.0},
      {" 30 m ", 30.0},
      {"30 metres", 30.0},
      {"100 ft", 30.48},
      {"100ft", 30.48},
      {"100 feet", 30.48},
      {"12'", 3.6576},
      {"12'6\"", 3.81},
      {"12' 6\"", 3.81},
      {"1,5", 1.5},             // decimal comma (1-2 digits after it)
      {"1,500", std::nullopt},  // thousands separator or a list: ambiguous
      {"concrete", std::nullopt},
      {"", std::nullopt},
      {"-3", std::nullopt},
      {"5;6", std::nullopt},
      {"30 storeys", std::nullopt},
      {"1e3", std::nullopt},
      {"nan", std::nullopt},
      {".", std::nullopt},
  };
  for (const Row& row : rows) {
    INFO("\"" << row.text << "\"");
    const std::optional<double> parsed = parseLengthMeters(row.text);
    REQUIRE(parsed.has_value() == row.meters.has_value());
    if (row.meters) CHECK(*parsed == Approx(*row.meters).epsilon(1e-12));
  }
  // NYC's heightroof is in feet: plain numbers take the unit of the input, explicit units win.
  CHECK(*parseLengthMeters("100", LengthUnit::Feet) == Approx(30.48));
  CHECK(*parseLengthMeters("30 m", LengthUnit::Feet) == Approx(30.0));
  CHECK(parseLengthUnit("ft") == LengthUnit::Feet);
  CHECK(parseLengthUnit("metres") == LengthUnit::Meters);
  CHECK_FALSE(parseLengthUnit("furlong").has_value());
}

TEST_CASE("Levels and start dates parse or are refused", "[ingest][attributes]") {
  CHECK(parseLevels("102") == 102.0);
  CHECK(parseLevels("2.5") == 2.5);
  CHECK_FALSE(parseLevels("concrete").has_value());
  CHECK_FALSE(parseLevels("-1").has_value());
  CHECK_FALSE(parseLevels("5;6").has_value());
  CHECK(parseMinLevel("-1") == -1.0);
  CHECK(parseMinLevel("24") == 24.0);

  CHECK(parseStartYear("1931") == 1931);
  CHECK(parseStartYear("1931-05-01") == 1931);
  CHECK(parseStartYear("~1900") == 1900);
  CHECK(parseStartYear("1930s") == 1930);
  CHECK(parseStartYear("c. 1920") == 1920);
  CHECK(parseStartYear("1930..1931") == 1930);
  CHECK_FALSE(parseStartYear("C19").has_value());
  CHECK_FALSE(parseStartYear("12345").has_value());
  CHECK_FALSE(parseStartYear("unknown").has_value());
}

TEST_CASE("Uses are normalized from building and amenity", "[ingest][attributes]") {
  struct Row {
    const char* building;
    const char* amenity;
    const char* use;
  };
  const Row rows[] = {
      {"office", "", "office"},
      {"apartments", "", "residential"},
      {"house", "", "house"},
      {"yes", "", "unknown"},
      {"yes", "hospital", "hospital"},
      {"yes", "fire_station", "fire_station"},
      {"commercial", "school", "school"},  // a generic building value gives way to the amenity
      {"office", "restaurant", "office"},  // a specific one does not
      {"church", "", "religious"},
      {"train_station", "", "transportation"},
      {"ventilation_shaft", "", "service"},
      {"spaceport", "", "other"},
      {"", "police", "police"},
      {"yes", "clinic", "clinic"},       // an outpatient clinic (Hazus COM7), not a hospital
      {"hospital", "clinic", "clinic"},  // building=hospital is any medical building
      {"hospital", "", "hospital"},
  };
  for (const Row& row : rows) {
    INFO(row.building << " / " << row.amenity);
    CHECK(normalizeUse(row.building, row.amenity) == row.use);
  }
}

TEST_CASE("Use and facility category follow one rule from the same tags", "[ingest][attributes]") {
  // The ingest reads the use from the building tag and the stored amenity value (normalizeFacility):
  // the category classifyFacility gives and the use agree.
  struct Row {
    const char* building;
    const char* amenity;
    const char* healthcare;
    const char* socialFacility;
    const char* use;
    FacilityCategory category;
  };
  const Row rows[] = {
      {"yes", "", "hospital", "", "hospital", FacilityCategory::Essential},
      {"hospital", "clinic", "", "", "clinic", FacilityCategory::None},
      {"yes", "", "clinic", "", "clinic", FacilityCategory::None},
      {"yes", "shelter", "", "", "unknown", FacilityCategory::None},  // a bus stop's shelter
      {"yes", "social_facility", "", "shelter", "shelter", FacilityCategory::SchoolShelter},
      {"yes", "social_facility", "", "group_home", "unknown", FacilityCategory::None},
      {"yes", "police", "", "", "police", FacilityCategory::Essential},
      {"yes", "ambulance_station", "", "", "ambulance_station", FacilityCategory::Essential},
  };
  for (const Row& row : rows) {
    INFO(row.building << " / " << row.amenity << " / " << row.healthcare << " / " << row.socialFacility);
    BuildingAttributes a;
    a.amenity = normalizeFacility(row.amenity, "", row.healthcare, row.socialFacility, "", "", "");
    a.use = normalizeUse(row.building, a.amenity);
    CHECK(a.use == row.use);
    CHECK(classifyFacility(a).category == row.category);
  }
}

TEST_CASE("Storey heights and default heights follow the documented tables", "[ingest][attributes]") {
  struct Row {
    const char* use;
    float storeyM;
    int defaultStoreys;
  };
  // docs/attributes.md, tables "Storey height by use" and "Default heights".
  const Row rows[] = {
      {"residential", 3.1f, 4}, {"house", 3.0f, 2},    {"hotel", 3.1f, 6},      {"office", 3.9f, 6},
      {"commercial", 3.9f, 2},  {"retail", 4.5f, 1},   {"industrial", 5.0f, 2}, {"warehouse", 6.0f, 1},
      {"school", 3.9f, 3},      {"hospital", 4.2f, 4}, {"religious", 6.0f, 1},  {"parking", 3.0f, 3},
      {"unknown", 3.5f, 2},     {"other", 3.5f, 2},    {"not-a-use", 3.5f, 2},
  };
  for (const Row& row : rows) {
    INFO(row.use);
    CHECK(storeyHeightForUse(row.use) == Approx(row.storeyM));
    CHECK(defaultStoreysForUse(row.use) == row.defaultStoreys);
    CHECK(defaultHeightForUse(row.use) == Approx(row.storeyM * static_cast<float>(row.defaultStoreys)));
  }
}

TEST_CASE("Heights and storeys are taken from tags or inferred, and say which", "[ingest][attributes]") {
  SECTION("height and levels tagged") {
    const ResolvedHeights h = resolveHeights({443.2, std::nullopt, 102.0, std::nullopt}, "office");
    CHECK(h.heightM == Approx(443.2f));
    CHECK(h.storeys == 102);
    CHECK(h.heightSource == ValueSource::Tagged);
    CHECK(h.storeysSource == ValueSource::Tagged);
  }
  SECTION("levels only: height = levels x storey height of the use") {
    const ResolvedHeights h = resolveHeights({std::nullopt, std::nullopt, 10.0, std::nullopt}, "office");
    CHECK(h.heightM == Approx(39.0f));
    CHECK(h.storeys == 10);
    CHECK(h.heightSource == ValueSource::Inferred);
    CHECK(h.storeysSource == ValueSource::Tagged);
  }
  SECTION("height only: storeys = round(height / storey height), at least 1") {
    CHECK(resolveHeights({31.0, std::nullopt, std::nullopt, std::nullopt}, "residential").storeys == 10);
    CHECK(resolveHeights({1.0, std::nullopt, std::nullopt, std::nullopt}, "residential").storeys == 1);
    CHECK(resolveHeights({31.0, std::nullopt, std::nullopt, std::nullopt}, "residential").storeysSource ==
          ValueSource::Inferred);
  }
  SECTION("nothing tagged: the default of the use") {
    const ResolvedHeights h = resolveHeights({}, "hospital");
    CHECK(h.heightM == Approx(16.8f));
    CHECK(h.storeys == 4);
    CHECK(h.heightSource == ValueSource::Inferred);
  }
  SECTION("a part without heights inherits its building's height") {
    CHECK(resolveHeights({}, "office", 50.0).heightM == Approx(50.0f));
  }
  SECTION("stacked part: min_height and building:min_level") {
    // The Empire State Building's w137425128: levels 24..29 between 90 m and 115 m.
    const ResolvedHeights h = resolveHeights({115.0, 90.0, 29.0, 24.0}, "office");
    CHECK(h.minHeightM == Approx(90.0f));
    CHECK(h.heightM == Approx(115.0f));
    CHECK(h.storeys == 5);
    CHECK(h.levelsFromGround == 29);
    // min_level alone places the bottom at min_level x storey height.
    CHECK(resolveHeights({std::nullopt, std::nullopt, 8.0, 3.0}, "office").minHeightM == Approx(11.7f));
  }
  SECTION("inconsistent min height stands the part on the ground") {
    CHECK(resolveHeights({12.5, 22.5, std::nullopt, std::nullopt}, "unknown").minHeightM == 0.0f);
  }
}

TEST_CASE("Structural types follow the documented rules", "[ingest][attributes]") {
  struct Row {
    const char* use;
    float heightM;
    int storeys;
    const char* material;
    const char* structure;
    int year;
    StructuralType expected;
  };
  using T = StructuralType;
  const Row rows[] = {
      // 1. building:structure first
      {"office", 40, 10, "brick", "steel_frame", 1960, T::S1H},
      {"office", 12, 3, "", "steel_braced_frame", 0, T::S2L},
      {"residential", 20, 6, "", "reinforced_concrete", 0, T::C1M},
      {"residential", 20, 6, "", "concrete_shear_wall", 0, T::C2M},
      {"industrial", 8, 1, "", "precast_tilt_up", 0, T::PC1},
      {"house", 6, 2, "", "timber_frame", 0, T::W1},
      {"office", 12, 3, "", "load_bearing_masonry", 1900, T::URMM},
      // 2. building:material
      {"house", 6, 2, "wood", "", 0, T::W1},
      {"retail", 6, 1, "wood", "", 0, T::W2},
      {"residential", 20, 6, "concrete", "", 0, T::C2M},
      {"office", 20, 6, "concrete", "", 0, T::C1M},
      {"office", 200, 50, "glass", "", 2010, T::S1H},
      {"residential", 200, 60, "glass", "", 2015, T::C2H},
      {"industrial", 8, 1, "metal", "", 0, T::S2L},
      {"residential", 15, 5, "brick", "", 1910, T::URMM},
      {"residential", 6, 2, "brick", "", 1910, T::URML},
      {"residential", 15, 5, "brick", "", 1965, T::RM1M},
      {"residential", 9, 3, "brick", "", 1965, T::RM1L},
      {"office", 120, 30, "brick", "", 1925, T::S1H},  // tall masonry: cladding on a frame
      {"office", 15, 4, "plaster", "", 1965, T::C1M},  // finishes say nothing: use rules
      // 3. use x storeys x year
      {"office", 443, 102, "", "", 1931, T::S1H},
      {"residential", 100, 30, "", "", 0, T::C2H},
      {"residential", 100, 30, "", "", 1925, T::S1H},
      {"hotel", 60, 20, "", "", 1990, T::C2H},
      {"house", 6, 2, "", "", 0, T::W1},
      {"mobile_home", 3, 1, "", "", 0, T::MH},
      {"roof", 4, 1, "", "", 0, T::S2L},
      {"parking", 9, 3, "", "", 0, T::C1L},
      {"warehouse", 6, 1, "", "", 1980, T::PC1},
      {"warehouse", 6, 1, "", "", 1920, T::URML},
      {"residential", 15, 5, "", "", 1975, T::C2M},
      {"office", 15, 5, "", "", 1975, T::C1M},
      {"residential", 18, 5, "", "", 1925, T::C3M},
      {"residential", 18, 5, "", "", 1880, T::URMM},
      {"unknown", 7, 2, "", "", 0, T::URML},
      {"unknown", 20, 0, "", "", 0, T::URMM},  // storeys unknown: from the height at 3.5 m
  };
  for (const Row& row : rows) {
    INFO(row.use << " " << row.heightM << " m " << row.storeys << " storeys, material '" << row.material
                 << "', structure '" << row.structure << "', " << row.year);
    CHECK(structuralTypeCode(inferStructuralType(row.use, row.heightM, row.storeys, row.material, row.structure,
                                                 row.year)) == structuralTypeCode(row.expected));
  }
}

TEST_CASE("Code eras follow the HAZUS year bands", "[ingest][attributes]") {
  CHECK(inferCodeEra(0) == CodeEra::Unknown);
  CHECK(inferCodeEra(1868) == CodeEra::PreCode);
  CHECK(inferCodeEra(1940) == CodeEra::PreCode);
  CHECK(inferCodeEra(1941) == CodeEra::LowCode);
  CHECK(inferCodeEra(1975) == CodeEra::LowCode);
  CHECK(inferCodeEra(1976) == CodeEra::ModerateCode);
  CHECK(inferCodeEra(1994) == CodeEra::ModerateCode);
  CHECK(inferCodeEra(1995) == CodeEra::HighCode);
  CHECK(inferCodeEra(2024) == CodeEra::HighCode);
}

TEST_CASE("Importance reasons are kept, but only essential facilities, schools and shelters are critical",
          "[ingest][attributes]") {
  struct Row {
    const char* use;
    const char* amenity;
    float heightM;
    bool hasParts;
    std::uint8_t reasons;
    bool critical;
  };
  const Row rows[] = {
      {"office", "", 30.0f, false, kReasonNone, false},
      {"hospital", "", 20.0f, false, kReasonHospital, true},
      {"unknown", "clinic", 8.0f, false, kReasonHospital, false},  // a clinic without beds
      {"fire_station", "", 10.0f, false, kReasonFireStation, true},
      {"unknown", "police", 10.0f, false, kReasonPolice, true},
      {"school", "", 12.0f, false, kReasonSchool, true},
      {"university", "", 30.0f, false, kReasonSchool, true},
      {"civic", "townhall", 20.0f, false, kReasonNone, false},
      {"civic", "community_centre", 9.0f, false, kReasonShelter, true},
      {"office", "", 100.0f, false, kReasonNone, false},  // "taller than 100 m"
      {"office", "", 100.5f, false, kReasonTall, false},  // a tall office is not critical
      {"office", "", 443.2f, true, kReasonTall | kReasonComplex, false},
      {"residential", "", 20.0f, true, kReasonComplex, false},
      {"hospital", "", 120.0f, true, kReasonHospital | kReasonTall | kReasonComplex, true},
  };
  for (const Row& row : rows) {
    INFO(row.use << " / " << row.amenity << " " << row.heightM << " m");
    BuildingAttributes a;
    a.use = row.use;
    a.amenity = row.amenity;
    a.heightM = row.heightM;
    classifyImportance(a, row.hasParts);
    CHECK(a.importanceReasons == row.reasons);
    CHECK(a.importance == (row.critical ? Importance::Critical : Importance::General));
  }
}

TEST_CASE("Facility tags other than amenity are folded into the stored amenity", "[ingest][attributes]") {
  CHECK(normalizeFacility("school", "ambulance_station", "", "", "", "", "") == "school");  // amenity wins
  CHECK(normalizeFacility("", "ambulance_station", "", "", "", "", "") == "ambulance_station");
  CHECK(normalizeFacility("", "", "hospital", "", "", "", "") == "hospital");
  CHECK(normalizeFacility("", "", "clinic", "", "", "", "") == "clinic");
  CHECK(normalizeFacility("", "", "doctor", "", "", "", "") == "clinic");
  CHECK(normalizeFacility("", "", "", "shelter", "", "", "") == "shelter");
  CHECK(normalizeFacility("social_facility", "", "", "shelter", "", "", "") == "shelter");
  CHECK(normalizeFacility("shelter", "", "", "", "", "", "") == "weather_shelter");  // OSM: against the weather
  CHECK(normalizeFacility("", "", "", "", "plant", "", "") == "power_plant");
  CHECK(normalizeFacility("", "", "", "", "substation", "", "") == "substation");
  CHECK(normalizeFacility("", "", "", "", "", "mall", "") == "mall");
  CHECK(normalizeFacility("", "", "", "", "", "", "chemical") == "chemical_works");
  CHECK(normalizeFacility("", "", "", "", "", "", "oil") == "refinery");
  CHECK(normalizeFacility(" ", "", "", "", "", "bakery", "brewery") == "");
}

TEST_CASE("Addresses are formatted from addr:*", "[ingest][attributes]") {
  CHECK(formatAddress("350", "5th Avenue", "10118", "New York") == "350 5th Avenue, 10118 New York");
  CHECK(formatAddress("1234", "Broadway", "10001", "") == "1234 Broadway, 10001");
  CHECK(formatAddress("", "Broadway", "", "") == "Broadway");
  CHECK(formatAddress("", "", "", "") == "");
}
