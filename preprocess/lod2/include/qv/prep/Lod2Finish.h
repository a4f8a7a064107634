// The last step of every LOD2 model, once its attributes are final (after matching): re-meshing at
// its floor levels, skinning to its storey bones and the far-view simplification.
#pragma once

#include "qv/core/Result.h"
#include "qv/prep/Lod2FarMesh.h"
#include "qv/prep/Lod2Model.h"
#include "qv/prep/Lod2Remesh.h"

namespace qv::prep {

struct FinishOptions {
  RemeshOptions remesh;
  FarMeshOptions far;
};

/// Takes model.skinned.mesh as the model's geometry (as imported, or already finished: cutting a
/// finished mesh again at new floor levels is correct, only the old cuts stay), welds it, re-meshes
/// it at the floors of model.attributes, skins it, simplifies the welded original into farMesh and
/// sets verticesAfter (verticesBefore is the importer's). Fails for an empty mesh, a building whose
/// height is not above its base, more storeys than bones can hold, or too many vertices; the
/// message names the model id.
Status finishModel(Lod2Model& model, const FinishOptions& options = {});

}  // namespace qv::prep
