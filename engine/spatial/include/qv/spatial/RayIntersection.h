// Exact ray intersection with building shapes, for picking once BoxTree::raycast has narrowed the
// candidates to a few boxes: an extruded footprint (LOD1) and a triangle soup (LOD2 models).
// Coordinates in any one frame (the viewer uses the city frame: metres, z up); the direction
// need not be normalized and every t is in its units. Allocates nothing.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include <glm/vec3.hpp>

namespace qv {

/// An extruded polygon with holes between two heights, over caller-owned arrays (not copied).
struct PrismView {
  const float* xy = nullptr;                  ///< interleaved x, y of all rings' points, ring after ring
  const std::uint16_t* ringCounts = nullptr;  ///< points of each ring (outer and holes, any order)
  std::uint32_t ringCount = 0;
  float offsetX = 0.0f, offsetY = 0.0f;  ///< added to every point
  float minZ = 0.0f, maxZ = 0.0f;        ///< floor and roof heights
};

/// Where the ray `origin + t * direction` first meets the prism (roof, floor or a wall, inside
/// decided even-odd over all rings), as t >= 0, or nullopt when it misses.
std::optional<float> rayPrism(const float origin[3], const float direction[3], const PrismView& prism);

/// Where the ray first meets a triangle of `positions` (each + `offset`), either side, as t >= 0,
/// or nullopt. `triangles` holds 3 indices per triangle; a triangle with an index out of range is
/// skipped, and a trailing incomplete triangle is ignored. Index: std::uint16_t or std::uint32_t.
template <typename Index>
std::optional<float> rayTriangles(const float origin[3], const float direction[3], std::span<const glm::vec3> positions,
                                  std::span<const Index> triangles, const glm::vec3& offset);

}  // namespace qv
