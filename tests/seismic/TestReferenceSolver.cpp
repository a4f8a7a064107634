#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "Issue21Frame.h"
#include "qv/seismic/GroundMotionReader.h"
#include "qv/seismic/ReferenceSolver.h"

using namespace qv::seismic;

namespace {

const std::string kRecords = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/ground-motions/";

GroundMotion elCentro() {
  auto m = readGroundMotionFile(kRecords + "elCentro.AT2");
  REQUIRE(m.ok());
  return std::move(m).value();
}

ShearBuilding chopraFrame() {
  ShearBuilding b;
  b.floorMassKg.assign(5, 45000.0);
  b.storeyStiffnessNPerM.assign(5, 5.482e6);
  b.storeyHeightM.assign(5, 4.0);
  b.damping = Damping::modal(0.05);
  return b;
}

// The Chopra frame with Bouc–Wen storeys and 5 % Rayleigh damping on modes 1 and 2.
ShearBuilding hystereticFrame(double yieldM, double alpha, double n, double gammaShare = 0.5) {
  ShearBuilding b = chopraFrame();
  const auto modes = computeModes(b);
  REQUIRE(modes.ok());
  b.damping = Damping::rayleighFromModes(0.05, modes->circularFrequencies[0], modes->circularFrequencies[1]);
  BoucWenStorey law;
  law.alpha = alpha;
  law.exponent = n;
  law.gammaShare = gammaShare;
  law.yieldDisplacementM = yieldM;
  b.hysteresis.assign(5, law);
  return b;
}

// A harmonic ground motion: amplitude (m/s²) · sin(2π f t) for `seconds`.
GroundMotion harmonic(double amplitude, double frequencyHz, double seconds, double dt) {
  GroundMotion m;
  m.name = "harmonic";
  m.timeStepS = dt;
  const auto count = static_cast<std::size_t>(seconds / dt);
  for (std::size_t k = 1; k <= count; ++k) {
    m.accelerationMps2.push_back(amplitude *
                                 std::sin(2.0 * std::numbers::pi * frequencyHz * static_cast<double>(k) * dt));
  }
  return m;
}

double maxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::fmax(d, std::fabs(a[i] - b[i]));
  return d;
}

double maxAbs(const std::vector<double>& a) {
  double d = 0.0;
  for (const double v : a) d = std::fmax(d, std::fabs(v));
  return d;
}

}  // namespace

TEST_CASE("Published oracle: Chopra Example 13.2.6 by Newmark average acceleration", "[seismic][reference]") {
  const auto r = solveReference(chopraFrame(), elCentro());
  REQUIRE(r.ok());
  CHECK(r->frames == 1560);  // the leading zero and 1559 samples at dt 0.02 s
  CHECK(r->stats.substeps == 1);
  CHECK(r->stats.steps == 1559);
  CHECK(r->stats.newtonIterations == 1559);  // linear: one solve per step
  CHECK(r->peakRoofDisplacementM == Approx(0.173303).epsilon(1e-4));
  CHECK(r->peakBaseShearN == Approx(323561.2).epsilon(1e-4));
  CHECK(r->peakStoreyShearN[4] == Approx(153613.9).epsilon(1e-4));
  CHECK(r->peakBaseMomentNm == Approx(3800187.4).epsilon(1e-4));
  CHECK(r->periodsS[0] == Approx(2.000).epsilon(2e-4));
  // Histories: frame 0 at rest, frame-major layout.
  CHECK(r->floorDisplacementM.size() == 1560 * 5);
  CHECK(r->floorDisplacementM[4] == 0.0);
  CHECK(r->groundAccelerationMps2[102] == Approx(-0.31882 * 9.81));
  CHECK(r->peakDriftRatio[0] == Approx(r->peakDriftM[0] / 4.0));
}

TEST_CASE("Rayleigh damping on a uniform frame gives the same modes 1-2 damping as modal", "[seismic][reference]") {
  // With Rayleigh on modes 1 and 2, the roof (dominated by mode 1) stays close to the modal result.
  ShearBuilding b = chopraFrame();
  const auto modes = computeModes(b);
  REQUIRE(modes.ok());
  b.damping = Damping::rayleighFromModes(0.05, modes->circularFrequencies[0], modes->circularFrequencies[1]);
  const auto rayleigh = solveReference(b, elCentro());
  REQUIRE(rayleigh.ok());
  CHECK(rayleigh->peakRoofDisplacementM == Approx(0.173303).epsilon(0.03));
}

TEST_CASE("Bouc-Wen with a very large yield displacement reproduces the linear solution", "[seismic][reference]") {
  const ShearBuilding nonlinear = hystereticFrame(1.0e6, 0.05, 1.0);
  ShearBuilding linear = nonlinear;
  linear.hysteresis.clear();
  const auto motion = elCentro();
  const auto a = solveReference(linear, motion);
  const auto b = solveReference(nonlinear, motion);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(maxAbsDifference(a->floorDisplacementM, b->floorDisplacementM) < 1e-6 * maxAbs(a->floorDisplacementM));
  CHECK(b->peakBaseShearN == Approx(a->peakBaseShearN).epsilon(1e-6));
}

TEST_CASE("Bouc-Wen energy balance closes within 1 % and hysteresis dissipates energy", "[seismic][reference]") {
  struct Case {
    const char* name;
    double yield, alpha, n, gammaShare;
    bool harmonicMotion;
  };
  const Case cases[] = {
      {"n=1 El Centro", 0.02, 0.1, 1.0, 0.5, false},
      {"n=2 El Centro", 0.02, 0.05, 2.0, 0.5, false},
      {"n=2 harmonic", 0.01, 0.05, 2.0, 0.5, true},
      {"n=1.5 general update", 0.02, 0.1, 1.5, 0.5, false},
      {"gamma > beta general update", 0.02, 0.1, 1.0, 0.9, false},
  };
  const GroundMotion record = elCentro();
  const GroundMotion sine = harmonic(3.0, 0.6, 20.0, 0.01);
  for (const Case& c : cases) {
    CAPTURE(c.name);
    ReferenceOptions o;
    o.computeEnergy = true;
    o.substeps = 4;
    o.freeVibrationSeconds = 5.0;
    const auto r =
        solveReference(hystereticFrame(c.yield, c.alpha, c.n, c.gammaShare), c.harmonicMotion ? sine : record, o);
    REQUIRE(r.ok());
    const EnergyBalance& e = r->energy;
    CHECK(e.inputJ > 0.0);
    CHECK(e.hystereticJ > 0.05 * e.inputJ);  // it yielded and dissipated a real share
    CHECK(e.dampingJ > 0.0);
    CHECK(e.relativeImbalance() < 0.01);
    CHECK(r->peakDriftM[0] > 2.0 * c.yield);  // well into the nonlinear range
  }
}

TEST_CASE("The response to -a(t) is the negative of the response to a(t)", "[seismic][reference]") {
  const GroundMotion record = elCentro();
  GroundMotion negated = record;
  for (double& a : negated.accelerationMps2) a = -a;
  for (const double gammaShare : {0.5, 0.9}) {
    const ShearBuilding b = hystereticFrame(0.02, 0.1, 1.0, gammaShare);
    const auto plus = solveReference(b, record);
    const auto minus = solveReference(b, negated);
    REQUIRE(plus.ok());
    REQUIRE(minus.ok());
    std::vector<double> sum(plus->floorDisplacementM.size());
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = plus->floorDisplacementM[i] + minus->floorDisplacementM[i];
    CHECK(maxAbs(sum) <= 1e-12 * maxAbs(plus->floorDisplacementM));
    CHECK(plus->residualRoofDisplacementM == Approx(-minus->residualRoofDisplacementM).margin(1e-12));
  }
}

TEST_CASE("Delay and scale shift and scale the linear response", "[seismic][reference]") {
  const GroundMotion record = elCentro();
  const auto base = solveReference(chopraFrame(), record);
  ReferenceOptions o;
  o.scale = 2.0;
  o.delaySeconds = 1.0;  // 50 record steps
  const auto shifted = solveReference(chopraFrame(), record, o);
  REQUIRE(base.ok());
  REQUIRE(shifted.ok());
  CHECK(shifted->frames == base->frames + 50);
  for (std::size_t f = 0; f < 50; ++f) CHECK(shifted->floorDisplacementM[f * 5 + 4] == 0.0);
  for (std::size_t f = 0; f < base->frames; f += 97) {
    CHECK(shifted->floorDisplacementM[(f + 50) * 5 + 4] ==
          Approx(2.0 * base->floorDisplacementM[f * 5 + 4]).margin(1e-12));
  }
  CHECK(shifted->peakRoofDisplacementM == Approx(2.0 * base->peakRoofDisplacementM));
}

TEST_CASE("Automatic sub-steps follow the periods, the oracle is not sub-stepped", "[seismic][reference]") {
  CHECK(automaticSubsteps(0.02, 2.0, 0.6852) == 1);
  CHECK(automaticSubsteps(0.01, 0.111, 0.0) == 2);  // one storey, T = 0.111 s: h <= 5.6 ms
  CHECK(automaticSubsteps(0.02, 0.3, 0.1) == 2);    // h <= min(15 ms, 10 ms)
  CHECK(automaticSubsteps(0.02, 0.01, 0.005, 16) == 16);
  // Sub-stepping a linear system changes the response only by the discretization error.
  ReferenceOptions o;
  o.substeps = 4;
  const auto fine = solveReference(chopraFrame(), elCentro(), o);
  REQUIRE(fine.ok());
  CHECK(fine->peakRoofDisplacementM == Approx(0.17395).epsilon(0.003));  // exact: 17.395 cm
}

TEST_CASE("Free vibration after the record decays, residual drift after yielding", "[seismic][reference]") {
  ReferenceOptions o;
  o.freeVibrationSeconds = 30.0;
  const auto linear = solveReference(chopraFrame(), elCentro(), o);
  REQUIRE(linear.ok());
  CHECK(std::fabs(linear->residualRoofDisplacementM) < 0.002 * linear->peakRoofDisplacementM);
  CHECK(linear->frames == 1560 + 1500);
  const auto yielded = solveReference(hystereticFrame(0.01, 0.02, 2.0), elCentro(), o);
  REQUIRE(yielded.ok());
  CHECK(std::fabs(yielded->residualDriftM[0]) > 1e-4);  // permanent set after yielding
  CHECK(yielded->stats.splitSteps == 0);
}

TEST_CASE("Automatic sub-steps keep a yielding frame's peaks within 0.5 % of converged", "[seismic][reference]") {
  // Issue 21: a 3-storey Bouc–Wen shear building under El Centro × 1.5 with 10 s of free vibration.
  // Two sub-steps from the periods alone gave a peak base shear 1.7 % low with the backward-Euler
  // update; OpenSees extrapolated to Δt → 0 gives 1 157 636 N.
  const ShearBuilding b = test::issue21Frame();
  ReferenceOptions options;
  options.scale = 1.5;
  options.freeVibrationSeconds = 10.0;
  options.keepHistory = false;
  const auto motion = elCentro();
  const auto automatic = solveReference(b, motion, options);
  REQUIRE(automatic.ok());
  ReferenceOptions convergedOptions = options;
  convergedOptions.substeps = 256;
  const auto converged = solveReference(b, motion, convergedOptions);
  REQUIRE(converged.ok());
  CHECK(converged->peakBaseShearN == Approx(1157636.0).epsilon(5e-4));
  const auto largest = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
  INFO("automatic: base shear " << automatic->peakBaseShearN << " N, roof " << automatic->peakRoofDisplacementM
                                << " m, drift " << largest(automatic->peakDriftRatio) << "; converged "
                                << converged->peakBaseShearN << " N, " << converged->peakRoofDisplacementM << " m, "
                                << largest(converged->peakDriftRatio) << "; steps " << automatic->stats.steps);
  // The defaults (exact update, the periods' two sub-steps): the issue's three peaks within 0.5 %.
  CHECK(automatic->peakBaseShearN == Approx(1157636.0).epsilon(0.005));
  CHECK(automatic->peakRoofDisplacementM == Approx(converged->peakRoofDisplacementM).epsilon(0.005));
  CHECK(largest(automatic->peakDriftRatio) == Approx(largest(converged->peakDriftRatio)).epsilon(0.005));
  // Every storey's peak drift within 1 % (the top storey, at 40 % of the first storey's drift, is
  // 0.7 % high: Newmark's error at these sub-steps, docs/seismic.md).
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(automatic->peakDriftRatio[i] == Approx(converged->peakDriftRatio[i]).epsilon(0.01));
  }
  // Equal steps stay equal (the OpenSees comparison): backward Euler, no refinement.
  ReferenceOptions fixedOptions = options;
  fixedOptions.substeps = 2;
  const auto fixed = solveReference(b, motion, fixedOptions);
  REQUIRE(fixed.ok());
  CHECK(fixed->stats.refinedSteps == 0);
  CHECK(fixed->peakBaseShearN == Approx(1137848.0).epsilon(1e-5));
  // The exact update needs no more steps than the periods ask for.
  CHECK(automatic->stats.substeps == 2);
  CHECK(automatic->stats.refinedSteps == 0);
  CHECK(automatic->stats.steps == fixed->stats.steps);
  // Backward Euler at the same steps is the 1.7 % low result; with its error bound it is within 0.5 %
  // again, at the price of refined steps.
  ReferenceOptions backwardEuler = options;
  backwardEuler.exactHystereticUpdate = false;
  backwardEuler.maxHystereticError = 1.0;
  const auto unbounded = solveReference(b, motion, backwardEuler);
  REQUIRE(unbounded.ok());
  CHECK(unbounded->peakBaseShearN == Approx(fixed->peakBaseShearN).epsilon(1e-9));
  backwardEuler.maxHystereticError = kDefaultMaxHystereticError;
  const auto bounded = solveReference(b, motion, backwardEuler);
  REQUIRE(bounded.ok());
  CHECK(bounded->peakBaseShearN == Approx(1157636.0).epsilon(0.005));
  CHECK(bounded->stats.refinedSteps > 0);
}

TEST_CASE("The exact update covers n = 2, and gamma below beta keeps the bounded backward Euler update",
          "[seismic][reference]") {
  const auto motion = elCentro();
  ReferenceOptions options;
  options.scale = 1.5;
  options.freeVibrationSeconds = 10.0;
  options.keepHistory = false;
  ReferenceOptions convergedOptions = options;
  convergedOptions.substeps = 256;
  for (const double gammaShare : {0.5, 0.25}) {
    for (const double exponent : {1.0, 2.0}) {
      CAPTURE(gammaShare, exponent);
      ShearBuilding b = test::issue21Frame();
      for (BoucWenStorey& h : b.hysteresis) {
        h.exponent = exponent;
        h.gammaShare = gammaShare;
      }
      const auto automatic = solveReference(b, motion, options);
      const auto converged = solveReference(b, motion, convergedOptions);
      REQUIRE(automatic.ok());
      REQUIRE(converged.ok());
      CHECK(automatic->peakBaseShearN == Approx(converged->peakBaseShearN).epsilon(0.005));
      CHECK(automatic->peakRoofDisplacementM == Approx(converged->peakRoofDisplacementM).epsilon(0.005));
      CHECK(automatic->peakDriftRatio[0] == Approx(converged->peakDriftRatio[0]).epsilon(0.005));
      // γ̂ = β̂: exact, at the periods' steps; γ̂ < β̂: backward Euler split by its error bound.
      CHECK((automatic->stats.refinedSteps > 0) == (gammaShare < 0.5));
    }
  }
}

TEST_CASE("With the exact update the yielding frame's peak base shear converges with the square of the step",
          "[seismic][reference]") {
  // The same record resampled at dt/4 (the piecewise-linear record is unchanged, so only the step
  // changes): automatic sub-steps then take h = 5 ms instead of 10 ms. Backward Euler's error halves
  // with the step (first order); the exact update leaves Newmark's, which falls four-fold.
  const ShearBuilding b = test::issue21Frame();
  const GroundMotion motion = elCentro();
  GroundMotion fine = motion;
  fine.timeStepS = motion.timeStepS / 4.0;
  fine.accelerationMps2.clear();
  for (std::size_t k = 1; k < 4 * (motion.size() + 1); ++k) {
    fine.accelerationMps2.push_back(motion.accelerationAt(static_cast<double>(k) * fine.timeStepS));
  }
  ReferenceOptions options;
  options.scale = 1.5;
  options.freeVibrationSeconds = 10.0;
  options.keepHistory = false;
  ReferenceOptions convergedOptions = options;
  convergedOptions.substeps = 256;
  const auto converged = solveReference(b, motion, convergedOptions);
  REQUIRE(converged.ok());
  for (const bool exact : {true, false}) {
    CAPTURE(exact);
    ReferenceOptions o = options;
    o.exactHystereticUpdate = exact;
    o.maxHystereticError = 1.0;  // backward Euler at the periods' steps alone
    const auto coarse = solveReference(b, motion, o);
    const auto refined = solveReference(b, fine, o);
    REQUIRE(coarse.ok());
    REQUIRE(refined.ok());
    CHECK(coarse->stats.substeps == 2);
    CHECK(refined->stats.substeps == 1);
    const double coarseError = std::fabs(coarse->peakBaseShearN / converged->peakBaseShearN - 1.0);
    const double refinedError = std::fabs(refined->peakBaseShearN / converged->peakBaseShearN - 1.0);
    INFO("base shear error " << 100.0 * coarseError << " % at 10 ms, " << 100.0 * refinedError << " % at 5 ms");
    if (exact) {
      CHECK(refinedError < coarseError / 3.0);
    } else {
      CHECK(refinedError > coarseError / 2.5);
    }
  }
}
