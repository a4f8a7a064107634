#include "qv/prep/Lod2Finish.h"

#include <string>

namespace qv::prep {

Status finishModel(Lod2Model& model, const FinishOptions& options) {
  if (model.skinned.mesh.triangles.empty()) return Error{model.id + ": the model has no triangles"};
  if (!(model.attributes.heightM > model.attributes.minHeightM))
    return Error{model.id + ": height " + std::to_string(model.attributes.heightM) + " m is not above its base " +
                 std::to_string(model.attributes.minHeightM) + " m"};
  const FloorLevels floors = floorLevels(model.attributes);
  // Checked before the re-meshing, whose cost grows with the storeys.
  if (floors.storeys > kMaxSkinnedStoreys)
    return Error{model.id + ": " + std::to_string(floors.storeys) + " storeys: a LOD2 model holds at most " +
                 std::to_string(kMaxSkinnedStoreys) + " (the tile format's limit)"};
  Lod2Mesh original = weldVertices(model.skinned.mesh);
  Result<Lod2Mesh> remeshed = remeshForFloors(original, floors, options.remesh);
  if (!remeshed.ok()) return Error{model.id + ": " + remeshed.error()};
  model.farMesh = simplifyFarMesh(original, options.far);
  model.skinned.mesh = std::move(*remeshed);
  model.skinned.finished = true;
  model.verticesAfter = static_cast<std::uint32_t>(model.skinned.mesh.positions.size());
  return {};
}

}  // namespace qv::prep
