// What the viewer knows about one building: its attributes, where it stands, and its response.
// The shape of `quakeview.building(id)` / `pick(x, y)` and of the inspection window.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "qv/format/BuildingAttributes.h"
#include "qv/format/ResponseTile.h"

namespace qv {

struct BuildingInfo {
  BuildingAttributes attributes;  ///< centroidX/Y in the city frame (metres from the origin)
  bool detailed = false;          ///< from a leaf tile (name and address present)
  std::string tile;               ///< "level/x/y" of the tile it came from
  bool hasResponse = false;
  BuildingResponse response;           ///< damage, peaks (meaningful when hasResponse)
  std::vector<float> storeyPeakDrift;  ///< per storey, ground up (empty without a response)
  // From the summary's optional sections, when the response has them (quakeview-prep response).
  std::optional<BuildingScaling> scaling;
  std::optional<BuildingSite> site;  ///< the shaking field at the site, with or without a result
  std::optional<BuildingSpread> spread;
  std::optional<BuildingLoss> loss;
  /// LOD2 buildings whose tile carries the model: where it came from ("cityjson", "obj",
  /// "osm-parts", "synthetic") and the triangles drawn (empty and 0 otherwise).
  std::string modelSource;
  std::uint32_t modelTriangles = 0;
};

/// `quakeview.building(id)` JSON: {id, name, use, address, x, y, heightM, heightSource, storeys,
/// storeysSource, structuralType, codeEra, importance, facility (facilityCategoryName),
/// facilityKind (FacilityClass::kind), lod, damageState, peakDriftRatio: [...],
/// peakRoofDisplacementM, pgaG} plus informative extras (minHeightM, footprintAreaM2,
/// structuralTypeDescription, importanceReasons, startYear, responseSource, noResultReason (null
/// with a result), approximate, unconvergedSteps, worstResidualRatio, detailed, and for LOD2 models
/// modelSource and modelTriangles), recordPgaG (with a result: the same value as pgaG, the scaled
/// record's peak, named for what it is) and siteShaking ({source: "shakemap" | "scenario", pgaG,
/// pgvCmS, psa03G, psa10G, psa30G, mmi, vs30Mps}, null values where the field gives none; null
/// without a field); with HAZUS results also spectralScaling, suite,
/// damageProbabilities, collapseProbability, expectedDamageState, mostLikelyDamageState and
/// consequences (README's table).
std::string buildingInfoJson(const BuildingInfo& info);

}  // namespace qv
