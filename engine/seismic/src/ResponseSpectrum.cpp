#include "qv/seismic/ResponseSpectrum.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "qv/core/NumberFormat.h"

namespace qv::seismic {
namespace {

constexpr double kTwoPi = 6.283185307179586477;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Sub-steps per period: the recurrence is exact at any step; this only bounds how far apart the
// states are between which the Hermite interpolant locates a peak (its error is about
// (2π/20)⁴/384 ≈ 3e-5 of the amplitude at worst, and much less in practice).
constexpr double kSubStepsPerPeriod = 20.0;

bool finitePositive(double v) {
  return std::isfinite(v) && v > 0.0;
}

// Coefficients of the exact recurrence over a step h for unit mass (k = ω²) and a load p(t) linear
// over the step (Chopra, Table 5.2.1, ζ < 1):
//   u₁ = A u₀ + B v₀ + C p₀ + D p₁,   v₁ = A' u₀ + B' v₀ + C' p₀ + D' p₁.
struct Recurrence {
  double a, b, c, d, ap, bp, cp, dp;
};

Recurrence recurrence(double omega, double zeta, double h) {
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double omegaD = omega * root;
  const double k = omega * omega;
  const double e = std::exp(-zeta * omega * h);
  const double s = std::sin(omegaD * h);
  const double co = std::cos(omegaD * h);
  const double zr = zeta / root;
  Recurrence r{};
  r.a = e * (zr * s + co);
  r.b = e * (s / omegaD);
  r.c = (2.0 * zeta / (omega * h) +
         e * (((1.0 - 2.0 * zeta * zeta) / (omegaD * h) - zr) * s - (1.0 + 2.0 * zeta / (omega * h)) * co)) /
        k;
  r.d = (1.0 - 2.0 * zeta / (omega * h) +
         e * ((2.0 * zeta * zeta - 1.0) / (omegaD * h) * s + 2.0 * zeta / (omega * h) * co)) /
        k;
  r.ap = -e * (omega / root * s);
  r.bp = e * (co - zr * s);
  r.cp = (-1.0 / h + e * ((omega / root + zeta / (h * root)) * s + co / h)) / k;
  r.dp = (1.0 - e * (zr * s + co)) / (k * h);
  return r;
}

// Largest |u| on a step of length h whose end states are (u0, v0) and (u1, v1), when the velocity
// changes sign inside: the extremum of the cubic Hermite interpolant u(s), s in [0, 1].
double hermitePeak(double u0, double v0, double u1, double v1, double h) {
  const double m0 = h * v0;
  const double m1 = h * v1;
  // du/ds = qa s² + qb s + qc
  const double qa = 6.0 * u0 + 3.0 * m0 - 6.0 * u1 + 3.0 * m1;
  const double qb = -6.0 * u0 - 4.0 * m0 + 6.0 * u1 - 2.0 * m1;
  const double qc = m0;
  double s = 0.5;
  if (std::abs(qa) < 1e-12 * (std::abs(qb) + std::abs(qc))) {
    if (qb != 0.0) s = -qc / qb;
  } else {
    const double disc = std::max(0.0, qb * qb - 4.0 * qa * qc);
    // Numerically stable roots; exactly one lies in (0, 1) because du/ds changes sign there.
    const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
    const double r1 = q != 0.0 ? q / qa : 0.5;
    const double r2 = q != 0.0 ? qc / q : 0.5;
    s = (r1 >= 0.0 && r1 <= 1.0) ? r1 : r2;
  }
  s = std::clamp(s, 0.0, 1.0);
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double u =
      (2.0 * s3 - 3.0 * s2 + 1.0) * u0 + (s3 - 2.0 * s2 + s) * m0 + (-2.0 * s3 + 3.0 * s2) * u1 + (s3 - s2) * m1;
  return std::abs(u);
}

}  // namespace

double pseudoSpectralAccelerationG(const GroundMotion& record, double periodS, double dampingRatio) {
  if (!finitePositive(periodS) || !(dampingRatio >= 0.0 && dampingRatio < 1.0)) return kNaN;
  if (!finitePositive(record.timeStepS)) return kNaN;
  const std::size_t n = record.size();
  if (n == 0) return 0.0;
  const double omega = kTwoPi / periodS;
  const double dt = record.timeStepS;
  const double subSteps = std::max(1.0, std::ceil(dt * kSubStepsPerPeriod / periodS));
  const double h = dt / subSteps;
  const auto m = static_cast<std::size_t>(subSteps);
  const Recurrence r = recurrence(omega, dampingRatio, h);

  double u = 0.0;
  double v = 0.0;
  double peak = 0.0;
  auto step = [&](double p0, double p1) {
    const double u1 = r.a * u + r.b * v + r.c * p0 + r.d * p1;
    const double v1 = r.ap * u + r.bp * v + r.cp * p0 + r.dp * p1;
    if (v * v1 < 0.0) peak = std::max(peak, hermitePeak(u, v, u1, v1, h));
    u = u1;
    v = v1;
    peak = std::max(peak, std::abs(u));
  };
  // Intervals [j·dt, (j+1)·dt] for j = 0..N: the load goes from -a_j to -a_{j+1}, with a_0 = 0,
  // a_j = sample j (1-based) and a_{N+1} = 0 (GroundMotion.h's time convention).
  const double invM = 1.0 / subSteps;
  for (std::size_t j = 0; j <= n; ++j) {
    const double a0 = j == 0 ? 0.0 : record.accelerationMps2[j - 1];
    const double a1 = j == n ? 0.0 : record.accelerationMps2[j];
    const double p0 = -a0;
    const double dp = (a0 - a1) * invM;
    for (std::size_t i = 0; i < m; ++i) {
      step(p0 + dp * static_cast<double>(i), p0 + dp * static_cast<double>(i + 1));
    }
  }
  // Free vibration for one damped period (see the header).
  const double dampedPeriod = periodS / std::sqrt(1.0 - dampingRatio * dampingRatio);
  const auto freeSteps = static_cast<std::size_t>(std::ceil(dampedPeriod / h)) + 1;
  for (std::size_t i = 0; i < freeSteps; ++i) step(0.0, 0.0);
  return peak * omega * omega / kGravityMps2;
}

Result<ResponseSpectrum> ResponseSpectrum::compute(const GroundMotion& record, double minPeriodS, double maxPeriodS,
                                                   double dampingRatio) {
  const std::string where = "response spectrum of " + record.name + ": ";
  if (record.size() == 0) return fail(where + "the record has no samples");
  if (!finitePositive(record.timeStepS))
    return fail(where + "time step " + formatDouble(record.timeStepS) + " s is not finite and > 0");
  if (!(record.peakAbsMps2() > 0.0) || !std::isfinite(record.peakAbsMps2()))
    return fail(where + "the record has no motion (all samples zero) or a non-finite sample");
  if (!(minPeriodS >= 0.001) || !std::isfinite(maxPeriodS) || !(minPeriodS < maxPeriodS) || maxPeriodS > 1000.0)
    return fail(where + "period range [" + formatDouble(minPeriodS) + ", " + formatDouble(maxPeriodS) +
                "] s is not 0.001 <= min < max <= 1000");
  if (!(dampingRatio >= 0.0 && dampingRatio < 1.0))
    return fail(where + "damping ratio " + formatDouble(dampingRatio) + " is outside [0, 1)");

  ResponseSpectrum s;
  s.dampingRatio_ = dampingRatio;
  const double lnMin = std::log(minPeriodS);
  const double lnMax = std::log(maxPeriodS);
  const double decades = (lnMax - lnMin) / std::log(10.0);
  const auto intervals = static_cast<std::size_t>(std::max(1.0, std::ceil(decades * kBasePointsPerDecade - 1e-9)));
  const double lnStep = (lnMax - lnMin) / static_cast<double>(intervals);

  std::string problem;
  auto saAt = [&](double lnPeriod) {
    const double period = std::exp(lnPeriod);
    const double sa = pseudoSpectralAccelerationG(record, period, dampingRatio);
    if (!(sa > 0.0) || !std::isfinite(sa)) {
      if (problem.empty())
        problem = where + "Sa at " + formatDouble(period) + " s is " + formatDouble(sa) + " (not finite and > 0)";
      return 1.0;
    }
    return sa;
  };
  auto push = [&](double lnPeriod, double sa) {
    s.lnPeriods_.push_back(lnPeriod);
    s.lnSaG_.push_back(std::log(sa));
  };
  // Adds the points strictly inside (lnA, lnB): always the mid-point; and where the mid-point's Sa
  // differs from the log-log interpolation between the ends by more than kRefineTolerance, both
  // halves recursively (see the header for why this bounds the error).
  auto refine = [&](auto& self, double lnA, double saA, double lnB, double saB, int depth) -> void {
    const double lnMid = 0.5 * (lnA + lnB);
    const double saMid = saAt(lnMid);
    const double interpolated = std::sqrt(saA * saB);
    const bool split =
        depth < kMinRefinements || (depth < kMaxRefinements && std::abs(interpolated / saMid - 1.0) > kRefineTolerance);
    if (split) self(self, lnA, saA, lnMid, saMid, depth + 1);
    push(lnMid, saMid);
    if (split) self(self, lnMid, saMid, lnB, saB, depth + 1);
  };
  double lnPrevious = lnMin;
  double saPrevious = saAt(lnMin);
  push(lnMin, saPrevious);
  for (std::size_t i = 1; i <= intervals && problem.empty(); ++i) {
    const double lnNext = i == intervals ? lnMax : lnMin + lnStep * static_cast<double>(i);
    const double saNext = saAt(lnNext);
    refine(refine, lnPrevious, saPrevious, lnNext, saNext, 0);
    push(lnNext, saNext);
    lnPrevious = lnNext;
    saPrevious = saNext;
  }
  // Kinks that the mid-point test misses (a kink beside a concave stretch can leave the mid-point
  // on the chord): passes that bisect every interval whose neighbours' slopes differ by more than
  // the interval can follow, |s(i+1) - s(i-1)|·Δ(i)/4 > kRefineTolerance (the bound of linear
  // interpolation across a kink between those slopes).
  for (int pass = 0; pass < kKinkPasses && problem.empty(); ++pass) {
    const std::vector<double> lnT = s.lnPeriods_;
    const std::vector<double> lnSa = s.lnSaG_;
    auto slope = [&](std::size_t i) { return (lnSa[i + 1] - lnSa[i]) / (lnT[i + 1] - lnT[i]); };
    s.lnPeriods_.clear();
    s.lnSaG_.clear();
    bool added = false;
    for (std::size_t i = 0; i + 1 < lnT.size(); ++i) {
      push(lnT[i], std::exp(lnSa[i]));
      const double before = i > 0 ? slope(i - 1) : slope(i);
      const double after = i + 2 < lnT.size() ? slope(i + 1) : slope(i);
      if (std::abs(after - before) * (lnT[i + 1] - lnT[i]) / 4.0 > kRefineTolerance) {
        const double lnMid = 0.5 * (lnT[i] + lnT[i + 1]);
        push(lnMid, saAt(lnMid));
        added = true;
      }
    }
    push(lnT.back(), std::exp(lnSa.back()));
    if (!added) break;
  }
  if (!problem.empty()) return fail(problem);
  s.periodsS_.resize(s.lnPeriods_.size());
  s.saG_.resize(s.lnPeriods_.size());
  for (std::size_t i = 0; i < s.lnPeriods_.size(); ++i) {
    s.periodsS_[i] = std::exp(s.lnPeriods_[i]);
    s.saG_[i] = std::exp(s.lnSaG_[i]);
  }
  s.periodsS_.front() = minPeriodS;
  s.periodsS_.back() = maxPeriodS;
  return s;
}

double ResponseSpectrum::saG(double periodS) const {
  if (!finitePositive(periodS)) return kNaN;
  if (periodS <= periodsS_.front()) return saG_.front();
  if (periodS >= periodsS_.back()) return saG_.back();
  const double lnPeriod = std::log(periodS);
  const auto upper = std::upper_bound(lnPeriods_.begin(), lnPeriods_.end(), lnPeriod);
  const auto i = static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(upper - lnPeriods_.begin(), 1, static_cast<std::ptrdiff_t>(lnPeriods_.size()) - 1));
  const double w = std::clamp((lnPeriod - lnPeriods_[i - 1]) / (lnPeriods_[i] - lnPeriods_[i - 1]), 0.0, 1.0);
  return std::exp(lnSaG_[i - 1] + w * (lnSaG_[i] - lnSaG_[i - 1]));
}

double shakeMapTargetSaG(const SpectralOrdinates& site, double periodS, double longPeriodTransitionS) {
  if (!finitePositive(periodS) || !finitePositive(longPeriodTransitionS)) return kNaN;
  if (!finitePositive(site.pgaG) || !finitePositive(site.psa03G) || !finitePositive(site.psa10G) ||
      !finitePositive(site.psa30G))
    return kNaN;
  struct Anchor {
    double periodS, saG;
  };
  const Anchor anchors[] = {{0.03, site.pgaG}, {0.3, site.psa03G}, {1.0, site.psa10G}, {3.0, site.psa30G}};
  if (periodS <= anchors[0].periodS) return site.pgaG;
  if (periodS <= 3.0) {
    std::size_t upper = 1;
    while (anchors[upper].periodS < periodS) ++upper;
    const Anchor& lo = anchors[upper - 1];
    const Anchor& hi = anchors[upper];
    if (periodS == hi.periodS) return hi.saG;
    const double w = std::log(periodS / lo.periodS) / std::log(hi.periodS / lo.periodS);
    return std::exp(std::log(lo.saG) + w * (std::log(hi.saG) - std::log(lo.saG)));
  }
  // ASCE 7-16 §11.4.6: Sa ∝ 1/T up to T_L, ∝ 1/T² beyond, continuous at T_L.
  const double corner = std::max(3.0, longPeriodTransitionS);
  if (periodS <= corner) return site.psa30G * 3.0 / periodS;
  return site.psa30G * 3.0 * corner / (periodS * periodS);
}

Result<SpectralScaling> spectralScaling(double targetSaG, double recordSaAtPeriodG) {
  if (!finitePositive(targetSaG))
    return fail("spectral scaling: target Sa " + formatDouble(targetSaG) + " g is not finite and > 0");
  if (!finitePositive(recordSaAtPeriodG))
    return fail("spectral scaling: record Sa " + formatDouble(recordSaAtPeriodG) +
                " g is not finite and > 0 (a record without motion at that period cannot be scaled)");
  const double scale = targetSaG / recordSaAtPeriodG;
  if (!std::isfinite(scale))
    return fail("spectral scaling: scale " + formatDouble(targetSaG) + " / " + formatDouble(recordSaAtPeriodG) +
                " is not finite");
  return SpectralScaling{targetSaG, recordSaAtPeriodG, scale};
}

Result<double> firstModePeriodS(const ShearBuilding& building) {
  auto modes = computeModes(building);
  if (!modes) return fail(modes.error());
  if (modes->periodsS.empty()) return fail("first-mode period: the model has no modes");
  return modes->periodsS.front();
}

}  // namespace qv::seismic
