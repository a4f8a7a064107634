// The consequences of a response for people who decide: the totals of the HAZUS losses (expected
// values with 90 % intervals, engine/seismic Loss.h) for the city and for each district of a
// `--districts` GeoJSON file, written as `response-<n>/consequences.json` (docs/losses.md) and shown
// by `info --json` and the viewer.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "qv/core/JsonWriter.h"
#include "qv/core/Result.h"
#include "qv/format/ResponseTile.h"
#include "qv/seismic/Loss.h"

namespace qv::prep {

/// Named areas (polygons with holes, multipolygons) in WGS84 degrees.
struct Districts {
  using Ring = std::vector<std::array<double, 2>>;  ///< lon, lat; closed or not
  using Polygon = std::vector<Ring>;                ///< outer ring first, then holes
  std::vector<std::string> names;
  std::vector<std::vector<Polygon>> areas;  ///< per district, its polygons
  /// The first district containing (lon, lat) (even-odd rule over each polygon's rings), or -1.
  [[nodiscard]] int find(double longitudeDeg, double latitudeDeg) const;
};

/// A GeoJSON FeatureCollection of Polygon / MultiPolygon features, each with a string property
/// "name". Errors name the file and the feature (index and name). Limits: 64 MiB, 10 000 features,
/// 1 000 000 vertices.
Result<Districts> readDistricts(const std::string& path);
Result<Districts> parseDistricts(std::string_view json, const std::string& name);

struct ConsequenceTotals {
  std::string timeOfDay;  ///< "night", "day", "commute"
  seismic::LossTotals city;
  struct District {
    std::string name;
    seismic::LossTotals totals;
  };
  std::vector<District> districts;
};

/// {"timeOfDay": ..., "city": {totals}, "districts": [{"name": ..., totals}, ...]} with totals as
/// writeLossTotals writes them.
std::string consequencesToJson(const ConsequenceTotals& totals);
Result<ConsequenceTotals> parseConsequences(std::string_view json, const std::string& name);

/// The members of one totals object: "buildings", "damage_states" ({"none": {"expected", "low",
/// "high"}, ... "complete"}), "collapsed", "occupants", "injuries" ({"severity_1" .. "severity_4"}),
/// "deaths" (= severity 4), "repair_cost_usd", "tags" ({"green", "yellow", "red"}). Every estimate is
/// {"expected", "low", "high"}: the expected value and the 5th and 95th percentiles.
void writeLossTotals(JsonWriter& w, const seismic::LossTotals& totals);

/// A building's losses as the response summary stores them (section LOSS).
BuildingLoss toSummaryLoss(const seismic::BuildingLoss& loss);

}  // namespace qv::prep
