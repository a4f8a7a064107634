#include "qv/anim/SeriesSampling.h"

#include <algorithm>
#include <cmath>

namespace qv {
namespace {

bool valid(std::span<const std::uint8_t> codes, const SeriesRef& s) {
  return s.base >= 0 && s.count > 0 && s.rateHz > 0.0f && static_cast<std::uint64_t>(s.base) + s.count <= codes.size();
}

}  // namespace

float seriesDriftAt(std::span<const std::uint8_t> codes, const SeriesRef& s, float fullScale, double t) {
  if (!valid(codes, s)) return -1.0f;
  if (t < static_cast<double>(s.startSeconds)) return 0.0f;
  const double last = static_cast<double>(s.count) - 1.0;
  const double u = std::clamp((t - static_cast<double>(s.startSeconds)) * s.rateHz - 0.5, 0.0, last);
  const double i0 = std::floor(u);
  const auto at = [&](double i) {
    const double c = codes[static_cast<std::size_t>(s.base + static_cast<std::int64_t>(i))] / 255.0;
    return c * c;
  };
  const double a = at(i0), b = at(std::min(i0 + 1.0, last));
  return static_cast<float>(fullScale * (a + (b - a) * (u - i0)));
}

Sway seriesSwayAt(float drift, float gainM, float periodXS, float periodYS, float startSeconds, double t,
                  float heightFraction) {
  if (!(drift > 0.0f) || !(gainM > 0.0f) || !(periodXS > 0.0f) || !(periodYS > 0.0f)) return {};
  const double since = t - static_cast<double>(startSeconds);
  if (!(since >= 0.0)) return {};
  constexpr double kTwoPi = 6.283185307179586;
  const double roof = static_cast<double>(gainM) * drift * std::clamp(static_cast<double>(heightFraction), 0.0, 1.0) *
                      0.7071067811865476;
  return {static_cast<float>(roof * std::sin(kTwoPi * since / periodXS)),
          static_cast<float>(roof * std::sin(kTwoPi * since / periodYS))};
}

float swayGainMeters(float peakRoofDisplacementM, float peakDriftRatio, float heightM) {
  if (!(peakRoofDisplacementM > 0.0f) || !(peakDriftRatio > 0.0f) || !(heightM > 0.0f)) return 0.0f;
  return std::min(peakRoofDisplacementM / peakDriftRatio, 1.5f * heightM);
}

float estimatedPeriodS(float storeys) {
  return std::max(0.1f, 0.1f * (std::isfinite(storeys) ? storeys : 1.0f));
}

SeriesRef mergeSeries(std::span<const std::uint8_t> codes, std::span<const SeriesRef> members, float rateHz,
                      std::vector<std::uint8_t>& out) {
  SeriesRef merged;
  merged.rateHz = rateHz;
  merged.base = static_cast<std::int64_t>(out.size());
  if (!(rateHz > 0.0f)) return merged;
  double start = INFINITY, end = -INFINITY;
  for (const SeriesRef& m : members) {
    if (!valid(codes, m)) continue;
    start = std::min(start, static_cast<double>(m.startSeconds));
    end = std::max(end, static_cast<double>(m.startSeconds) + static_cast<double>(m.count) / m.rateHz);
  }
  if (!(end > start)) return merged;
  merged.startSeconds = static_cast<float>(start);
  const double windows = std::ceil((end - start) * rateHz - 1e-6);
  merged.count = static_cast<std::uint32_t>(std::clamp(windows, 1.0, 1e7));
  out.resize(out.size() + merged.count, 0);
  std::uint8_t* into = out.data() + merged.base;
  for (const SeriesRef& m : members) {
    if (!valid(codes, m)) continue;
    for (std::uint32_t i = 0; i < m.count; ++i) {
      const double centre = static_cast<double>(m.startSeconds) + (i + 0.5) / m.rateHz;
      const auto j = static_cast<std::int64_t>(std::floor((centre - start) * rateHz));
      if (j < 0 || j >= static_cast<std::int64_t>(merged.count)) continue;
      into[j] = std::max(into[j], codes[static_cast<std::size_t>(m.base) + i]);
    }
  }
  return merged;
}

}  // namespace qv
