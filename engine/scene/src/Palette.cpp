#include "qv/scene/Palette.h"

#include <algorithm>

namespace qv {

Rgb paletteRamp(float t) {
  t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const auto i = std::min(static_cast<int>(t), 3);
  const float f = t - static_cast<float>(i);
  const Rgb a = kDamagePalette[static_cast<std::size_t>(i)];
  const Rgb b = kDamagePalette[static_cast<std::size_t>(i) + 1];
  return {a.r + (b.r - a.r) * f, a.g + (b.g - a.g) * f, a.b + (b.b - a.b) * f};
}

}  // namespace qv
