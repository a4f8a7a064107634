// Finished LOD2 models as buildings of the city model, the form the tile writer stores
// (docs/lod2.md, "Tile section"; docs/formats.md, "MESH").
#pragma once

#include "qv/core/Result.h"
#include "qv/prep/CityModel.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// "cityjson:…" → CityJson, "obj:…" → Obj, "osm-parts" → OsmParts, "synthetic" → Synthetic, anything else → Other.
MeshSource meshSourceOf(const Lod2Model& model);

/// The building a finished model (finishModel) becomes: its attributes (lod 2); one part, the
/// footprint extruded from minHeightM to heightM (the LOD1 fallback older viewers draw); and the
/// skinned and far meshes with triangles grouped by kind. Fails, naming the model, when the model
/// is not finished, its footprint has fewer than 3 points, its far mesh more than 65535 vertices
/// or its storeys more than kMaxMeshStoreys.
Result<Building> buildingFromModel(const Lod2Model& model);

}  // namespace qv::prep
