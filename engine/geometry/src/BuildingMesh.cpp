#include "qv/geometry/BuildingMesh.h"

#include <algorithm>
#include <cmath>

namespace qv {
namespace {

std::int8_t packNormal(float v) {
  return static_cast<std::int8_t>(std::lround(v * 127.0f));
}

}  // namespace

std::size_t appendExtrusion(MeshData& mesh, const ExtrusionInput& in) {
  if (!(in.topZ > in.baseZ) || in.points.empty()) return 0;
  const std::size_t trianglesBefore = mesh.indices.size() / 3;

  // Ring heights: base, the floor levels strictly inside, top.
  std::vector<float> heights;
  heights.reserve(in.levels.size() + 2);
  heights.push_back(in.baseZ);
  for (float z : in.levels) {
    if (z > heights.back() + 1e-3f && z < in.topZ - 1e-3f) heights.push_back(z);
  }
  heights.push_back(in.topZ);
  const auto levelCount = static_cast<std::uint32_t>(heights.size());

  std::uint32_t ringBegin = 0;
  for (std::uint32_t ringEnd : in.ringEnds) {
    if (ringEnd > in.points.size() || ringEnd < ringBegin) break;  // malformed: stop quietly
    const std::uint32_t n = ringEnd - ringBegin;
    for (std::uint32_t e = 0; n >= 2 && e < n; ++e) {
      const glm::vec2 a = in.points[ringBegin + e];
      const glm::vec2 b = in.points[ringBegin + (e + 1) % n];
      const glm::vec2 d = b - a;
      const float length = std::sqrt(d.x * d.x + d.y * d.y);
      if (length < 1e-3f) continue;
      // Outward for a counter-clockwise outer ring and for clockwise holes alike.
      const std::int8_t nx = packNormal(d.y / length);
      const std::int8_t ny = packNormal(-d.x / length);
      const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
      for (float z : heights) {
        mesh.vertices.push_back({a.x, a.y, z, nx, ny, 0, kWall, in.slot});
        mesh.vertices.push_back({b.x, b.y, z, nx, ny, 0, kWall, in.slot});
      }
      for (std::uint32_t k = 0; k + 1 < levelCount; ++k) {
        const std::uint32_t a0 = first + 2 * k, b0 = a0 + 1, a1 = a0 + 2, b1 = a0 + 3;
        // Both triangles end on a bottom-ring vertex: the provoking vertex carries storey k.
        mesh.indices.insert(mesh.indices.end(), {b1, a0, b0, b1, a1, a0});
      }
    }
    ringBegin = ringEnd;
  }

  if (!in.roofTriangles.empty()) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    for (const glm::vec2& p : in.points) {
      mesh.vertices.push_back({p.x, p.y, in.topZ, 0, 0, 127, kRoof, in.slot});
    }
    for (std::size_t t = 0; t + 2 < in.roofTriangles.size(); t += 3) {
      const std::uint32_t i0 = in.roofTriangles[t], i1 = in.roofTriangles[t + 1], i2 = in.roofTriangles[t + 2];
      if (i0 >= in.points.size() || i1 >= in.points.size() || i2 >= in.points.size()) continue;
      mesh.indices.insert(mesh.indices.end(), {first + i0, first + i1, first + i2});
    }
  }
  return mesh.indices.size() / 3 - trianglesBefore;
}

void floorLevelsBetween(const FloorGrid& floors, float baseZ, float topZ, float marginM, std::vector<float>& out) {
  if (!(floors.storeyHeightM > 0.1f)) return;
  constexpr int kMaxLevels = 1000;  // beyond any real building: a corrupt count or height stops here
  // Levels at or below the base are skipped without a loop (a part high up a tower). The clamp
  // keeps the conversion defined for any height; NaN starts at the first level.
  const float storeysBelowBase = std::floor((baseZ - floors.groundZ) / floors.storeyHeightM);
  const int firstLevel =
      storeysBelowBase > 0.0f ? static_cast<int>(std::min(storeysBelowBase, static_cast<float>(kMaxLevels))) + 1 : 1;
  const int endLevel = std::min(floors.storeys, kMaxLevels);
  // z grows with k, so the first level too close to the top ends the list.
  for (int k = firstLevel; k < endLevel; ++k) {
    const float z = floors.groundZ + static_cast<float>(k) * floors.storeyHeightM;
    if (z >= topZ - marginM) break;
    if (z > baseZ + marginM) out.push_back(z);
  }
}

void floorLevelsBetween(float baseZ, float topZ, float storeyHeight, std::vector<float>& out) {
  floorLevelsBetween(FloorGrid{0.0f, storeyHeight, 1000}, baseZ, topZ, 1e-3f, out);
}

void triangulateConvexRing(std::uint32_t first, std::uint32_t count, std::vector<std::uint32_t>& out) {
  for (std::uint32_t i = 1; i + 1 < count; ++i) {
    out.insert(out.end(), {first, first + i, first + i + 1});
  }
}

std::size_t appendTriangleMesh(MeshData& mesh, const TriangleMeshInput& in) {
  std::size_t appended = 0;
  const std::size_t n = in.positions.size();
  for (std::size_t t = 0; t + 2 < in.triangles.size(); t += 3) {
    std::uint32_t index[3] = {in.triangles[t], in.triangles[t + 1], in.triangles[t + 2]};
    if (index[0] >= n || index[1] >= n || index[2] >= n) continue;
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = in.positions[index[k]] + in.offset;
    const glm::vec3 u = p[1] - p[0], v = p[2] - p[0];
    const glm::vec3 c{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
    const float length = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
    if (!(length > 1e-9f)) continue;
    const glm::vec3 normal = c / length;
    std::uint8_t kind = kWall;
    if (t / 3 < in.kinds.size() && in.kinds[t / 3] != kKindFromNormal) {
      kind = in.kinds[t / 3];
    } else if (normal.z > 0.7f) {
      kind = kRoof;
    } else if (normal.z < -0.7f) {
      kind = kGround;
    }
    // Rotate (keeping the winding) so the lowest vertex comes last.
    int lowest = 0;
    for (int k = 1; k < 3; ++k) {
      if (p[k].z < p[lowest].z) lowest = k;
    }
    const int first = (lowest + 1) % 3;
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& q = p[(first + k) % 3];
      mesh.vertices.push_back(
          {q.x, q.y, q.z, packNormal(normal.x), packNormal(normal.y), packNormal(normal.z), kind, in.slot});
    }
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    ++appended;
  }
  return appended;
}

}  // namespace qv
