// The last step of every LOD2 model, once its attributes are final (after matching): re-meshing at
// its floor levels and the far-view simplification. No skin is stored: the viewer moves each
// vertex with the floors below and above it by its height (qv/anim/FloorBlend.h, docs/lod2.md).
#pragma once

#include "qv/core/Result.h"
#include "qv/format/CityTile.h"
#include "qv/prep/Lod2FarMesh.h"
#include "qv/prep/Lod2Model.h"
#include "qv/prep/Lod2Remesh.h"

namespace qv::prep {

/// Largest number of storeys a LOD2 model can carry (the tile format's kMaxMeshStoreys).
inline constexpr int kMaxSkinnedStoreys = kMaxMeshStoreys;

struct FinishOptions {
  RemeshOptions remesh;
  FarMeshOptions far;
};

/// Takes model.skinned.mesh as the model's geometry (as imported, or already finished: cutting a
/// finished mesh again at new floor levels is correct, only the old cuts stay), welds it, re-meshes
/// it at the floors of model.attributes, marks it finished, simplifies the welded original into
/// farMesh and sets verticesAfter (verticesBefore is the importer's). Fails for an empty mesh, a
/// building whose height is not above its base, more than kMaxSkinnedStoreys storeys, or too many
/// vertices; the message names the model id.
Status finishModel(Lod2Model& model, const FinishOptions& options = {});

}  // namespace qv::prep
