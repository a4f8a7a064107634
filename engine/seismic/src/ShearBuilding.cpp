#include "qv/seismic/ShearBuilding.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "Tridiagonal.h"
#include "qv/core/NumberFormat.h"

namespace qv::seismic {
namespace {

constexpr double kTwoPi = 6.283185307179586477;
constexpr std::size_t kMaxStoreys = 1000;

}  // namespace

Result<BoucWenStorey> BoucWenStorey::fromOpenSees(double alpha, double n, double gamma, double beta) {
  if (!(alpha >= 0.0 && alpha <= 1.0)) return fail("Bouc-Wen alpha must be in [0, 1], not " + formatDouble(alpha));
  if (!(n >= 1.0 && n <= 20.0)) return fail("Bouc-Wen n must be in [1, 20], not " + formatDouble(n));
  if (!(gamma >= 0.0 && beta >= 0.0 && std::isfinite(gamma) && std::isfinite(beta))) {
    return fail("Bouc-Wen gamma and beta must be finite and >= 0, not " + formatDouble(gamma) + ", " +
                formatDouble(beta));
  }
  if (!(gamma + beta > 0.0)) return fail("Bouc-Wen gamma + beta must be > 0 (z would never saturate)");
  BoucWenStorey storey;
  storey.alpha = alpha;
  storey.exponent = n;
  storey.gammaShare = gamma / (gamma + beta);
  storey.yieldDisplacementM = std::pow(gamma + beta, -1.0 / n);
  if (!(storey.yieldDisplacementM > 0.0 && std::isfinite(storey.yieldDisplacementM))) {
    return fail("Bouc-Wen gamma + beta = " + formatDouble(gamma + beta) + " gives no finite yield displacement");
  }
  return storey;
}

Damping Damping::rayleighFromModes(double ratio, double omega1, double omega2) {
  if (!(omega2 > omega1)) return rayleigh(ratio * omega1, ratio / omega1);
  const double a0 = 2.0 * ratio * omega1 * omega2 / (omega1 + omega2);
  const double a1 = 2.0 * ratio / (omega1 + omega2);
  return rayleigh(a0, a1);
}

Status validateShearBuilding(const ShearBuilding& b) {
  const std::size_t n = b.storeys();
  if (n == 0 || n > kMaxStoreys) {
    return fail("shear building: " + std::to_string(n) + " storeys (1 to " + std::to_string(kMaxStoreys) +
                " are supported)");
  }
  if (b.storeyStiffnessNPerM.size() != n) {
    return fail("shear building: " + std::to_string(n) + " floor masses but " +
                std::to_string(b.storeyStiffnessNPerM.size()) + " storey stiffnesses");
  }
  if (!b.storeyHeightM.empty() && b.storeyHeightM.size() != n) {
    return fail("shear building: " + std::to_string(b.storeyHeightM.size()) + " storey heights for " +
                std::to_string(n) + " storeys");
  }
  if (!b.hysteresis.empty() && b.hysteresis.size() != n) {
    return fail("shear building: " + std::to_string(b.hysteresis.size()) + " hysteresis laws for " + std::to_string(n) +
                " storeys");
  }
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  for (std::size_t i = 0; i < n; ++i) {
    const std::string where =
        " of " + std::string(i + 1 == n ? "the top " : "") + "floor/storey " + std::to_string(i + 1);
    if (!positive(b.floorMassKg[i]) || b.floorMassKg[i] > 1e12)
      return fail("shear building: mass " + formatDouble(b.floorMassKg[i]) + " kg" + where);
    if (!positive(b.storeyStiffnessNPerM[i]) || b.storeyStiffnessNPerM[i] > 1e16)
      return fail("shear building: stiffness " + formatDouble(b.storeyStiffnessNPerM[i]) + " N/m" + where);
    if (!b.storeyHeightM.empty() && (!positive(b.storeyHeightM[i]) || b.storeyHeightM[i] > 1000.0))
      return fail("shear building: height " + formatDouble(b.storeyHeightM[i]) + " m" + where);
    if (!b.hysteresis.empty()) {
      const BoucWenStorey& h = b.hysteresis[i];
      if (!(h.alpha >= 0.0 && h.alpha <= 1.0)) return fail("shear building: Bouc-Wen alpha out of [0, 1]" + where);
      if (!(h.exponent >= 1.0 && h.exponent <= 20.0)) return fail("shear building: Bouc-Wen n out of [1, 20]" + where);
      if (!(h.gammaShare >= 0.0 && h.gammaShare <= 1.0))
        return fail("shear building: Bouc-Wen gamma share out of [0, 1]" + where);
      if (!(h.yieldDisplacementM > 0.0) || std::isnan(h.yieldDisplacementM))
        return fail("shear building: yield displacement " + formatDouble(h.yieldDisplacementM) + " m" + where);
    }
  }
  const Damping& d = b.damping;
  if (d.kind == DampingKind::Rayleigh) {
    if (!(d.massCoefficient >= 0.0 && std::isfinite(d.massCoefficient) && d.stiffnessCoefficient >= 0.0 &&
          std::isfinite(d.stiffnessCoefficient)))
      return fail("shear building: Rayleigh coefficients must be finite and >= 0");
  } else if (!(d.modalRatio >= 0.0 && d.modalRatio < 1.0)) {
    return fail("shear building: modal damping ratio must be in [0, 1), not " + formatDouble(d.modalRatio));
  }
  for (const double t : b.damageDriftThresholds) {
    if (!(t >= 0.0 && t < 1.0)) return fail("shear building: damage drift thresholds must be in [0, 1)");
  }
  return {};
}

Result<Modes> computeModes(const ShearBuilding& b, bool withShapes) {
  if (const Status s = validateShearBuilding(b); !s) return Error{s.error()};
  const std::size_t n = b.storeys();
  // A = M^-1/2 K M^-1/2: diagonal (k_i + k_{i+1}) / m_i, off-diagonal -k_{i+1} / sqrt(m_i m_{i+1}).
  std::vector<double> diagonal(n);
  std::vector<double> offDiagonal(n, 0.0);  // offDiagonal[i] couples i and i + 1
  for (std::size_t i = 0; i < n; ++i) {
    const double above = i + 1 < n ? b.storeyStiffnessNPerM[i + 1] : 0.0;
    diagonal[i] = (b.storeyStiffnessNPerM[i] + above) / b.floorMassKg[i];
    if (i + 1 < n) offDiagonal[i] = -above / std::sqrt(b.floorMassKg[i] * b.floorMassKg[i + 1]);
  }
  std::vector<double> vectors;
  if (withShapes) {
    vectors.assign(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) vectors[i * n + i] = 1.0;
  }
  if (!detail::symmetricTridiagonalEigen(diagonal, offDiagonal, withShapes ? &vectors : nullptr)) {
    return fail("shear building: the eigenvalue iteration did not converge");
  }
  // Ascending eigenvalues (the routine sorts); shapes in the columns of `vectors` (row-major n×n).
  Modes modes;
  modes.circularFrequencies.assign(n, 0.0);
  modes.periodsS.assign(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    if (!(diagonal[j] > 0.0)) return fail("shear building: a mode has a non-positive stiffness eigenvalue");
    modes.circularFrequencies[j] = std::sqrt(diagonal[j]);
    modes.periodsS[j] = kTwoPi / modes.circularFrequencies[j];
  }
  if (withShapes) {
    modes.shapes.resize(n * n);
    for (std::size_t j = 0; j < n; ++j) {
      // φ = M^-1/2 ψ; sign fixed so the roof moves positively.
      const double sign = vectors[(n - 1) * n + j] < 0.0 ? -1.0 : 1.0;
      for (std::size_t i = 0; i < n; ++i) {
        modes.shapes[j * n + i] = sign * vectors[i * n + j] / std::sqrt(b.floorMassKg[i]);
      }
    }
  }
  return modes;
}

}  // namespace qv::seismic
