#include "qv/seismic/Damage.h"

#include <cstddef>

#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/HazusTables.h"

namespace qv::seismic {
namespace {

// The thresholds live in the shipped HAZUS table (HazusTables.h, generated from the SimCenter
// file); its rows are StructuralType 1..23 in order, so the type's value minus one indexes it.
static_assert(hazus::kStructuralTypes + 1 == static_cast<std::size_t>(StructuralType::Count));

}  // namespace

std::array<double, 4> hazusDriftThresholds(StructuralType type, CodeEra era, int storeys) {
  const StructuralType t = resolvedStructuralType(type, storeys);
  if (t == StructuralType::Unknown || t >= StructuralType::Count) return {0, 0, 0, 0};
  const hazus::StructuralRow& row = hazus::kStructural[static_cast<std::size_t>(t) - 1];
  const CodeEra e = resolvedCodeEra(t, era);
  const std::size_t column = e == CodeEra::Unknown || e >= CodeEra::Count ? 2 : static_cast<std::size_t>(e) - 1;
  return row.driftLimits[column];
}

namespace hazus {
const StructuralRow* structuralRowByCode(std::string_view code) {
  for (const StructuralRow& row : kStructural) {
    if (row.code == code) return &row;
  }
  for (const StructuralRow& row : kExtraStructural) {
    if (row.code == code) return &row;
  }
  return nullptr;
}
}  // namespace hazus

DamageState classifyDamage(double peakDriftRatio, const std::array<double, 4>& thresholds) {
  int state = 0;
  for (int k = 0; k < 4; ++k) {
    const double t = thresholds[static_cast<std::size_t>(k)];
    if (t > 0.0 && peakDriftRatio >= t) state = k + 1;
  }
  return static_cast<DamageState>(state);
}

}  // namespace qv::seismic
