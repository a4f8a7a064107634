// The consequences file (`response-<n>/consequences.json`, docs/losses.md): the totals of a
// response's HAZUS losses for the city and for each district, written by `quakeview-prep response`
// and read by `info` and the viewer. One codec for writer and readers.
#pragma once

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

struct ConsequenceTotals {
  std::string timeOfDay;         ///< "night", "day", "commute"
  PopulationFigures population;  ///< written as "population" when given
  LossTotals city;
  struct District {
    std::string name;
    LossTotals totals;
  };
  std::vector<District> districts;
};

/// {"format": "quakeview-consequences", "version": 1, "timeOfDay": ..., "interval": ..., ["population":
/// {"night": N, "day": N, "source": "..."} (members given only),] "city":
/// {totals}, "districts": [{"name": ..., totals}, ...]} with totals as writeLossTotals writes them.
std::string consequencesToJson(const ConsequenceTotals& totals);
/// Errors name `name` and the member at fault. Limits: 10 000 districts.
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
