// Exports of a building list (the filtered list of the control panel) for spreadsheets and GIS.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "qv/geometry/GeoFrame.h"
#include "qv/scene/CityScene.h"
#include "qv/scene/ViewConsequences.h"
#include "qv/seismic/ConsequencesFile.h"

namespace qv {

/// Where an export's numbers came from. Every export carries it (docs/formats.md "Exports"): a
/// file forwarded by e-mail must still say whether its shaking is a scenario or an actual event.
struct ExportProvenance {
  std::string city;        ///< the city's name ("" when the manifest has none)
  std::string shaking;     ///< shakingStatement(): "SCENARIO (computed, not a recorded event)", ...
  std::string earthquake;  ///< the ShakeMap (id, version, description) or the scenario, or ""
  std::string records;     ///< the ground-motion record(s), "; "-separated
  std::string method;      ///< how responses were computed ("MDOF shear building, Bouc-Wen", "imported")
  std::string filter;      ///< the active filters as describeFilters() says them ("none" when inactive)
  std::string timeOfDay;   ///< the time of day the consequences assume, or ""
};

/// The provenance as one line, "QuakeView <title> | City: ... | Shaking: ... | Earthquake: ... |
/// Records: ... | Method: ... | Time of day: ... | Filter: ..." (empty parts left out; commas become
/// spaces): the comment line of the CSV exports without its "# ", and the report's footer.
std::string provenanceText(std::string_view title, const ExportProvenance& provenance);

/// Whether the shaking is a SCENARIO or an ACTUAL event, in the words the panel shows:
/// "ACTUAL EVENT (ShakeMap of a recorded earthquake)", "SCENARIO (a ShakeMap scenario, not a
/// recorded event)", "SCENARIO (computed, not a recorded event)", "IMPORTED RESULTS (not stated
/// whether a scenario or an actual event)" or "NOT STATED whether a scenario or an actual event".
std::string shakingStatement(const ResponseInfo& response);

/// The active filters as short phrases joined by " | " ("damage at least moderate | use: school or
/// hospital | critical facilities only (essential or school/shelter) | facility: high occupancy or
/// hazardous"), "none" when no filter is active. No commas (the CSV provenance line keeps it whole).
std::string describeFilters(const BuildingFilters& filters);

/// The provenance of exports from `tileset` (without a response: shaking "no response computed").
ExportProvenance exportProvenance(const Tileset& tileset, const BuildingFilters& filters);

/// Whether the city's sources include OpenStreetMap data (.osm, .pbf, .osm.bz2, or named so): its
/// pictures and reports then carry OpenStreetMap's attribution (ODbL).
bool fromOpenStreetMap(const Tileset& tileset);

/// The caption a picture of the view carries (quakeview.screenshot(), the panel's "Save image"), so
/// that an image forwarded alone still says what it shows: its lines, first the shaking statement
/// (SCENARIO or ACTUAL, as exportProvenance says it) with the earthquake; then the city, the time
/// shown and the filters; then the method, "patterns across a city, not a safety assessment" and
/// the map data's attribution (OpenStreetMap's where the city's sources are OSM files); and the
/// file name to save it under (exportFileName, "view", "png").
struct ImageCaption {
  bool actual = false;  ///< an ACTUAL event (its line is drawn in red, a scenario's in orange)
  std::vector<std::string> lines;
  std::string fileName;
};
ImageCaption imageCaption(const Tileset& tileset, const BuildingFilters& filters, double timeSeconds,
                          double durationSeconds);

/// A download's file name that says what it holds: "quakeview-<city>-<event>-<what>[-<filter>].<ext>",
/// each part lower-case ASCII letters, digits and '-' ("quakeview-midtown-actual-us7000abcd-buildings-
/// damage-moderate-use-school.csv"; several uses "use-hospital-school", the critical filter
/// "critical", categories "facility-essential-high-occupancy"); <event> is "scenario", "actual" (with the ShakeMap's
/// event id), "imported", "unstated" or "no-response". At most 150 characters before the extension.
std::string exportFileName(const Tileset& tileset, const BuildingFilters& filters, std::string_view what,
                           std::string_view extension);

/// RFC 4180 CSV, UTF-8 with a byte-order mark (so spreadsheets read names as UTF-8). With a
/// provenance, its first line is a comment, "# QuakeView building list | City: ... | Shaking: ...
/// | Earthquake: ... | Records: ... | Method: ... | Filter: ..." (commas in its values become
/// spaces so that it stays one cell wide per part; pandas: comment='#'). Then a header row: id, name, address, use,
/// importance, damage_state, peak_drift_ratio, peak_roof_displacement_m, pga_g, height_m, storeys, lon, lat, x_m, y_m,
/// then the HAZUS columns (blank for a building without probabilities): p_none … p_complete, p_collapse,
/// expected_damage_state, p_tag_green, p_tag_yellow, p_tag_red, occupants, occupants_inferred (1/0),
/// injuries_1 … injuries_3, deaths, repair_cost_usd, replacement_value_usd, value_inferred (1/0),
/// repair_time_days. A value that does not exist is a blank field, never a zero: a building without a
/// result has blank peak_drift_ratio, peak_roof_displacement_m and pga_g, a building without
/// storeys a blank storeys.
/// Safe to open in a spreadsheet: a text field that begins with =, +, -, @, a tab or a carriage
/// return is written as a quoted field with a leading apostrophe ("'=SUM(A1)"), so no formula
/// runs; numeric columns are plain numbers (negative ones too). Invalid UTF-8 becomes U+FFFD.
std::string exportCsv(std::span<const BuildingListEntry> buildings, const GeoFrame& geo,
                      const ExportProvenance* provenance = nullptr);

/// A GeoJSON FeatureCollection of Points (WGS84 lon/lat at each building's centroid) with the
/// same fields as properties (null where the CSV is blank) plus "facility" (facilityCategoryName).
/// In both formats "importance" is "critical" only for essential facilities, schools and shelters
/// (FacilityCategory; never for height or parts). Strings are valid UTF-8 (invalid bytes
/// become U+FFFD) and kept otherwise as they are: a GIS shows them as text. With a provenance, the
/// collection has a foreign member "quakeview" holding its fields (city, shaking, earthquake,
/// records, method, filter, time_of_day).
std::string exportGeoJson(std::span<const BuildingListEntry> buildings, const GeoFrame& geo,
                          const ExportProvenance* provenance = nullptr);

/// The consequence totals as CSV, one row per area: the city, then the view when given, then each
/// district; columns area_kind ("city", "view", "district"), area (the district's name), buildings,
/// time_of_day, then for each quantity its expected value and the 5th
/// and 95th percentiles (`_low`, `_high`): none, slight, moderate, extensive, complete (expected
/// building counts), collapsed, tag_green, tag_yellow, tag_red, occupants, injuries_1 .. injuries_3,
/// deaths, repair_cost_usd, then the view's ground: west, south, east, north (degrees around the
/// footprint centres of the buildings it counts; blank on the other rows and without `viewArea`),
/// the view row's `area` saying the same ("lon …..…, lat …..…", viewAreaText). Text fields are made
/// safe as in exportCsv; byte-order mark and provenance comment line as in exportCsv
/// ("# QuakeView consequences | ...").
std::string exportConsequencesCsv(const seismic::ConsequenceTotals& totals, const seismic::LossTotals* view,
                                  const ExportProvenance* provenance = nullptr, const ViewArea* viewArea = nullptr);

}  // namespace qv
