// History sampling: a compact response history (per direction, modal coordinates sampled at a
// fixed rate, stored as 8- or 16-bit integers with a scale per mode; HistoryDirection in
// qv/format/ResponseTile.h) read at any time t by uniform Catmull-Rom interpolation.
//
// `historyTap` says which four samples t needs and their weights; `modalCoordinates` applies them
// to one direction; `SampleWindow` keeps one building's four samples between frames, since t moves
// by a fraction of a sample per frame and most frames can reuse them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace qv {

/// Modes per direction a history may hold (the format's limit).
constexpr std::size_t kMaxHistoryModes = 8;

/// Where time t falls in a history: the four samples around it and their Catmull-Rom weights.
struct HistoryTap {
  std::uint32_t i0 = 0, i1 = 0, i2 = 0, i3 = 0;
  float w0 = 0.0f, w1 = 0.0f, w2 = 0.0f, w3 = 0.0f;
};

/// Samples are at t = startSeconds + i / sampleRateHz, i = 0 .. sampleCount - 1; times before
/// the first sample hold it, times after the last hold the last. Requires sampleCount > 0.
HistoryTap historyTap(float startSeconds, float sampleRateHz, std::uint32_t sampleCount, double timeSeconds);

/// The modal coordinates of one direction at a tap (scaled to metres per unit shape): reads
/// `coordinates` (time-major, sample i's row at i * rowStride) and `scales`, and writes `modes`
/// values (at most kMaxHistoryModes; more are ignored) to `out`. `modes` defaults to rowStride.
void modalCoordinates(const std::int16_t* coordinates, std::size_t rowStride, const float* scales,
                      const HistoryTap& tap, float* out, std::size_t modes = SIZE_MAX);

/// One building's history as the frame loop samples it: pointers into the decoded history, which
/// the caller keeps alive while it samples.
struct HistoryStream {
  const std::int16_t* x = nullptr;  ///< coordinates, time-major, modesX per sample
  const std::int16_t* y = nullptr;  ///< coordinates, time-major, modesY per sample
  const float* scalesX = nullptr;   ///< modesX values
  const float* scalesY = nullptr;   ///< modesY values
  float startSeconds = 0.0f;
  float sampleRateHz = 0.0f;
  std::uint32_t sampleCount = 0;        ///< 0: no motion (sampling writes nothing)
  std::uint8_t modesX = 0, modesY = 0;  ///< each at most kMaxHistoryModes
};

/// The four samples one building last interpolated (rows of kMaxHistoryModes, x and y). A fresh
/// window holds none.
struct SampleWindow {
  std::uint32_t samples[4] = {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX};
  std::int16_t x[4 * kMaxHistoryModes] = {};
  std::int16_t y[4 * kMaxHistoryModes] = {};
};

/// The modal coordinates of `history` at time t: kMaxHistoryModes values of x, then of y, to
/// `out` (2 * kMaxHistoryModes floats; entries beyond modesX / modesY are left as they are).
/// Reads from the history only the samples `window` does not already hold, and updates it. The
/// result equals modalCoordinates on the full history. Does nothing when sampleCount is 0.
void windowedModalCoordinates(const HistoryStream& history, double timeSeconds, SampleWindow& window, float* out);

}  // namespace qv
