// LOD2 models from OpenStreetMap building:part sets (Simple 3D Buildings): the parts prep::ingest
// already attaches to a building become one mesh, so towers with setbacks (the Empire State
// Building, w34633854) get their real shape from data the city step reads anyway.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/prep/CityModel.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// Assembles one mesh from the building's parts: each part an extruded prism between its
/// minHeightM and heightM (walls from every ring, outer and holes; a flat roof; a bottom face,
/// kind Other, when minHeightM > 0), roofs flat for now (roof:shape is kept in the parts for later).
/// The model keeps the building's id and attributes (lod 2), replacesExisting = true, source
/// `source` ("osm-parts"; "synthetic" for synth-city's towers), footprint = the union of the parts' outer rings; not
/// yet re-meshed (finishModel). Fails when no part has a valid polygon and height, naming the building.
Result<Lod2Model> modelFromOsmParts(const Building& building, const std::string& source = "osm-parts");

/// Re-meshing target for part models (FinishOptions::remesh.maxEdgeM). They are prisms: skinning
/// moves each floor's ring by translation, so wall strips need vertices only at the floor cuts;
/// splitting edges to half a storey (the import default, for free-form CityJSON/OBJ surfaces) would
/// multiply a city's vertices by ten (Midtown: 1.4 M → 33.5 M) for no visible change.
inline constexpr double kPartModelMaxEdgeM = 20.0;

/// True when the building's geometry came from building:part members (ingest attached parts to its
/// outline), i.e. when the city step makes it a LOD2 model.
bool hasOsmParts(const Building& building);

struct OsmPartsReport {
  std::uint64_t candidates = 0;       ///< buildings with building:part members
  std::uint64_t assembled = 0;        ///< of them now LOD2 models
  std::uint64_t verticesBefore = 0;   ///< sum over the assembled models, before re-meshing
  std::uint64_t verticesAfter = 0;    ///< after re-meshing at every floor
  std::uint64_t farTriangles = 0;     ///< sum over their far meshes
  std::vector<std::string> warnings;  ///< one per candidate left at LOD1, naming it and why
  double seconds = 0.0;
};

/// The city step's LOD2 pass: every building with building:part members becomes a finished LOD2
/// model (modelFromOsmParts, finishModel, buildingFromModel) whose LOD1 fallback stays its parts'
/// prisms (so the setbacks remain when the viewer switches LOD2 off). A building that cannot be
/// assembled or finished keeps its LOD1 parts and gets a warning. Work is spread over `threads`
/// (0: the hardware's). The result does not depend on the thread count.
OsmPartsReport assembleOsmPartModels(CityModel& city, const FinishOptions& options = {}, unsigned threads = 0,
                                     const std::string& source = "osm-parts");

}  // namespace qv::prep
