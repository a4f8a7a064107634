// Point in polygon by the even-odd rule, for any ring of points p with p[0] = x and p[1] = y
// (glm::dvec2, std::array<double, 2>): the districts a building falls in (response) and the ones
// a city's input offers (chooseDistricts).
#pragma once

#include <cstddef>

namespace qv::prep {

/// Whether (x, y) is inside `ring` (closed implicitly or explicitly, any orientation). Over a
/// polygon's rings (outer, then holes), inside is the exclusive or of the rings' answers.
template <typename Ring>
bool insideRing(const Ring& ring, double x, double y) {
  bool inside = false;
  if (ring.size() < 3) return false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const double xi = ring[i][0], yi = ring[i][1], xj = ring[j][0], yj = ring[j][1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

}  // namespace qv::prep
