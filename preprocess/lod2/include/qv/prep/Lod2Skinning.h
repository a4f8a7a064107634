// Skinning of a LOD2 mesh to its storey skeleton: one bone per floor level (0 = ground ..
// storeys = roof), chained from the ground up; every vertex is bound to the bones of the floor at or
// below it and the floor above it, with weights linear in height that sum to 1.
#pragma once

#include "qv/core/Result.h"
#include "qv/prep/Lod2Model.h"
#include "qv/prep/Lod2Remesh.h"

namespace qv::prep {

/// Largest number of storeys a skinned mesh can carry (bones are stored as one byte, 0 .. storeys).
inline constexpr int kMaxSkinnedStoreys = 255;

/// Bone and weight of one height: k = the floor level at or below z, weight = (z - level k) /
/// storey height in [0, 1). Within kFloorToleranceM of level k: bone k, weight exactly 0. Below the
/// base: bone 0, weight 0; at or above the roof: bone storeys, weight 0.
struct BoneWeight {
  std::uint8_t bone = 0;
  float weight = 0.0f;
};
BoneWeight boneWeightAt(double z, const FloorLevels& floors);

/// Skins every vertex of `mesh` (normally the output of remeshForFloors). Fails when the building
/// has more than kMaxSkinnedStoreys storeys.
Result<SkinnedMesh> skinToFloors(Lod2Mesh mesh, const FloorLevels& floors);

}  // namespace qv::prep
