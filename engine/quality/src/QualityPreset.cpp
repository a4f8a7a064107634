#include "qv/quality/QualityPreset.h"

#include <algorithm>
#include <cmath>

#include "qv/quality/FrameGovernor.h"

namespace qv {

QualitySettings qualitySettings(QualityPreset preset, int governorStep) {
  QualitySettings s;  // High (desktop)
  switch (preset) {
    case QualityPreset::High:
      break;
    case QualityPreset::Balanced:
      s = {24.0f, 6.0f, 120, 600.0f, 6000};
      break;
    case QualityPreset::Low:
      s = {48.0f, 8.0f, 48, 300.0f, 1500};
      break;
  }
  const DetailScale scale = detailScaleForStep(governorStep);
  s.maxScreenSpaceError *= scale.screenSpaceError;
  s.blockPixels *= scale.screenSpaceError;
  s.maxDrawTiles = std::max<std::uint32_t>(
      8u, static_cast<std::uint32_t>(std::lround(static_cast<float>(s.maxDrawTiles) * scale.drawTiles)));
  s.animationRadiusM *= scale.animationRadius;
  s.maxAnimatedBuildings =
      static_cast<std::uint32_t>(std::lround(static_cast<float>(s.maxAnimatedBuildings) * scale.animatedBuildings));
  return s;
}

const char* qualityName(QualityPreset preset) {
  switch (preset) {
    case QualityPreset::High:
      return "High (desktop)";
    case QualityPreset::Balanced:
      return "Balanced";
    default:
      return "Low (weak devices)";
  }
}

}  // namespace qv
