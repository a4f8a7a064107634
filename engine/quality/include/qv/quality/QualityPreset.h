// The quality presets: how much the viewer draws and animates in each, before the frame-time
// governor's step (FrameGovernor.h) scales it. The numbers live here, not in the panel: the
// panel, the page's ?quality= and the device's weak-device start all choose a preset by name.
#pragma once

#include <cstdint>

namespace qv {

/// Values are stable: the panel's combo and ?quality=high|balanced|low use them.
enum class QualityPreset : int { High = 0, Balanced = 1, Low = 2 };

/// What a preset draws and animates.
struct QualitySettings {
  float maxScreenSpaceError = 12.0f;  ///< allowed LOD error in pixels (larger: coarser tiles)
  float blockPixels = 4.0f;           ///< far-view block cell width in pixels (larger: fewer blocks)
  std::uint32_t maxDrawTiles = 240;   ///< city tiles drawn at most (draw calls)
  float animationRadiusM = 1000.0f;   ///< buildings within this distance of the eye sway (metres)
  std::uint32_t maxAnimatedBuildings = 20000;
  friend bool operator==(const QualitySettings&, const QualitySettings&) = default;
};

/// The preset's settings at the governor's `governorStep` (detailScaleForStep: 0 is the preset
/// itself; each step coarser). At least 8 tiles are always drawn.
[[nodiscard]] QualitySettings qualitySettings(QualityPreset preset, int governorStep = 0);

/// The preset's name as the panel shows it: "High (desktop)", "Balanced", "Low (weak devices)".
[[nodiscard]] const char* qualityName(QualityPreset preset);

}  // namespace qv
