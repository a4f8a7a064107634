#include "qv/prep/Lod2Skinning.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace qv::prep {

BoneWeight boneWeightAt(double z, const FloorLevels& floors) {
  const int storeys = floors.storeys;
  const double roof = floors.levelM(storeys);
  if (z <= floors.baseM + kFloorToleranceM) return {0, 0.0f};
  if (z >= roof - kFloorToleranceM) return {static_cast<std::uint8_t>(storeys), 0.0f};
  const double storeysUp = (z - floors.baseM) / floors.storeyHeightM;
  int k = std::clamp(static_cast<int>(std::floor(storeysUp)), 0, storeys - 1);
  // Snap to a level within the tolerance (the floor cuts put vertices there up to rounding).
  if (std::abs(z - floors.levelM(k + 1)) <= kFloorToleranceM) return {static_cast<std::uint8_t>(k + 1), 0.0f};
  if (std::abs(z - floors.levelM(k)) <= kFloorToleranceM) return {static_cast<std::uint8_t>(k), 0.0f};
  const double w = std::clamp((z - floors.levelM(k)) / floors.storeyHeightM, 0.0, 1.0);
  return {static_cast<std::uint8_t>(k), static_cast<float>(w)};
}

Result<SkinnedMesh> skinToFloors(Lod2Mesh mesh, const FloorLevels& floors) {
  if (floors.storeys > kMaxSkinnedStoreys)
    return Error{std::to_string(floors.storeys) + " storeys: a skinned mesh holds at most " +
                 std::to_string(kMaxSkinnedStoreys) + " (one byte per bone index)"};
  if (!(floors.storeyHeightM > 0.0))
    return Error{"skinning needs a positive storey height (got " + std::to_string(floors.storeyHeightM) + " m)"};
  SkinnedMesh skinned;
  skinned.bone.assign(mesh.positions.size(), 0);
  skinned.weight.assign(mesh.positions.size(), 0.0f);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const BoneWeight bw = boneWeightAt(mesh.positions[i].z, floors);
    skinned.bone[i] = bw.bone;
    skinned.weight[i] = bw.weight;
  }
  skinned.mesh = std::move(mesh);
  return skinned;
}

}  // namespace qv::prep
