// The shipped HAZUS tables (engine/seismic/src/HazusTables.cpp, generated) equal the SimCenter file
// they come from, value by value: ../shared/data/hazus/hazus_data_eq.json.
#include <simdjson.h>

#include <catch2/catch.hpp>
#include <string>

#include "qv/format/BuildingAttributes.h"
#include "qv/seismic/HazusTables.h"
#include "qv/seismic/Loss.h"

using namespace qv;
using namespace qv::seismic;

namespace {

constexpr const char* kEras[] = {"Pre_code", "Low_code", "Moderate_code", "High_code"};  // CodeEra 1..4

struct HazusFile {
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
};

double number(simdjson::dom::element e) {
  double v = 0;
  if (e.get(v) == simdjson::SUCCESS) return v;
  std::int64_t i = 0;
  REQUIRE(e.get(i) == simdjson::SUCCESS);
  return static_cast<double>(i);
}

simdjson::dom::element at(simdjson::dom::element e, std::string_view key) {
  simdjson::dom::element out;
  INFO(std::string(key));
  REQUIRE(e[key].get(out) == simdjson::SUCCESS);
  return out;
}

// Every element of the JSON array `e` equals `shipped`, same length.
template <std::size_t N>
void checkArray(simdjson::dom::element e, const std::array<double, N>& shipped, const std::string& what) {
  simdjson::dom::array a;
  INFO(what);
  REQUIRE(e.get(a) == simdjson::SUCCESS);
  REQUIRE(a.size() == N);
  std::size_t i = 0;
  for (simdjson::dom::element v : a) {
    INFO("index " << i);
    CHECK(number(v) == shipped[i]);
    ++i;
  }
}

}  // namespace

TEST_CASE("Every shipped HAZUS value equals the SimCenter file's", "[loss][hazus]") {
  HazusFile file;
  REQUIRE(file.parser.load(QUAKEVIEW_SHARED_DATA_DIR "/hazus/hazus_data_eq.json").get(file.doc) == simdjson::SUCCESS);
  const auto str = at(file.doc, "Structural_Fragility_Groups");

  // Structural rows follow qv::StructuralType and carry its codes.
  // ... then the file's other types (for type mixtures), each found by its code.
  int compared = 0;
  for (std::size_t t = 0; t < hazus::kStructuralTypes + hazus::kExtraStructuralTypes; ++t) {
    const bool extra = t >= hazus::kStructuralTypes;
    const hazus::StructuralRow& row =
        extra ? hazus::kExtraStructural[t - hazus::kStructuralTypes] : hazus::kStructural[t];
    INFO(row.code);
    if (!extra) CHECK(row.code == structuralTypeCode(static_cast<StructuralType>(t + 1)));
    CHECK(hazus::structuralRowByCode(row.code) == &row);
    for (std::size_t e = 0; e < hazus::kCodeEras; ++e) {
      simdjson::dom::element limits;
      const bool present = at(at(str, "EDP_limits"), kEras[e])[row.code].get(limits) == simdjson::SUCCESS;
      CHECK(row.inFile[e] == present);
      // Where the file lacks a type at an era (C3, URM above low code), the row repeats low code.
      checkArray(present ? limits : at(at(at(str, "EDP_limits"), "Low_code"), row.code), row.driftLimits[e],
                 std::string(row.code) + " " + kEras[e]);
      compared += 4;
    }
    CHECK(number(at(at(str, "P_collapse"), row.code)) == row.collapseProbability);
    constexpr const char* kStates[] = {"DS1", "DS2", "DS3", "DS4", "Collapse"};
    for (std::size_t k = 0; k < 5; ++k) {
      checkArray(at(at(at(str, "Injury_rates"), kStates[k]), row.code), row.injuryRatesPercent[k],
                 std::string(row.code) + " injuries " + kStates[k]);
    }
    compared += 1 + 20;
  }
  for (std::size_t e = 0; e < hazus::kCodeEras; ++e) {
    CHECK(number(at(at(str, "Fragility_beta"), kEras[e])) == hazus::kStructuralBeta[e]);
  }

  const auto nsd = at(file.doc, "NonStructural_Drift_Sensitive_Fragility_Groups");
  const auto nsa = at(file.doc, "NonStructural_Acceleration_Sensitive_Fragility_Groups");
  for (std::size_t o = 0; o < hazus::kOccupancies; ++o) {
    const hazus::OccupancyRow& row = hazus::kOccupancy[o];
    INFO(row.code);
    CHECK(row.code == occupancyCode(static_cast<Occupancy>(o)));
    checkArray(at(at(str, "Repair_cost"), row.code), row.structuralRepairCostPercent, "structural repair cost");
    checkArray(at(at(str, "Repair_time"), row.code), row.structuralRepairTimeDays, "repair time");
    checkArray(at(at(nsd, "Repair_cost"), row.code), row.nsDriftRepairCostPercent, "drift-sensitive repair cost");
    checkArray(at(at(nsa, "Repair_cost"), row.code), row.nsAccelerationRepairCostPercent,
               "acceleration-sensitive repair cost");
    compared += 16;
  }
  // The file has exactly the 28 occupancies we ship.
  simdjson::dom::object costs;
  REQUIRE(at(str, "Repair_cost").get(costs) == simdjson::SUCCESS);
  CHECK(costs.size() == hazus::kOccupancies);

  checkArray(at(nsd, "EDP_limits"), hazus::kNsDriftLimits, "drift-sensitive limits");
  CHECK(number(at(nsd, "Fragility_beta")) == hazus::kNsDriftBeta);
  for (std::size_t e = 0; e < hazus::kCodeEras; ++e) {
    checkArray(at(at(nsa, "EDP_limits"), kEras[e]), hazus::kNsAccelerationLimitsG[e],
               std::string("acceleration-sensitive limits ") + kEras[e]);
  }
  CHECK(number(at(nsa, "Fragility_beta")) == hazus::kNsAccelerationBeta);
  CHECK(number(at(nsa, "Offset")) == hazus::kNsAccelerationOffset);

  for (const hazus::PopulationRow& row : hazus::kPopulationDistribution) {
    checkArray(at(at(file.doc, "Population_Distribution"), row.name), row.share, std::string(row.name));
  }
  // Parts of the day: every hour the file lists is in that part in the shipped table.
  constexpr const char* kParts[] = {"Nighttime", "Daytime", "Commute"};
  int hours = 0;
  for (std::size_t part = 0; part < 3; ++part) {
    simdjson::dom::array a;
    REQUIRE(at(at(file.doc, "Parts_of_day"), kParts[part]).get(a) == simdjson::SUCCESS);
    for (simdjson::dom::element h : a) {
      const auto hour = static_cast<std::size_t>(number(h));
      REQUIRE(hour < 24);
      CHECK(hazus::kPartOfDayByHour[hour] == part);
      CHECK(timeOfDayAtHour(static_cast<int>(hour)) == static_cast<TimeOfDay>(part));
      ++hours;
    }
  }
  CHECK(hours == 24);
  CHECK(compared == (23 + 13) * (16 + 21) + 28 * 16);
}
