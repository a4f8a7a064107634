#include "qv/seismic/TypeMixture.h"

#include <algorithm>

namespace qv::seismic {

TypeMixtureInfo hazusTypeMixture(Occupancy occupancy, int storeys) {
  const std::size_t o = std::min(static_cast<std::size_t>(occupancy), hazus::kOccupancies - 1);
  const int n = std::max(storeys, 1);
  const std::size_t band = n <= 2 ? 0 : n == 3 ? 1 : n <= 7 ? 2 : 3;
  const hazus::MappingRow& row = hazus::kEastCoastMapping[o][band];
  return {row.shares, static_cast<Occupancy>(o), row.substituted,
          band <= 1   ? "low-rise"
          : band == 2 ? "mid-rise"
                      : "high-rise"};
}

TypeMixtureInfo buildingTypeMixture(const BuildingAttributes& attributes) {
  if (!hasTypeMixture(attributes)) return {};
  const int storeys = std::max<int>(attributes.storeys, 1);
  return hazusTypeMixture(occupancyFromUse(attributes.use, storeys), storeys);
}

}  // namespace qv::seismic
