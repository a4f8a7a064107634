// Issue 21's 3-storey Bouc–Wen shear building (OpenSees parameters: floor mass 60 000 kg, storey
// stiffness 4.0e7 N/m, α 0.1, n 1, γ = β = 14.28571429, Rayleigh a0 0.8468543453, a1 0.002288968202),
// shared by the reference and the batched solver tests. Under El Centro × 1.5 with 10 s of free
// vibration, OpenSees extrapolated to Δt → 0 gives a peak base shear of 1 157 636 N.
#pragma once

#include <catch2/catch.hpp>

#include "qv/seismic/ShearBuilding.h"

namespace qv::seismic::test {

inline ShearBuilding issue21Frame() {
  ShearBuilding b;
  b.floorMassKg.assign(3, 60000.0);
  b.storeyStiffnessNPerM.assign(3, 4.0e7);
  b.storeyHeightM.assign(3, 3.0);
  b.damping = Damping::rayleigh(0.8468543453, 0.002288968202);
  const auto law = BoucWenStorey::fromOpenSees(0.1, 1.0, 14.28571429, 14.28571429);
  REQUIRE(law.ok());
  b.hysteresis.assign(3, *law);
  return b;
}

}  // namespace qv::seismic::test
