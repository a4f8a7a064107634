// City ingest: OpenStreetMap (.osm, .osm.bz2, .osm.gz, .osm.pbf through libosmium) and GeoJSON
// FeatureCollections (.geojson, .json through simdjson) to a CityModel of clean, projected
// buildings with storeys and seismic attributes. The rules (ids, OSM semantics, units, cleaning,
// inference) are in docs/attributes.md.
//
// Errors never escape as exceptions: libosmium, GeographicLib and file errors become a Result
// error naming the file and the position (XML line:column, PBF byte offset, JSON line:column,
// OSM object id).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/prep/CityModel.h"

namespace qv::prep {

struct IngestOptions {
  /// GeoJSON property names and the unit of plain height numbers. The defaults are OSM's keys, so
  /// `osmium export` output reads as-is; NYC's building footprints need
  /// heightProperty "heightroof", heightUnit "ft", yearProperty "cnstrct_yr".
  std::string idProperty = "id";  ///< fallback: feature.id, then the feature index: "g:<value or index>"
  std::string nameProperty = "name";
  std::string heightProperty = "height";
  std::string heightUnit = "m";  ///< "m" or "ft" (also "metres", "meters", "feet"): plain numbers only
  std::string levelsProperty = "building:levels";
  std::string minHeightProperty = "min_height";
  std::string yearProperty = "start_date";
  std::string useProperty = "building";
  /// People at peak occupancy and the replacement value (USD) where a GeoJSON gives them; the
  /// consequences infer both from floor area and use otherwise.
  std::string occupantsProperty = "occupants";
  std::string valueProperty = "replacement_value";
  /// Projection centre {lon, lat} in degrees; default: the centre of the data's bounds.
  std::optional<std::array<double, 2>> originLonLat;
  /// Worker threads for projection and cleaning (0: the machine's cores, at most 4).
  unsigned threads = 0;
  /// Read the map under the buildings from OSM inputs (streets, railways, water, parks, open land,
  /// coastline, place names: docs/attributes.md "Ground features") into CityModel::ground. Off:
  /// nothing of it is looked at or kept. GeoJSON inputs have no ground either way.
  bool ground = true;
};

/// What the readers saw, for the summary and the tests.
struct IngestStats {
  std::uint64_t osmNodes = 0;
  std::uint64_t osmWays = 0;                   ///< ways tagged building=* (not "no")
  std::uint64_t osmRelations = 0;              ///< multipolygon relations tagged building=* (not "no")
  std::uint64_t osmPartObjects = 0;            ///< building:part ways and multipolygons without building=*
  std::uint64_t osmTypeBuildingRelations = 0;  ///< type=building relations (groups, not buildings)
  std::uint64_t partsAttached = 0;             ///< parts that became geometry of a building
  std::uint64_t partsAttachedByRelation = 0;   ///< ... of them through a type=building relation
  std::uint64_t partsStandalone = 0;           ///< parts without a containing outline: own buildings
  std::uint64_t geojsonFeatures = 0;           ///< features in the GeoJSON inputs
  std::uint64_t buildings = 0;                 ///< buildings in the model
  std::uint64_t points = 0;            ///< distinct footprint vertices projected (a shared OSM node counts once)
  std::uint64_t groundLines = 0;       ///< streets, railways, paths and rivers in CityModel::ground
  std::uint64_t groundAreas = 0;       ///< water, parks, forest and open land (one per outer ring)
  std::uint64_t groundPlaces = 0;      ///< named places
  std::uint64_t groundCoastlines = 0;  ///< natural=coastline ways (or their pieces between missing nodes)
  std::uint64_t groundSkipped = 0;     ///< ground objects seen but not kept (CityModel::ground.skipped)
  double readSeconds = 0.0;            ///< parsing the inputs and assembling multipolygons
  double buildSeconds = 0.0;           ///< projection, cleaning, parts, attributes
};

/// Reads every input (format from the file name: .osm, .osm.bz2, .osm.gz, .osm.pbf, .pbf,
/// .geojson, .json), merges them (an id seen twice keeps its first building, the rest is counted
/// as "duplicate-id"), cleans, projects and infers attributes. Fails on an unreadable, truncated
/// or corrupt input, a building way or multipolygon member referencing missing nodes (with how
/// many and the first ids), coordinates that are not WGS84 degrees or span more than 10 degrees,
/// or when no building remains. `stats` may be null.
Result<CityModel> readCity(const std::vector<std::string>& inputPaths, const IngestOptions& options,
                           IngestStats* stats = nullptr);

}  // namespace qv::prep
