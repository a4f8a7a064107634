// Response spectra and spectral scaling: the pseudo-spectral acceleration of a record at a period, a
// record's spectrum on a dense period grid for fast lookups, the spectral target of a ShakeMap node,
// and the scale that brings a record's Sa(T1) to a target (docs/spectral-scaling.md).
//
// Units: periods in seconds, spectral and peak accelerations in g (g = kGravityMps2 = 9.81 m/s², the
// library's convention), damping as a ratio of critical (0.05 = 5 %).
//
// SDOF solution: the exact recurrence for a linear oscillator under a piecewise-linear excitation
// (Nigam & Jennings 1969, "Calculation of response spectra from strong-motion earthquake records",
// BSSA 59(2); Chopra, Dynamics of Structures, §5.2 and Table 5.2.1). The record follows the time
// convention of GroundMotion.h (zero at t = 0, the samples at dt..N·dt, zero at (N+1)·dt and after),
// so the piecewise-linear input is the record itself, not an approximation of it.
#pragma once

#include <vector>

#include "qv/core/Result.h"
#include "qv/seismic/GroundMotion.h"
#include "qv/seismic/ShearBuilding.h"

namespace qv::seismic {

/// Pseudo-spectral acceleration (g) of `record` at `periodS`: ω²·max|u(t)| of the oscillator
/// ü + 2ζω u̇ + ω² u = -a_g(t), at rest at t = 0, ω = 2π / periodS, ζ = `dampingRatio`.
///   - Each record interval is cut into equal sub-steps of at most periodS / 20 (the recurrence is
///     exact on each); between sub-steps the peak is located on the cubic Hermite interpolant of
///     (u, u̇) at both ends whenever the velocity changes sign, so a peak between sub-steps is found
///     to within about 3e-5 relative (the interpolant's error at 20 steps a period, (2π/20)⁴/384).
///   - After the record (t > (N+1)·dt) the oscillator runs on in free vibration for one damped period
///     T_D = T / √(1 - ζ²): the free response's extrema come every T_D / 2 with decreasing
///     amplitude, so its largest value is reached within that time; long periods reach their peak.
/// Cost: (N + 1)·max(1, ⌈20·dt / T⌉) recurrence steps plus one damped period.
/// Returns 0 for a record without samples; NaN when periodS is not finite and > 0, dampingRatio is
/// not in [0, 1), or the record's time step is not finite and > 0.
double pseudoSpectralAccelerationG(const GroundMotion& record, double periodS, double dampingRatio = 0.05);

/// A record's pseudo-acceleration spectrum on a dense period grid, for fast lookups of many periods
/// (every building of a city, both directions, every record of a suite).
///   - Grid, adaptive: a base grid of kBasePointsPerDecade points per decade, uniform in ln T from
///     minPeriodS to maxPeriodS inclusive; every base interval bisected kMinRefinements times, and
///     again (up to kMaxRefinements times) wherever the exact Sa at the mid-point differs from the
///     log-log interpolation between the interval's ends by more than kRefineTolerance; then up to
///     kKinkPasses passes bisect every interval whose neighbours' log-log slopes differ by more than
///     it can follow (|s(i+1) - s(i-1)|·Δ ln T / 4 > kRefineTolerance). Why adaptive: a response
///     spectrum is the maximum over time of smooth functions of T, so it has V-shaped kinks wherever
///     the time of the peak jumps; slopes change there by up to ~10 in log-log, which a uniform grid
///     would need ~7 000 points per decade to follow to 0.1 % (measured: 500 per decade left 1.5 %).
///   - saG(T) interpolates linearly in ln Sa vs ln T between the two neighbouring grid periods.
///     Measured error against pseudoSpectralAccelerationG (El Centro 1940, Kobe Takatori and a
///     synthetic record, 20 000 log-uniform random periods each over 0.01..10 s): at most 0.046 %,
///     mean 0.003 %. Stated bound: kInterpolationErrorBound (0.1 %), which
///     tests/seismic/TestResponseSpectrum.cpp checks on El Centro and a synthetic record.
///   - Outside [minPeriodS, maxPeriodS] saG clamps: Sa(minPeriodS) below, Sa(maxPeriodS) above
///     (callers that need other periods compute a spectrum covering them).
/// Cost: about 1 800 to 2 200 exact evaluations for 0.01..10 s (0.1 to 0.2 s per record in an
/// optimized build on this project's 2-core machine); a lookup is a binary search.
class ResponseSpectrum {
 public:
  static constexpr int kBasePointsPerDecade = 100;
  static constexpr double kRefineTolerance = 5e-4;
  static constexpr int kMinRefinements = 1;
  static constexpr int kMaxRefinements = 8;
  static constexpr int kKinkPasses = 6;
  /// Relative error bound of saG against pseudoSpectralAccelerationG stated and tested above.
  static constexpr double kInterpolationErrorBound = 1e-3;

  /// Errors (naming the record): no samples, time step not finite and > 0, all-zero record,
  /// periods not 0.001 <= minPeriodS < maxPeriodS <= 1000 s (the cost of a period grows as
  /// dt / T below 20 dt), dampingRatio outside [0, 1).
  static Result<ResponseSpectrum> compute(const GroundMotion& record, double minPeriodS = 0.01,
                                          double maxPeriodS = 10.0, double dampingRatio = 0.05);

  /// Sa (g) at periodS, clamped to the grid's range as documented above; NaN when periodS is not
  /// finite and > 0.
  [[nodiscard]] double saG(double periodS) const;

  [[nodiscard]] double minPeriodS() const { return periodsS_.front(); }
  [[nodiscard]] double maxPeriodS() const { return periodsS_.back(); }
  [[nodiscard]] double dampingRatio() const { return dampingRatio_; }
  /// Grid periods (s), ascending, and Sa (g) at each.
  [[nodiscard]] const std::vector<double>& periodsS() const { return periodsS_; }
  [[nodiscard]] const std::vector<double>& saGValues() const { return saG_; }

 private:
  std::vector<double> periodsS_;
  std::vector<double> saG_;
  std::vector<double> lnPeriods_;
  std::vector<double> lnSaG_;
  double dampingRatio_ = 0.05;
};

/// ShakeMap spectral ordinates of a site (g, each finite and > 0): PGA and the 5 %-damped PSA at
/// 0.3, 1 and 3 s (ShakeMap's PSA03, PSA10, PSA30 grid fields).
struct SpectralOrdinates {
  double pgaG, psa03G, psa10G, psa30G;
};

/// Target Sa (g) at `periodS` from a ShakeMap node:
///   - T <= 0.03 s: PGA;
///   - 0.03..3 s: linear in ln Sa vs ln T through (0.03 s, PGA), (0.3 s, PSA03), (1 s, PSA10),
///     (3 s, PSA30);
///   - beyond 3 s, the long-period shape of ASCE 7-16 §11.4.6 (Fig. 11.4-1): Sa = PSA30·(3/T) up
///     to the long-period transition T_L, then PSA30·3·T_L / T² (constant spectral displacement).
///     T_L = 6 s is the ASCE 7-16 Fig. 22-14 value for New York. With T_L <= 3 s the 1/T² branch
///     starts at 3 s: PSA30·(3/T)².
/// NaN when periodS or longPeriodTransitionS is not finite and > 0, or an ordinate is not.
double shakeMapTargetSaG(const SpectralOrdinates& site, double periodS, double longPeriodTransitionS = 6.0);

/// The scale that brings a record whose Sa at the period is `recordSaG` to `targetSaG`.
struct SpectralScaling {
  double targetSaG;  ///< g
  double recordSaG;  ///< g, the unscaled record's Sa at the same period and damping
  double scale;      ///< targetSaG / recordSaG
};

/// Errors name the problem: a target or record Sa that is not finite and > 0.
Result<SpectralScaling> spectralScaling(double targetSaG, double recordSaAtPeriodG);

/// First-mode period T1 (s) of a shear building's initial system (computeModes' first period); the
/// error of validateShearBuilding / computeModes when the model is invalid.
Result<double> firstModePeriodS(const ShearBuilding& building);

}  // namespace qv::seismic
