// Exports of a building list (the filtered list of the control panel) for spreadsheets and GIS.
#pragma once

#include <span>
#include <string>

#include "qv/geometry/GeoFrame.h"
#include "qv/scene/CityScene.h"

namespace qv {

/// RFC 4180 CSV with a header row: id, name, address, use, importance, damage_state,
/// peak_drift_ratio, peak_roof_displacement_m, pga_g, height_m, storeys, lon, lat, x_m, y_m.
std::string exportCsv(std::span<const BuildingListEntry> buildings, const GeoFrame& geo);

/// A GeoJSON FeatureCollection of Points (WGS84 lon/lat at each building's centroid) with the
/// same fields as properties.
std::string exportGeoJson(std::span<const BuildingListEntry> buildings, const GeoFrame& geo);

}  // namespace qv
