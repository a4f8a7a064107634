// ShearBuilding: a multi-degree-of-freedom lumped-mass shear building in one horizontal direction.
//
// Frame and units: floors are numbered 1..N from the bottom (index 0 is floor 1); floor i carries
// mass m_i (kg) and moves by u_i (m) relative to the ground; storey i (index i-1) joins floor i-1
// (the ground for i = 1) to floor i and has height h_i (m), initial stiffness k_i (N/m), drift
// δ_i = u_i - u_{i-1} (m) and drift ratio δ_i / h_i. The ground accelerates by a_g(t) (m/s²); the
// equation of motion is M ü + C u̇ + f_s(u) = -M 1 a_g.
//
// Storey law: linear (f = k δ) or Bouc–Wen in the form of OpenSees' BoucWen uniaxial material with
// A = 1 and no degradation: f = α k δ + (1 - α) k z, dz = [1 - |z|^n (γ + β sgn(dδ·z))] dδ, z in
// metres. Stored normalised: z = dy·ẑ with dy = (γ + β)^(-1/n) the displacement at which z
// saturates, and γ̂ = γ / (γ + β), β̂ = β / (γ + β) (so γ̂ + β̂ = 1):
//   f = α k δ + (1 - α) k dy ẑ,   dẑ = (dδ / dy) [1 - |ẑ|^n (γ̂ + β̂ sgn(dδ·ẑ))].
// Damping: Rayleigh (C = a0 M + a1 K0 with K0 the initial stiffness) or classical modal (the same
// ratio in every mode of the initial system).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"

namespace qv::seismic {

/// Bouc–Wen parameters of one storey in the normalised form above.
struct BoucWenStorey {
  double alpha = 1.0;       ///< post-yield / initial stiffness, [0, 1]; 1 = linear
  double exponent = 1.0;    ///< n >= 1: sharpness of the transition
  double gammaShare = 0.5;  ///< γ̂ = γ / (γ + β), [0, 1]; β̂ = 1 - γ̂
  double yieldDisplacementM = std::numeric_limits<double>::infinity();  ///< dy > 0 (m)

  /// From OpenSees' parameters (alpha, n, gamma, beta; gamma + beta > 0, gamma and beta >= 0).
  static Result<BoucWenStorey> fromOpenSees(double alpha, double n, double gamma, double beta);
  /// γ̂ <= β̂: the unloading branch is never softer than the initial stiffness. The batched city
  /// solver requires this and n in {1, 2}; the reference solver handles any valid parameters.
  [[nodiscard]] bool unloadingStiff() const { return gammaShare <= 0.5; }
};

enum class DampingKind { Rayleigh, Modal };

struct Damping {
  DampingKind kind = DampingKind::Rayleigh;
  double massCoefficient = 0.0;       ///< a0 (1/s), Rayleigh
  double stiffnessCoefficient = 0.0;  ///< a1 (s), Rayleigh (times the initial stiffness)
  double modalRatio = 0.05;           ///< ζ in every mode, Modal

  static Damping rayleigh(double a0, double a1) { return {DampingKind::Rayleigh, a0, a1, 0.0}; }
  /// Rayleigh with ratio ζ at circular frequencies ω1 < ω2 (rad/s); with ω2 <= 0 (one mode), ζ at ω1
  /// split evenly between the mass and stiffness terms.
  static Damping rayleighFromModes(double ratio, double omega1, double omega2);
  static Damping modal(double ratio) { return {DampingKind::Modal, 0.0, 0.0, ratio}; }
};

struct ShearBuilding {
  std::vector<double> floorMassKg;           ///< N values, floor 1 first
  std::vector<double> storeyStiffnessNPerM;  ///< N initial stiffnesses, storey 1 first
  std::vector<double> storeyHeightM;         ///< N values, or empty (drift ratios then unavailable)
  std::vector<BoucWenStorey> hysteresis;     ///< N values, or empty for a linear building
  Damping damping;
  /// Average inter-storey drift ratios at the thresholds of slight, moderate, extensive and complete
  /// structural damage (Hazus); all zero when no damage state is to be assessed.
  std::array<double, 4> damageDriftThresholds{};
  StructuralType structuralType = StructuralType::Unknown;  ///< informative
  CodeEra codeEra = CodeEra::Unknown;                       ///< informative

  [[nodiscard]] std::size_t storeys() const { return floorMassKg.size(); }
  [[nodiscard]] bool linear() const { return hysteresis.empty(); }
};

/// Checks sizes (1..1000 storeys, matching vectors), finite positive masses, stiffnesses, heights
/// and yield displacements, α in [0, 1], n in [1, 20], γ̂ in [0, 1], and finite non-negative damping.
Status validateShearBuilding(const ShearBuilding& building);

struct Modes {
  std::vector<double> circularFrequencies;  ///< ω_j (rad/s), ascending (mode 1 first)
  std::vector<double> periodsS;             ///< T_j = 2π / ω_j, descending
  /// Mass-normalised shapes (φᵀ M φ = 1), column-major: shapes[j * N + i] is floor i of mode j; empty
  /// unless requested.
  std::vector<double> shapes;
};

/// Modes of the initial (linear) system: K φ = ω² M φ, solved as the symmetric tridiagonal
/// M^-1/2 K M^-1/2 by implicit QL (Wilkinson shifts). O(N²) without shapes, O(N³) with them.
Result<Modes> computeModes(const ShearBuilding& building, bool withShapes = false);

}  // namespace qv::seismic
