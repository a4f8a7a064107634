#include "qv/geometry/Frustum.h"

#include <glm/geometric.hpp>

namespace qv {

Frustum::Frustum(const glm::mat4& m) {
  // Gribb & Hartmann, "Fast Extraction of Viewing Frustum Planes from the World-View-Projection
  // Matrix" (2001): each plane is row 3 ± row i of the matrix. glm is column-major: m[col][row].
  const glm::vec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::vec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::vec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::vec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
  planes_ = {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3 + row2, row3 - row2};
  for (glm::vec4& p : planes_) {
    const float length = glm::length(glm::vec3(p));
    if (length > 0.0f) p /= length;
  }
}

Containment Frustum::classify(const Box& box) const {
  unsigned mask = 0x3fu;  // all six planes
  return classify(box, mask);
}

Containment Frustum::classify(const Box& box, unsigned& mask) const {
  for (unsigned i = 0; i < 6; ++i) {
    const unsigned bit = 1u << i;
    if ((mask & bit) == 0) continue;
    const glm::vec4& p = planes_[i];
    const float px = p.x >= 0.0f ? box.maxX : box.minX;
    const float py = p.y >= 0.0f ? box.maxY : box.minY;
    const float pz = p.z >= 0.0f ? box.maxZ : box.minZ;
    if (p.x * px + p.y * py + p.z * pz + p.w < 0.0f) return Containment::Outside;
    const float nx = p.x >= 0.0f ? box.minX : box.maxX;
    const float ny = p.y >= 0.0f ? box.minY : box.maxY;
    const float nz = p.z >= 0.0f ? box.minZ : box.maxZ;
    if (p.x * nx + p.y * ny + p.z * nz + p.w >= 0.0f) mask &= ~bit;
  }
  return mask == 0 ? Containment::Inside : Containment::Intersects;
}

}  // namespace qv
