// Building models from city attributes: each building becomes a ShearBuilding (docs/seismic.md).
//
//   floor mass      footprint area × unit mass of the structural family (kg/m², unitFloorMassKgPerM2)
//   period          T1 = Ct h^x, ASCE 7-16 §12.8.2.1 and Table 12.8-2 in SI units, h the height (m):
//                   steel moment frames (S1) Ct 0.0724 x 0.8, concrete moment frames (C1) 0.0466 x 0.9,
//                   all other systems 0.0488 x 0.75
//   stiffness       k_i ∝ 1 - (1 - r)(i - 1)/(N - 1): linear taper from the base to r·k_base at the top
//                   storey (r = 0.5 by default; Miranda & Reyes 2002), scaled so T1 is met exactly
//   damping         5 % Rayleigh on modes 1 and 2 (one mode: 5 % at ω1)
//   hysteresis      Bouc–Wen per storey: yield drift ratio Dy / (α2 h_typ) and post-yield ratio
//                   α = [(Au - Ay)/(Du - Dy)] / (Ay / Dy) from the Hazus capacity curve of the type
//                   and era (Hazus 5.1 Technical Manual Tables 5-7a..d, heights and α2 of Tables 5-1
//                   and 5-5); n = 2 for steel, 1 otherwise; γ̂ = β̂ = 0.5
//   damage          Hazus drift thresholds (Damage.h)
// Unknown types use C1 of the storey count's height class, unknown eras moderate code.
#pragma once

#include <span>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"
#include "qv/seismic/ShearBuilding.h"

namespace qv::seismic {

struct BuildingModelOptions {
  double dampingRatio = 0.05;            ///< Rayleigh ratio on modes 1 and 2, [0, 0.5]
  double topToBaseStiffnessRatio = 0.5;  ///< r in (0, 1]; 1 = uniform
  double periodFactor = 1.0;             ///< multiplies the code period (e.g. 1.1 for the Y model)
  double defaultStoreyHeightM = 3.0;     ///< used when the attributes carry no height
  bool nonlinear = true;                 ///< false: linear storeys (no Bouc–Wen)
};

/// A Hazus capacity curve (yield and ultimate points of the pushover spectrum) with the typical
/// building height and the modal factor α2 that turn spectral displacement into drift.
struct HazusCapacity {
  double yieldDisplacementIn = 0.0;     ///< Dy (inches)
  double yieldAccelerationG = 0.0;      ///< Ay (g)
  double ultimateDisplacementIn = 0.0;  ///< Du (inches)
  double ultimateAccelerationG = 0.0;   ///< Au (g)
  double typicalHeightFt = 0.0;         ///< roof height of the Hazus model building (feet)
  double alpha2 = 0.75;                 ///< fraction of the height at the pushover-mode displacement
  /// Yield drift ratio Dy / (α2 h).
  [[nodiscard]] double yieldDriftRatio() const { return yieldDisplacementIn / (alpha2 * typicalHeightFt * 12.0); }
  /// Post-yield / initial stiffness of the bilinear curve through the two points.
  [[nodiscard]] double postYieldStiffnessRatio() const;
};

/// The type actually used for tables: `type` itself, or C1L/C1M/C1H by storeys when Unknown.
StructuralType resolvedStructuralType(StructuralType type, int storeys);
/// The era actually used for tables: moderate code when Unknown; low code for C3 and URM above it.
CodeEra resolvedCodeEra(StructuralType type, CodeEra era);

HazusCapacity hazusCapacity(StructuralType type, CodeEra era, int storeys = 1);
/// kg per m² of floor area (docs/seismic.md gives the sources).
double unitFloorMassKgPerM2(StructuralType type, int storeys = 1);
/// ASCE 7-16 approximate fundamental period T = Ct h^x (SI), h in metres.
double codePeriodS(StructuralType type, double heightM, int storeys = 1);
/// Bouc–Wen law of a storey of `storeyHeightM` for the type and era.
BoucWenStorey hazusBoucWen(StructuralType type, CodeEra era, double storeyHeightM, int storeys = 1);

/// The model of one building. Errors (absurd inputs: storeys outside 1..200, non-finite or
/// non-positive area, storey heights outside 1..60 m, options out of range) name the building id.
Result<ShearBuilding> buildingModelFromAttributes(const BuildingAttributes& attributes,
                                                  const BuildingModelOptions& options = {});

/// The models of many buildings, in order; a failed entry carries its message (skip or report it).
std::vector<Result<ShearBuilding>> buildingModelsFromAttributes(std::span<const BuildingAttributes> attributes,
                                                                const BuildingModelOptions& options = {});

}  // namespace qv::seismic
