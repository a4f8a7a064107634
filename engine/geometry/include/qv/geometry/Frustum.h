// View frustum as six planes, for culling boxes in the city frame.
#pragma once

#include <array>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "qv/geometry/Bounds.h"

namespace qv {

enum class Containment { Outside, Intersects, Inside };

class Frustum {
 public:
  Frustum() = default;
  /// viewProjection: clip = viewProjection * world, OpenGL clip conventions (-w <= x,y,z <= w).
  explicit Frustum(const glm::mat4& viewProjection);

  /// Conservative: Outside only when the box is entirely behind one plane.
  [[nodiscard]] Containment classify(const Box& box) const;
  /// classify() against only the planes whose bit is set in `mask` (bit i = plane i); clears
  /// the bits of planes the box lies wholly inside, so a hierarchy skips them for its children.
  [[nodiscard]] Containment classify(const Box& box, unsigned& mask) const;
  [[nodiscard]] bool intersects(const Box& box) const { return classify(box) != Containment::Outside; }

  /// Planes (a, b, c, d) with a·x + b·y + c·z + d >= 0 inside; normals are unit length.
  [[nodiscard]] const std::array<glm::vec4, 6>& planes() const { return planes_; }

 private:
  std::array<glm::vec4, 6> planes_{};
  // Per plane, the box coordinates (indices into minX..maxZ) of its farthest corner along the
  // normal, x y z, then of its nearest: chosen once here instead of for every box.
  std::array<std::array<unsigned char, 6>, 6> corners_{{{3, 4, 5, 0, 1, 2},
                                                        {3, 4, 5, 0, 1, 2},
                                                        {3, 4, 5, 0, 1, 2},
                                                        {3, 4, 5, 0, 1, 2},
                                                        {3, 4, 5, 0, 1, 2},
                                                        {3, 4, 5, 0, 1, 2}}};
};

}  // namespace qv
