#include "qv/spatial/BoxTree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace qv {
namespace {

// Interleaves the low 16 bits of x and y (Morton / Z-order).
std::uint32_t morton(std::uint32_t x, std::uint32_t y) {
  auto spread = [](std::uint32_t v) {
    v &= 0xFFFFu;
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    v = (v | (v << 1)) & 0x55555555u;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}

float diagonal(const Box& b) {
  return std::hypot(b.maxX - b.minX, b.maxY - b.minY, b.maxZ - b.minZ);
}

// Distances from `p` to the nearest point of `b` (0 inside) and to its farthest corner.
float nearestDistance(const glm::vec3& p, const Box& b) {
  return std::hypot(std::max({b.minX - p.x, 0.0f, p.x - b.maxX}), std::max({b.minY - p.y, 0.0f, p.y - b.maxY}),
                    std::max({b.minZ - p.z, 0.0f, p.z - b.maxZ}));
}
float farthestDistance(const glm::vec3& p, const Box& b) {
  return std::hypot(std::max(p.x - b.minX, b.maxX - p.x), std::max(p.y - b.minY, b.maxY - p.y),
                    std::max(p.z - b.minZ, b.maxZ - p.z));
}

}  // namespace

std::optional<float> rayBoxEntry(const glm::vec3& o, const glm::vec3& inv, const Box& b, float maxT) {
  float t0 = 0.0f, t1 = maxT;
  const float mins[3] = {b.minX, b.minY, b.minZ};
  const float maxs[3] = {b.maxX, b.maxY, b.maxZ};
  for (int axis = 0; axis < 3; ++axis) {
    float near = (mins[axis] - o[axis]) * inv[axis];
    float far = (maxs[axis] - o[axis]) * inv[axis];
    if (std::isnan(near) || std::isnan(far)) {
      // The ray is parallel to this slab and starts on its boundary plane: inside iff within.
      if (o[axis] < mins[axis] || o[axis] > maxs[axis]) return std::nullopt;
      continue;
    }
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
    if (t0 > t1) return std::nullopt;
  }
  return t0;
}

void BoxTree::build(std::span<const Box> boxes, std::uint32_t leafSize) {
  nodes_.clear();
  order_.clear();
  sorted_.clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  if (n == 0) return;
  Box all;
  for (const Box& b : boxes) all.expand(b);
  const float sx = all.maxX > all.minX ? 65535.0f / (all.maxX - all.minX) : 0.0f;
  const float sy = all.maxY > all.minY ? 65535.0f / (all.maxY - all.minY) : 0.0f;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const float cx = 0.5f * (boxes[i].minX + boxes[i].maxX);
    const float cy = 0.5f * (boxes[i].minY + boxes[i].maxY);
    const auto qx = static_cast<std::uint32_t>(std::clamp((cx - all.minX) * sx, 0.0f, 65535.0f));
    const auto qy = static_cast<std::uint32_t>(std::clamp((cy - all.minY) * sy, 0.0f, 65535.0f));
    keyed[i] = {morton(qx, qy), i};
  }
  std::sort(keyed.begin(), keyed.end());
  order_.resize(n);
  sorted_.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    order_[p] = keyed[p].second;
    sorted_[p] = boxes[keyed[p].second];
  }
  nodes_.reserve(2 * (n / std::max(1u, leafSize)) + 2);
  buildNode(0, n, std::max(1u, leafSize));
}

std::uint32_t BoxTree::buildNode(std::uint32_t begin, std::uint32_t end, std::uint32_t leafSize) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back(Node{Box{}, begin, end, 0, 0});
  if (end - begin <= leafSize) {
    Box box;
    float minDiagonal = std::numeric_limits<float>::max(), maxDiagonal = 0.0f;
    for (std::uint32_t p = begin; p < end; ++p) {
      box.expand(sorted_[p]);
      minDiagonal = std::min(minDiagonal, diagonal(sorted_[p]));
      maxDiagonal = std::max(maxDiagonal, diagonal(sorted_[p]));
    }
    nodes_[index].box = box;
    nodes_[index].minDiagonal = minDiagonal;
    nodes_[index].maxDiagonal = maxDiagonal;
    return index;
  }
  // Split the Morton range in the middle: children are adjacent ranges, so nodes stay contiguous.
  const std::uint32_t mid = begin + (end - begin) / 2;
  const std::uint32_t left = buildNode(begin, mid, leafSize);
  const std::uint32_t right = buildNode(mid, end, leafSize);
  Box box = nodes_[left].box;
  box.expand(nodes_[right].box);
  nodes_[index].box = box;
  nodes_[index].left = left;
  nodes_[index].right = right;
  nodes_[index].minDiagonal = std::min(nodes_[left].minDiagonal, nodes_[right].minDiagonal);
  nodes_[index].maxDiagonal = std::max(nodes_[left].maxDiagonal, nodes_[right].maxDiagonal);
  return index;
}

void BoxTree::emit(std::vector<IndexRange>& out, std::uint32_t begin, std::uint32_t end, bool inside) const {
  if (!out.empty() && out.back().end == begin && out.back().inside == inside) {
    out.back().end = end;
  } else {
    out.push_back(IndexRange{begin, end, inside});
  }
}

void BoxTree::query(const Frustum& frustum, std::vector<IndexRange>& out, const SizeCull& size) const {
  if (nodes_.empty()) return;
  // Each entry carries the planes its box still straddles (a plane a node lies wholly inside is
  // not tested again below it) and whether some of its boxes may be too small on screen.
  struct Entry {
    std::uint32_t node;
    unsigned mask;
    bool sizes;
  };
  Entry stack[64];
  int top = 0;
  stack[top++] = {0, 0x3fu, size.minAngle > 0.0f};
  const auto bigEnough = [&size](const Box& b) { return diagonal(b) >= size.minAngle * nearestDistance(size.eye, b); };
  while (top > 0) {
    const auto [index, parentMask, parentSizes] = stack[--top];
    const Node& node = nodes_[index];
    unsigned mask = parentMask;
    const Containment c = mask == 0 ? Containment::Inside : frustum.classify(node.box, mask);
    if (c == Containment::Outside) continue;
    bool sizes = parentSizes;
    if (sizes) {
      // Every box here is at least as far as the node's box and no larger than its largest.
      if (node.maxDiagonal < size.minAngle * nearestDistance(size.eye, node.box)) continue;
      sizes = node.minDiagonal < size.minAngle * farthestDistance(size.eye, node.box);
    }
    if (c == Containment::Inside && !sizes) {
      emit(out, node.begin, node.end, true);
      continue;
    }
    if (c == Containment::Inside) mask = 0;
    if (node.left == 0) {
      for (std::uint32_t p = node.begin; p < node.end; ++p) {
        unsigned m = mask;
        const Containment pc = m == 0 ? Containment::Inside : frustum.classify(sorted_[p], m);
        if (pc == Containment::Outside || (sizes && !bigEnough(sorted_[p]))) continue;
        emit(out, p, p + 1, pc == Containment::Inside);
      }
      continue;
    }
    // Right first so the left (lower positions) pops first and ranges come out in order.
    stack[top++] = {node.right, mask, sizes};
    stack[top++] = {node.left, mask, sizes};
  }
}

std::uint32_t BoxTree::countVisible(const Frustum& frustum) const {
  std::vector<IndexRange> ranges;
  query(frustum, ranges);
  std::uint32_t n = 0;
  for (const IndexRange& r : ranges) n += r.end - r.begin;
  return n;
}

void BoxTree::raycast(const glm::vec3& origin, const glm::vec3& direction, float maxT,
                      std::vector<std::pair<float, std::uint32_t>>& hits) const {
  if (nodes_.empty()) return;
  const glm::vec3 inv(1.0f / direction.x, 1.0f / direction.y, 1.0f / direction.z);
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  const std::size_t first = hits.size();
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!rayBoxEntry(origin, inv, node.box, maxT)) continue;
    if (node.left == 0) {
      for (std::uint32_t p = node.begin; p < node.end; ++p) {
        if (const auto t = rayBoxEntry(origin, inv, sorted_[p], maxT)) hits.emplace_back(*t, p);
      }
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = node.left;
  }
  std::sort(hits.begin() + static_cast<std::ptrdiff_t>(first), hits.end());
}

}  // namespace qv
