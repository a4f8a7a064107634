// The built-in default suite of `quakeview-prep response` (docs/seismic.md, "The default suite"):
// what a ShakeMap or a scenario is analysed under when the user gives no record.
//
//   - Site shapes. Sites whose target spectra have the same shape (within the quantisation below)
//     share one suite. A ShakeMap site's shape is its three ratios PSA03/PGA, PSA10/PSA03 and
//     PSA30/PSA10, each rounded to a multiple of kShakeMapShapeStep in ln; a scenario site's is its
//     distance, rounded to a multiple of kScenarioDistanceStep in ln (magnitude, Vs30 and mechanism
//     are the scenario's, the same everywhere). The class's target is the shape at the lattice
//     point (never an average over the city's sites), so it does not depend on which buildings a
//     run holds.
//   - Records. For each shape, kDefaultSuiteSeeds two-component synthetic records: the Kanai-Tajimi
//     motion of the seed (SyntheticMotion.h), its Fourier amplitudes then adjusted iteratively
//     until its 5 %-damped spectrum is within `tolerance` of the shape's target at every control
//     period (frequency-domain spectral matching, as in Gasparini & Vanmarcke 1976, SIMQKE). The
//     phases, and so the motion's build-up and decay in time, stay those of the seed's motion.
//   - Each record is then scaled per building and direction to the site's own target at T1 as any
//     suite is; the suite's mean spectrum follows the site's target between 0.2 T1 and 2 T1 to
//     within 10 % (tests/response/TestDefaultSuite.cpp, bench_default_suite).
//
// Units: periods in seconds, spectral accelerations in g, distances in km.
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <vector>

#include "qv/core/Result.h"
#include "qv/seismic/GroundMotion.h"
#include "qv/seismic/GroundMotionModel.h"
#include "qv/seismic/ResponseSpectrum.h"
#include "qv/seismic/SyntheticMotion.h"

namespace qv::prep {

/// The seeds of the default suite's records (each two components), in the order the suite lists
/// them. Named in the manifest's records as "built-in default suite: ...".
inline constexpr std::uint64_t kDefaultSuiteSeeds[] = {1, 2, 3, 4, 5};

/// A target 5 %-damped pseudo-acceleration spectrum given at points: linear in ln Sa vs ln T
/// between them, the end values beyond them.
struct TargetSpectrum {
  std::vector<double> periodsS;  ///< ascending, > 0
  std::vector<double> saG;       ///< > 0, one per period
  [[nodiscard]] double at(double periodS) const;
};

struct SpectrumMatchOptions {
  double minPeriodS = 0.02;  ///< control periods: log-uniform from here ...
  double maxPeriodS = 15.0;  ///< ... to here
  int controlPeriods = 56;
  int maxIterations = 30;
  double tolerance = 0.04;  ///< |Sa / target - 1| at every control period
  double dampingRatio = 0.05;
};

/// How a matched motion ended: the iterations taken and its worst |Sa / target - 1| over the
/// control periods.
struct SpectrumMatchReport {
  int iterations = 0;
  double worstMisfit = 0.0;
};

/// `seedMotion` (a component generated with `parameters`) matched to `target` as described above,
/// baseline corrected with the generator's envelope (zero ground velocity at the end). Its name
/// adds ", spectrum-matched". Errors: a seed without samples, a target without points or with a
/// period or value that is not finite and > 0 or periods not ascending, bad control periods.
Result<seismic::GroundMotion> matchSyntheticMotion(const seismic::GroundMotion& seedMotion,
                                                   const seismic::SyntheticMotionParameters& parameters,
                                                   const TargetSpectrum& target,
                                                   const SpectrumMatchOptions& options = {},
                                                   SpectrumMatchReport* report = nullptr);

/// The shape of a site's target, quantised (see above). Ordered, for maps.
struct SiteShape {
  enum class Kind : std::uint8_t { ShakeMap, Scenario };
  Kind kind = Kind::ShakeMap;
  std::array<int, 3> key{0, 0, 0};
  auto operator<=>(const SiteShape&) const = default;
};

inline constexpr double kShakeMapShapeStep = 0.04;    ///< ln of each ratio: 4 %, so 2 % at most off
inline constexpr double kScenarioDistanceStep = 0.1;  ///< ln of the distance: 10 %

/// A ShakeMap site's shape (every ordinate finite and > 0).
SiteShape shakeMapSiteShape(const seismic::SpectralOrdinates& site);
/// A scenario site's shape at `distanceKm` (clamped to >= 0.1 km).
SiteShape scenarioSiteShape(double distanceKm);

/// The shape's target, scaled to a PGA of 0.35 g, on a dense period grid (0.01 to 20 s): the
/// ShakeMap target function (shakeMapTargetSaG) of the lattice point's ordinates, or the scenario's
/// BSSA14 medians at the lattice point's distance (times its site factor).
TargetSpectrum shapeTarget(const SiteShape& shape, const seismic::Scenario* scenario);

/// One two-component record of the default suite for a shape.
struct DefaultSuiteRecord {
  std::uint64_t seed = 0;
  seismic::GroundMotion x, y;
  SpectrumMatchReport matchX, matchY;
};

/// The default suite for a shape: one record per kDefaultSuiteSeeds, in that order.
Result<std::vector<DefaultSuiteRecord>> defaultSuiteFor(const SiteShape& shape, const seismic::Scenario* scenario,
                                                        const SpectrumMatchOptions& options = {});

/// The same, one record (the seed's): for callers that spread the seeds over threads.
Result<DefaultSuiteRecord> defaultSuiteRecord(std::uint64_t seed, const TargetSpectrum& target,
                                              const SpectrumMatchOptions& options = {});

}  // namespace qv::prep
