#include <catch2/catch.hpp>

#include "qv/format/FacilityCategory.h"

using namespace qv;

TEST_CASE("Facility categories follow the emergency managers' rules, one case per rule", "[facility]") {
  struct Case {
    const char* what;
    const char* use;
    const char* amenity;
    float footprintM2;
    std::uint16_t storeys;
    unsigned reasons;
    FacilityCategory category;
    const char* kind;
  };
  using F = FacilityCategory;
  const Case c = GENERATE(
      Case{"hospital by use", "hospital", "", 800.0f, 5, 0, F::Essential, "hospital"},
      Case{"hospital by amenity", "unknown", "hospital", 800.0f, 5, 0, F::Essential, "hospital"},
      Case{"a clinic without beds is not essential", "hospital", "clinic", 300.0f, 2, kReasonHospital, F::None, ""},
      Case{"fire station", "fire_station", "", 400.0f, 2, 0, F::Essential, "fire_station"},
      Case{"police", "civic", "police", 600.0f, 3, 0, F::Essential, "police"},
      Case{"ambulance station", "unknown", "ambulance_station", 300.0f, 1, 0, F::Essential, "ambulance_station"},
      Case{"school", "school", "", 2000.0f, 3, 0, F::SchoolShelter, "school"},
      Case{"kindergarten", "unknown", "kindergarten", 200.0f, 1, 0, F::SchoolShelter, "kindergarten"},
      Case{"university", "university", "", 5000.0f, 6, 0, F::SchoolShelter, "university"},
      Case{"shelter", "unknown", "shelter", 500.0f, 1, 0, F::SchoolShelter, "shelter"},
      Case{"old tile's shelter bit", "civic", "", 500.0f, 1, kReasonShelter, F::SchoolShelter, "shelter"},
      Case{"stadium", "sports", "", 30000.0f, 1, 0, F::HighOccupancy, "sports"},
      Case{"theatre", "commercial", "theatre", 1500.0f, 3, 0, F::HighOccupancy, "theatre"},
      Case{"church", "religious", "place_of_worship", 900.0f, 1, 0, F::HighOccupancy, "place_of_worship"},
      Case{"transit station", "transportation", "", 4000.0f, 1, 0, F::HighOccupancy, "transportation"},
      Case{"mall", "retail", "mall", 20000.0f, 2, 0, F::HighOccupancy, "mall"},
      Case{"large hotel", "hotel", "", 1000.0f, 10, 0, F::HighOccupancy, "large_hotel"},
      Case{"small hotel", "hotel", "", 300.0f, 4, 0, F::None, ""},
      Case{"large retail", "retail", "", 6000.0f, 2, 0, F::HighOccupancy, "large_retail"},
      Case{"fuel station", "retail", "fuel", 100.0f, 1, 0, F::Hazardous, "fuel"},
      Case{"power plant", "industrial", "power_plant", 5000.0f, 2, 0, F::Hazardous, "power_plant"},
      Case{"substation", "unknown", "substation", 100.0f, 1, 0, F::Hazardous, "substation"},
      Case{"chemical works", "industrial", "chemical_works", 5000.0f, 2, 0, F::Hazardous, "chemical_works"},
      Case{"a school that is also a place of worship is a school", "school", "place_of_worship", 900.0f, 2, 0,
           F::SchoolShelter, "school"},
      Case{"tall office is not critical", "office", "", 2500.0f, 40, kReasonTall | kReasonComplex, F::None, ""},
      Case{"multi-part residential is not critical", "residential", "", 800.0f, 8, kReasonComplex, F::None, ""},
      Case{"plain house", "house", "", 120.0f, 2, 0, F::None, ""});
  CAPTURE(c.what);
  const FacilityClass got = classifyFacility(c.use, c.amenity, c.footprintM2, c.storeys, c.reasons);
  CHECK(facilityCategoryName(got.category) == facilityCategoryName(c.category));
  CHECK(got.kind == c.kind);
}

TEST_CASE("Facility category names round-trip and have sources", "[facility]") {
  for (auto i = 1u; i < static_cast<unsigned>(FacilityCategory::Count); ++i) {
    const auto category = static_cast<FacilityCategory>(i);
    CAPTURE(i);
    CHECK(parseFacilityCategory(facilityCategoryName(category)) == category);
    CHECK_FALSE(facilityCategorySource(category).empty());
  }
  CHECK_FALSE(parseFacilityCategory("none"));
  CHECK_FALSE(parseFacilityCategory("critical"));
  CHECK(facilityCategoryName(static_cast<FacilityCategory>(99)) == "none");
  CHECK(facilityCategoryLabel(FacilityCategory::SchoolShelter) == "school or shelter");
}
