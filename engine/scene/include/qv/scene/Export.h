// Exports of a building list (the filtered list of the control panel) for spreadsheets and GIS.
#pragma once

#include <span>
#include <string>

#include "qv/geometry/GeoFrame.h"
#include "qv/scene/CityScene.h"

namespace qv {

/// RFC 4180 CSV with a header row: id, name, address, use, importance, damage_state,
/// peak_drift_ratio, peak_roof_displacement_m, pga_g, height_m, storeys, lon, lat, x_m, y_m.
/// Safe to open in a spreadsheet: a text field that begins with =, +, -, @, a tab or a carriage
/// return is written as a quoted field with a leading apostrophe ("'=SUM(A1)"), so no formula
/// runs; numeric columns are plain numbers (negative ones too). Invalid UTF-8 becomes U+FFFD.
std::string exportCsv(std::span<const BuildingListEntry> buildings, const GeoFrame& geo);

/// A GeoJSON FeatureCollection of Points (WGS84 lon/lat at each building's centroid) with the
/// same fields as properties. Strings are valid UTF-8 (invalid bytes become U+FFFD) and kept
/// otherwise as they are: a GIS shows them as text.
std::string exportGeoJson(std::span<const BuildingListEntry> buildings, const GeoFrame& geo);

}  // namespace qv
