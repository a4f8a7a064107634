// Exports of a building list (the filtered list of the control panel) for spreadsheets and GIS.
#pragma once

#include <span>
#include <string>

#include "qv/geometry/GeoFrame.h"
#include "qv/scene/CityScene.h"
#include "qv/seismic/ConsequencesFile.h"

namespace qv {

/// RFC 4180 CSV with a header row: id, name, address, use, importance, damage_state,
/// peak_drift_ratio, peak_roof_displacement_m, pga_g, height_m, storeys, lon, lat, x_m, y_m, then the
/// HAZUS columns (blank for a building without probabilities): p_none … p_complete, p_collapse,
/// expected_damage_state, p_tag_green, p_tag_yellow, p_tag_red, occupants, occupants_inferred (1/0),
/// injuries_1 … injuries_3, deaths, repair_cost_usd, replacement_value_usd, value_inferred (1/0),
/// repair_time_days.
/// Safe to open in a spreadsheet: a text field that begins with =, +, -, @, a tab or a carriage
/// return is written as a quoted field with a leading apostrophe ("'=SUM(A1)"), so no formula
/// runs; numeric columns are plain numbers (negative ones too). Invalid UTF-8 becomes U+FFFD.
std::string exportCsv(std::span<const BuildingListEntry> buildings, const GeoFrame& geo);

/// A GeoJSON FeatureCollection of Points (WGS84 lon/lat at each building's centroid) with the
/// same fields as properties. Strings are valid UTF-8 (invalid bytes become U+FFFD) and kept
/// otherwise as they are: a GIS shows them as text.
std::string exportGeoJson(std::span<const BuildingListEntry> buildings, const GeoFrame& geo);

/// The consequence totals as CSV, one row per area: the city, then the view when given, then each
/// district; columns area_kind ("city", "view", "district"), area (the district's name), buildings,
/// time_of_day, then for each quantity its expected value and the 5th
/// and 95th percentiles (`_low`, `_high`): none, slight, moderate, extensive, complete (expected
/// building counts), collapsed, tag_green, tag_yellow, tag_red, occupants, injuries_1 .. injuries_3,
/// deaths, repair_cost_usd. Text fields are made safe as in exportCsv.
std::string exportConsequencesCsv(const seismic::ConsequenceTotals& totals, const seismic::LossTotals* view);

}  // namespace qv
