// GroundMotion: one horizontal component of an earthquake acceleration record.
//
// Units: metres per second squared (records in g are converted with g = 9.81 m/s², the convention
// of the project's published oracle, Chopra Example 13.2.6).
//
// Time convention (docs/seismic.md): a record of N samples at step dt is applied as a(0) = 0 and
// a(k·dt) = sample k for k = 1..N, linear in between, and a((N+1)·dt) = 0 with zero after that (the
// leading zero of Chopra's and OpenSees' examples, and a trailing zero so the end of the record
// releases the building into free vibration instead of a step). Before t = 0 the ground is at rest.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace qv::seismic {

/// Standard gravity used for every g conversion in the library (the oracle's convention).
inline constexpr double kGravityMps2 = 9.81;

enum class AccelerationUnit { G, MetresPerSecond2, CentimetresPerSecond2 };

/// Metres per second squared per unit: 9.81 for g, 1 for m/s², 0.01 for cm/s².
double metresPerSecond2Per(AccelerationUnit unit);
/// "g", "m/s2", "cm/s2".
std::string_view accelerationUnitName(AccelerationUnit unit);
/// Accepts "g", "m/s2" (also "m/s^2", "mps2") and "cm/s2" (also "cm/s^2", "gal"); nullopt otherwise.
std::optional<AccelerationUnit> parseAccelerationUnit(std::string_view text);

struct GroundMotion {
  std::string name;                      ///< file name or "synthetic (seed 7)"; used in messages
  double timeStepS = 0.0;                ///< dt > 0
  std::vector<double> accelerationMps2;  ///< sample k (0-based) applies at t = (k + 1)·dt

  [[nodiscard]] std::size_t size() const { return accelerationMps2.size(); }
  /// N·dt: the time of the last sample.
  [[nodiscard]] double durationS() const { return timeStepS * static_cast<double>(size()); }
  /// a(t) under the time convention above (0 for t <= 0 and t >= (N+1)·dt).
  [[nodiscard]] double accelerationAt(double timeS) const;
  /// Largest |sample| in m/s² (0 for an empty record).
  [[nodiscard]] double peakAbsMps2() const;
  /// 0-based index of the largest |sample| (0 for an empty record).
  [[nodiscard]] std::size_t peakIndex() const;
};

}  // namespace qv::seismic
