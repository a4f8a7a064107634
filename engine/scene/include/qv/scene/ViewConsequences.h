// The consequences of the buildings in view: sums of the HAZUS losses the response summary stores
// per building (section LOSS), with a 90 % interval by a normal approximation.
//
// Method: buildings are independent (as in the city totals of `quakeview-prep response`). A count
// (buildings in a damage state, collapsed, with a tag) is a sum of Bernoulli indicators, variance
// Σ p (1 − p); repair cost and injuries add the per-building variances the summary stores
// (BuildingLoss::repairCostStdUsd, injuriesStd: exact for the tool's model). The interval is the
// expected value ± 1.645 standard deviations, clipped at zero and at the number of buildings for
// counts. The city's and districts' totals in consequences.json are Monte Carlo percentiles instead
// (docs/losses.md); the two agree closely for many buildings and differ for a few very skewed ones.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "qv/format/ResponseTile.h"
#include "qv/format/Tileset.h"
#include "qv/seismic/ConsequencesFile.h"
#include "qv/seismic/Loss.h"

namespace qv {

class ConsequenceSums {
 public:
  void clear() { *this = ConsequenceSums{}; }
  /// Adds one building with a result and probabilities.
  void add(const BuildingLoss& loss);
  [[nodiscard]] std::uint64_t buildings() const { return buildings_; }
  /// Expected values and 90 % intervals (occupants: the exact sum, no interval).
  [[nodiscard]] seismic::LossTotals totals() const;

 private:
  struct Sum {
    double mean = 0.0, variance = 0.0;
    void add(double m, double v) {
      mean += m;
      variance += v;
    }
  };
  std::uint64_t buildings_ = 0;
  std::array<Sum, 5> states_{};
  Sum collapsed_, damaged_, cost_;
  std::array<Sum, 4> injuries_{};
  std::array<Sum, 3> tags_{};
  double occupants_ = 0.0;
};

/// The ground a view's totals cover: the box around the footprint centres of the buildings they
/// count, in degrees (Viewer::viewArea).
struct ViewArea {
  double west = 0.0, south = 0.0, east = 0.0, north = 0.0;
};
/// "lon -74.01230..-73.98110, lat 40.70120..40.72510" (5 decimals: about a metre).
std::string viewAreaText(const ViewArea& area);

/// `quakeview.consequences()` JSON: {eventType ("SCENARIO", "ACTUAL" or null), shakingField,
/// shakemap ({eventId, version, processTimestamp, eventTimestamp, description} or null), timeOfDay,
/// city, view (totals with `bounds` {west, south, east, north}, the degrees around the buildings
/// counted, null when none is in view; or null), districts: [{name, ...totals}], districtsSource (what
/// the districts are, null for files before it), districtsInferred}, totals being {buildings,
/// damageStates: {none, slight, moderate, extensive, complete}, collapsed, occupants, injuries:
/// {severity1 .. severity4}, deaths, repairCostUsd, tags: {green, yellow, red}}, every estimate
/// {expected, low, high}. "null" without a response.
std::string consequencesJson(const ResponseInfo* response, const seismic::ConsequenceTotals* file,
                             const seismic::LossTotals* view, const ViewArea* viewArea = nullptr);

}  // namespace qv
