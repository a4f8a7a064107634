// The consequences file (`response-<n>/consequences.json`, docs/losses.md): the totals of a
// response's HAZUS losses for the city and for each district, written by `quakeview-prep response`
// and read by `info` and the viewer. One codec for writer and readers.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/JsonWriter.h"
#include "qv/core/Result.h"
#include "qv/seismic/Loss.h"

namespace qv::seismic {

/// The population the city's occupants compare with, as the user gave it (`response --population-night
/// N --population-day N --population-source TEXT`). Negative: not given.
struct PopulationFigures {
  double night = -1, day = -1;
  std::string source;
  [[nodiscard]] bool given() const { return night >= 0 || day >= 0; }
};

/// Expected damage of one group of buildings (an occupancy class or a structural type), as the HAZUS
/// summary report's tables give it: expected values only (sums of the buildings' probabilities and
/// consequences; the Monte Carlo intervals are the city's and the districts').
struct ClassTotals {
  std::string key;  ///< "RES3", "COM6" (occupancyCode) or "C1", "URM" (structuralTypeCode)
  std::uint64_t buildings = 0;
  std::array<double, 5> damageStates{};  ///< expected counts none..complete
  double damaged = 0;                    ///< moderate or worse
  double collapsed = 0, repairCostUsd = 0, occupants = 0;
  std::array<double, 4> injuries{};  ///< at the run's time of day, severity 1..4
};

/// How many of the analysed buildings had an attribute the data does not give, so that the model
/// used a stated assumption (docs/losses.md, docs/attributes.md).
struct InferredCounts {
  std::uint64_t buildings = 0;         ///< analysed buildings (with HAZUS results)
  std::uint64_t structuralType = 0;    ///< type not in the data: a mixture of Hazus types by occupancy
  std::uint64_t codeEra = 0;           ///< no year of construction: design levels spread
  std::uint64_t use = 0;               ///< no use: the mixed-use occupancy
  std::uint64_t occupants = 0;         ///< occupants from floor area and density
  std::uint64_t replacementValue = 0;  ///< value from floor area and cost per m²
};

struct ConsequenceTotals {
  std::string timeOfDay;         ///< "night", "day", "commute"
  PopulationFigures population;  ///< written as "population" when given
  LossTotals city;
  struct District {
    std::string name;
    LossTotals totals;
    /// Its boundary for maps: the outer ring of each of its polygons, (lon, lat) degrees, simplified
    /// to a few metres; empty when the file keeps none (files before it).
    std::vector<std::vector<std::array<double, 2>>> outline;
  };
  std::vector<District> districts;
  /// What the districts are ("OpenStreetMap boundary=administrative admin_level=10 areas", "a
  /// districts file given to the response (--districts)"), and whether they are inferred (each
  /// building to its nearest place name, no drawn boundary); empty without districts and in files
  /// written before it.
  std::string districtsSource;
  bool districtsInferred = false;
  /// The city by HAZUS occupancy class and by the modelled structural type (buildings whose type is
  /// a mixture count under the type modelled for their motion), the classes in code order; empty
  /// in files written before them.
  std::vector<ClassTotals> byOccupancy, byStructure;
  std::optional<InferredCounts> inferred;  ///< absent in files written before it
};

/// {"format": "quakeview-consequences", "version": 1, "timeOfDay": ..., "interval": ..., ["population":
/// {"night": N, "day": N, "source": "..."} (members given only),] "city":
/// {totals}, "districts": [{"name": ..., totals[, "outline": [[[lon, lat], ...], ...]]}, ...],
/// ["districts_source": "...", "districts_inferred": false,] ["by_occupancy":
/// [{"class": "RES3", class totals}, ...], "by_structure": [{"type": "C1", class totals}, ...], "inferred":
/// {"buildings", "structural_type", "code_era", "use", "occupants", "replacement_value"}]} with totals as
/// writeLossTotals writes them and class totals {"buildings", "damage_states": {"none" .. "complete"},
/// "moderate_or_worse", "collapsed", "repair_cost_usd", "occupants", "injuries": {"severity_1" ..
/// "severity_4"}} (expected values, plain numbers).
std::string consequencesToJson(const ConsequenceTotals& totals);
/// Errors name `name` and the member at fault. Limits: 10 000 districts; per district outline 1,000
/// rings and 20,000 points, each ring of at least 3 points within [-180, 180] x [-90, 90].
Result<ConsequenceTotals> parseConsequences(std::string_view json, const std::string& name);

/// The members of one totals object: "buildings", "damage_states" ({"none": {"expected", "low",
/// "high"}, ... "complete"}), "moderate_or_worse" (buildings with moderate damage or worse; optional
/// when read: files before it give the states' sum with NaN bounds), "collapsed", "occupants" (at the run's time of
/// day), "occupants_by_time" ({"night", "day", "commute"}: people present at each; optional when read), "injuries"
/// ({"severity_1" .. "severity_4"}), "deaths" (= severity 4), "repair_cost_usd", "tags" ({"green", "yellow", "red"}).
/// Every estimate is
/// {"expected", "low", "high"}: the expected value and the 5th and 95th percentiles.
void writeLossTotals(JsonWriter& w, const LossTotals& totals);

}  // namespace qv::seismic
