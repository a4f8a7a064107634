// BoxTree: a static bounding-volume hierarchy over the buildings of one tile, answering "which
// buildings does the frustum see" as contiguous ranges of a spatial (Morton) order, and "what does
// this ray hit first". Built once when a tile loads; queries allocate nothing but their output.
//
// The hierarchy is the quadtree of the tile's Morton order: every node covers a contiguous range
// of `order()`, so a visible node is a range, and a tile whose buildings are laid out in that
// order (the viewer does) can draw exactly the visible ranges.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "qv/geometry/Bounds.h"
#include "qv/geometry/Frustum.h"

namespace qv {

/// Positions [begin, end) in BoxTree::order(); `inside` when every box of it is fully in view.
struct IndexRange {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  bool inside = false;
};

/// Screen-size culling for BoxTree::query: a box whose diagonal, seen from `eye`, spans less than
/// `minAngle` radians (about a pixel: the vertical field of view over the viewport height) is
/// left out. minAngle 0: none is.
struct SizeCull {
  glm::vec3 eye{0.0f};
  float minAngle = 0.0f;
};

class BoxTree {
 public:
  /// Builds the tree over `boxes` (any count, including 0). Leaves hold up to `leafSize` boxes.
  void build(std::span<const Box> boxes, std::uint32_t leafSize = 8);

  /// Permutation: order()[position] is the index (into the boxes given to build) at that position.
  [[nodiscard]] const std::vector<std::uint32_t>& order() const { return order_; }
  [[nodiscard]] const Box& bounds() const { return nodes_.empty() ? empty_ : nodes_[0].box; }
  [[nodiscard]] std::size_t size() const { return order_.size(); }

  /// Appends the visible ranges (merged when adjacent), in order. Boxes touching the frustum count;
  /// boxes smaller on screen than `size` allows do not.
  void query(const Frustum& frustum, std::vector<IndexRange>& out, const SizeCull& size = {}) const;
  /// Number of boxes the frustum sees (the sum of query()'s ranges).
  [[nodiscard]] std::uint32_t countVisible(const Frustum& frustum) const;

  /// Positions (not box indices) whose boxes a ray enters within [0, maxT], nearest entry first.
  /// `direction` need not be normalized; t is in its units.
  void raycast(const glm::vec3& origin, const glm::vec3& direction, float maxT,
               std::vector<std::pair<float, std::uint32_t>>& hits) const;

 private:
  struct Node {
    Box box;
    std::uint32_t begin = 0, end = 0;              // positions
    std::uint32_t left = 0, right = 0;             // child node indices; 0 for a leaf (the root is never a child)
    float minDiagonal = 0.0f, maxDiagonal = 0.0f;  // of the boxes in [begin, end)
  };
  std::uint32_t buildNode(std::uint32_t begin, std::uint32_t end, std::uint32_t leafSize);
  void emit(std::vector<IndexRange>& out, std::uint32_t begin, std::uint32_t end, bool inside) const;

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;
  std::vector<Box> sorted_;  // boxes in order()
  Box empty_;
};

/// Ray / box slab test: the entry distance when the ray meets the box within [0, maxT].
std::optional<float> rayBoxEntry(const glm::vec3& origin, const glm::vec3& inverseDirection, const Box& box,
                                 float maxT);

}  // namespace qv
