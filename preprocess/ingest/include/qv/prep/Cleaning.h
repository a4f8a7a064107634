// Footprint geometry cleaning and the planar helpers built on it (area, centroid, containment).
// Works on any polygon with holes in a metric plane (the city frame: metres east and north), in
// the layout of qv::prep::BuildingPart: all rings' points, outer ring first, then holes;
// ringEnds[i] is one past the last point of ring i.
//
// The rules (docs/attributes.md "Cleaning"): rings are closed implicitly (a repeated last point is
// dropped), duplicate vertices (closer than 1 mm) and collinear vertices (less than 1 mm off the
// line through their neighbours, spikes included) are removed, the outer ring is made
// counter-clockwise and holes clockwise. A polygon is dropped when its outer ring keeps fewer than
// 3 points, encloses less than 0.01 m² or is a sliver (mean width 2 × area / perimeter under
// 5 cm), spans more than 2 km, or when a ring crosses or touches itself or rings cross each other.
// Degenerate holes and holes outside the outer ring are removed and the polygon kept.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/prep/CityModel.h"

namespace qv::prep {

/// Drop reasons, the keys of CityModel::drops (docs/attributes.md lists them all).
namespace drop {
inline constexpr std::string_view kTooFewPoints = "too-few-points";
inline constexpr std::string_view kZeroArea = "zero-area";
inline constexpr std::string_view kTooLarge = "too-large";
inline constexpr std::string_view kSelfIntersecting = "self-intersecting";
inline constexpr std::string_view kInvalidCoordinates = "invalid-coordinates";
/// Ring-level: a hole removed from a kept polygon.
inline constexpr std::string_view kHoleOutsideOuter = "hole-outside-outer";
inline constexpr std::string_view kDegenerateHole = "degenerate-hole";
}  // namespace drop

/// Tolerances of cleanPolygon (the defaults are the documented rules).
struct CleanOptions {
  double duplicateToleranceM = 0.001;  ///< vertices closer than this are one vertex
  double collinearToleranceM = 0.001;  ///< a vertex this close to its neighbours' line is removed
  double minAreaM2 = 0.01;             ///< smaller outer rings are "zero-area"
  double minMeanWidthM = 0.05;         ///< so are slivers: 2 x area / perimeter below this
  double maxExtentM = 2000.0;          ///< larger width or depth is "too-large"
};

/// Cleans one polygon with holes in place (see the file comment). Returns the drop reason (one of
/// drop::k*) when the polygon must be dropped, with points/ringEnds then unspecified, or an empty
/// string when it is kept, cleaned. Holes removed from a kept polygon are counted in `ringDrops`
/// (when not null) under kHoleOutsideOuter or kDegenerateHole.
std::string cleanPolygon(std::vector<glm::dvec2>& points, std::vector<std::uint32_t>& ringEnds,
                         DropCounts* ringDrops = nullptr, const CleanOptions& options = {});

/// Signed area of one ring (positive when counter-clockwise), square metres; the ring's last point
/// need not repeat the first.
double signedRingArea(const glm::dvec2* points, std::size_t count);

/// Area of a cleaned polygon: outer area minus holes, square metres (>= 0).
double polygonArea(const std::vector<glm::dvec2>& points, const std::vector<std::uint32_t>& ringEnds);

/// Area-weighted centroid of a cleaned polygon with holes (may lie outside a concave polygon).
glm::dvec2 polygonCentroid(const std::vector<glm::dvec2>& points, const std::vector<std::uint32_t>& ringEnds);

/// True when p lies inside the polygon (inside the outer ring and outside every hole), by the
/// even-odd rule over all rings; a point on an edge may count either way.
bool pointInPolygon(glm::dvec2 p, const std::vector<glm::dvec2>& points, const std::vector<std::uint32_t>& ringEnds);

/// A point strictly inside the polygon (a "point on surface": the middle of the widest interior
/// span of the horizontal line through the middle of the outer ring's bounds), or nullopt for a
/// degenerate polygon. Unlike the centroid it is inside L- and U-shaped footprints too.
std::optional<glm::dvec2> interiorPoint(const std::vector<glm::dvec2>& points,
                                        const std::vector<std::uint32_t>& ringEnds);

}  // namespace qv::prep
