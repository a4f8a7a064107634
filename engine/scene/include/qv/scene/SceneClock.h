// SceneClock: the time the scene reads, injected so tests advance it instead of sleeping.
//
// The scene reads it for retry backoff (when a failed file may be fetched again), for the frame
// interval that widens the decode budget, and to measure its own work per frame. `SteadyClock`
// reads std::chrono::steady_clock (the viewer); `FakeClock` only moves when told to (tests,
// deterministic benchmarks).
#pragma once

namespace qv {

class SceneClock {
 public:
  virtual ~SceneClock() = default;
  /// Monotonic seconds since an arbitrary epoch (never decreasing).
  [[nodiscard]] virtual double nowSeconds() const = 0;
};

class SteadyClock final : public SceneClock {
 public:
  [[nodiscard]] double nowSeconds() const override;
};

/// The process-wide steady clock, for callers that inject none.
SceneClock& steadyClock();

class FakeClock final : public SceneClock {
 public:
  [[nodiscard]] double nowSeconds() const override { return nowSeconds_; }
  /// Moves time forward by `seconds` (>= 0).
  void advance(double seconds) { nowSeconds_ += seconds; }

 private:
  double nowSeconds_ = 0.0;
};

}  // namespace qv
