// The city path: nonlinear time histories of many buildings at once.
//
// Each building is solved in X and Y (two independent shear-building systems). Systems are sorted by
// storey count (then Bouc–Wen exponent, then delay) and packed into SIMD lanes, structure of arrays:
// 8 lanes of float or 4 of double per batch, as two interleaved groups of 16-byte vectors (a
// building's X and Y share a batch); lanes with fewer storeys are padded with decoupled floors that
// stay at rest. Per time step: Newmark average acceleration solved for the floor accelerations by
// Newton iterations (the first linearised about the previous step, then the consistent tangent of the
// closed-form Bouc–Wen update, n in {1, 2}), each a Thomas solve of the tridiagonal effective matrix
// across all lanes. Sub-steps per output step follow automaticSubsteps() (the largest need of the
// batch), with the exact Bouc–Wen update where every lane has γ̂ = β̂ (else the implicit backward-Euler
// update, a step cut into the pieces its error estimate asks for when it exceeds
// ResponseOptions::maxHystereticError in some lane); a step is halved, recursively, when a lane does
// not converge. Float batches converge to a residual of 1e-3 of the force terms (histories within
// ~1e-3 of the double reference), double batches to 1e-10.
//
// Contract: single-threaded; one ResponseSolver per thread (it owns its workspaces, which grow to the
// largest batch and are reused, so memory is bounded by one batch of histories). Results stream to a
// sink building by building; the sink must copy what it keeps. Units: metres, seconds, newtons; floor
// displacements are relative to the ground; drift ratios are storey drift / storey height.
//
// Time axis: frames at t = f·dt (dt = the output step, by default the X record's step), f = 0 ..
// frames-1, frame 0 at rest. Building b sees scale_b · a(t - delay_b) in each direction (the same
// delay for X and Y; the Y scale may differ, BuildingShaking::scaleY), so shaking before its arrival is
// zero.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "qv/core/Result.h"
#include "qv/seismic/Damage.h"
#include "qv/seismic/GroundMotion.h"
#include "qv/seismic/ReferenceSolver.h"
#include "qv/seismic/ShearBuilding.h"

namespace qv::seismic {

enum class Precision { Float, Double };

/// Per-building excitation: the record times `scale`, starting `delaySeconds` late (see
/// shakingAtSite in GroundMotionModel.h).
struct BuildingShaking {
  double scale = 1.0;         ///< X (and Y unless scaleY is set)
  double delaySeconds = 0.0;  ///< >= 0
  /// The Y record's scale when > 0 (spectral scaling at the Y model's own period); 0: `scale`.
  double scaleY = 0.0;
};

struct ResponseOptions {
  double outputStepS = 0.0;        ///< 0: the X record's step
  std::size_t frameCount = 0;      ///< 0: 1 + ceil((largest delay of the call + record length) / dt)
  bool floorDisplacements = true;  ///< keep the per-frame floor displacements
  bool driftRatios = false;        ///< keep the per-frame storey drift ratios (needs storey heights)
  Precision precision = Precision::Float;
  int maxNewtonIterations = 10;  ///< per attempt of a step
  int maxSubsteps = 16;
  int fixedSubsteps = 0;  ///< 0: automaticSubsteps() and the exact update (or the bound); else equal steps
  /// A step some lane does not converge in is split in two, recursively, this many levels (0 .. 10);
  /// a step still unconverged at the last level is accepted, counted and its residual recorded.
  int maxSplits = 4;
  /// With automatic sub-steps: batches whose storeys all have n in {1, 2} and γ̂ = β̂ (every city
  /// model) integrate the Bouc–Wen variable exactly along each step's drift increment
  /// (ReferenceOptions::exactHystereticUpdate), so the update adds no error and the periods' sub-steps
  /// keep yielding frames within 0.5 % of converged peaks at no extra steps (docs/seismic.md,
  /// "Sub-stepping"). false, or fixed sub-steps: backward Euler in every lane.
  bool exactHystereticUpdate = true;
  /// With automatic sub-steps, for batches on the backward-Euler update (some storey with γ̂ < β̂, or
  /// exactHystereticUpdate false): a step whose update's estimated local error per unit change
  /// of ẑ exceeds this in some storey of the batch is taken again as the 2^L equal pieces the estimate
  /// asks for (it is proportional to the step), at most maxSplits levels in all (ReferenceOptions::
  /// maxHystereticError; >= 1: off, sub-steps from the periods alone). Such systems are batched by their
  /// a priori need of splitting (scaled relative-velocity spectrum × step / yield drift), so a batch of
  /// buildings that stay nearly elastic is not split for one that yields.
  double maxHystereticError = kDefaultMaxHystereticError;
};

struct DirectionResponse {
  std::vector<float> floorDisplacementM;  ///< [frame * storeys + i], floor i+1; empty unless requested
  std::vector<float> driftRatio;          ///< [frame * storeys + i], storey i+1; empty unless requested
  std::vector<float> peakDriftM;          ///< per storey, over every step
  std::vector<float> peakDriftRatio;      ///< per storey; empty without storey heights
  std::vector<float> residualDriftRatio;  ///< per storey at the last frame; empty without heights
  float peakRoofDisplacementM = 0.0f;
  float residualRoofDisplacementM = 0.0f;                ///< signed, at the last frame
  float peakFloorAccelerationMps2 = 0.0f;                ///< absolute acceleration, all floors
  std::vector<float> peakFloorAccelerationPerFloorMps2;  ///< absolute, per floor (floor 1 first)
  float peakBaseShearN = 0.0f;                           ///< restoring force of storey 1 (damping excluded)
};

struct BuildingResponse {
  std::size_t storeys = 0;
  std::size_t frames = 0;
  double timeStepS = 0.0;
  bool hasY = false;
  DirectionResponse x;
  DirectionResponse y;                     ///< meaningful when hasY
  float maxDriftRatio = 0.0f;              ///< over storeys and directions (0 without heights)
  DamageState damage = DamageState::None;  ///< from maxDriftRatio and the X model's thresholds
  std::uint32_t nonConvergedSteps = 0;     ///< steps accepted without Newton convergence (X + Y)
  float worstResidualRatio = 0.0f;         ///< of those steps: the largest residual / size of the force terms
};

/// Called once per building, in batch order (not index order), from the solving thread.
using ResponseSink = std::function<void(std::size_t buildingIndex, const BuildingResponse& response)>;

class ResponseSolver {
 public:
  explicit ResponseSolver(const ResponseOptions& options = {});
  ~ResponseSolver();
  ResponseSolver(ResponseSolver&&) noexcept;
  ResponseSolver& operator=(ResponseSolver&&) noexcept;
  ResponseSolver(const ResponseSolver&) = delete;
  ResponseSolver& operator=(const ResponseSolver&) = delete;

  /// Solves every building of `buildings` (X models; `buildingsY`, when not empty, gives Y models with
  /// the same storey counts) under `motionX` and, when given, `motionY`, with `shaking[b]` per
  /// building (same size as `buildings`). Requirements checked first (nothing is solved on error):
  /// valid models, Rayleigh damping, Bouc–Wen storeys with n in {1, 2} and γ̂ <= 0.5 (or linear).
  Status solve(std::span<const ShearBuilding> buildings, std::span<const BuildingShaking> shaking,
               const GroundMotion& motionX, const GroundMotion* motionY, const ResponseSink& sink,
               std::span<const ShearBuilding> buildingsY = {});

  /// Counters accumulated over every solve() call, in system units (one building direction).
  [[nodiscard]] const SolverStats& stats() const;
  [[nodiscard]] const ResponseOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Convenience for small sets (tests, tools): every response in index order.
Result<std::vector<BuildingResponse>> solveResponses(std::span<const ShearBuilding> buildings,
                                                     std::span<const BuildingShaking> shaking,
                                                     const GroundMotion& motionX, const GroundMotion* motionY,
                                                     const ResponseOptions& options = {});

}  // namespace qv::seismic
