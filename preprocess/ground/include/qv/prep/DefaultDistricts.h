// The districts a city's consequences are totalled by when `quakeview-prep response` is given no
// --districts (docs/losses.md "Districts by default"): chosen by `city` and `synth-city` from the
// city's own input and written beside its tiles as districts.geojson (the format --districts
// reads), with what they came from in the manifest (qv/format/Tileset.h DistrictsInfo).
//
// 1. Boundaries drawn by the input (administrative areas, places' areas; GroundBoundary): of the
//    sets that divide the city into at least two districts and hold at least 90 % of its
//    buildings, the finest (largest fineness). Not inferred.
// 2. Otherwise the input's named places (neighbourhoods, suburbs, quarters; towns and villages
//    when there are fewer than two of those): each building to its nearest place name, the
//    districts being the places' Voronoi cells over the city. Inferred, and marked so.
// 3. Otherwise none (the shared Manhattan file has buildings only).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/format/Tileset.h"
#include "qv/geometry/GeoFrame.h"
#include "qv/prep/GroundFeatures.h"

namespace qv::prep {

struct DefaultDistricts {
  struct District {
    std::string name;
    /// Polygons, each its outer ring then holes; city frame, metres.
    std::vector<std::vector<std::vector<glm::dvec2>>> polygons;
    std::uint64_t buildings = 0;  ///< buildings whose centre is in it (the first district that holds it)
  };
  std::vector<District> districts;  ///< each with at least one building, ordered by name
  std::string source;               ///< what they were made from (DistrictsInfo::source)
  bool inferred = false;            ///< nearest place names, not drawn boundaries
  double coverage = 0.0;            ///< share of the buildings inside a district
};

/// The districts of a city whose buildings have the centres `buildings` (city frame) from its
/// input's boundaries and places, or nullopt when the input offers none that divide the city.
/// `origin` names the input in the source text ("OpenStreetMap", "synth-city"). Deterministic.
std::optional<DefaultDistricts> chooseDistricts(const GroundFeatures& ground, std::span<const glm::dvec2> buildings,
                                                const std::string& origin);

/// The districts as a GeoJSON FeatureCollection of MultiPolygons in WGS84 degrees (7 decimals),
/// each feature's properties {"name", "buildings"}, as `response --districts` reads it.
std::string districtsGeoJson(const DefaultDistricts& districts, const GeoFrame& frame);

}  // namespace qv::prep
