// The implicit (backward Euler) update of the normalised Bouc–Wen variable over one time step, and
// its consistent tangent. Private to engine::seismic; shared by the reference and batched solvers.
//
// With x = Δδ / dy the drift increment since the start of the step, the update solves
//   ẑ - ẑ₀ - x [1 - |ẑ|^n (γ̂ + β̂ sgn(x ẑ))] = 0,
// the same equation OpenSees' BoucWen material solves by Newton iterations.
//
// Closed form for n in {1, 2} when γ̂ <= β̂ (unloading never softer than the initial stiffness). The
// solution has the sign σ of N = ẑ₀ + x (σ from the sign bit of N; when N = 0 the solution is ẑ = 0
// on either branch), so sgn(x ẑ) = sgn(x σ) is known before solving. With c = 1 when loading (x σ >= 0, γ̂ + β̂ = 1) and
// c = γ̂ - β̂ <= 0 when unloading, c·xσ >= 0 and the equation is
//   n = 1:  (1 + c x σ) ẑ = N                      (linear)
//   n = 2:  c x ẑ² + ẑ - N = 0                      (quadratic)
// both written as A ẑ² + B ẑ - N = 0 with the stable root ẑ = 2N / (B + S), S = sqrt(B² + 4AN) >= B >= 1,
// and tangent dẑ/dx = (1 - c |ẑ|^n) / S. No division can fail and |ẑ| <= 1 is preserved.
#pragma once

#include <cmath>

namespace qv::seismic::detail {

/// Closed-form update. `nIsTwo` is 1 for n = 2 and 0 for n = 1; `cUnload` = γ̂ - β̂ <= 0. The batched
/// solver performs the same operations on SIMD lanes (ResponseSolver.cpp).
template <typename T>
inline void boucWenClosedForm(T zPrevious, T x, T nIsTwo, T cUnload, T& z, T& slope) {
  const T total = zPrevious + x;
  const T sign = std::signbit(total) ? T(-1) : T(1);
  const T xs = x * sign;  // growth of |ẑ| when positive
  const T c = xs >= T(0) ? T(1) : cUnload;
  const T cx = c * xs;  // >= 0
  const T b = T(1) + (T(1) - nIsTwo) * cx;
  const T s = std::sqrt(b * b + T(4) * nIsTwo * cx * (total * sign));
  z = T(2) * total / (b + s);
  const T absZ = z * sign;
  const T power = absZ * (nIsTwo * absZ + (T(1) - nIsTwo));
  slope = (T(1) - c * power) / s;
}

/// General update for any n >= 1 and γ̂ in [0, 1]: Newton iterations from the closed-form-like start,
/// with step halving when an iterate would leave |ẑ| <= 2 (the solution stays within the saturation
/// bound). Returns false when it does not converge (the caller then sub-divides the time step).
inline bool boucWenGeneral(double zPrevious, double x, double n, double gammaShare, double& z, double& slope) {
  const double betaShare = 1.0 - gammaShare;
  if (x == 0.0) {
    z = zPrevious;
    const double psi = gammaShare + betaShare;  // direction undefined: loading branch
    slope = 1.0 - std::pow(std::fabs(z), n) * psi;
    return true;
  }
  z = zPrevious;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double absZ = std::fabs(z);
    const double s = x * z >= 0.0 ? 1.0 : -1.0;
    const double psi = gammaShare + betaShare * s;
    const double powerN = std::pow(absZ, n);
    const double g = z - zPrevious - x * (1.0 - powerN * psi);
    const double dPower = absZ > 0.0 ? n * std::pow(absZ, n - 1.0) * (z > 0.0 ? 1.0 : -1.0) : 0.0;
    const double dg = 1.0 + x * dPower * psi;
    double step = dg != 0.0 ? g / dg : g;
    double next = z - step;
    while (std::fabs(next) > 2.0) {
      step *= 0.5;
      next = z - step;
    }
    z = next;
    if (std::fabs(step) <= 1e-15 * (1.0 + std::fabs(z))) {
      const double absZn = std::fabs(z);
      const double sn = x * z >= 0.0 ? 1.0 : -1.0;
      const double psin = gammaShare + betaShare * sn;
      const double dPowerN = absZn > 0.0 ? n * std::pow(absZn, n - 1.0) * (z > 0.0 ? 1.0 : -1.0) : 0.0;
      const double dgn = 1.0 + x * dPowerN * psin;
      slope = (1.0 - std::pow(absZn, n) * psin) / (dgn != 0.0 ? dgn : 1.0);
      return true;
    }
  }
  return false;
}

}  // namespace qv::seismic::detail
