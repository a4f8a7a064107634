// Polygon geometry of the LOD2 importer, on CGAL: triangulation of planar faces with holes (a
// constrained Delaunay triangulation in the face's plane, rather than a hand-written ear clipper),
// the ground footprint of a mesh (the union of its triangles' projections) and footprint overlaps
// for matching. CGAL's exceptions never leave these functions.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// Triangulates one planar (or nearly planar) polygon with holes in 3D: `points` split into rings
/// by `ringEnds` (ring i = [ringEnds[i-1] or 0, ringEnds[i])), outer ring first, holes after, as in
/// CityJSON (outer ring counter-clockwise seen from the side the face looks at). The polygon is
/// projected onto the plane of its outer ring (Newell normal) and triangulated there; the triangles,
/// index triples into `points`, keep the outer ring's orientation and use no new points. Appends to
/// `out` and returns true; returns false (out unchanged) for a degenerate face (no area) or rings
/// that cross each other after projection.
bool triangulateFace(std::span<const glm::dvec3> points, std::span<const std::uint32_t> ringEnds,
                     std::vector<std::uint32_t>& out);

/// Newell's normal of a ring (length = twice the ring's area; zero for a degenerate ring).
glm::dvec3 newellNormal(std::span<const glm::dvec3> ring);

/// The outer ring (counter-clockwise, first point not repeated, cleaned of collinear points) of the
/// largest piece of the union of all triangles projected to the ground plane. Empty when the mesh
/// has no triangle with a projected area. Falls back to the convex hull of the vertices when the
/// union cannot be computed.
std::vector<glm::dvec2> groundFootprint(const Lod2Mesh& mesh);

/// The outer ring of the largest piece of the union of simple rings (any orientation), as above.
std::vector<glm::dvec2> unionOuterRing(const std::vector<std::vector<glm::dvec2>>& rings);

/// Area of the intersection of two simple rings (any orientation), square metres; 0 when either is
/// not simple.
double intersectionAreaM2(const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b);

/// Convex hull (counter-clockwise, Andrew's monotone chain) of points; fewer than 3 points when
/// they are all collinear.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> points);

}  // namespace qv::prep
