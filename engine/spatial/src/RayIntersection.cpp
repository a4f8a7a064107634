// Möller–Trumbore for triangles; for prisms, the roof and floor planes with an even-odd point in
// polygon test, and every ring edge as a vertical quad.
#include "qv/spatial/RayIntersection.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace qv {

std::optional<float> rayPrism(const float o[3], const float d[3], const PrismView& p) {
  float best = INFINITY;
  // Roof and floor planes: inside the polygon (even-odd over all rings) at z = maxZ / minZ.
  auto inside = [&](float x, float y) {
    bool in = false;
    std::uint32_t begin = 0;
    for (std::uint32_t r = 0; r < p.ringCount; ++r) {
      const std::uint32_t n = p.ringCounts[r];
      for (std::uint32_t i = 0, j = n - 1; i < n; j = i++) {
        const float xi = p.xy[2 * (begin + i)] + p.offsetX, yi = p.xy[2 * (begin + i) + 1] + p.offsetY;
        const float xj = p.xy[2 * (begin + j)] + p.offsetX, yj = p.xy[2 * (begin + j) + 1] + p.offsetY;
        if (((yi > y) != (yj > y)) && (x < (xj - xi) * (y - yi) / (yj - yi) + xi)) in = !in;
      }
      begin += n;
    }
    return in;
  };
  if (std::abs(d[2]) > 1e-9f) {
    for (float z : {p.maxZ, p.minZ}) {
      const float t = (z - o[2]) / d[2];
      if (t >= 0.0f && t < best && inside(o[0] + t * d[0], o[1] + t * d[1])) best = t;
    }
  }
  // Walls: the vertical quad of every ring edge.
  std::uint32_t begin = 0;
  for (std::uint32_t r = 0; r < p.ringCount; ++r) {
    const std::uint32_t n = p.ringCounts[r];
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t j = (i + 1) % n;
      const float ax = p.xy[2 * (begin + i)] + p.offsetX, ay = p.xy[2 * (begin + i) + 1] + p.offsetY;
      const float bx = p.xy[2 * (begin + j)] + p.offsetX, by = p.xy[2 * (begin + j) + 1] + p.offsetY;
      // Solve o + t d = a + s (b - a) in the plane: 2×2 system in (t, s).
      const float ex = bx - ax, ey = by - ay;
      const float det = d[0] * (-ey) - d[1] * (-ex);
      if (std::abs(det) < 1e-12f) continue;
      const float rx = ax - o[0], ry = ay - o[1];
      const float t = (rx * (-ey) - ry * (-ex)) / det;
      const float s = (d[0] * ry - d[1] * rx) / det;
      if (t < 0.0f || t >= best || s < 0.0f || s > 1.0f) continue;
      const float z = o[2] + t * d[2];
      if (z >= p.minZ && z <= p.maxZ) best = t;
    }
    begin += n;
  }
  if (!std::isfinite(best)) return std::nullopt;
  return best;
}

template <typename Index>
std::optional<float> rayTriangles(const float o[3], const float d[3], std::span<const glm::vec3> positions,
                                  std::span<const Index> triangles, const glm::vec3& offset) {
  // Möller–Trumbore, both faces.
  const glm::vec3 origin(o[0], o[1], o[2]), dir(d[0], d[1], d[2]);
  float best = INFINITY;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    if (triangles[t] >= positions.size() || triangles[t + 1] >= positions.size() ||
        triangles[t + 2] >= positions.size())
      continue;
    const glm::vec3 a = positions[triangles[t]] + offset;
    const glm::vec3 e1 = positions[triangles[t + 1]] + offset - a;
    const glm::vec3 e2 = positions[triangles[t + 2]] + offset - a;
    const glm::vec3 p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    const float inv = 1.0f / det;
    const glm::vec3 s = origin - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float hit = glm::dot(e2, q) * inv;
    if (hit >= 0.0f && hit < best) best = hit;
  }
  if (best == INFINITY) return std::nullopt;
  return best;
}

template std::optional<float> rayTriangles<std::uint32_t>(const float[3], const float[3], std::span<const glm::vec3>,
                                                          std::span<const std::uint32_t>, const glm::vec3&);
template std::optional<float> rayTriangles<std::uint16_t>(const float[3], const float[3], std::span<const glm::vec3>,
                                                          std::span<const std::uint16_t>, const glm::vec3&);

}  // namespace qv
