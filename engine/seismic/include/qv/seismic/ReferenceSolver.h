// The single-building reference solver (double precision): Newmark's average acceleration method
// (γ = 1/2, β = 1/4, unconditionally stable) on the coupled system, Newton iterations with the
// consistent tangent of the Bouc–Wen storeys' update (exact along the step's drift increment for
// n in {1, 2} and γ̂ = β̂ with automatic sub-steps, backward Euler otherwise; see
// ReferenceOptions::exactHystereticUpdate), a tridiagonal (Thomas) solve for
// Rayleigh damping and a dense Cholesky solve for classical modal damping. A time step whose Newton
// iterations do not converge is split in two, recursively. This is the oracle path (the mdof
// command, Chopra's example) and the yardstick of the batched city solver.
//
// Time axis: output frames at t = f·dt (dt = the record's step), f = 0..frames-1, frame 0 the state
// at rest. The excitation is scale · a(t - delay) under the time convention of GroundMotion.h; the run
// covers delay + the record + `freeVibrationSeconds`.
#pragma once

#include <cstddef>
#include <vector>

#include "qv/core/Result.h"
#include "qv/seismic/GroundMotion.h"
#include "qv/seismic/ShearBuilding.h"

namespace qv::seismic {

/// Sub-steps per record step so that h <= T1/20 and h <= T2/10 (period errors of Newmark's method
/// below 0.2 % and 0.8 %), capped at `maxSubsteps`. T2 <= 0 means a single mode.
int automaticSubsteps(double recordStepS, double period1S, double period2S, int maxSubsteps = 64);

/// The default bound on the estimated local error of the hysteretic update (see
/// ReferenceOptions::maxHystereticError).
inline constexpr double kDefaultMaxHystereticError = 0.005;

struct ReferenceOptions {
  double scale = 1.0;                 ///< multiplies the record
  double delaySeconds = 0.0;          ///< >= 0: the record starts this late
  double freeVibrationSeconds = 0.0;  ///< >= 0: simulated time after the record ends
  std::size_t frameCount = 0;         ///< 0: cover delay + record + free vibration; else exactly this
  int substeps = 0;                   ///< per record step: 0 = automaticSubsteps(), else 1..1000
  int maxNewtonIterations = 25;
  /// With automatic sub-steps (substeps = 0): storeys with n in {1, 2} and γ̂ = β̂ integrate the
  /// Bouc–Wen variable exactly along the step's drift increment (the update has no error of its own;
  /// the periods' sub-steps then keep yielding frames within 0.5 % of converged peaks). false, or
  /// fixed sub-steps: backward Euler in every storey, the equation OpenSees' BoucWen material solves.
  bool exactHystereticUpdate = true;
  /// With automatic sub-steps: a step whose backward-Euler Bouc–Wen update (storeys not integrated
  /// exactly) has an estimated local error above this, per unit change of the normalised variable ẑ,
  /// in some storey is split in two, recursively, up to 64 times finer (docs/seismic.md,
  /// "Sub-stepping"). The accumulated error of a yield excursion then stays about this fraction of
  /// its change of ẑ. >= 1: off (equal steps).
  double maxHystereticError = kDefaultMaxHystereticError;
  bool keepHistory = true;     ///< fill the per-frame vectors
  bool computeEnergy = false;  ///< fill `energy`
};

/// Energy terms in joules accumulated from the start (relative-motion formulation): the input
/// -∫ u̇ᵀ M 1 a_g dt equals kinetic + damping + elastic (recoverable strain) + hysteretic.
/// The hysteretic term integrates the Bouc–Wen dissipation rate (1-α) k dy ẑ |ẑ|^n ψ dδ by the
/// trapezoidal rule, independently of the discrete update, so the balance checks the integration.
struct EnergyBalance {
  double inputJ = 0.0;
  double kineticJ = 0.0;
  double dampingJ = 0.0;
  double elasticJ = 0.0;
  double hystereticJ = 0.0;
  /// |input - (kinetic + damping + elastic + hysteretic)| / |input| (0 when there is no input).
  [[nodiscard]] double relativeImbalance() const;
};

struct SolverStats {
  std::size_t steps = 0;              ///< time steps taken (after sub-stepping and splitting)
  std::size_t newtonIterations = 0;   ///< linear solves
  std::size_t nonConvergedSteps = 0;  ///< steps accepted without converging (batched solver only)
  std::size_t splitSteps = 0;         ///< steps split because Newton did not converge
  std::size_t refinedSteps = 0;       ///< steps split because the hysteretic update changed too much
  int substeps = 1;                   ///< sub-steps per record step
};

struct ReferenceResponse {
  double timeStepS = 0.0;  ///< output step (the record's)
  std::size_t frames = 0;
  std::size_t storeys = 0;
  std::vector<double> periodsS;  ///< of the initial system, mode 1 first
  // Per frame, frame-major ([frame * storeys + i]); empty unless keepHistory.
  std::vector<double> floorDisplacementM;      ///< floor i+1 relative to the ground
  std::vector<double> storeyForceN;            ///< restoring force of storey i+1 (damping excluded)
  std::vector<double> groundAccelerationMps2;  ///< [frame]
  // Peaks over every time step (absolute values).
  double peakRoofDisplacementM = 0.0;
  double peakBaseShearN = 0.0;             ///< restoring force of storey 1
  double peakBaseMomentNm = 0.0;           ///< Σ storey force × storey height (0 without heights)
  double peakFloorAccelerationMps2 = 0.0;  ///< absolute (relative + ground), over all floors
  std::vector<double> peakStoreyShearN;
  std::vector<double> peakDriftM;
  std::vector<double> peakDriftRatio;  ///< empty without storey heights
  // At the last frame.
  double residualRoofDisplacementM = 0.0;
  std::vector<double> residualDriftM;
  EnergyBalance energy;
  SolverStats stats;
};

Result<ReferenceResponse> solveReference(const ShearBuilding& building, const GroundMotion& motion,
                                         const ReferenceOptions& options = {});

}  // namespace qv::seismic
