#include "qv/prep/Lod2Model.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace qv::prep {

std::string_view surfaceKindName(SurfaceKind kind) {
  switch (kind) {
    case SurfaceKind::Wall:
      return "wall";
    case SurfaceKind::Roof:
      return "roof";
    case SurfaceKind::Ground:
      return "ground";
    case SurfaceKind::Other:
      return "other";
  }
  return "other";
}

double surfaceAreaM2(const Lod2Mesh& mesh) {
  double area = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const glm::dvec3& a = mesh.positions[mesh.triangles[t]];
    const glm::dvec3& b = mesh.positions[mesh.triangles[t + 1]];
    const glm::dvec3& c = mesh.positions[mesh.triangles[t + 2]];
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area;
}

double enclosedVolumeM3(const Lod2Mesh& mesh) {
  double volume = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const glm::dvec3& a = mesh.positions[mesh.triangles[t]];
    const glm::dvec3& b = mesh.positions[mesh.triangles[t + 1]];
    const glm::dvec3& c = mesh.positions[mesh.triangles[t + 2]];
    volume += glm::dot(a, glm::cross(b, c));
  }
  return volume / 6.0;
}

double crossSectionAreaM2(const Lod2Mesh& mesh, double z) {
  double twiceArea = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const glm::dvec3 p[3] = {mesh.positions[mesh.triangles[t]], mesh.positions[mesh.triangles[t + 1]],
                             mesh.positions[mesh.triangles[t + 2]]};
    glm::dvec2 hits[2];
    int count = 0;
    for (int i = 0; i < 3 && count < 2; ++i) {
      const glm::dvec3& a = p[i];
      const glm::dvec3& b = p[(i + 1) % 3];
      if ((a.z < z) == (b.z < z)) continue;
      const double s = (z - a.z) / (b.z - a.z);
      hits[count++] = glm::dvec2(a.x + s * (b.x - a.x), a.y + s * (b.y - a.y));
    }
    if (count != 2) continue;
    // The section's boundary runs along up × normal, keeping the solid on its left.
    const glm::dvec3 normal = glm::cross(p[1] - p[0], p[2] - p[0]);
    const glm::dvec2 along(-normal.y, normal.x);
    glm::dvec2 from = hits[0];
    glm::dvec2 to = hits[1];
    if (glm::dot(to - from, along) < 0.0) std::swap(from, to);
    twiceArea += from.x * to.y - to.x * from.y;
  }
  return 0.5 * twiceArea;
}

HeightRange heightRange(const Lod2Mesh& mesh) {
  if (mesh.positions.empty()) return {};
  HeightRange range{mesh.positions.front().z, mesh.positions.front().z};
  for (const glm::dvec3& p : mesh.positions) {
    range.minZ = std::min(range.minZ, p.z);
    range.maxZ = std::max(range.maxZ, p.z);
  }
  return range;
}

SurfaceKind kindFromNormal(const glm::dvec3& normal, bool atBase) {
  const double length = glm::length(normal);
  if (!(length > 0.0)) return SurfaceKind::Wall;
  // sin(15°): faces within 15 degrees of vertical are walls.
  constexpr double kSinWallTolerance = 0.25881904510252074;
  const double nz = normal.z / length;
  if (nz > kSinWallTolerance) return SurfaceKind::Roof;
  if (nz < -kSinWallTolerance) return atBase ? SurfaceKind::Ground : SurfaceKind::Other;
  return SurfaceKind::Wall;
}

}  // namespace qv::prep
