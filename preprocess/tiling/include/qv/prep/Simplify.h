// Coarse outlines for the inner (far-view) tiles: one simple ring per building.
#pragma once

#include <span>
#include <vector>

#include <glm/vec2.hpp>

namespace qv::prep {

/// Douglas–Peucker simplification of a closed ring (first point not repeated) with the given
/// tolerance in metres. Returns at least 3 points when the ring has them; may self-intersect for
/// large tolerances (callers check, see coarseOutline).
std::vector<glm::dvec2> simplifyRing(std::span<const glm::dvec2> ring, double toleranceM);

/// The minimum-area rectangle enclosing the points (rotating calipers on the convex hull),
/// counter-clockwise. Empty for fewer than 3 non-collinear points.
std::vector<glm::dvec2> orientedBoundingRectangle(std::span<const glm::dvec2> points);

/// A counter-clockwise simple ring that stands for the footprint at `toleranceM`: the simplified
/// outer ring when it keeps its shape, else the oriented bounding rectangle. `errorM` receives how
/// far the result may be from the original (the larger of the tolerance and the rectangle's
/// excess).
std::vector<glm::dvec2> coarseOutline(std::span<const glm::dvec2> outerRing, double toleranceM, double& errorM);

/// Signed area (positive counter-clockwise).
double signedArea(std::span<const glm::dvec2> ring);

/// True when no two non-adjacent edges of the closed ring intersect.
bool isSimpleRing(std::span<const glm::dvec2> ring);

}  // namespace qv::prep
