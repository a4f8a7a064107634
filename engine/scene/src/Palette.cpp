#include "qv/scene/Palette.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>

namespace qv {
namespace {

// Piecewise linear through five stops at t = 0, ¼, ½, ¾, 1 (t clamped).
Rgb fiveStopRamp(const std::array<Rgb, 5>& stops, float t) {
  t = std::clamp(t, 0.0f, 1.0f) * 4.0f;
  const auto i = std::min(static_cast<int>(t), 3);
  const float f = t - static_cast<float>(i);
  const Rgb a = stops[static_cast<std::size_t>(i)];
  const Rgb b = stops[static_cast<std::size_t>(i) + 1];
  return {a.r + (b.r - a.r) * f, a.g + (b.g - a.g) * f, a.b + (b.b - a.b) * f};
}

std::string glslVec3(const Rgb& c) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "vec3(%.4f, %.4f, %.4f)", static_cast<double>(c.r), static_cast<double>(c.g),
                static_cast<double>(c.b));
  return buffer;
}

// The GLSL twin of fiveStopRamp.
std::string glslFiveStopRamp(const char* name, const std::array<Rgb, 5>& stops) {
  std::string s = "vec3 " + std::string(name) + "(float t) {\n  t = clamp(t, 0.0, 1.0) * 4.0;\n";
  for (std::size_t i = 0; i < 4; ++i) {
    s += "  if (t < " + std::to_string(i + 1) + ".0) return mix(" + glslVec3(stops[i]) + ", " + glslVec3(stops[i + 1]) +
         ", t - " + std::to_string(i) + ".0);\n";
  }
  s += "  return " + glslVec3(stops[4]) + ";\n}\n";
  return s;
}

}  // namespace

Rgb paletteRamp(float t) {
  return fiveStopRamp(kDamagePalette, t);
}

Rgb notAnimatedGrey(float t) {
  return fiveStopRamp(kNotAnimatedPalette, t);
}

float driftRampPosition(float drift) {
  if (!(drift > kDriftStops[0])) return 0.0f;  // also NaN
  for (std::size_t i = 0; i + 1 < kDriftStops.size(); ++i) {
    if (drift < kDriftStops[i + 1]) {
      return (static_cast<float>(i) + (drift - kDriftStops[i]) / (kDriftStops[i + 1] - kDriftStops[i])) / 4.0f;
    }
  }
  return 1.0f;
}

std::string paletteGlsl() {
  std::string s = "const vec3 kNoResult = " + glslVec3(kNoResultColor) + ";\n";
  s += "const vec3 kSelected = " + glslVec3(kSelectedColor) + ";\n";
  s += "const vec3 kDimmed = " + glslVec3(kDimmedColor) + ";\n";
  s += "const vec3 kTagGreen = " + glslVec3(kTagPalette[0]) + ";\n";
  s += "const vec3 kTagYellow = " + glslVec3(kTagPalette[1]) + ";\n";
  s += "const vec3 kTagRed = " + glslVec3(kTagPalette[2]) + ";\n";
  s += "const vec3[" + std::to_string(kGroundPalette.size()) + "] kGroundClass = vec3[" +
       std::to_string(kGroundPalette.size()) + "](";
  for (std::size_t i = 0; i < kGroundPalette.size(); ++i) s += (i > 0 ? ", " : "") + glslVec3(kGroundPalette[i]);
  s += ");\n";
  s += glslFiveStopRamp("ramp", kDamagePalette);
  s += glslFiveStopRamp("notAnimatedGrey", kNotAnimatedPalette);
  // The GLSL twin of driftRampPosition.
  s += "float driftPosition(float d) {\n";
  for (std::size_t i = 0; i + 1 < kDriftStops.size(); ++i) {
    char line[160];
    std::snprintf(line, sizeof line, "  if (d < %.6f) return (%zu.0 + (d - %.6f) / %.6f) * 0.25;\n",
                  static_cast<double>(kDriftStops[i + 1]), i, static_cast<double>(kDriftStops[i]),
                  static_cast<double>(kDriftStops[i + 1] - kDriftStops[i]));
    s += line;
  }
  s += "  return 1.0;\n}\n";
  return s;
}

}  // namespace qv
