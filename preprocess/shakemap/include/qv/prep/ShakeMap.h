// prep::shakemap — reads a USGS ShakeMap `grid.xml` (ShakeMap 3.5 and 4) into a regular grid of
// ground-motion fields, and samples it bilinearly at any point inside the grid.
//
// Format (USGS ShakeMap 3.5 manual, "grid.xml"; ShakeMap 4 manual, "Products: grid.xml"):
//   <shakemap_grid event_id shakemap_version code_version process_timestamp shakemap_originator
//                  map_status shakemap_event_type="SCENARIO|ACTUAL">
//     <event event_id magnitude depth(km) lat lon event_timestamp event_network event_description/>
//     <grid_specification lon_min lat_min lon_max lat_max nominal_lon_spacing nominal_lat_spacing
//                         nlon nlat/>
//     <event_specific_uncertainty .../>            (ignored)
//     <grid_field index="1" name="LON" units="dd"/>  one per column, index 1-based
//     ...
//     <grid_data> one line per node, whitespace-separated numbers, one per grid_field </grid_data>
//   </shakemap_grid>
// Rows run longitude fastest (lon_min .. lon_max), from lat_max down to lat_min: node k sits at
// column k % nlon, row k / nlon, lon = lon_min + column * dlon, lat = lat_max - row * dlat, with
// dlon = (lon_max - lon_min) / (nlon - 1) and dlat likewise.
//
// Rules this reader applies:
//   - Columns are found by their grid_field name (case-insensitive, a namespace prefix on element
//     names is ignored), never by position: ShakeMap 3.5 writes LON LAT PGA PGV MMI PSA03 PSA10
//     PSA30 SVEL, ShakeMap 4 writes LON LAT MMI PGA PGV PSA03 PSA10 PSA30 SVEL. Fields other than
//     those (STDPGA, URAT, PSA06, ...) are ignored: their values must still be numbers, but may be
//     non-finite. LON, LAT and PGA are required; PGV, MMI, PSA03/10/30 and SVEL are optional.
//   - Units (case-insensitive): PGA and PSA* "pctg" or "%g" (percent of g, divided by 100) or "g";
//     PGV "cms" or "cm/s"; SVEL "ms" or "m/s"; MMI "intensity"; LON/LAT "dd", "deg" or "degrees".
//     An empty units attribute takes the field's ShakeMap default (PGA/PSA percent g, PGV cm/s,
//     SVEL m/s, MMI intensity, LON/LAT decimal degrees). Any other unit of a known field is an error.
//   - Stored values: float(value / 100) for percent g, float(value) otherwise.
//   - The lattice: nlon, nlat >= 2; lon_min < lon_max, lat_min < lat_max; a nominal spacing, when
//     given, must put the last node within half a cell of the declared maximum. Every row's LON and
//     LAT must equal its node's lattice position within 1e-4 degrees (files print 4 decimals), so
//     rows out of order are refused too. Known fields must be finite.
//   - Exactly nlon * nlat rows: fewer (truncated grids exist in the wild) or more is an error.
//   - <grid_data> holds only numbers and whitespace (no comments, CDATA or character references;
//     no ShakeMap writes them), in an ASCII-compatible encoding (UTF-8, ASCII, ISO-8859-1).
//     Numbers are read locale-independently (std::from_chars, or an exactly equivalent fast path
//     for plain decimals); a leading '+' is accepted. Blank lines are skipped.
//   - Security: any DOCTYPE (hence any entity declaration: "billion laughs", external entities) is
//     refused as soon as it starts; nothing external is ever fetched; element nesting is bounded by
//     ShakeMapLimits::maxDepth, input size by maxBytes, and nlon * nlat * fields by maxValues, which
//     is checked from the declared sizes before anything is allocated.
// Errors are returned, never thrown; each names the file and the line ("grid.xml:42: ...").
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"

namespace qv::prep {

/// shakemap_event_type: a planning scenario, a real event, or something else / absent.
enum class ShakeMapEventType { Scenario, Actual, Unknown };
/// "SCENARIO", "ACTUAL", "UNKNOWN".
std::string_view shakeMapEventTypeName(ShakeMapEventType type);

/// The event a ShakeMap describes. Strings are the file's text (empty when absent); numbers are NaN
/// when absent or not a number (the metadata is shown, never computed with).
struct ShakeMapEvent {
  std::string eventId;           ///< <shakemap_grid event_id>, else <event event_id>
  std::string shakemapVersion;   ///< shakemap_version (the map's revision number)
  std::string codeVersion;       ///< code_version (the ShakeMap software: "3.5.1586", "4.0.1")
  std::string processTimestamp;  ///< process_timestamp
  std::string originator;        ///< shakemap_originator (network code)
  std::string mapStatus;         ///< map_status ("RELEASED", "REVIEWED", ...)
  ShakeMapEventType type = ShakeMapEventType::Unknown;
  double magnitude = std::numeric_limits<double>::quiet_NaN();
  double depthKm = std::numeric_limits<double>::quiet_NaN();
  double latitudeDeg = std::numeric_limits<double>::quiet_NaN();   ///< epicentre
  double longitudeDeg = std::numeric_limits<double>::quiet_NaN();  ///< epicentre
  std::string eventTimestamp;                                      ///< event_timestamp (origin time as written)
  std::string network;                                             ///< event_network
  std::string description;                                         ///< event_description
};

/// Every field at one point, in normalised units; NaN for fields the file does not have.
struct ShakeMapSample {
  double pgaG = std::numeric_limits<double>::quiet_NaN();     ///< peak ground acceleration, g
  double pgvCmS = std::numeric_limits<double>::quiet_NaN();   ///< peak ground velocity, cm/s
  double mmi = std::numeric_limits<double>::quiet_NaN();      ///< modified Mercalli intensity
  double psa03G = std::numeric_limits<double>::quiet_NaN();   ///< 5 %-damped PSA at 0.3 s, g
  double psa10G = std::numeric_limits<double>::quiet_NaN();   ///< ... at 1.0 s, g
  double psa30G = std::numeric_limits<double>::quiet_NaN();   ///< ... at 3.0 s, g
  double vs30Mps = std::numeric_limits<double>::quiet_NaN();  ///< Vs30 (SVEL), m/s
};

/// A ShakeMap grid. Each field vector is empty when the file has no such field, else holds
/// lonCount * latCount values at index row * lonCount + column, row 0 at latMax (the file's order:
/// longitude fastest, rows from lat_max down).
struct ShakeMapGrid {
  ShakeMapEvent event;
  std::size_t lonCount = 0, latCount = 0;                         ///< nlon, nlat (>= 2)
  double lonMin = 0.0, lonMax = 0.0, latMin = 0.0, latMax = 0.0;  ///< degrees, node centres
  /// Degrees between nodes: (max - min) / (count - 1), the lattice the rows are checked against
  /// (the file's nominal spacing agrees with it within half a cell over the whole grid).
  double lonSpacing = 0.0, latSpacing = 0.0;
  std::vector<float> pga;    ///< g
  std::vector<float> pgv;    ///< cm/s
  std::vector<float> mmi;    ///< intensity
  std::vector<float> psa03;  ///< g
  std::vector<float> psa10;  ///< g
  std::vector<float> psa30;  ///< g
  std::vector<float> vs30;   ///< m/s (SVEL)

  /// PSA03, PSA10 and PSA30 are all present.
  [[nodiscard]] bool hasSpectra() const;
  /// "lon -76.03..-72.03, lat 39.03..42.07 (161 x 123 nodes)".
  [[nodiscard]] std::string describeExtent() const;
};

struct ShakeMapLimits {
  std::size_t maxValues = 50'000'000;  ///< nlon * nlat * number of grid_fields
  std::size_t maxBytes = 2ull << 30;   ///< size of the XML text
  int maxDepth = 16;                   ///< element nesting (a grid.xml has 2 levels)
};

/// Reads and parses the file at `path` (at most limits.maxBytes); errors name `path` and the line.
Result<ShakeMapGrid> readShakeMapGrid(const std::string& path, const ShakeMapLimits& limits = {});
/// Parses XML text; `name` (a file name) starts every error message.
Result<ShakeMapGrid> parseShakeMapGrid(std::string_view xml, std::string_view name, const ShakeMapLimits& limits = {});

/// Bilinear interpolation of every present field at (lon, lat) in degrees between the four nodes
/// around it; nullopt outside the grid's extent [lonMin, lonMax] x [latMin, latMax] (points on the
/// boundary are inside) or for non-finite coordinates. Fields absent from the file stay NaN.
std::optional<ShakeMapSample> sampleShakeMap(const ShakeMapGrid& grid, double longitudeDeg, double latitudeDeg);

}  // namespace qv::prep
