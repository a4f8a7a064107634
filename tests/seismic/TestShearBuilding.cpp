#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "qv/seismic/ShearBuilding.h"

using namespace qv::seismic;

namespace {

ShearBuilding chopraFrame() {
  ShearBuilding b;
  b.floorMassKg.assign(5, 45000.0);
  b.storeyStiffnessNPerM.assign(5, 5.482e6);
  b.storeyHeightM.assign(5, 4.0);
  b.damping = Damping::modal(0.05);
  return b;
}

}  // namespace

TEST_CASE("Modes of Chopra's 5-storey frame (Example 13.2.6)", "[seismic][modes]") {
  const auto modes = computeModes(chopraFrame(), true);
  REQUIRE(modes.ok());
  const double published[] = {2.000, 0.6852, 0.4346, 0.3383, 0.2967};
  REQUIRE(modes->periodsS.size() == 5);
  for (std::size_t j = 0; j < 5; ++j) {
    CAPTURE(j);
    CHECK(modes->periodsS[j] == Approx(published[j]).epsilon(2e-4));
  }
  // Uniform chain, closed form: ω_j = 2 sqrt(k/m) sin((2j-1)π / (2(2N+1))).
  for (std::size_t j = 0; j < 5; ++j) {
    const double exact =
        2.0 * std::sqrt(5.482e6 / 45000.0) * std::sin((2.0 * static_cast<double>(j) + 1.0) * std::numbers::pi / 22.0);
    CHECK(modes->circularFrequencies[j] == Approx(exact).epsilon(1e-12));
  }
  // Mass-orthonormal shapes.
  for (std::size_t j = 0; j < 5; ++j) {
    for (std::size_t k = 0; k < 5; ++k) {
      double dot = 0.0;
      for (std::size_t i = 0; i < 5; ++i) dot += modes->shapes[j * 5 + i] * 45000.0 * modes->shapes[k * 5 + i];
      CHECK(dot == Approx(j == k ? 1.0 : 0.0).margin(1e-12));
    }
  }
  CHECK(modes->shapes[0 * 5 + 4] > 0.0);  // roof moves positively in mode 1
}

TEST_CASE("Modes of a non-uniform tall building", "[seismic][modes]") {
  ShearBuilding b;
  const std::size_t n = 160;
  for (std::size_t i = 0; i < n; ++i) {
    b.floorMassKg.push_back(1.0e6 * (1.0 - 0.3 * static_cast<double>(i) / n));
    b.storeyStiffnessNPerM.push_back(5.0e9 * (1.0 - 0.5 * static_cast<double>(i) / n));
  }
  const auto modes = computeModes(b, true);
  REQUIRE(modes.ok());
  for (std::size_t j = 1; j < n; ++j) CHECK(modes->periodsS[j] < modes->periodsS[j - 1]);
  // Rayleigh quotient of the first shape reproduces ω1².
  double kq = 0.0;
  double mq = 0.0;
  const double* phi = modes->shapes.data();
  for (std::size_t i = 0; i < n; ++i) {
    const double drift = phi[i] - (i > 0 ? phi[i - 1] : 0.0);
    kq += b.storeyStiffnessNPerM[i] * drift * drift;
    mq += b.floorMassKg[i] * phi[i] * phi[i];
  }
  CHECK(kq / mq == Approx(modes->circularFrequencies[0] * modes->circularFrequencies[0]).epsilon(1e-9));
}

TEST_CASE("Shear building validation and Bouc-Wen conversion", "[seismic][modes]") {
  ShearBuilding b = chopraFrame();
  b.storeyStiffnessNPerM[2] = -1.0;
  const auto s = validateShearBuilding(b);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error() == "shear building: stiffness -1 N/m of floor/storey 3");
  b = chopraFrame();
  b.floorMassKg.pop_back();
  CHECK(validateShearBuilding(b).error() == "shear building: 4 floor masses but 5 storey stiffnesses");
  CHECK_FALSE(validateShearBuilding(ShearBuilding{}).ok());

  // OpenSees BoucWen form: dy = (gamma + beta)^(-1/n).
  const auto bw = BoucWenStorey::fromOpenSees(0.1, 2.0, 2500.0, 7500.0);
  REQUIRE(bw.ok());
  CHECK(bw->yieldDisplacementM == Approx(0.01));
  CHECK(bw->gammaShare == Approx(0.25));
  CHECK(bw->unloadingStiff());
  CHECK(BoucWenStorey::fromOpenSees(0.1, 1.0, 0.0, 0.0).error() ==
        "Bouc-Wen gamma + beta must be > 0 (z would never saturate)");
  CHECK_FALSE(BoucWenStorey::fromOpenSees(1.5, 1.0, 1.0, 1.0).ok());
  CHECK_FALSE(BoucWenStorey::fromOpenSees(0.1, 0.5, 1.0, 1.0).ok());

  const Damping d = Damping::rayleighFromModes(0.05, 3.0, 9.0);
  CHECK(0.5 * (d.massCoefficient / 3.0 + d.stiffnessCoefficient * 3.0) == Approx(0.05));
  CHECK(0.5 * (d.massCoefficient / 9.0 + d.stiffnessCoefficient * 9.0) == Approx(0.05));
}
