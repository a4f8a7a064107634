// Reading a drift series (qv::DriftSeries: one byte a window, the largest storey drift in each
// window on a square-root scale) at a time: the C++ mirror of the building vertex shader's
// seriesDrift (engine/render/src/Shaders.cpp), and the merge of several buildings' series into one
// (a far-view block shows the worst of its members at each moment).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace qv {

/// One series in a table of codes: codes[base .. base + count) at `rateHz` windows a second from
/// `startSeconds`; code c means the drift fullScale (c / 255)^2.
struct SeriesRef {
  std::int64_t base = -1;  ///< -1: no series
  float startSeconds = 0.0f;
  std::uint32_t count = 0;
  float rateHz = 0.0f;
};

/// The drift at time t: 0 before the start; the windows' values at their centres, linear in
/// between (the first window's before its centre, the last one's after its centre); -1 without a
/// series (or one outside `codes`).
[[nodiscard]] float seriesDriftAt(std::span<const std::uint8_t> codes, const SeriesRef& series, float fullScale,
                                  double t);

/// The members' series merged: windows at `rateHz` from the earliest member's start to the latest
/// member's end, each the largest code any member has at that time (a member's window lands in the
/// merged window that holds its centre). Appends to `out` and returns the merged series' start
/// and count (base is out's size before, count 0 when no member has a series).
SeriesRef mergeSeries(std::span<const std::uint8_t> codes, std::span<const SeriesRef> members, float rateHz,
                      std::vector<std::uint8_t>& out);

}  // namespace qv
