// Districts for the consequence totals of `quakeview-prep response --districts` (the totals' file
// is engine/seismic ConsequencesFile.h), and a building's losses as the summary stores them.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/ResponseTile.h"
#include "qv/seismic/ConsequencesFile.h"
#include "qv/seismic/Loss.h"

namespace qv::prep {

/// Named areas (polygons with holes, multipolygons) in WGS84 degrees.
struct Districts {
  using Ring = std::vector<std::array<double, 2>>;  ///< lon, lat; closed or not
  using Polygon = std::vector<Ring>;                ///< outer ring first, then holes
  std::vector<std::string> names;
  std::vector<std::vector<Polygon>> areas;  ///< per district, its polygons
  /// Per district and polygon, its outer ring's box {minLon, minLat, maxLon, maxLat} (parseDistricts
  /// fills it; find skips the polygons whose box leaves the point out). May be empty.
  std::vector<std::vector<std::array<double, 4>>> boxes;
  /// The file's own top-level members (a city's districts.geojson has them; DefaultDistricts.h):
  /// what the districts were made from, whether they are inferred (nearest place names), and the
  /// name of a row for the buildings in none ("" : no such row).
  std::string source;
  bool inferred = false;
  std::string outsideName;
  /// The first district containing (lon, lat) (even-odd rule over each polygon's rings), or -1.
  [[nodiscard]] int find(double longitudeDeg, double latitudeDeg) const;
  /// District `d`'s outline for maps (ConsequenceTotals::District::outline): the outer ring of each
  /// polygon, simplified (Douglas-Peucker, prep/Simplify.h) to 5 m, more where that leaves over
  /// 20,000 points in all; rings that vanish are left out.
  [[nodiscard]] std::vector<std::vector<std::array<double, 2>>> outline(std::size_t d) const;
};

/// A GeoJSON FeatureCollection of Polygon / MultiPolygon features, each with a string property
/// "name", and optional top-level "source" (text), "inferred" (boolean) and "outside" (text: the
/// name of a row for the buildings in no district). Errors name the file and the feature (index and name). Limits: 64
/// MiB, 10 000 features, 1 000 000 vertices.
Result<Districts> readDistricts(const std::string& path);
Result<Districts> parseDistricts(std::string_view json, const std::string& name);

/// What the report's tables group a building by, and which of its attributes the model inferred.
struct LossClass {
  seismic::Occupancy occupancy = seismic::Occupancy::RES1;
  StructuralType type = StructuralType::Unknown;  ///< the modelled (resolved) type
  bool typeInferred = false, eraInferred = false, useInferred = false;

  static LossClass of(const seismic::Exposure& exposure);
};

/// The city's damage by occupancy class and by structural type (rows in code order, classes without
/// buildings left out) and the inferred-attribute counts, from each building's losses and class
/// (aligned spans), into `totals`.
void addClassTotals(std::span<const seismic::BuildingLoss> losses, std::span<const LossClass> classes,
                    seismic::ConsequenceTotals& totals);

/// A building's losses as the response summary stores them (section LOSS).
BuildingLoss toSummaryLoss(const seismic::BuildingLoss& loss);

}  // namespace qv::prep
