#include "qv/anim/HistorySampling.h"

#include <algorithm>

namespace qv {

HistoryTap historyTap(float startSeconds, float sampleRateHz, std::uint32_t sampleCount, double t) {
  const double position =
      std::clamp((t - static_cast<double>(startSeconds)) * sampleRateHz, 0.0, static_cast<double>(sampleCount - 1));
  HistoryTap tap;
  tap.i1 = static_cast<std::uint32_t>(position);
  const std::uint32_t last = sampleCount - 1;
  tap.i0 = tap.i1 > 0 ? tap.i1 - 1 : 0;
  tap.i2 = std::min(tap.i1 + 1, last);
  tap.i3 = std::min(tap.i1 + 2, last);
  // Uniform Catmull-Rom weights (the cubic through the four nearest samples' tangents): with 8
  // samples a period it stays within 1 % of a sinusoid, where straight lines need 25.
  const auto u = static_cast<float>(position - tap.i1);
  const float u2 = u * u, u3 = u2 * u;
  tap.w0 = 0.5f * (-u3 + 2.0f * u2 - u);
  tap.w1 = 0.5f * (3.0f * u3 - 5.0f * u2 + 2.0f);
  tap.w2 = 0.5f * (-3.0f * u3 + 4.0f * u2 + u);
  tap.w3 = 0.5f * (u3 - u2);
  return tap;
}

void modalCoordinates(const std::int16_t* coordinates, std::size_t rowStride, const float* scales,
                      const HistoryTap& tap, float* out, std::size_t modes) {
  if (modes == SIZE_MAX) modes = rowStride;
  const std::int16_t* q0 = coordinates + std::size_t{tap.i0} * rowStride;
  const std::int16_t* q1 = coordinates + std::size_t{tap.i1} * rowStride;
  const std::int16_t* q2 = coordinates + std::size_t{tap.i2} * rowStride;
  const std::int16_t* q3 = coordinates + std::size_t{tap.i3} * rowStride;
  for (std::size_t k = 0; k < std::min(modes, kMaxHistoryModes); ++k) {
    out[k] = (tap.w0 * static_cast<float>(q0[k]) + tap.w1 * static_cast<float>(q1[k]) +
              tap.w2 * static_cast<float>(q2[k]) + tap.w3 * static_cast<float>(q3[k])) *
             scales[k];
  }
}

void windowedModalCoordinates(const HistoryStream& h, double timeSeconds, SampleWindow& w, float* out) {
  if (h.sampleCount == 0) return;
  constexpr std::size_t kRow = kMaxHistoryModes;
  const HistoryTap tap = historyTap(h.startSeconds, h.sampleRateHz, h.sampleCount, timeSeconds);
  const std::uint32_t wanted[4] = {tap.i0, tap.i1, tap.i2, tap.i3};
  if (!std::equal(wanted, wanted + 4, w.samples)) {
    // Samples the window holds are moved, the others read (the one cache miss per new sample;
    // WebAssembly has no prefetch, the short loop lets the processor overlap the misses).
    SampleWindow fresh;
    for (std::size_t slot = 0; slot < 4; ++slot) {
      const std::uint32_t i = wanted[slot];
      const auto kept = std::find(w.samples, w.samples + 4, i);
      if (kept != w.samples + 4) {
        const auto from = static_cast<std::size_t>(kept - w.samples);
        std::copy_n(w.x + from * kRow, kRow, fresh.x + slot * kRow);
        std::copy_n(w.y + from * kRow, kRow, fresh.y + slot * kRow);
      } else {
        std::copy_n(h.x + std::size_t{i} * h.modesX, h.modesX, fresh.x + slot * kRow);
        std::copy_n(h.y + std::size_t{i} * h.modesY, h.modesY, fresh.y + slot * kRow);
      }
      fresh.samples[slot] = i;
    }
    w = fresh;
  }
  const HistoryTap local{0, 1, 2, 3, tap.w0, tap.w1, tap.w2, tap.w3};  // the window's rows
  modalCoordinates(w.x, kRow, h.scalesX, local, out, h.modesX);
  modalCoordinates(w.y, kRow, h.scalesY, local, out + kRow, h.modesY);
}

}  // namespace qv
