// Consistency and equality of decoded response tiles (what the viewer indexes without checking).
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "FuzzSupport.h"
#include "qv/format/ResponseTile.h"

namespace qv::fuzz {

inline void checkSummaryConsistent(const ResponseSummaryTile& t) {
  for (const BuildingResponse& b : t.buildings) {
    check(std::size_t{b.firstStorey} + b.storeys <= t.storeyPeakDrift.size(), "storey range out of bounds");
  }
  check(t.odds.empty() || t.odds.size() == t.buildings.size(), "drawing probabilities not one per building");
  for (const BuildingDamageOdds& o : t.odds) {
    for (const float p : o.atLeast) check(std::isfinite(p) && p >= 0.0f && p <= 1.0f, "a probability out of [0, 1]");
  }
}

inline void checkSameSummary(const ResponseSummaryTile& a, const ResponseSummaryTile& b) {
  check(a.buildings.size() == b.buildings.size() && a.storeyPeakDrift == b.storeyPeakDrift,
        "round trip changed the summary");
  for (std::size_t i = 0; i < a.buildings.size(); ++i) {
    const BuildingResponse& p = a.buildings[i];
    const BuildingResponse& q = b.buildings[i];
    check(p.damage == q.damage && p.source == q.source && p.storeys == q.storeys &&
              p.peakDriftRatio == q.peakDriftRatio && p.peakRoofDisplacementM == q.peakRoofDisplacementM &&
              p.pgaG == q.pgaG && p.peakFloorAccelerationMs2 == q.peakFloorAccelerationMs2 &&
              p.residualDriftRatio == q.residualDriftRatio && p.firstStorey == q.firstStorey,
          "round trip changed a building's summary");
  }
  // The optional sections (spectral scaling, suite spread, HAZUS losses, drawing probabilities) survive too.
  check(a.scaling == b.scaling && a.spread == b.spread && a.storeySpread == b.storeySpread && a.losses == b.losses &&
            a.odds == b.odds,
        "round trip changed an optional section");
}

/// Samples every history at a few times (the viewer's use): must stay in bounds and finite.
inline void checkHistoryUsable(const ResponseHistoryTile& t) {
  for (const BuildingHistory& h : t.buildings) {
    if (h.floors == 0) continue;
    for (const HistoryDirection* d : {&h.x, &h.y}) {
      check(d->shapes.size() == std::size_t{h.floors} * d->modes && d->scales.size() == d->modes &&
                d->coordinates.size() == std::size_t{d->modes} * h.sampleCount,
            "history arrays do not match their counts");
    }
    std::vector<float> x(std::size_t{h.floors} + 1), y(std::size_t{h.floors} + 1);
    for (double time : {-1.0, 0.0, 0.37, static_cast<double>(h.startSeconds) + 1.5, 1.0e6}) {
      sampleHistory(h, time, x, y);
    }
  }
}

inline void checkSameHistory(const ResponseHistoryTile& a, const ResponseHistoryTile& b) {
  check(a.durationSeconds == b.durationSeconds && a.buildings.size() == b.buildings.size(),
        "round trip changed the history tile");
  for (std::size_t i = 0; i < a.buildings.size(); ++i) {
    const BuildingHistory& p = a.buildings[i];
    const BuildingHistory& q = b.buildings[i];
    check(p.floors == q.floors, "round trip changed the floors");
    if (p.floors == 0) continue;
    check(p.sampleRateHz == q.sampleRateHz && p.startSeconds == q.startSeconds && p.sampleCount == q.sampleCount &&
              p.bits == q.bits,
          "round trip changed the sampling");
    for (const auto& [d, e] : {std::pair{&p.x, &q.x}, std::pair{&p.y, &q.y}}) {
      check(d->modes == e->modes && d->shapes == e->shapes && d->scales == e->scales &&
                d->coordinates.size() == e->coordinates.size(),
            "round trip changed a history");
      for (std::size_t k = 0; k < d->coordinates.size(); ++k) {
        // The 8-bit encoding writes -127..127, while the decoder also reads -128 (reported to the
        // codec's owner); that one value comes back as -127.
        const bool clampedByEncoder = p.bits == 8 && d->coordinates[k] == -128 && e->coordinates[k] == -127;
        check(d->coordinates[k] == e->coordinates[k] || clampedByEncoder, "round trip changed a coordinate");
      }
    }
  }
}

}  // namespace qv::fuzz
