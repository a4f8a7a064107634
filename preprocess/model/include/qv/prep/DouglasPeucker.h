// Douglas–Peucker simplification of a polyline's points, shared by the footprints' coarse
// outlines (prep::tiling, Simplify.cpp) and the map's lines and rings (prep::ground).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

namespace qv::prep {

/// Squared distance from p to the segment ab (no square root in the simplification's inner loop).
inline double squaredDistanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double len2 = ab.x * ab.x + ab.y * ab.y;
  double t = len2 > 0.0 ? ((p.x - a.x) * ab.x + (p.y - a.y) * ab.y) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const glm::dvec2 q = a + ab * t;
  return (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y);
}

/// Sets keep[i] for the points of pts(first, last) that Douglas–Peucker keeps at tolerance `tol`
/// (metres); the ends are the caller's to keep. Iterative with an explicit stack: rings of a
/// million points must not recurse a million deep. `keep` has at least `last + 1` entries.
inline void douglasPeucker(std::span<const glm::dvec2> pts, std::size_t first, std::size_t last, double tol,
                           std::vector<bool>& keep) {
  std::vector<std::pair<std::size_t, std::size_t>> stack = {{first, last}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    double worst = -1.0;
    std::size_t index = a;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double d = squaredDistanceToSegment(pts[i], pts[a], pts[b]);
      if (d > worst) {
        worst = d;
        index = i;
      }
    }
    if (worst > tol * tol) {
      keep[index] = true;
      stack.emplace_back(a, index);
      stack.emplace_back(index, b);
    }
  }
}

}  // namespace qv::prep
