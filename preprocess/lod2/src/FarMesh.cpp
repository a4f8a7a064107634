#include "qv/prep/Lod2FarMesh.h"

#include <algorithm>
#include <cmath>

#include <meshoptimizer.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "qv/prep/Lod2Remesh.h"

namespace qv::prep {

Lod2Mesh simplifyFarMesh(const Lod2Mesh& mesh, const FarMeshOptions& options) {
  // Collapses need shared vertices: parts imported separately are welded first.
  Lod2Mesh welded = weldVertices(mesh);
  if (welded.triangles.empty()) return welded;
  // meshoptimizer takes float positions: relative to the mesh's lowest corner they keep
  // sub-millimetre precision for any building.
  glm::dvec3 lowest = welded.positions.front();
  for (const glm::dvec3& p : welded.positions) lowest = glm::min(lowest, p);
  std::vector<float> positions;
  positions.reserve(welded.positions.size() * 3);
  for (const glm::dvec3& p : welded.positions) {
    const glm::dvec3 d = p - lowest;
    positions.insert(positions.end(), {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)});
  }
  const std::size_t indexCount = welded.triangles.size();
  const double ratio = std::clamp(options.targetTriangleRatio, 0.0, 1.0);
  const std::size_t triangleCount = indexCount / 3;
  const std::size_t targetIndexCount =
      std::max<std::size_t>(3, static_cast<std::size_t>(std::llround(static_cast<double>(triangleCount) * ratio)) * 3);
  std::vector<std::uint32_t> simplified(indexCount);
  float resultError = 0.0f;
  const std::size_t count = meshopt_simplify(simplified.data(), welded.triangles.data(), indexCount, positions.data(),
                                             welded.positions.size(), 3 * sizeof(float), targetIndexCount,
                                             options.maxRelativeError, 0, &resultError);
  if (count == 0 || count >= indexCount) return welded;
  simplified.resize(count);

  // Keep only the vertices still used, in order of first use.
  Lod2Mesh far;
  std::vector<std::uint32_t> remap(welded.positions.size(), ~0u);
  for (std::uint32_t& index : simplified) {
    if (remap[index] == ~0u) {
      remap[index] = static_cast<std::uint32_t>(far.positions.size());
      far.positions.push_back(welded.positions[index]);
    }
    index = remap[index];
  }
  far.triangles = std::move(simplified);
  // Collapses change which faces a triangle belongs to: kinds are taken from the normals again.
  double minZ = far.positions.front().z;
  for (const glm::dvec3& p : far.positions) minZ = std::min(minZ, p.z);
  far.kinds.reserve(far.triangles.size() / 3);
  for (std::size_t t = 0; t + 2 < far.triangles.size(); t += 3) {
    const glm::dvec3& a = far.positions[far.triangles[t]];
    const glm::dvec3& b = far.positions[far.triangles[t + 1]];
    const glm::dvec3& c = far.positions[far.triangles[t + 2]];
    far.kinds.push_back(kindFromNormal(glm::cross(b - a, c - a), std::max({a.z, b.z, c.z}) - minZ <= 0.01));
  }
  return far;
}

}  // namespace qv::prep
