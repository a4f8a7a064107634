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

/// A building's sway where its floors are not moved one by one (beyond the full-detail distance,
/// or not chosen for it): the picture of its motion its drift series gives, the C++ mirror of the
/// vertex shader's seriesSway. The roof moves gainM × drift in all (drift: seriesDriftAt's value
/// now; gainM: the building's peak roof displacement over its peak storey drift), split evenly
/// between X and Y (a drift series has no direction), each axis oscillating at its first-mode
/// period from the series' start; a point at `heightFraction` of the building's height (clamped to
/// [0, 1]) moves that fraction of the roof's (the first mode as a straight line). Zero before the
/// start, for a negative drift (no series), a gain of 0 or a non-positive period.
struct Sway {
  float dxMeters = 0.0f;
  float dyMeters = 0.0f;
};
[[nodiscard]] Sway seriesSwayAt(float drift, float gainM, float periodXS, float periodYS, float startSeconds, double t,
                                float heightFraction);

/// The gain seriesSwayAt takes for a building with these peaks (its summary's peak roof
/// displacement and peak storey drift ratio), at most 1.5 × its height: 0 without both peaks.
[[nodiscard]] float swayGainMeters(float peakRoofDisplacementM, float peakDriftRatio, float heightM);

/// A first-mode period for sway when the response does not store one (no spectral scaling): the
/// rule of thumb T = 0.1 s × storeys (at least 0.1 s).
[[nodiscard]] float estimatedPeriodS(float storeys);

/// The members' series merged: windows at `rateHz` from the earliest member's start to the latest
/// member's end, each the largest code any member has at that time (a member's window lands in the
/// merged window that holds its centre). Appends to `out` and returns the merged series' start
/// and count (base is out's size before, count 0 when no member has a series).
SeriesRef mergeSeries(std::span<const std::uint8_t> codes, std::span<const SeriesRef> members, float rateHz,
                      std::vector<std::uint8_t>& out);

}  // namespace qv
