// What the panels' cached picture (qv/quality/PanelCache.h) needs to know of a frame's ImGui draw
// data: a key that changes whenever anything drawn changes, and the screen rectangles of the
// windows, in framebuffer pixels from the top-left, in drawing order (bottom window first).
#pragma once

#include <cstdint>
#include <vector>

#include "qv/quality/PanelCache.h"

struct ImDrawData;

namespace qv::ui {

/// A 64-bit key of everything `data` draws: every vertex (position, texture coordinate, colour),
/// index and command (clip rectangle, texture, range). Equal keys mean the same picture (a
/// different picture gives the same key with a probability of about 2^-64).
[[nodiscard]] std::uint64_t drawDataKey(const ImDrawData& data);

/// Per draw list (one per window, plus ImGui's overlays), the pixels its triangles can touch: the
/// bounding box of its vertices within the union of its clip rectangles, scaled by the
/// framebuffer scale and rounded outwards. Lists that draw nothing are left out.
[[nodiscard]] std::vector<PixelRect> panelRects(const ImDrawData& data);

}  // namespace qv::ui
