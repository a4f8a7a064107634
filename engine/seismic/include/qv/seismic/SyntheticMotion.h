// Synthetic ground motion for the embedded default scenario: Kanai–Tajimi filtered white noise under
// a Jennings-type time envelope, baseline-corrected (zero final ground velocity) and scaled to a
// target peak ground acceleration.
//
// Deterministic on every compiler and target: the library's own PRNG (xoshiro256** seeded by
// splitmix64), Box–Muller with its own logarithm and sine/cosine built from + - * / only, and a
// filter integrated with pure arithmetic; the file is compiled without floating-point contraction.
// The same seed gives bit-identical samples natively and in WebAssembly (a test pins a hash).
//
// Sources: Kanai (1957) and Tajimi (1960) for the ground filter (firm ground: ωg = 15.6 rad/s,
// ζg = 0.6); Jennings, Housner & Tsai (1968) for the envelope shape (quadratic rise, plateau,
// exponential decay). Parameter defaults are documented in docs/seismic.md.
#pragma once

#include <cstdint>
#include <utility>

#include "qv/core/Result.h"
#include "qv/seismic/GroundMotion.h"

namespace qv::seismic {

struct SyntheticMotionParameters {
  std::uint64_t seed = 1;
  double peakGroundAccelerationG = 0.3;  ///< target |a|max in g (> 0, <= 5)
  double durationS = 30.0;               ///< record length (>= 1 s, <= 600 s)
  double timeStepS = 0.01;               ///< sample step (0.001 .. 0.1 s)
  double groundFrequencyHz = 2.5;        ///< Kanai–Tajimi ωg / 2π (0.1 .. 20 Hz)
  double groundDampingRatio = 0.6;       ///< Kanai–Tajimi ζg (0.05 .. 2)
  /// Envelope: (t/rise)² until `riseFraction`·duration, 1 until `plateauEndFraction`·duration, then
  /// exp(-c (t - t2)) with c chosen so the envelope is 5 % at the end of the record.
  double riseFraction = 0.1;
  double plateauEndFraction = 0.4;
};

/// One component. Errors name the parameter that is out of range.
Result<GroundMotion> generateSyntheticMotion(const SyntheticMotionParameters& parameters);

/// Two horizontal components from one seed: X uses `seed`, Y a different stream derived from it.
Result<std::pair<GroundMotion, GroundMotion>> generateSyntheticPair(const SyntheticMotionParameters& parameters);

/// Envelope value e(t) in [0, 1] of `parameters` (exposed for tests).
double syntheticEnvelope(const SyntheticMotionParameters& parameters, double timeS);

}  // namespace qv::seismic
