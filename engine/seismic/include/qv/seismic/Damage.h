// Structural damage states from peak inter-storey drift, with the Hazus thresholds.
//
// Source: Hazus Earthquake Model Technical Manual (FEMA, Hazus 5.1, 2022), Tables 5-9a to 5-9d,
// "Structural fragility curve parameters": the median average inter-story drift ratio at the
// threshold of each structural damage state, per model building type and seismic design level.
// The values are the shipped HAZUS table (HazusTables.h, generated from the SimCenter Damage and
// Loss Model Library's hazus_data_eq.json), the same medians Loss.h's fragilities use. Types not
// permitted at the high and moderate code levels (C3, URM) use their low-code values; an unknown
// era uses moderate code. Loss.h gives the probabilistic counterpart (probabilities of each state).
#pragma once

#include <array>

#include "qv/format/BuildingAttributes.h"
#include "qv/format/DamageState.h"

namespace qv::seismic {

/// The damage states are the response tiles' (qv/format/DamageState.h, one definition in the format
/// library below this one): None … Complete from classifyDamage; NoResult only for a building
/// without a result.
using qv::DamageState;
using qv::damageStateName;

/// Drift ratios at the thresholds of slight, moderate, extensive and complete damage (ascending).
/// Unknown types use C1 of the height class of `storeys` (<= 3 low, <= 7 mid, else high).
std::array<double, 4> hazusDriftThresholds(StructuralType type, CodeEra era, int storeys = 1);

/// The highest state whose threshold `peakDriftRatio` reaches (None below the first, and None when
/// every threshold is zero: nothing to assess). Monotonic in the drift.
DamageState classifyDamage(double peakDriftRatio, const std::array<double, 4>& thresholds);

}  // namespace qv::seismic
