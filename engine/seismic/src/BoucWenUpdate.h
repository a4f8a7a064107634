// Updates of the normalised Bouc–Wen variable over one time step, with their consistent tangents:
// the implicit (backward Euler) update and, for n in {1, 2} with γ̂ = β̂, the exact integral along the
// step's drift increment. Private to engine::seismic; shared by the reference and batched solvers.
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
//
// Exact integral (boucWenExact), n in {1, 2} and γ̂ = β̂ = 1/2. The model is rate-independent, so
// along any monotonic drift path over the step ẑ solves dẑ/dx = 1 - |ẑ|^n (γ̂ + β̂ sgn(x ẑ)) in x
// from 0 to Δδ/dy. With σ = sgn x, s = |x| and w = σ ẑ (w >= 0 loading, w < 0 unloading):
//   unloading (w < 0): dw/ds = 1 (γ̂ - β̂ = 0: a straight branch at the initial stiffness) until w = 0;
//   loading (w >= 0):  dw/ds = 1 - w^n, so after a loading length L from w,
//     n = 1:  w + (1 - w) E(L)                           E(y) = 1 - e^(-y)
//     n = 2:  tanh(atanh w + L) = w + E(1 - w²) / (2 - E + w E),  E = E(2L)  (tanh L = E / (2 - E)).
// A step that starts unloading with s > -w unloads to 0 and loads for L = s + w. The tangent is
// dẑ/dx = 1 - |ẑ|^n at the end when loading, 1 when unloading. The update then has no error of its
// own, so sub-steps need follow only Newmark's (second-order) error. E is computed from + - * / and
// exact scaling by powers of two (no library exp: the same bits on every IEEE-754 target where the
// compiler does not fuse a·b + c, see SyntheticMotion.cpp), with relative accuracy of
// a few ulp also for small arguments (no cancellation in 1 - e^(-y)).
#pragma once

#include <algorithm>
#include <cmath>

namespace qv::seismic::detail {

/// j! for j = 0 .. 14 (exact in double).
inline constexpr double kFactorials[15] = {1.0,       1.0,        2.0,         6.0,          24.0,
                                           120.0,     720.0,      5040.0,      40320.0,      362880.0,
                                           3628800.0, 39916800.0, 479001600.0, 6227020800.0, 87178291200.0};

/// 1 - e^(-y) for y >= 0 (y above 80 counts as 80). y = k ln2 - r with |r| <= ln2/2: e^(-y) =
/// 2^(-k) (1 + m), m = e^r - 1 by its Taylor series in Horner form (14 terms: below 1e-17 relative), so for k = 0
/// the result is -m with no cancellation. The batched solver mirrors it on SIMD lanes.
inline double oneMinusExpNegative(double y) {
  constexpr double kInverseLn2 = 1.4426950408889634074;
  constexpr double kLn2High = 6.93147180369123816490e-01;  // fdlibm's split: k·kLn2High is exact
  constexpr double kLn2Low = 1.90821492927058770002e-10;
  y = std::min(y, 80.0);
  const double k = std::floor(y * kInverseLn2 + 0.5);
  const double r = (k * kLn2High - y) + k * kLn2Low;
  double p = 1.0 / kFactorials[14];
  for (int j = 13; j >= 1; --j) p = 1.0 / kFactorials[j] + r * p;
  const double m = r * p;
  const double scale = std::ldexp(1.0, -static_cast<int>(k));
  return (1.0 - scale) - scale * m;
}

/// Exact update for n in {1, 2} (`nIsTwo` 1 or 0) and γ̂ = β̂ (see the header comment). The batched
/// solver performs the same operations on SIMD lanes (ResponseSolver.cpp).
inline void boucWenExact(double zPrevious, double x, double nIsTwo, double& z, double& slope) {
  const double sign = std::signbit(x) ? -1.0 : 1.0;
  const double w0 = zPrevious * sign;
  const double s = x * sign;
  const double unload = std::min(s, std::max(-w0, 0.0));  // the straight unloading branch, down to ẑ = 0
  const double w = w0 + unload;                           // < 0 still unloading, else the loading start
  const double load = s - unload;                         // 0 while unloading
  const double e = oneMinusExpNegative(load * (1.0 + nIsTwo));
  const double numerator = e * (1.0 - w) * (1.0 + nIsTwo * w);
  const double denominator = 1.0 + nIsTwo * ((1.0 - e) + w * e);
  const double end = w + numerator / denominator;
  z = end * sign;
  const double loading = std::max(end, 0.0);
  slope = 1.0 - loading * (nIsTwo * loading + (1.0 - nIsTwo));
}

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
