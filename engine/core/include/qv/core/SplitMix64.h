// splitmix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014;
// Vigna's reference splitmix64.c): a small, fast, well-mixed 64-bit generator whose sequence is
// fixed by its integer arithmetic, so every compiler and target (native, WebAssembly) draws the
// same numbers from the same seed. Used directly (Monte Carlo loss, benchmarks) and to seed larger
// generators (xoshiro256**).
#pragma once

#include <cstdint>

namespace qv {

struct SplitMix64 {
  std::uint64_t state = 0;  ///< the seed, then advanced by every draw

  /// The next 64 random bits.
  constexpr std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in (0, 1]: the top 53 bits plus one, times 2^-53 (never 0).
  double uniformOpenClosed() { return static_cast<double>((next() >> 11) + 1) * 0x1.0p-53; }
  /// Uniform in (0, 1): the top 53 bits plus one half, times 2^-53 (never 0 or 1, so a logarithm
  /// of it or of one minus it is finite).
  double uniformOpen() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53; }
};

}  // namespace qv
