// Re-meshing for storey deformation, in two exact steps (no point leaves the original surface):
//
// 1. Floor cuts. Each triangle is clipped to every storey band it spans (the slab between two
//    consecutive floor levels). A band piece of a triangle is convex; its corners are original
//    vertices or points where an original edge crosses a floor plane. Such a point is created once
//    per (edge, plane) and shared with the neighbouring triangle, so the cut mesh has no cracks.
// 2. Edge splits. Rounds of midpoint subdivision: every edge longer than the target is split at its
//    midpoint (decided per edge, so both triangles of an edge agree), each triangle replaced by 2,
//    3 or 4 according to how many of its edges are split. A midpoint lies within its edge's band,
//    so step 1's property holds throughout.
#include "qv/prep/Lod2Remesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace qv::prep {
namespace {

struct EdgePlaneKey {
  std::uint32_t a;  ///< the smaller vertex index
  std::uint32_t b;
  std::uint32_t plane;
  bool operator==(const EdgePlaneKey&) const = default;
};

struct EdgePlaneHash {
  std::size_t operator()(const EdgePlaneKey& k) const noexcept {
    std::uint64_t h = (static_cast<std::uint64_t>(k.a) << 32) | k.b;
    h ^= static_cast<std::uint64_t>(k.plane) * 0x9E3779B97F4A7C15ull;
    h ^= h >> 29;
    return static_cast<std::size_t>(h * 0xBF58476D1CE4E5B9ull);
  }
};

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

class FloorCutter {
 public:
  FloorCutter(const Lod2Mesh& mesh, const FloorLevels& floors, Lod2Mesh& out) : in_(mesh), out_(out) {
    for (int k = 0; k <= floors.storeys; ++k) planes_.push_back(floors.levelM(k));
  }

  void run() {
    out_.positions = in_.positions;
    for (std::size_t t = 0; t < in_.kinds.size(); ++t) cutTriangle(t);
  }

 private:
  [[nodiscard]] double z(std::uint32_t v) const { return out_.positions[v].z; }

  void emit(std::uint32_t a, std::uint32_t b, std::uint32_t c, SurfaceKind kind) {
    out_.triangles.insert(out_.triangles.end(), {a, b, c});
    out_.kinds.push_back(kind);
  }

  /// The point where edge (a, b) crosses plane p: computed from the smaller index to the larger one,
  /// so both triangles of the edge get the same vertex.
  std::uint32_t crossing(std::uint32_t a, std::uint32_t b, std::uint32_t plane) {
    if (a > b) std::swap(a, b);
    const auto [it, inserted] = crossings_.emplace(EdgePlaneKey{a, b, plane}, 0u);
    if (!inserted) return it->second;
    const glm::dvec3 pa = out_.positions[a];
    const glm::dvec3 pb = out_.positions[b];
    const double level = planes_[plane];
    const double s = (level - pa.z) / (pb.z - pa.z);
    glm::dvec3 p = pa + s * (pb - pa);
    p.z = level;
    it->second = static_cast<std::uint32_t>(out_.positions.size());
    out_.positions.push_back(p);
    return it->second;
  }

  [[nodiscard]] bool strictlyCrosses(double za, double zb, double level) const {
    return (za < level - kFloorToleranceM && zb > level + kFloorToleranceM) ||
           (za > level + kFloorToleranceM && zb < level - kFloorToleranceM);
  }

  void cutTriangle(std::size_t t) {
    const std::uint32_t v[3] = {in_.triangles[3 * t], in_.triangles[3 * t + 1], in_.triangles[3 * t + 2]};
    const SurfaceKind kind = in_.kinds[t];
    const double zMin = std::min({z(v[0]), z(v[1]), z(v[2])});
    const double zMax = std::max({z(v[0]), z(v[1]), z(v[2])});
    // Planes strictly inside the triangle's height range.
    const auto first = std::upper_bound(planes_.begin(), planes_.end(), zMin + kFloorToleranceM);
    const auto last = std::lower_bound(planes_.begin(), planes_.end(), zMax - kFloorToleranceM);
    if (first >= last) {
      emit(v[0], v[1], v[2], kind);
      return;
    }
    const auto firstPlane = static_cast<std::uint32_t>(first - planes_.begin());
    const auto endPlane = static_cast<std::uint32_t>(last - planes_.begin());
    // Bands: (-inf, first], [first, first + 1], ..., [last - 1, +inf).
    for (std::uint32_t band = firstPlane; band <= endPlane; ++band) {
      const bool hasLow = band > firstPlane;
      const bool hasHigh = band < endPlane;
      const std::uint32_t lowPlane = band - 1;
      const std::uint32_t highPlane = band;
      const double lo = hasLow ? planes_[lowPlane] : -std::numeric_limits<double>::infinity();
      const double hi = hasHigh ? planes_[highPlane] : std::numeric_limits<double>::infinity();
      polygon_.clear();
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t a = v[i];
        const std::uint32_t b = v[(i + 1) % 3];
        const double za = z(a);
        const double zb = z(b);
        if (za >= lo - kFloorToleranceM && za <= hi + kFloorToleranceM) push(a);
        const bool crossLow = hasLow && strictlyCrosses(za, zb, lo);
        const bool crossHigh = hasHigh && strictlyCrosses(za, zb, hi);
        // Along a -> b the lower plane comes first when the edge rises.
        if (zb > za) {
          if (crossLow) push(crossing(a, b, lowPlane));
          if (crossHigh) push(crossing(a, b, highPlane));
        } else {
          if (crossHigh) push(crossing(a, b, highPlane));
          if (crossLow) push(crossing(a, b, lowPlane));
        }
      }
      while (polygon_.size() > 1 && polygon_.back() == polygon_.front()) polygon_.pop_back();
      if (polygon_.size() < 3) continue;
      // A convex piece: a fan. Its sides lie on distinct lines (parts of the triangle's edges and
      // the two planes), so fan triangles only degenerate for degenerate input; those are dropped.
      for (std::size_t i = 1; i + 1 < polygon_.size(); ++i) {
        const glm::dvec3& p0 = out_.positions[polygon_[0]];
        const glm::dvec3& p1 = out_.positions[polygon_[i]];
        const glm::dvec3& p2 = out_.positions[polygon_[i + 1]];
        if (glm::length(glm::cross(p1 - p0, p2 - p0)) <= 1e-12) continue;
        emit(polygon_[0], polygon_[i], polygon_[i + 1], kind);
      }
    }
  }

  void push(std::uint32_t vertex) {
    if (polygon_.empty() || polygon_.back() != vertex) polygon_.push_back(vertex);
  }

  const Lod2Mesh& in_;
  Lod2Mesh& out_;
  std::vector<double> planes_;
  std::unordered_map<EdgePlaneKey, std::uint32_t, EdgePlaneHash> crossings_;
  std::vector<std::uint32_t> polygon_;
};

/// One round of midpoint subdivision; false when no edge was longer than the target.
bool splitLongEdges(Lod2Mesh& mesh, double maxEdgeM, bool splitFlatTriangles,
                    std::unordered_map<std::uint64_t, std::uint32_t>& midpoints,
                    std::unordered_map<std::uint64_t, bool>& splittable) {
  // Edges at the target within 1 ppm (half-storey pieces of a storey-high edge, with the target
  // from a float storey height) stay whole.
  const double maxSquared = maxEdgeM * maxEdgeM * (1.0 + 2e-6);
  midpoints.clear();
  // An edge may be split when a triangle that is not flat (a horizontal triangle at one height moves
  // as a whole) uses it; deciding per edge keeps both of its triangles in agreement.
  splittable.clear();
  if (!splitFlatTriangles) {
    for (std::size_t t = 0; t < mesh.kinds.size(); ++t) {
      const std::uint32_t v[3] = {mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]};
      const double z0 = mesh.positions[v[0]].z;
      const bool flat = std::abs(mesh.positions[v[1]].z - z0) <= kFloorToleranceM &&
                        std::abs(mesh.positions[v[2]].z - z0) <= kFloorToleranceM;
      if (flat) continue;
      for (int i = 0; i < 3; ++i) {
        const glm::dvec3 d = mesh.positions[v[(i + 1) % 3]] - mesh.positions[v[i]];
        if (glm::dot(d, d) > maxSquared) splittable[edgeKey(v[i], v[(i + 1) % 3])] = true;
      }
    }
  }
  const auto midpoint = [&](std::uint32_t a, std::uint32_t b) -> std::uint32_t {
    const glm::dvec3 d = mesh.positions[b] - mesh.positions[a];
    if (glm::dot(d, d) <= maxSquared) return std::numeric_limits<std::uint32_t>::max();
    if (!splitFlatTriangles && !splittable.count(edgeKey(a, b))) return std::numeric_limits<std::uint32_t>::max();
    const auto [it, inserted] = midpoints.emplace(edgeKey(a, b), 0u);
    if (inserted) {
      it->second = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
    }
    return it->second;
  };
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> triangles;
  std::vector<SurfaceKind> kinds;
  triangles.reserve(mesh.triangles.size() * 2);
  kinds.reserve(mesh.kinds.size() * 2);
  bool split = false;
  for (std::size_t t = 0; t < mesh.kinds.size(); ++t) {
    std::uint32_t v[3] = {mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]};
    std::uint32_t m[3] = {midpoint(v[0], v[1]), midpoint(v[1], v[2]), midpoint(v[2], v[0])};  // m[i] on v[i] v[i+1]
    const SurfaceKind kind = mesh.kinds[t];
    const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      triangles.insert(triangles.end(), {a, b, c});
      kinds.push_back(kind);
    };
    const int count = (m[0] != kNone) + (m[1] != kNone) + (m[2] != kNone);
    if (count == 0) {
      add(v[0], v[1], v[2]);
      continue;
    }
    split = true;
    if (count == 3) {
      add(v[0], m[0], m[2]);
      add(m[0], v[1], m[1]);
      add(m[2], m[1], v[2]);
      add(m[0], m[1], m[2]);
      continue;
    }
    if (count == 1) {
      // Rotate so the split edge is v0 v1.
      const int r = m[0] != kNone ? 0 : (m[1] != kNone ? 1 : 2);
      const std::uint32_t a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3], mid = m[r];
      add(a, mid, c);
      add(mid, b, c);
      continue;
    }
    // Two split edges: rotate so the unsplit one is v2 v0 (edges v0 v1 and v1 v2 split).
    const int r = m[2] == kNone ? 0 : (m[0] == kNone ? 1 : 2);
    const std::uint32_t a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3];
    const std::uint32_t mab = m[r], mbc = m[(r + 1) % 3];
    add(mab, b, mbc);
    // The quad a, mab, mbc, c split along its shorter diagonal.
    const double d1 = glm::length(mesh.positions[mbc] - mesh.positions[a]);
    const double d2 = glm::length(mesh.positions[c] - mesh.positions[mab]);
    if (d1 <= d2) {
      add(a, mab, mbc);
      add(a, mbc, c);
    } else {
      add(a, mab, c);
      add(mab, mbc, c);
    }
  }
  mesh.triangles.swap(triangles);
  mesh.kinds.swap(kinds);
  return split;
}

}  // namespace

FloorLevels floorLevels(const BuildingAttributes& attributes) {
  FloorLevels floors;
  floors.baseM = static_cast<double>(attributes.minHeightM);
  floors.storeys = std::max<std::uint16_t>(attributes.storeys, 1);
  floors.storeyHeightM =
      (static_cast<double>(attributes.heightM) - static_cast<double>(attributes.minHeightM)) / floors.storeys;
  return floors;
}

double targetEdgeLengthM(const FloorLevels& floors, const RemeshOptions& options) {
  if (options.maxEdgeM > 0.0) return options.maxEdgeM;
  return std::max(0.5 * floors.storeyHeightM, options.minAutoEdgeM);
}

Lod2Mesh weldVertices(const Lod2Mesh& mesh) {
  struct PositionHash {
    std::size_t operator()(const glm::dvec3& p) const noexcept {
      const std::hash<double> h;
      std::size_t seed = h(p.x);
      seed ^= h(p.y) + 0x9E3779B97F4A7C15ull + (seed << 6) + (seed >> 2);
      seed ^= h(p.z) + 0x9E3779B97F4A7C15ull + (seed << 6) + (seed >> 2);
      return seed;
    }
  };
  Lod2Mesh out;
  std::unordered_map<glm::dvec3, std::uint32_t, PositionHash> index;
  std::vector<std::uint32_t> remap(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto [it, inserted] = index.emplace(mesh.positions[i], static_cast<std::uint32_t>(out.positions.size()));
    if (inserted) out.positions.push_back(mesh.positions[i]);
    remap[i] = it->second;
  }
  for (std::size_t t = 0; t < mesh.kinds.size(); ++t) {
    const std::uint32_t a = remap[mesh.triangles[3 * t]];
    const std::uint32_t b = remap[mesh.triangles[3 * t + 1]];
    const std::uint32_t c = remap[mesh.triangles[3 * t + 2]];
    if (a == b || b == c || c == a) continue;
    out.triangles.insert(out.triangles.end(), {a, b, c});
    out.kinds.push_back(mesh.kinds[t]);
  }
  return out;
}

Result<Lod2Mesh> remeshForFloors(const Lod2Mesh& mesh, const FloorLevels& floors, const RemeshOptions& options) {
  if (!(floors.storeyHeightM > 0.0) || floors.storeys < 1)
    return Error{"re-meshing needs a positive storey height (got " + std::to_string(floors.storeyHeightM) + " m)"};
  Lod2Mesh cut;
  FloorCutter(mesh, floors, cut).run();
  const double target = targetEdgeLengthM(floors, options);
  std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
  std::unordered_map<std::uint64_t, bool> splittable;
  for (int round = 0; round < 64; ++round) {
    if (!splitLongEdges(cut, target, options.splitFlatTriangles, midpoints, splittable)) break;
    if (cut.positions.size() > options.maxVertices) {
      return Error{"re-meshing to edges of at most " + std::to_string(target) + " m would exceed " +
                   std::to_string(options.maxVertices) + " vertices (raise the target edge length)"};
    }
  }
  return cut;
}

}  // namespace qv::prep
