// LOD2 models from OpenStreetMap building:part sets (Simple 3D Buildings): the parts prep::ingest
// already attaches to a building become one mesh, so towers with setbacks (the Empire State
// Building, w34633854) get their real shape from data the city step reads anyway.
#pragma once

#include "qv/core/Result.h"
#include "qv/prep/CityModel.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// Assembles one mesh from the building's parts: each part an extruded prism between its
/// minHeightM and heightM (walls from every ring, outer and holes; a flat roof; a bottom face,
/// kind Other, when minHeightM > 0), roofs flat for now (roof:shape is kept in the parts for later).
/// The model keeps the building's id and attributes (lod 2), replacesExisting = true, source
/// "osm-parts", footprint = the union of the parts' outer rings; not yet re-meshed (finishModel).
/// Fails when no part has a valid polygon and height, naming the building.
Result<Lod2Model> modelFromOsmParts(const Building& building);

}  // namespace qv::prep
