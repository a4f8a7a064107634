// The 2D city, for browsers without WebGL2 (web/quakeview.js draws it on a 2D canvas): each drawn
// building's footprint from above, in the colour the 3D view gives it. The scene chooses and culls
// tiles as for the 3D view (screen-bounded: coarse tiles far away, leaves near), so the shapes a
// frame holds follow the screen, not the city.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "qv/scene/Palette.h"
#include "qv/scene/RenderDevice.h"

namespace qv {

/// One frame of the 2D map, as the page reads it from the engine's memory (qv_map2d): `data` holds,
/// per shape, its colour (0xRRGGBB as a float, exact), its point count n, then n (x, y) pairs in CSS
/// pixels from the canvas's top-left corner. n = 1: a building under about two pixels, drawn as a
/// dot; n >= 3: a footprint ring (the outer ring of each part).
struct Map2dFrame {
  std::vector<float> data;
  std::uint32_t shapes = 0;
  std::uint32_t points = 0;
  void clear() {
    data.clear();
    shapes = 0;
    points = 0;
  }
};

/// The colour of a building from its row of the building table in `mode` at scene time `t`, as the
/// vertex and fragment shaders give it (the C++ mirror of render/src/Shaders.cpp): `series` the
/// series table's codes, `floors` its floor rows when it is animated floor by floor (else empty).
/// Dimmed buildings fade to kDimmedColor, the selected one towards kSelectedColor.
Rgb buildingRowColor(const BuildingGpuRecord& row, ColorMode mode, double t, std::span<const std::uint8_t> series,
                     std::span<const FloorGpuRecord> floors);

/// 0xRRGGBB of a colour (each channel clamped to [0, 1]).
std::uint32_t packRgb(Rgb color);

}  // namespace qv
