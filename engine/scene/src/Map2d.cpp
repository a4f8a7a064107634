#include "qv/scene/Map2d.h"

#include <algorithm>
#include <cmath>

#include "qv/anim/SeriesSampling.h"

namespace qv {
namespace {

Rgb mix(Rgb a, Rgb b, float t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

constexpr Rgb kPlain = {0.82f, 0.80f, 0.76f};  // the shader's neutral and "results not loaded yet"

}  // namespace

std::uint32_t packRgb(Rgb c) {
  const auto byte = [](float v) { return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return (byte(c.r) << 16) | (byte(c.g) << 8) | byte(c.b);
}

Rgb buildingRowColor(const BuildingGpuRecord& b, ColorMode mode, double t, std::span<const std::uint8_t> series,
                     std::span<const FloorGpuRecord> floors) {
  const float damage = b.damageState;
  const auto flags = static_cast<unsigned>(b.flags + 0.5f);
  const float lossCode = b.lossCode;
  Rgb color = kPlain;
  if (mode == ColorMode::CurrentDrift) {
    float now = -1.0f;
    if (b.floorBase >= 0.0f && floors.size() >= 2) {
      // Animated floor by floor: its largest storey drift now.
      const float storeyHeight = std::max(b.storeyHeightMeters, 0.1f);
      now = 0.0f;
      for (std::size_t k = 0; k + 1 < floors.size(); ++k) {
        now = std::max(
            now, std::hypot(floors[k + 1].dxMeters - floors[k].dxMeters, floors[k + 1].dyMeters - floors[k].dyMeters) /
                     storeyHeight);
      }
    } else {
      const SeriesRef ref{b.seriesBase < 0.0f ? -1 : static_cast<std::int64_t>(b.seriesBase), b.seriesStart,
                          b.seriesCount < 0.5f ? 0u : static_cast<std::uint32_t>(b.seriesCount + 0.5f), b.seriesRateHz};
      now = seriesDriftAt(series, ref, kSeriesFullScale, t);
    }
    color = now >= 0.0f ? paletteRamp(driftRampPosition(now)) : notAnimatedGrey(driftRampPosition(b.peakValue));
  } else if (mode == ColorMode::PeakDrift) {
    color = paletteRamp(driftRampPosition(b.peakValue));
  } else if (mode == ColorMode::DamageState) {
    color = damage < kDamageNoResult + 0.5f ? kNoResultColor : paletteRamp(damage / kDamageComplete);
  } else if (mode == ColorMode::ModerateOrWorse || mode == ColorMode::ExpectedDamage ||
             mode == ColorMode::InspectionTag) {
    const float code = std::max(lossCode, 0.0f);
    const float tag = std::floor(code / static_cast<float>(kLossCodeTagFactor));
    const float rest = code - tag * static_cast<float>(kLossCodeTagFactor);
    const float expected = std::floor(rest / static_cast<float>(kLossCodeExpectedFactor));
    const float moderate = rest - expected * static_cast<float>(kLossCodeExpectedFactor);
    if (mode == ColorMode::ModerateOrWorse) {
      color = paletteRamp(moderate / static_cast<float>(kLossCodeLevels));
    } else if (mode == ColorMode::ExpectedDamage) {
      color = paletteRamp(expected / static_cast<float>(kLossCodeLevels));
    } else {
      color = kTagPalette[tag < 0.5f ? 0 : (tag < 1.5f ? 1 : 2)];
    }
  }
  const bool pending = damage < kDamagePending + 0.5f;
  if (pending) color = kPlain;
  const bool probabilistic =
      mode == ColorMode::ModerateOrWorse || mode == ColorMode::ExpectedDamage || mode == ColorMode::InspectionTag;
  const bool missing = damage < kDamageNoResult + 0.5f || (probabilistic && lossCode < -0.5f);
  if (mode != ColorMode::Neutral && missing && !pending) color = kNoResultColor;
  if ((flags & kFlagDimmed) != 0u) color = mix(color, kDimmedColor, 0.85f);
  if ((flags & kFlagSelected) != 0u) color = mix(color, kSelectedColor, 0.65f);
  return color;
}

}  // namespace qv
