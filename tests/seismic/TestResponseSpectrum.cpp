#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/GroundMotionModel.h"
#include "qv/seismic/GroundMotionReader.h"
#include "qv/seismic/ResponseSpectrum.h"
#include "qv/seismic/SyntheticMotion.h"

using namespace qv::seismic;

namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kElCentro = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/ground-motions/elCentro.AT2";

GroundMotion elCentro() {
  auto record = readGroundMotionFile(kElCentro);
  REQUIRE(record.ok());
  return std::move(record.value());
}

GroundMotion synthetic() {
  SyntheticMotionParameters p;
  p.seed = 11;
  p.durationS = 20.0;
  p.timeStepS = 0.01;
  p.peakGroundAccelerationG = 0.25;
  auto record = generateSyntheticMotion(p);
  REQUIRE(record.ok());
  return std::move(record.value());
}

// Independent spectrum ordinate for the acceptance test: Newmark's average-acceleration method
// (Chopra §5.4, γ = 1/2, β = 1/4) on the record linearly interpolated at dt/100, run on in free
// vibration for two periods after the record; peak |u| sampled at every step. Its period error
// ((ωh)²/12) and sampling error are far below the 0.5 % the test allows at these periods.
double newmarkSaG(const GroundMotion& record, double periodS, double zeta) {
  const double omega = 2.0 * kPi / periodS;
  const double k = omega * omega;
  const double c = 2.0 * zeta * omega;
  const int sub = 100;
  const double h = record.timeStepS / sub;
  const double end = record.timeStepS * static_cast<double>(record.size() + 1) + 2.0 * periodS;
  const auto steps = static_cast<std::size_t>(std::ceil(end / h));
  double u = 0.0, v = 0.0, a = 0.0, peak = 0.0;
  for (std::size_t i = 1; i <= steps; ++i) {
    const double t = h * static_cast<double>(i);
    const double p = -record.accelerationAt(t);
    const double uStar = u + h * v + 0.25 * h * h * a;
    const double vStar = v + 0.5 * h * a;
    const double aNext = (p - c * vStar - k * uStar) / (1.0 + 0.5 * c * h + 0.25 * k * h * h);
    u = uStar + 0.25 * h * h * aNext;
    v = vStar + 0.5 * h * aNext;
    a = aNext;
    peak = std::max(peak, std::abs(u));
  }
  return peak * k / kGravityMps2;
}

GroundMotion scaled(const GroundMotion& record, double scale) {
  GroundMotion out = record;
  for (double& x : out.accelerationMps2) x *= scale;
  return out;
}

}  // namespace

TEST_CASE("A record scaled to a target Sa at T1 has that Sa at T1 by an independent computation", "[spectrum]") {
  // The acceptance test: the scale comes from the record's ResponseSpectrum (as the city
  // pipeline uses it), the check from Newmark integration written here.
  const double targetSaG = 0.4;
  for (const GroundMotion& record : {elCentro(), synthetic()}) {
    const auto spectrum = ResponseSpectrum::compute(record, 0.1, 5.0);
    REQUIRE(spectrum.ok());
    for (const double t1 : {0.2, 0.75, 2.0, 4.0}) {
      CAPTURE(record.name, t1);
      const auto scaling = spectralScaling(targetSaG, spectrum->saG(t1));
      REQUIRE(scaling.ok());
      CHECK(scaling->targetSaG == targetSaG);
      const double independent = newmarkSaG(scaled(record, scaling->scale), t1, 0.05);
      CHECK(independent == Approx(targetSaG).epsilon(0.005));
      // The exact function on the scaled record agrees too (linear oscillator: Sa scales with the record).
      CHECK(pseudoSpectralAccelerationG(scaled(record, scaling->scale), t1) == Approx(targetSaG).epsilon(0.002));
    }
  }
}

TEST_CASE("Pseudo-spectral acceleration of a ramped step matches the closed form", "[spectrum]") {
  // Undamped oscillator under a ground acceleration that rises linearly over t_r to a0 and stays
  // (Chopra §4.5, step force with finite rise time): peak u = (a0/ω²)(1 + |sin(π t_r/T)| / (π t_r/T)).
  // The record ends after a whole number of periods, where the ramped step leaves no free vibration.
  for (const double riseS : {0.01, 0.25}) {
    const double periodS = 1.0;
    GroundMotion step;
    step.name = "step";
    step.timeStepS = riseS;
    step.accelerationMps2.assign(static_cast<std::size_t>(std::lround(5.0 * periodS / riseS)), 0.1 * kGravityMps2);
    const double x = kPi * riseS / periodS;
    CAPTURE(riseS);
    CHECK(pseudoSpectralAccelerationG(step, periodS, 0.0) == Approx(0.1 * (1.0 + std::sin(x) / x)).epsilon(5e-5));
  }
}

TEST_CASE("Pseudo-spectral acceleration: limits and invalid input", "[spectrum]") {
  const GroundMotion record = elCentro();
  const double pgaG = record.peakAbsMps2() / kGravityMps2;
  // A rigid oscillator follows the ground: Sa -> PGA as T -> 0.
  CHECK(pseudoSpectralAccelerationG(record, 0.005) == Approx(pgaG).epsilon(0.01));
  CHECK(std::isnan(pseudoSpectralAccelerationG(record, 0.0)));
  CHECK(std::isnan(pseudoSpectralAccelerationG(record, -1.0)));
  CHECK(std::isnan(pseudoSpectralAccelerationG(record, NAN)));
  CHECK(std::isnan(pseudoSpectralAccelerationG(record, 1.0, 1.0)));
  CHECK(std::isnan(pseudoSpectralAccelerationG(record, 1.0, -0.1)));
  GroundMotion empty;
  empty.timeStepS = 0.01;
  CHECK(pseudoSpectralAccelerationG(empty, 1.0) == 0.0);
  GroundMotion noStep = record;
  noStep.timeStepS = 0.0;
  CHECK(std::isnan(pseudoSpectralAccelerationG(noStep, 1.0)));
}

TEST_CASE("ResponseSpectrum interpolates within its stated bound of the exact function", "[spectrum]") {
  // From 0.03 s (El Centro) and 0.05 s (synthetic): the shortest periods cost the most sub-steps and
  // this file must stay quick under the sanitizers. The header's figures cover 0.01..10 s (measured
  // with 20 000 periods a record in an optimized build).
  struct Case {
    GroundMotion record;
    double minPeriodS;
  };
  for (const Case& c : {Case{elCentro(), 0.03}, Case{synthetic(), 0.05}}) {
    const GroundMotion& record = c.record;
    const auto spectrum = ResponseSpectrum::compute(record, c.minPeriodS);
    REQUIRE(spectrum.ok());
    CHECK(spectrum->minPeriodS() == c.minPeriodS);
    CHECK(spectrum->maxPeriodS() == 10.0);
    CHECK(std::is_sorted(spectrum->periodsS().begin(), spectrum->periodsS().end()));
    // Random periods over the whole range (log-uniform), and every 25th mid-point between grid periods.
    std::mt19937 random(5);
    std::uniform_real_distribution<double> lnPeriod(std::log(c.minPeriodS), std::log(10.0));
    std::vector<double> periods;
    for (int i = 0; i < 80; ++i) periods.push_back(std::exp(lnPeriod(random)));
    const auto& grid = spectrum->periodsS();
    for (std::size_t i = 0; i + 1 < grid.size(); i += 25) periods.push_back(std::sqrt(grid[i] * grid[i + 1]));
    double worst = 0.0;
    for (const double t : periods) {
      const double exact = pseudoSpectralAccelerationG(record, t);
      worst = std::max(worst, std::abs(spectrum->saG(t) / exact - 1.0));
    }
    CAPTURE(record.name, grid.size());
    CHECK(worst < ResponseSpectrum::kInterpolationErrorBound);
    // At grid periods the stored value is the exact one.
    CHECK(spectrum->saG(grid[10]) == Approx(pseudoSpectralAccelerationG(record, grid[10])).epsilon(1e-12));
    // Clamping outside the range, NaN for periods that are not positive.
    CHECK(spectrum->saG(0.001) == spectrum->saGValues().front());
    CHECK(spectrum->saG(50.0) == spectrum->saGValues().back());
    CHECK(std::isnan(spectrum->saG(0.0)));
    CHECK(std::isnan(spectrum->saG(NAN)));
  }
}

TEST_CASE("ResponseSpectrum rejects records and ranges it cannot describe", "[spectrum]") {
  const GroundMotion record = synthetic();
  GroundMotion silent = record;
  std::fill(silent.accelerationMps2.begin(), silent.accelerationMps2.end(), 0.0);
  const auto zero = ResponseSpectrum::compute(silent);
  REQUIRE_FALSE(zero.ok());
  CHECK(zero.error().find("no motion") != std::string::npos);
  CHECK(zero.error().find(record.name) != std::string::npos);
  CHECK_FALSE(ResponseSpectrum::compute(GroundMotion{"empty", 0.01, {}}).ok());
  CHECK_FALSE(ResponseSpectrum::compute(record, 1.0, 0.5).ok());
  CHECK_FALSE(ResponseSpectrum::compute(record, 0.0, 1.0).ok());
  CHECK_FALSE(ResponseSpectrum::compute(record, 1e-4, 1.0).ok());
  CHECK_FALSE(ResponseSpectrum::compute(record, 0.1, INFINITY).ok());
  CHECK_FALSE(ResponseSpectrum::compute(record, 0.1, 1.0, 1.0).ok());
}

TEST_CASE("ShakeMap target spectrum: anchors, log-log pieces and the long-period fall-off", "[spectrum]") {
  const SpectralOrdinates site{0.2, 0.5, 0.3, 0.1};
  // Anchors, and PGA at and below 0.03 s.
  CHECK(shakeMapTargetSaG(site, 0.01) == 0.2);
  CHECK(shakeMapTargetSaG(site, 0.03) == Approx(0.2).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 0.3) == Approx(0.5).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 1.0) == Approx(0.3).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 3.0) == Approx(0.1).epsilon(1e-12));
  // Log-log: at the geometric mean of two anchor periods, the geometric mean of their ordinates.
  CHECK(shakeMapTargetSaG(site, std::sqrt(0.03 * 0.3)) == Approx(std::sqrt(0.2 * 0.5)).epsilon(1e-12));  // 0.316228
  CHECK(shakeMapTargetSaG(site, std::sqrt(3.0)) == Approx(0.173205).epsilon(1e-5));
  // T = 0.5 s: w = ln(0.5/0.3) / ln(1/0.3) = 0.424283, Sa = 0.5 (0.3/0.5)^w = 0.402572 (by hand).
  CHECK(shakeMapTargetSaG(site, 0.5) == Approx(0.402572).epsilon(1e-5));
  // Beyond 3 s: PSA30·3/T up to T_L = 6 s, then PSA30·3·6/T².
  CHECK(shakeMapTargetSaG(site, 4.0) == Approx(0.075).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 6.0) == Approx(0.05).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 8.0) == Approx(0.028125).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 12.0) == Approx(0.0125).epsilon(1e-12));
  // Another T_L: 8 s keeps 1/T until 8 s; 2 s (below 3 s) gives 1/T² from 3 s on.
  CHECK(shakeMapTargetSaG(site, 8.0, 8.0) == Approx(0.0375).epsilon(1e-12));
  CHECK(shakeMapTargetSaG(site, 4.0, 2.0) == Approx(0.05625).epsilon(1e-12));
  // Monotone between anchors (rising to 0.3 s, falling after) and continuous at 3 s and T_L.
  double previous = 0.0;
  for (double t = 0.03; t <= 0.3; t *= 1.05) {
    CHECK(shakeMapTargetSaG(site, t) >= previous);
    previous = shakeMapTargetSaG(site, t);
  }
  previous = 1.0;
  for (double t = 0.31; t <= 20.0; t *= 1.05) {
    CHECK(shakeMapTargetSaG(site, t) < previous);
    previous = shakeMapTargetSaG(site, t);
  }
  CHECK(shakeMapTargetSaG(site, 3.0 * (1 + 1e-9)) == Approx(0.1).epsilon(1e-6));
  CHECK(shakeMapTargetSaG(site, 6.0 * (1 + 1e-9)) == Approx(0.05).epsilon(1e-6));
  // Invalid input: NaN.
  CHECK(std::isnan(shakeMapTargetSaG(site, 0.0)));
  CHECK(std::isnan(shakeMapTargetSaG(site, -1.0)));
  CHECK(std::isnan(shakeMapTargetSaG(site, NAN)));
  CHECK(std::isnan(shakeMapTargetSaG(site, 1.0, 0.0)));
  CHECK(std::isnan(shakeMapTargetSaG({0.0, 0.5, 0.3, 0.1}, 1.0)));
  CHECK(std::isnan(shakeMapTargetSaG({0.2, NAN, 0.3, 0.1}, 1.0)));
  CHECK(std::isnan(shakeMapTargetSaG({0.2, 0.5, -0.3, 0.1}, 1.0)));
  CHECK(std::isnan(shakeMapTargetSaG({0.2, 0.5, 0.3, INFINITY}, 1.0)));
}

TEST_CASE("Spectral scaling: scale and errors naming the problem", "[spectrum]") {
  const auto ok = spectralScaling(0.3, 0.12);
  REQUIRE(ok.ok());
  CHECK(ok->scale == Approx(2.5));
  CHECK(ok->recordSaG == 0.12);
  const auto badTarget = spectralScaling(0.0, 0.12);
  REQUIRE_FALSE(badTarget.ok());
  CHECK(badTarget.error().find("target Sa") != std::string::npos);
  const auto badRecord = spectralScaling(0.3, NAN);
  REQUIRE_FALSE(badRecord.ok());
  CHECK(badRecord.error().find("record Sa") != std::string::npos);
  CHECK_FALSE(spectralScaling(-1.0, 0.1).ok());
  CHECK_FALSE(spectralScaling(0.3, 0.0).ok());
}

TEST_CASE("First-mode period of a building model is computeModes' first period", "[spectrum]") {
  for (const int storeys : {1, 5, 30}) {
    qv::BuildingAttributes attributes;
    attributes.id = "w" + std::to_string(storeys);
    attributes.storeys = static_cast<std::uint16_t>(storeys);
    attributes.heightM = 3.2f * static_cast<float>(storeys);
    attributes.footprintAreaM2 = 400.0f;
    const auto model = buildingModelFromAttributes(attributes);
    REQUIRE(model.ok());
    const auto modes = computeModes(*model);
    REQUIRE(modes.ok());
    const auto t1 = firstModePeriodS(*model);
    REQUIRE(t1.ok());
    CAPTURE(storeys);
    CHECK(*t1 == modes->periodsS.front());
    // The model is built to meet the code period (BuildingModel.h).
    CHECK(*t1 ==
          Approx(codePeriodS(resolvedStructuralType(attributes.structuralType, storeys), attributes.heightM, storeys))
              .epsilon(1e-6));
  }
  ShearBuilding invalid;
  invalid.floorMassKg = {1000.0};
  invalid.storeyStiffnessNPerM = {-1.0};
  CHECK_FALSE(firstModePeriodS(invalid).ok());
}

TEST_CASE("BSSA14 PSA matches OpenQuake's verification tables", "[spectrum][gmpe]") {
  // Rows of the BSSA14 verification tables shipped with the OpenQuake engine
  // (openquake/hazardlib/tests/gsim/data/BSSA2014/BSSA_2014_NOSOF_MEAN.csv for the unspecified
  // mechanism and BSSA_2014_MEAN.csv with rake -90 / 0 / 90 for normal / strike-slip / reverse; PSA
  // in g). 0.21 s is not a tabulated period (between 0.2 and 0.22 s).
  struct Case {
    double magnitude, rjbKm, vs30;
    FaultMechanism mechanism;
    double periodS, psaG;
  };
  const Case cases[] = {
      {7.0, 20.0, 760.0, FaultMechanism::Unspecified, 0.3, 0.282258},
      {7.0, 20.0, 760.0, FaultMechanism::Unspecified, 1.0, 0.0971904},
      {7.0, 20.0, 760.0, FaultMechanism::Unspecified, 0.21, 0.326582},
      {6.0, 50.0, 400.0, FaultMechanism::Unspecified, 3.0, 0.00567045},
      {5.0, 0.0, 200.0, FaultMechanism::Unspecified, 1.0, 0.0698678},
      {8.0, 100.0, 600.0, FaultMechanism::Unspecified, 10.0, 0.00948811},
      {7.0, 0.0, 250.0, FaultMechanism::Normal, 0.3, 0.96927},
      {7.0, 0.0, 250.0, FaultMechanism::StrikeSlip, 1.0, 0.695767},
      {7.0, 0.0, 250.0, FaultMechanism::Reverse, 3.0, 0.213786},
      {6.0, 20.0, 760.0, FaultMechanism::StrikeSlip, 0.21, 0.254378},
      {4.0, 75.0, 400.0, FaultMechanism::Reverse, 0.3, 0.00140984},
      {8.0, 50.0, 200.0, FaultMechanism::Normal, 10.0, 0.0245935},
      {8.0, 50.0, 200.0, FaultMechanism::Reverse, 1.0, 0.223435},
  };
  for (const Case& c : cases) {
    CAPTURE(c.magnitude, c.rjbKm, c.vs30, static_cast<int>(c.mechanism), c.periodS);
    CHECK(bssa14MedianPsaG(c.periodS, c.magnitude, c.rjbKm, c.vs30, c.mechanism) == Approx(c.psaG).epsilon(0.005));
  }
}

TEST_CASE("BSSA14 PSA: PGA at T = 0, table values at tabulated periods, log-log between", "[spectrum][gmpe]") {
  for (const FaultMechanism mechanism :
       {FaultMechanism::Unspecified, FaultMechanism::StrikeSlip, FaultMechanism::Normal, FaultMechanism::Reverse}) {
    for (const double m : {3.5, 5.5, 7.5}) {
      for (const double vs30 : {180.0, 400.0, 760.0, 1200.0}) {
        CHECK(bssa14MedianPsaG(0.0, m, 15.0, vs30, mechanism) == bssa14MedianPgaG(m, 15.0, vs30, mechanism));
      }
    }
  }
  // Continuous across tabulated periods (the interpolation meets the table's value there) ...
  for (const double t : {0.01, 0.2, 0.3, 0.667, 1.0, 3.0, 9.5}) {
    const double atTable = bssa14MedianPsaG(t, 6.5, 10.0, 400.0);
    CAPTURE(t);
    CHECK(bssa14MedianPsaG(t * (1 - 1e-9), 6.5, 10.0, 400.0) == Approx(atTable).epsilon(1e-6));
    CHECK(bssa14MedianPsaG(t * (1 + 1e-9), 6.5, 10.0, 400.0) == Approx(atTable).epsilon(1e-6));
  }
  // ... linear in ln PSA vs ln T between two neighbouring tabulated periods (0.2 and 0.22 s) ...
  const double lo = bssa14MedianPsaG(0.2, 6.5, 10.0, 400.0);
  const double hi = bssa14MedianPsaG(0.22, 6.5, 10.0, 400.0);
  CHECK(bssa14MedianPsaG(std::sqrt(0.2 * 0.22), 6.5, 10.0, 400.0) == Approx(std::sqrt(lo * hi)).epsilon(1e-12));
  // ... the 0.01 s row below 0.01 s, 1/T² beyond 10 s, NaN for negative periods.
  CHECK(bssa14MedianPsaG(0.005, 6.5, 10.0, 400.0) == bssa14MedianPsaG(0.01, 6.5, 10.0, 400.0));
  CHECK(bssa14MedianPsaG(20.0, 6.5, 10.0, 400.0) == Approx(bssa14MedianPsaG(10.0, 6.5, 10.0, 400.0) / 4.0));
  CHECK(std::isnan(bssa14MedianPsaG(-1.0, 6.5, 10.0, 400.0)));
  CHECK(std::isnan(bssa14MedianPsaG(NAN, 6.5, 10.0, 400.0)));
}
