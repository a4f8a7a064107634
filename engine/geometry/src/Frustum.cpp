#include "qv/geometry/Frustum.h"

#include <cstddef>
#include <cstring>

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
  for (std::size_t i = 0; i < 6; ++i) {
    const glm::vec4& p = planes_[i];
    const unsigned char far[3] = {static_cast<unsigned char>(p.x >= 0.0f ? 3 : 0),
                                  static_cast<unsigned char>(p.y >= 0.0f ? 4 : 1),
                                  static_cast<unsigned char>(p.z >= 0.0f ? 5 : 2)};
    corners_[i] = {far[0],
                   far[1],
                   far[2],
                   static_cast<unsigned char>(3 - far[0]),
                   static_cast<unsigned char>(5 - far[1]),
                   static_cast<unsigned char>(7 - far[2])};
  }
}

Containment Frustum::classify(const Box& box) const {
  unsigned mask = 0x3fu;  // all six planes
  return classify(box, mask);
}

Containment Frustum::classify(const Box& box, unsigned& mask) const {
  static_assert(sizeof(Box) == 6 * sizeof(float));
  float b[6];  // minX minY minZ maxX maxY maxZ
  std::memcpy(b, &box, sizeof b);
  for (unsigned i = 0; i < 6; ++i) {
    const unsigned bit = 1u << i;
    if ((mask & bit) == 0) continue;
    const glm::vec4& p = planes_[i];
    const auto& k = corners_[i];
    if (p.x * b[k[0]] + p.y * b[k[1]] + p.z * b[k[2]] + p.w < 0.0f) return Containment::Outside;
    if (p.x * b[k[3]] + p.y * b[k[4]] + p.z * b[k[5]] + p.w >= 0.0f) mask &= ~bit;
  }
  return mask == 0 ? Containment::Inside : Containment::Intersects;
}

}  // namespace qv
