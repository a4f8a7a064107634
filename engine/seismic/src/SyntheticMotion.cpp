#include "qv/seismic/SyntheticMotion.h"

#include <cmath>
#include <string>
#include <vector>

#include "DeterministicMath.h"
#include "qv/core/NumberFormat.h"

namespace qv::seismic {
namespace {

Status checkRange(const char* what, double value, double low, double high) {
  if (!(value >= low && value <= high)) {
    return fail(std::string("synthetic motion: ") + what + " must be in [" + formatDouble(low) + ", " +
                formatDouble(high) + "], not " + formatDouble(value));
  }
  return {};
}

Status validate(const SyntheticMotionParameters& p) {
  for (const Status& s :
       {checkRange("peakGroundAccelerationG", p.peakGroundAccelerationG, 1e-6, 5.0),
        checkRange("durationS", p.durationS, 1.0, 600.0), checkRange("timeStepS", p.timeStepS, 0.001, 0.1),
        checkRange("groundFrequencyHz", p.groundFrequencyHz, 0.1, 20.0),
        checkRange("groundDampingRatio", p.groundDampingRatio, 0.05, 2.0),
        checkRange("riseFraction", p.riseFraction, 0.01, 0.9),
        checkRange("plateauEndFraction", p.plateauEndFraction, p.riseFraction, 0.95)}) {
    if (!s) return s;
  }
  return {};
}

GroundMotion generate(const SyntheticMotionParameters& p, std::uint64_t streamSeed, const char* component) {
  const auto count = static_cast<std::size_t>(std::floor(p.durationS / p.timeStepS + 0.5));
  const double omega = detail::kTwoPi * p.groundFrequencyHz;
  const double damping = 2.0 * p.groundDampingRatio * omega;  // c of the unit-mass filter
  const double stiffness = omega * omega;                     // k of the unit-mass filter
  // The filter x'' + c x' + k x = -w(t), w piecewise constant per sample, integrated by Newmark's
  // average acceleration on four sub-steps per sample (pure arithmetic: reproducible). The ground
  // acceleration is the absolute acceleration of the filter mass, -(c x' + k x).
  constexpr int kSubsteps = 4;
  const double h = p.timeStepS / kSubsteps;
  const double effectiveStiffness = stiffness + 2.0 * damping / h + 4.0 / (h * h);
  detail::Xoshiro256 random(streamSeed);
  double x = 0.0;
  double v = 0.0;
  double w = random.normal();
  double a = -w;
  std::vector<double> samples(count);
  std::vector<double> envelope(count);
  for (std::size_t k = 0; k < count; ++k) {
    for (int s = 0; s < kSubsteps; ++s) {
      const double load = -w + (4.0 / (h * h) * x + 4.0 / h * v + a) + damping * (2.0 / h * x + v);
      const double xNew = load / effectiveStiffness;
      const double vNew = 2.0 / h * (xNew - x) - v;
      const double aNew = 4.0 / (h * h) * (xNew - x) - 4.0 / h * v - a;
      x = xNew;
      v = vNew;
      a = aNew;
    }
    const double t = static_cast<double>(k + 1) * p.timeStepS;
    envelope[k] = syntheticEnvelope(p, t);
    samples[k] = -(damping * v + stiffness * x) * envelope[k];
    w = random.normal();  // the next sample interval's noise
  }
  // Baseline correction: remove a multiple of the envelope so the ground velocity at the end
  // (dt·Σ samples under the piecewise-linear convention) is zero; the start stays at rest.
  double sumSamples = 0.0;
  double sumEnvelope = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    sumSamples += samples[k];
    sumEnvelope += envelope[k];
  }
  const double shift = sumEnvelope > 0.0 ? sumSamples / sumEnvelope : 0.0;
  double peak = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    samples[k] -= shift * envelope[k];
    peak = std::fmax(peak, std::fabs(samples[k]));
  }
  const double scale = peak > 0.0 ? p.peakGroundAccelerationG * kGravityMps2 / peak : 0.0;
  for (double& value : samples) value *= scale;

  GroundMotion motion;
  motion.name = "synthetic " + std::string(component) + " (seed " + std::to_string(p.seed) + ")";
  motion.timeStepS = p.timeStepS;
  motion.accelerationMps2 = std::move(samples);
  return motion;
}

constexpr std::uint64_t kSecondComponent = 0xD1B54A32D192ED03ull;

}  // namespace

double syntheticEnvelope(const SyntheticMotionParameters& p, double timeS) {
  const double rise = p.riseFraction * p.durationS;
  const double plateauEnd = p.plateauEndFraction * p.durationS;
  if (timeS <= 0.0) return 0.0;
  if (timeS < rise) {
    const double r = timeS / rise;
    return r * r;
  }
  if (timeS <= plateauEnd) return 1.0;
  // exp(-c (t - t2)) reaching 0.05 at the end: c = ln 20 / (duration - t2).
  const double decay = detail::deterministicLog(20.0) / (p.durationS - plateauEnd);
  return detail::deterministicExp(-decay * (timeS - plateauEnd));
}

Result<GroundMotion> generateSyntheticMotion(const SyntheticMotionParameters& parameters) {
  if (const Status s = validate(parameters); !s) return Error{s.error()};
  return generate(parameters, parameters.seed, "X");
}

Result<std::pair<GroundMotion, GroundMotion>> generateSyntheticPair(const SyntheticMotionParameters& parameters) {
  if (const Status s = validate(parameters); !s) return Error{s.error()};
  return std::make_pair(generate(parameters, parameters.seed, "X"),
                        generate(parameters, parameters.seed ^ kSecondComponent, "Y"));
}

}  // namespace qv::seismic
