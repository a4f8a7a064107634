// Elementary functions from + - * / and exact power-of-two scaling only, so their results are the
// same on every IEEE-754 target (glibc, musl/Emscripten, MSVC) when the calling file is compiled
// without contraction (-ffp-contract=off). Accuracy is a few ulp, far more than a noise generator
// needs; bit-reproducibility is the point. Private to engine::seismic.
#pragma once

#include <cmath>
#include <cstdint>

#include "qv/core/SplitMix64.h"

namespace qv::seismic::detail {

inline constexpr double kLn2 = 0.6931471805599453094;
inline constexpr double kTwoPi = 6.283185307179586477;

/// Natural logarithm for x > 0 (finite). frexp is exact; the series is atanh's on [-0.172, 0.172].
inline double deterministicLog(double x) {
  int exponent = 0;
  double m = std::frexp(x, &exponent);  // x = m·2^e, m in [0.5, 1)
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    exponent -= 1;
  }
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  // 2·atanh(s) = 2(s + s³/3 + s⁵/5 + ...), |s| <= 0.1716: 11 terms reach 1e-17.
  double term = s;
  double sum = s;
  for (int k = 3; k <= 23; k += 2) {
    term *= s2;
    sum += term / static_cast<double>(k);
  }
  return 2.0 * sum + static_cast<double>(exponent) * kLn2;
}

/// e^x for |x| <= 700: x = k·ln2 + r with |r| <= ln2/2, Taylor series of e^r, exact scaling by 2^k.
inline double deterministicExp(double x) {
  if (x < -700.0) return 0.0;
  if (x > 700.0) x = 700.0;
  const double k = std::floor(x / kLn2 + 0.5);
  const double r = x - k * kLn2;
  double term = 1.0;
  double sum = 1.0;
  for (int n = 1; n <= 18; ++n) {
    term *= r / static_cast<double>(n);
    sum += term;
  }
  return std::ldexp(sum, static_cast<int>(k));
}

/// cos(2πu) and sin(2πu) for u in [0, 1): quadrant from round(4u), Taylor series on |r| <= π/4.
inline void deterministicSinCosTurns(double u, double& cosine, double& sine) {
  const double q = std::floor(4.0 * u + 0.5);  // 0..4
  const double r = (u - 0.25 * q) * kTwoPi;    // |r| <= π/4
  const double r2 = r * r;
  double s = r;
  double c = 1.0;
  double ts = r;
  double tc = 1.0;
  for (int n = 1; n <= 11; ++n) {
    ts *= -r2 / static_cast<double>((2 * n) * (2 * n + 1));
    tc *= -r2 / static_cast<double>((2 * n - 1) * (2 * n));
    s += ts;
    c += tc;
  }
  switch (static_cast<int>(q) & 3) {
    case 0:
      cosine = c;
      sine = s;
      break;
    case 1:
      cosine = -s;
      sine = c;
      break;
    case 2:
      cosine = -c;
      sine = -s;
      break;
    default:
      cosine = s;
      sine = -c;
      break;
  }
}

/// xoshiro256** (Blackman & Vigna 2018).
class Xoshiro256 {
 public:
  explicit Xoshiro256(std::uint64_t seed) {
    SplitMix64 seeder{seed};  // seeds the state from one 64-bit value, as Blackman & Vigna advise
    for (auto& word : state_) word = seeder.next();
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }
  /// Uniform in (0, 1): 53 random bits, never exactly 0 (the logarithm of Box–Muller needs that).
  double uniformOpen() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }
  /// Standard normal pairs by Box–Muller; returns one, keeps the other.
  double normal() {
    if (hasSpare_) {
      hasSpare_ = false;
      return spare_;
    }
    const double u1 = uniformOpen();
    const double u2 = uniformOpen();
    const double radius = std::sqrt(-2.0 * deterministicLog(u1));
    double c = 0.0;
    double s = 0.0;
    deterministicSinCosTurns(u2, c, s);
    spare_ = radius * s;
    hasSpare_ = true;
    return radius * c;
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4] = {};
  double spare_ = 0.0;
  bool hasSpare_ = false;
};

}  // namespace qv::seismic::detail
