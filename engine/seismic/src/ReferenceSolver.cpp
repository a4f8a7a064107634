#include "qv/seismic/ReferenceSolver.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "BoucWenUpdate.h"
#include "qv/core/NumberFormat.h"

namespace qv::seismic {

int automaticSubsteps(double recordStepS, double period1S, double period2S, int maxSubsteps) {
  double limit = period1S / 20.0;
  if (period2S > 0.0) limit = std::fmin(limit, period2S / 10.0);
  if (!(limit > 0.0) || !(recordStepS > 0.0)) return 1;
  const double needed = std::ceil(recordStepS / limit - 1e-9);
  return static_cast<int>(std::clamp(needed, 1.0, static_cast<double>(std::max(1, maxSubsteps))));
}

double EnergyBalance::relativeImbalance() const {
  if (inputJ == 0.0) return 0.0;
  return std::fabs(inputJ - (kineticJ + dampingJ + elasticJ + hystereticJ)) / std::fabs(inputJ);
}

namespace {

enum class StepOutcome { Accepted, NotConverged, TooCoarse };

// Accuracy splits go at most 2^6 = 64 times finer than the automatic sub-step.
constexpr int kMaxAccuracySplits = 6;

// One storey's law, precomputed.
struct StoreyLaw {
  double k0 = 0.0;
  double elastic = 0.0;     // α k0 (k0 for a linear storey)
  double hysteretic = 0.0;  // (1 - α) k0 dy: force per unit ẑ (0 for a linear storey)
  double inverseYield = 0.0;
  double exponent = 1.0;
  double gammaShare = 0.5;
  double nIsTwo = 0.0;
  double cUnload = 0.0;
  bool closedForm = true;
  bool exact = false;  // integrated exactly (boucWenExact) when the run allows it
  bool linear = true;
};

// The backward-Euler Bouc–Wen update's local error per unit change of ẑ over a step of x = Δδ/dy:
// its leading term is ½ x² |d²ẑ/dx²|, and d²ẑ/dx² = −n |ẑ|^(n−1) ψ dẑ/dx with ψ = γ̂ + β̂ sgn(x ẑ),
// so per unit of Δẑ ≈ x dẑ/dx it is ½ |x| ψ n |ẑ|^(n−1). Bounding it bounds the error accumulated
// over a yield excursion relative to that excursion's change of ẑ (the update is first order: the
// error of a fixed step halves with the step). Zero while unloading with γ̂ = β̂ (straight branch).
inline double hystereticErrorEstimate(const StoreyLaw& law, double x, double z) {
  const double psi = law.gammaShare + (1.0 - law.gammaShare) * (x * z >= 0.0 ? 1.0 : -1.0);
  const double power = law.exponent == 1.0 ? 1.0 : law.exponent * std::pow(std::fabs(z), law.exponent - 1.0);
  return 0.5 * std::fabs(x) * std::fabs(psi) * power;
}

class Integrator {
 public:
  // `exactUpdate`: storeys with n in {1, 2} and γ̂ = β̂ use the exact update, the others backward Euler.
  Integrator(const ShearBuilding& b, const GroundMotion& motion, const ReferenceOptions& o, const Modes& modes,
             bool exactUpdate)
      : motion_(motion), options_(o), n_(b.storeys()), mass_(b.floorMassKg), damping_(b.damping) {
    laws_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      StoreyLaw& law = laws_[i];
      law.k0 = b.storeyStiffnessNPerM[i];
      law.elastic = law.k0;
      if (!b.hysteresis.empty() && std::isfinite(b.hysteresis[i].yieldDisplacementM)) {
        const BoucWenStorey& h = b.hysteresis[i];
        law.linear = false;
        law.elastic = h.alpha * law.k0;
        law.hysteretic = (1.0 - h.alpha) * law.k0 * h.yieldDisplacementM;
        law.inverseYield = 1.0 / h.yieldDisplacementM;
        law.exponent = h.exponent;
        law.gammaShare = h.gammaShare;
        law.nIsTwo = h.exponent == 2.0 ? 1.0 : 0.0;
        law.cUnload = 2.0 * h.gammaShare - 1.0;
        law.closedForm = (h.exponent == 1.0 || h.exponent == 2.0) && h.gammaShare <= 0.5;
        law.exact = exactUpdate && (h.exponent == 1.0 || h.exponent == 2.0) && h.gammaShare == 0.5;
      }
    }
    modal_ = damping_.kind == DampingKind::Modal;
    if (modal_) {
      // C = M Φ diag(2 ζ ω) Φᵀ M with mass-normalised Φ (classical damping, Chopra §11.4).
      dampingMatrix_.assign(n_ * n_, 0.0);
      for (std::size_t k = 0; k < n_; ++k) {
        const double c = 2.0 * damping_.modalRatio * modes.circularFrequencies[k];
        for (std::size_t i = 0; i < n_; ++i) {
          const double mi = mass_[i] * modes.shapes[k * n_ + i] * c;
          for (std::size_t j = 0; j < n_; ++j) {
            dampingMatrix_[i * n_ + j] += mi * modes.shapes[k * n_ + j] * mass_[j];
          }
        }
      }
    }
    u_.assign(n_, 0.0);
    v_.assign(n_, 0.0);
    a_.assign(n_, 0.0);
    z_.assign(n_, 0.0);
    drift_.assign(n_, 0.0);
    force_.assign(n_, 0.0);
    du_.assign(n_, 0.0);
    zTrial_.assign(n_, 0.0);
    forceTrial_.assign(n_, 0.0);
    tangent_.assign(n_, 0.0);
    vNew_.assign(n_, 0.0);
    aNew_.assign(n_, 0.0);
    dampingForce_.assign(n_, 0.0);
    residual_.assign(n_, 0.0);
    correction_.assign(n_, 0.0);
    diagonal_.assign(n_, 0.0);
    offDiagonal_.assign(n_, 0.0);
    pivot_.assign(n_, 0.0);
    if (modal_) dense_.assign(n_ * n_, 0.0);
  }

  double ground(double t) const { return options_.scale * motion_.accelerationAt(t - options_.delaySeconds); }

  // Advances the state from t0 by h. On failure (Newton did not converge, or some backward-Euler
  // storey's Bouc–Wen update's estimated error exceeds `maxHystereticError`, see
  // hystereticErrorEstimate; exactly integrated storeys have none) the state is unchanged.
  StepOutcome step(double t0, double h, double maxHystereticError, SolverStats& stats, EnergyBalance* energy) {
    const double c0 = 4.0 / (h * h);
    const double c1 = 2.0 / h;
    const double c2 = 4.0 / h;
    const double agOld = ground(t0);
    const double ag = ground(t0 + h);
    // Predictor: constant acceleration over the step.
    for (std::size_t i = 0; i < n_; ++i) du_[i] = h * v_[i] + 0.5 * h * h * a_[i];
    bool converged = false;
    bool stagnated = false;
    for (int iteration = 0; iteration <= options_.maxNewtonIterations; ++iteration) {
      if (!evaluate(c0, c1, c2, ag)) return StepOutcome::NotConverged;
      // Convergence: residual small against the size of the terms, or no progress left to make.
      double residualMax = 0.0;
      double scaleMax = 1e-300;
      for (std::size_t i = 0; i < n_; ++i) {
        residualMax = std::fmax(residualMax, std::fabs(residual_[i]));
        scaleMax = std::fmax(scaleMax, std::fabs(mass_[i] * aNew_[i]) + std::fabs(mass_[i] * ag) +
                                           std::fabs(forceTrial_[i]) + std::fabs(dampingForce_[i]));
      }
      if (residualMax <= 1e-10 * scaleMax || stagnated) {
        converged = true;
        break;
      }
      if (iteration == options_.maxNewtonIterations) break;
      if (!solveCorrection(c0, c1)) return StepOutcome::NotConverged;
      ++stats.newtonIterations;
      double correctionMax = 0.0;
      double sizeMax = 1e-300;
      for (std::size_t i = 0; i < n_; ++i) {
        du_[i] += correction_[i];
        correctionMax = std::fmax(correctionMax, std::fabs(correction_[i]));
        sizeMax = std::fmax(sizeMax, std::fabs(u_[i]) + std::fabs(du_[i]));
      }
      stagnated = correctionMax <= 1e-15 * sizeMax;
    }
    if (!converged) return StepOutcome::NotConverged;
    if (maxHystereticError < 1.0) {
      for (std::size_t i = 0; i < n_; ++i) {
        const StoreyLaw& law = laws_[i];
        if (law.linear || law.exact) continue;
        const double x = (du_[i] - (i > 0 ? du_[i - 1] : 0.0)) * law.inverseYield;
        if (hystereticErrorEstimate(law, x, zTrial_[i]) > maxHystereticError) return StepOutcome::TooCoarse;
      }
    }
    if (energy != nullptr) accumulateEnergy(*energy, agOld, ag);
    for (std::size_t i = 0; i < n_; ++i) {
      u_[i] += du_[i];
      v_[i] = vNew_[i];
      a_[i] = aNew_[i];
      drift_[i] += du_[i] - (i > 0 ? du_[i - 1] : 0.0);
      z_[i] = zTrial_[i];
      force_[i] = forceTrial_[i];
    }
    lastGround_ = ag;
    ++stats.steps;
    return StepOutcome::Accepted;
  }

  const std::vector<double>& displacement() const { return u_; }
  const std::vector<double>& acceleration() const { return a_; }
  const std::vector<double>& drift() const { return drift_; }
  const std::vector<double>& force() const { return force_; }
  double lastGround() const { return lastGround_; }

  double kineticEnergy() const {
    double e = 0.0;
    for (std::size_t i = 0; i < n_; ++i) e += 0.5 * mass_[i] * v_[i] * v_[i];
    return e;
  }
  double elasticEnergy() const {
    double e = 0.0;
    for (std::size_t i = 0; i < n_; ++i) {
      const StoreyLaw& law = laws_[i];
      e += 0.5 * law.elastic * drift_[i] * drift_[i];
      if (!law.linear) {
        const double zDim = z_[i] / law.inverseYield;  // ẑ dy (m)
        e += 0.5 * (law.hysteretic * law.inverseYield) * zDim * zDim;
      }
    }
    return e;
  }

 private:
  // Storey states, forces and the residual at the current increment du_.
  bool evaluate(double c0, double c1, double c2, double ag) {
    for (std::size_t i = 0; i < n_; ++i) {
      const StoreyLaw& law = laws_[i];
      const double dDrift = du_[i] - (i > 0 ? du_[i - 1] : 0.0);
      const double driftNew = drift_[i] + dDrift;
      if (law.linear) {
        zTrial_[i] = 0.0;
        forceTrial_[i] = law.elastic * driftNew;
        tangent_[i] = law.elastic;
        continue;
      }
      const double x = dDrift * law.inverseYield;
      double z = 0.0;
      double slope = 0.0;
      if (law.exact) {
        detail::boucWenExact(z_[i], x, law.nIsTwo, z, slope);
      } else if (law.closedForm) {
        detail::boucWenClosedForm(z_[i], x, law.nIsTwo, law.cUnload, z, slope);
      } else if (!detail::boucWenGeneral(z_[i], x, law.exponent, law.gammaShare, z, slope)) {
        return false;
      }
      zTrial_[i] = z;
      forceTrial_[i] = law.elastic * driftNew + law.hysteretic * z;
      tangent_[i] = law.elastic + law.hysteretic * law.inverseYield * slope;
    }
    for (std::size_t i = 0; i < n_; ++i) {
      vNew_[i] = c1 * du_[i] - v_[i];
      aNew_[i] = c0 * du_[i] - c2 * v_[i] - a_[i];
    }
    dampingTimes(vNew_, dampingForce_);
    for (std::size_t i = 0; i < n_; ++i) {
      const double above = i + 1 < n_ ? forceTrial_[i + 1] : 0.0;
      residual_[i] = -mass_[i] * (ag + aNew_[i]) - dampingForce_[i] - (forceTrial_[i] - above);
    }
    return true;
  }

  // out = C v.
  void dampingTimes(const std::vector<double>& v, std::vector<double>& out) const {
    if (modal_) {
      for (std::size_t i = 0; i < n_; ++i) {
        double sum = 0.0;
        for (std::size_t j = 0; j < n_; ++j) sum += dampingMatrix_[i * n_ + j] * v[j];
        out[i] = sum;
      }
      return;
    }
    for (std::size_t i = 0; i < n_; ++i) {
      const double below = i > 0 ? v[i - 1] : 0.0;
      const double above = i + 1 < n_ ? v[i + 1] : 0.0;
      const double kBelow = laws_[i].k0;
      const double kAbove = i + 1 < n_ ? laws_[i + 1].k0 : 0.0;
      const double kv = kBelow * (v[i] - below) - kAbove * (above - v[i]);
      out[i] = damping_.massCoefficient * mass_[i] * v[i] + damping_.stiffnessCoefficient * kv;
    }
  }

  // Solves (c0 M + c1 C + K_t) correction = residual.
  bool solveCorrection(double c0, double c1) {
    if (!modal_) {
      const double a0 = damping_.massCoefficient;
      const double a1 = damping_.stiffnessCoefficient;
      for (std::size_t i = 0; i < n_; ++i) {
        const double kAbove = i + 1 < n_ ? laws_[i + 1].k0 : 0.0;
        const double tAbove = i + 1 < n_ ? tangent_[i + 1] : 0.0;
        diagonal_[i] = (c0 + c1 * a0) * mass_[i] + c1 * a1 * (laws_[i].k0 + kAbove) + tangent_[i] + tAbove;
        offDiagonal_[i] = -(c1 * a1 * kAbove + tAbove);
      }
      // Thomas algorithm (symmetric positive definite: no pivoting needed).
      pivot_[0] = diagonal_[0];
      correction_[0] = residual_[0];
      for (std::size_t i = 1; i < n_; ++i) {
        const double l = offDiagonal_[i - 1] / pivot_[i - 1];
        pivot_[i] = diagonal_[i] - l * offDiagonal_[i - 1];
        correction_[i] = residual_[i] - l * correction_[i - 1];
      }
      for (std::size_t i = n_; i-- > 0;) {
        if (!(pivot_[i] > 0.0)) return false;
        const double next = i + 1 < n_ ? correction_[i + 1] : 0.0;
        correction_[i] = (correction_[i] - offDiagonal_[i] * next) / pivot_[i];
      }
      return true;
    }
    // Dense: c0 M + c1 C + K_t, Cholesky factorisation in place (lower triangle).
    for (std::size_t k = 0; k < n_ * n_; ++k) dense_[k] = c1 * dampingMatrix_[k];
    for (std::size_t i = 0; i < n_; ++i) {
      dense_[i * n_ + i] += c0 * mass_[i] + tangent_[i] + (i + 1 < n_ ? tangent_[i + 1] : 0.0);
      if (i + 1 < n_) {
        dense_[i * n_ + i + 1] -= tangent_[i + 1];
        dense_[(i + 1) * n_ + i] -= tangent_[i + 1];
      }
    }
    for (std::size_t j = 0; j < n_; ++j) {
      double d = dense_[j * n_ + j];
      for (std::size_t k = 0; k < j; ++k) d -= dense_[j * n_ + k] * dense_[j * n_ + k];
      if (!(d > 0.0)) return false;
      const double root = std::sqrt(d);
      dense_[j * n_ + j] = root;
      for (std::size_t i = j + 1; i < n_; ++i) {
        double s = dense_[i * n_ + j];
        for (std::size_t k = 0; k < j; ++k) s -= dense_[i * n_ + k] * dense_[j * n_ + k];
        dense_[i * n_ + j] = s / root;
      }
    }
    for (std::size_t i = 0; i < n_; ++i) {
      double s = residual_[i];
      for (std::size_t k = 0; k < i; ++k) s -= dense_[i * n_ + k] * correction_[k];
      correction_[i] = s / dense_[i * n_ + i];
    }
    for (std::size_t i = n_; i-- > 0;) {
      double s = correction_[i];
      for (std::size_t k = i + 1; k < n_; ++k) s -= dense_[k * n_ + i] * correction_[k];
      correction_[i] = s / dense_[i * n_ + i];
    }
    return true;
  }

  void accumulateEnergy(EnergyBalance& e, double agOld, double ag) {
    // Input and damping work by the trapezoidal rule, exact for Newmark's average acceleration.
    std::vector<double>& vMean = correction_;  // scratch
    for (std::size_t i = 0; i < n_; ++i) vMean[i] = 0.5 * (v_[i] + vNew_[i]);
    std::vector<double>& cv = pivot_;  // scratch
    dampingTimes(vMean, cv);
    for (std::size_t i = 0; i < n_; ++i) {
      e.inputJ -= du_[i] * mass_[i] * 0.5 * (agOld + ag);
      e.dampingJ += du_[i] * cv[i];
    }
    // Hysteretic dissipation: rate (1-α) k0 dy ẑ |ẑ|^n ψ(sgn(dδ ẑ)) dδ, trapezoidal in time.
    for (std::size_t i = 0; i < n_; ++i) {
      const StoreyLaw& law = laws_[i];
      if (law.linear) continue;
      const double dDrift = du_[i] - (i > 0 ? du_[i - 1] : 0.0);
      auto rate = [&](double z) {
        const double psi = law.gammaShare + (1.0 - law.gammaShare) * (dDrift * z >= 0.0 ? 1.0 : -1.0);
        return z * std::pow(std::fabs(z), law.exponent) * psi;
      };
      e.hystereticJ += law.hysteretic * 0.5 * (rate(z_[i]) + rate(zTrial_[i])) * dDrift;
    }
  }

  const GroundMotion& motion_;
  const ReferenceOptions& options_;
  std::size_t n_;
  const std::vector<double>& mass_;
  Damping damping_;
  bool modal_ = false;
  std::vector<StoreyLaw> laws_;
  std::vector<double> dampingMatrix_;
  std::vector<double> u_, v_, a_, z_, drift_, force_;
  std::vector<double> du_, zTrial_, forceTrial_, tangent_, vNew_, aNew_, dampingForce_, residual_, correction_,
      diagonal_, offDiagonal_, pivot_, dense_;
  double lastGround_ = 0.0;
};

// Advances by h, splitting the step in two (recursively) when Newton does not converge (8 levels)
// or when the hysteretic update is too coarse (kMaxAccuracySplits levels; at that depth the step is
// accepted as it is). `onStep` runs after every accepted step. A failed step leaves the integrator
// unchanged (it commits only converged states).
template <typename OnStep>
bool advance(Integrator& integrator, double t0, double h, int depth, double maxHystereticError, SolverStats& stats,
             EnergyBalance* energy, const OnStep& onStep) {
  const double limit = depth >= kMaxAccuracySplits ? 2.0 : maxHystereticError;
  const StepOutcome outcome = integrator.step(t0, h, limit, stats, energy);
  if (outcome == StepOutcome::Accepted) {
    onStep();
    return true;
  }
  if (depth >= 8) return false;
  ++(outcome == StepOutcome::TooCoarse ? stats.refinedSteps : stats.splitSteps);
  return advance(integrator, t0, 0.5 * h, depth + 1, maxHystereticError, stats, energy, onStep) &&
         advance(integrator, t0 + 0.5 * h, 0.5 * h, depth + 1, maxHystereticError, stats, energy, onStep);
}

}  // namespace

Result<ReferenceResponse> solveReference(const ShearBuilding& building, const GroundMotion& motion,
                                         const ReferenceOptions& options) {
  if (const Status s = validateShearBuilding(building); !s) return Error{s.error()};
  if (!(motion.timeStepS > 0.0) || motion.size() == 0) {
    return fail("motion '" + motion.name + "': empty or without a time step");
  }
  if (!(std::isfinite(options.scale)) || !(options.delaySeconds >= 0.0 && options.delaySeconds <= 1e5) ||
      !(options.freeVibrationSeconds >= 0.0 && options.freeVibrationSeconds <= 1e5)) {
    return fail("reference solver: scale must be finite and delay/free vibration in [0, 1e5] s");
  }
  if (options.substeps < 0 || options.substeps > 1000 || options.maxNewtonIterations < 1 ||
      options.maxNewtonIterations > 1000) {
    return fail("reference solver: substeps must be in [0, 1000] and Newton iterations in [1, 1000]");
  }
  const bool modal = building.damping.kind == DampingKind::Modal;
  auto modes = computeModes(building, modal);
  if (!modes) return Error{modes.error()};
  const std::size_t n = building.storeys();
  const double dt = motion.timeStepS;
  const double totalTime = options.delaySeconds + motion.durationS() + options.freeVibrationSeconds;
  const double framesDouble =
      options.frameCount > 0 ? static_cast<double>(options.frameCount) : std::ceil(totalTime / dt - 1e-9) + 1.0;
  if (framesDouble > 5e7 || framesDouble < 2.0) return fail("reference solver: 2 to 5e7 output frames are supported");
  const auto frames = static_cast<std::size_t>(framesDouble);
  const double t1 = modes->periodsS[0];
  const double t2 = n > 1 ? modes->periodsS[1] : 0.0;
  const int substeps = options.substeps > 0 ? options.substeps : automaticSubsteps(dt, t1, t2);

  ReferenceResponse out;
  out.timeStepS = dt;
  out.frames = frames;
  out.storeys = n;
  out.periodsS = modes->periodsS;
  out.stats.substeps = substeps;
  out.peakStoreyShearN.assign(n, 0.0);
  out.peakDriftM.assign(n, 0.0);
  const bool heights = !building.storeyHeightM.empty();
  if (options.keepHistory) {
    out.floorDisplacementM.assign(frames * n, 0.0);
    out.storeyForceN.assign(frames * n, 0.0);
    out.groundAccelerationMps2.assign(frames, 0.0);
  }

  const bool exactUpdate = options.substeps == 0 && options.exactHystereticUpdate;
  Integrator integrator(building, motion, options, *modes, exactUpdate);
  EnergyBalance* energy = options.computeEnergy ? &out.energy : nullptr;
  const double h = dt / substeps;
  // Peaks at every accepted step.
  const auto updatePeaks = [&] {
    const auto& u = integrator.displacement();
    const auto& acc = integrator.acceleration();
    const auto& drift = integrator.drift();
    const auto& force = integrator.force();
    const double ag = integrator.lastGround();
    out.peakRoofDisplacementM = std::fmax(out.peakRoofDisplacementM, std::fabs(u[n - 1]));
    out.peakBaseShearN = std::fmax(out.peakBaseShearN, std::fabs(force[0]));
    double moment = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      out.peakStoreyShearN[i] = std::fmax(out.peakStoreyShearN[i], std::fabs(force[i]));
      out.peakDriftM[i] = std::fmax(out.peakDriftM[i], std::fabs(drift[i]));
      out.peakFloorAccelerationMps2 = std::fmax(out.peakFloorAccelerationMps2, std::fabs(acc[i] + ag));
      if (heights) moment += force[i] * building.storeyHeightM[i];
    }
    out.peakBaseMomentNm = std::fmax(out.peakBaseMomentNm, std::fabs(moment));
  };
  // Equal steps when the caller fixes the sub-steps; automatic sub-steps also bound the error of the
  // backward-Euler updates (storeys not integrated exactly).
  const double maxHystereticError = options.substeps > 0 ? 2.0 : options.maxHystereticError;
  for (std::size_t f = 1; f < frames; ++f) {
    for (int s = 0; s < substeps; ++s) {
      const double t0 = static_cast<double>(f - 1) * dt + static_cast<double>(s) * h;
      if (!advance(integrator, t0, h, 0, maxHystereticError, out.stats, energy, updatePeaks)) {
        return fail("reference solver: Newton iterations did not converge at t = " + formatDouble(t0) +
                    " s even after splitting the step 256 times");
      }
    }
    if (options.keepHistory) {
      for (std::size_t i = 0; i < n; ++i) {
        out.floorDisplacementM[f * n + i] = integrator.displacement()[i];
        out.storeyForceN[f * n + i] = integrator.force()[i];
      }
      out.groundAccelerationMps2[f] = integrator.lastGround();
    }
  }
  if (heights) {
    out.peakDriftRatio.resize(n);
    for (std::size_t i = 0; i < n; ++i) out.peakDriftRatio[i] = out.peakDriftM[i] / building.storeyHeightM[i];
  }
  out.residualRoofDisplacementM = integrator.displacement()[n - 1];
  out.residualDriftM = integrator.drift();
  if (energy != nullptr) {
    out.energy.kineticJ = integrator.kineticEnergy();
    out.energy.elasticJ = integrator.elasticEnergy();
  }
  return out;
}

}  // namespace qv::seismic
