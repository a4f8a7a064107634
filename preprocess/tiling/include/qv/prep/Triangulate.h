// Roof triangulation of footprints with holes, with CGAL's constrained Delaunay triangulation
// (a library that handles holes, touching rings and degenerate input, rather than a hand-written
// ear clipper).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace qv::prep {

/// Triangulates the polygon given by `points` split into rings by `ringEnds` (outer ring first;
/// any winding). Appends triangles as index triples into `points`, counter-clockwise, covering
/// exactly the inside (even-odd nesting). Returns false (and leaves `out` unchanged) when CGAL
/// rejects the input, e.g. rings that cross each other.
/// `usedConstrained` (optional) tells whether the constrained triangulation ran: a convex single
/// ring is triangulated as a fan, in a fraction of the time.
bool triangulatePolygon(std::span<const glm::dvec2> points, std::span<const std::uint32_t> ringEnds,
                        std::vector<std::uint32_t>& out, bool* usedConstrained = nullptr);

}  // namespace qv::prep
