#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "qv/seismic/SyntheticMotion.h"

using namespace qv::seismic;

namespace {

// FNV-1a over the bit patterns of the samples: a fingerprint that any change of arithmetic moves.
std::uint64_t fingerprint(const GroundMotion& m) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const double v : m.accelerationMps2) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) {
      h ^= (bits >> (8 * byte)) & 0xffu;
      h *= 0x100000001b3ull;
    }
  }
  return h;
}

}  // namespace

TEST_CASE("Synthetic motion is deterministic: same seed, same samples, other seed, other samples",
          "[seismic][synthetic]") {
  SyntheticMotionParameters p;
  p.seed = 42;
  const auto a = generateSyntheticMotion(p);
  const auto b = generateSyntheticMotion(p);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a->accelerationMps2 == b->accelerationMps2);
  p.seed = 43;
  const auto c = generateSyntheticMotion(p);
  REQUIRE(c.ok());
  CHECK(a->accelerationMps2 != c->accelerationMps2);
  // Bit-identical on every compiler and target (GCC, clang, em++ under node): pinned fingerprint.
  CHECK(fingerprint(*a) == 0x6fbd22ef92f531dcull);
}

TEST_CASE("Synthetic motion hits the target PGA, starts at rest and ends with zero velocity", "[seismic][synthetic]") {
  SyntheticMotionParameters p;
  p.seed = 7;
  p.peakGroundAccelerationG = 0.35;
  p.durationS = 20.0;
  p.timeStepS = 0.01;
  const auto m = generateSyntheticMotion(p);
  REQUIRE(m.ok());
  CHECK(m->size() == 2000);
  CHECK(m->timeStepS == 0.01);
  CHECK(m->peakAbsMps2() / kGravityMps2 == Approx(0.35).epsilon(1e-12));
  // The envelope is zero at the start: the first second is much weaker than the peak.
  CHECK(syntheticEnvelope(p, 0.0) == 0.0);
  CHECK(syntheticEnvelope(p, 1.0) == Approx(0.25));  // (t / 2 s)²
  CHECK(syntheticEnvelope(p, 5.0) == 1.0);
  CHECK(syntheticEnvelope(p, 20.0) == Approx(0.05).epsilon(1e-12));
  CHECK(std::fabs(m->accelerationMps2[0]) < 0.01 * m->peakAbsMps2());
  // Baseline correction: dt·Σa = final ground velocity = 0.
  double velocity = 0.0;
  for (const double a : m->accelerationMps2) velocity += a * m->timeStepS;
  CHECK(std::fabs(velocity) < 1e-9);
}

TEST_CASE("Synthetic pairs use different streams, parameters are validated", "[seismic][synthetic]") {
  SyntheticMotionParameters p;
  p.seed = 9;
  const auto pair = generateSyntheticPair(p);
  REQUIRE(pair.ok());
  CHECK(pair->first.accelerationMps2 != pair->second.accelerationMps2);
  CHECK(pair->first.peakAbsMps2() == Approx(pair->second.peakAbsMps2()));
  const auto x = generateSyntheticMotion(p);
  REQUIRE(x.ok());
  CHECK(x->accelerationMps2 == pair->first.accelerationMps2);
  p.timeStepS = 0.5;
  const auto bad = generateSyntheticMotion(p);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error() == "synthetic motion: timeStepS must be in [0.001, 0.1], not 0.5");
}
