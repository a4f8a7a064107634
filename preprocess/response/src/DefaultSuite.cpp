#include "qv/prep/DefaultSuite.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include <unsupported/Eigen/FFT>

#include "qv/core/NumberFormat.h"

namespace qv::prep {
namespace {

bool finitePositive(double v) {
  return std::isfinite(v) && v > 0.0;
}

// Linear interpolation of `values` at `at` between the ascending `points`, the end values beyond.
double interpolate(const std::vector<double>& points, const std::vector<double>& values, double at) {
  if (at <= points.front()) return values.front();
  if (at >= points.back()) return values.back();
  const auto upper = static_cast<std::size_t>(std::upper_bound(points.begin(), points.end(), at) - points.begin());
  const double w = (at - points[upper - 1]) / (points[upper] - points[upper - 1]);
  return values[upper - 1] + w * (values[upper] - values[upper - 1]);
}

// Zero ground velocity at the end: remove the multiple of the envelope that carries the motion's
// net velocity (dt·Σ a), as the synthetic generator does, so the start stays at rest.
void correctBaseline(std::vector<double>& a, const seismic::SyntheticMotionParameters& p) {
  double sumA = 0.0, sumE = 0.0;
  std::vector<double> envelope(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    envelope[k] = seismic::syntheticEnvelope(p, static_cast<double>(k + 1) * p.timeStepS);
    sumA += a[k];
    sumE += envelope[k];
  }
  const double shift = sumE > 0.0 ? sumA / sumE : 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) a[k] -= shift * envelope[k];
}

}  // namespace

double TargetSpectrum::at(double periodS) const {
  if (periodsS.empty() || !finitePositive(periodS)) return std::nan("");
  std::vector<double> lnT(periodsS.size()), lnSa(saG.size());
  for (std::size_t i = 0; i < periodsS.size(); ++i) {
    lnT[i] = std::log(periodsS[i]);
    lnSa[i] = std::log(saG[i]);
  }
  return std::exp(interpolate(lnT, lnSa, std::log(periodS)));
}

Result<seismic::GroundMotion> matchSyntheticMotion(const seismic::GroundMotion& seedMotion,
                                                   const seismic::SyntheticMotionParameters& parameters,
                                                   const TargetSpectrum& target, const SpectrumMatchOptions& options,
                                                   SpectrumMatchReport* report) {
  if (target.periodsS.empty() || target.periodsS.size() != target.saG.size())
    return Error{"spectrum matching: the target spectrum has no points"};
  for (std::size_t i = 0; i < target.periodsS.size(); ++i) {
    if (!finitePositive(target.periodsS[i]) || !finitePositive(target.saG[i]) ||
        (i > 0 && !(target.periodsS[i] > target.periodsS[i - 1])))
      return Error{"spectrum matching: target point " + std::to_string(i) + " (" + formatDouble(target.periodsS[i]) +
                   " s, " + formatDouble(target.saG[i]) + " g) is not a positive ascending period with Sa > 0"};
  }
  if (seedMotion.accelerationMps2.empty() || !finitePositive(seedMotion.timeStepS))
    return Error{"spectrum matching: the seed motion has no samples"};
  if (!(options.controlPeriods >= 2 && finitePositive(options.minPeriodS) && options.maxPeriodS > options.minPeriodS))
    return Error{"spectrum matching: the control periods need 0 < minPeriodS < maxPeriodS and at least 2 periods"};

  const std::size_t n = seedMotion.accelerationMps2.size();
  const double dt = seedMotion.timeStepS;
  std::vector<double> lnT(static_cast<std::size_t>(options.controlPeriods));
  std::vector<double> targetSa(lnT.size());
  for (std::size_t j = 0; j < lnT.size(); ++j) {
    lnT[j] = std::log(options.minPeriodS) + std::log(options.maxPeriodS / options.minPeriodS) * static_cast<double>(j) /
                                                static_cast<double>(lnT.size() - 1);
    targetSa[j] = target.at(std::exp(lnT[j]));
  }
  // Zero-padded to at least twice the record (a power of two), so the amplitude adjustments,
  // smooth in frequency, spread little motion past the record's end.
  std::size_t fftSize = 1;
  while (fftSize < 2 * n) fftSize *= 2;
  Eigen::FFT<double> fft;
  std::vector<double> signal(fftSize, 0.0);
  std::vector<std::complex<double>> spectrum;
  std::vector<double> lnRatio(lnT.size());

  seismic::GroundMotion motion = seedMotion;
  // The iterations do not always improve monotonically (the record's end cuts what an adjustment
  // spreads beyond it): the best motion seen is kept.
  seismic::GroundMotion best;
  SpectrumMatchReport done;
  done.worstMisfit = std::numeric_limits<double>::infinity();
  for (int iteration = 0;; ++iteration) {
    double worst = 0.0;
    for (std::size_t j = 0; j < lnT.size(); ++j) {
      const double sa = seismic::pseudoSpectralAccelerationG(motion, std::exp(lnT[j]), options.dampingRatio);
      if (!finitePositive(sa))
        return Error{"spectrum matching: the motion has no response at " + formatDouble(std::exp(lnT[j])) + " s"};
      worst = std::max(worst, std::abs(sa / targetSa[j] - 1.0));
      lnRatio[j] = std::log(targetSa[j] / sa);
    }
    if (worst < done.worstMisfit) {
      done = {iteration, worst};
      best = motion;
    }
    if (worst <= options.tolerance || iteration >= options.maxIterations) break;
    std::fill(signal.begin(), signal.end(), 0.0);
    std::copy(motion.accelerationMps2.begin(), motion.accelerationMps2.end(), signal.begin());
    fft.fwd(spectrum, signal);
    for (std::size_t k = 1; k <= fftSize / 2; ++k) {
      const double periodS = static_cast<double>(fftSize) * dt / static_cast<double>(k);
      // The ratio's ln, linear in ln T between control periods, the end values beyond them.
      const double factor = std::exp(interpolate(lnT, lnRatio, std::log(periodS)));
      spectrum[k] *= factor;
      if (k != fftSize - k) spectrum[fftSize - k] *= factor;
    }
    fft.inv(signal, spectrum);
    std::copy(signal.begin(), signal.begin() + static_cast<std::ptrdiff_t>(n), motion.accelerationMps2.begin());
    correctBaseline(motion.accelerationMps2, parameters);
  }
  if (report) *report = done;
  best.name = seedMotion.name + ", spectrum-matched";
  return best;
}

SiteShape shakeMapSiteShape(const seismic::SpectralOrdinates& site) {
  auto step = [](double ratio) { return static_cast<int>(std::lround(std::log(ratio) / kShakeMapShapeStep)); };
  return SiteShape{SiteShape::Kind::ShakeMap,
                   {step(site.psa03G / site.pgaG), step(site.psa10G / site.psa03G), step(site.psa30G / site.psa10G)}};
}

SiteShape scenarioSiteShape(double distanceKm) {
  const double d = std::max(0.1, std::isfinite(distanceKm) ? distanceKm : 0.1);
  return SiteShape{SiteShape::Kind::Scenario,
                   {static_cast<int>(std::lround(std::log(d) / kScenarioDistanceStep)), 0, 0}};
}

TargetSpectrum shapeTarget(const SiteShape& shape, const seismic::Scenario* scenario) {
  constexpr double kPga = 0.35;
  constexpr int kPoints = 160;  // 0.01 .. 20 s
  TargetSpectrum t;
  seismic::SpectralOrdinates site{kPga, 0, 0, 0};
  site.psa03G = kPga * std::exp(shape.key[0] * kShakeMapShapeStep);
  site.psa10G = site.psa03G * std::exp(shape.key[1] * kShakeMapShapeStep);
  site.psa30G = site.psa10G * std::exp(shape.key[2] * kShakeMapShapeStep);
  const double distanceKm = std::exp(shape.key[0] * kScenarioDistanceStep);
  const bool scenarioShape = shape.kind == SiteShape::Kind::Scenario && scenario != nullptr;
  const double scenarioPga = scenarioShape
                                 ? seismic::bssa14MedianPsaG(0.0, scenario->magnitude, distanceKm,
                                                             scenario->vs30MetresPerSecond, scenario->mechanism)
                                 : 1.0;
  for (int i = 0; i < kPoints; ++i) {
    const double periodS = 0.01 * std::pow(2000.0, static_cast<double>(i) / (kPoints - 1));
    t.periodsS.push_back(periodS);
    t.saG.push_back(scenarioShape ? kPga *
                                        seismic::bssa14MedianPsaG(periodS, scenario->magnitude, distanceKm,
                                                                  scenario->vs30MetresPerSecond, scenario->mechanism) /
                                        scenarioPga
                                  : seismic::shakeMapTargetSaG(site, periodS));
  }
  return t;
}

Result<DefaultSuiteRecord> defaultSuiteRecord(std::uint64_t seed, const TargetSpectrum& target,
                                              const SpectrumMatchOptions& options) {
  seismic::SyntheticMotionParameters p;
  p.seed = seed;
  p.peakGroundAccelerationG = target.at(0.01);
  auto pair = seismic::generateSyntheticPair(p);
  if (!pair.ok()) return Error{pair.error()};
  DefaultSuiteRecord r;
  r.seed = seed;
  auto x = matchSyntheticMotion(pair->first, p, target, options, &r.matchX);
  if (!x.ok()) return Error{x.error()};
  auto y = matchSyntheticMotion(pair->second, p, target, options, &r.matchY);
  if (!y.ok()) return Error{y.error()};
  r.x = std::move(x).value();
  r.y = std::move(y).value();
  return r;
}

Result<std::vector<DefaultSuiteRecord>> defaultSuiteFor(const SiteShape& shape, const seismic::Scenario* scenario,
                                                        const SpectrumMatchOptions& options) {
  const TargetSpectrum target = shapeTarget(shape, scenario);
  std::vector<DefaultSuiteRecord> suite;
  for (const std::uint64_t seed : kDefaultSuiteSeeds) {
    auto r = defaultSuiteRecord(seed, target, options);
    if (!r.ok()) return Error{r.error()};
    suite.push_back(std::move(r).value());
  }
  return suite;
}

}  // namespace qv::prep
