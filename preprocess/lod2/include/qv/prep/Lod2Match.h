// Matching LOD2 models to the LOD1 buildings of a city: a model replaces the building it belongs to,
// found by id or by footprint overlap; unmatched models are new buildings.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/format/BuildingAttributes.h"
#include "qv/prep/CityModel.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// A building of the city as matching sees it.
struct ExistingBuilding {
  std::string id;                     ///< w…, r…, s…, g:…
  std::vector<glm::dvec2> footprint;  ///< outer ring, city frame, any orientation
  BuildingAttributes attributes;
};

/// The buildings of a city model: footprint = the outer ring of a one-part building, else the outer
/// ring of the union of its parts' outer rings.
std::vector<ExistingBuilding> existingBuildings(const CityModel& city);

struct MatchOptions {
  /// Footprint overlap (intersection area / the smaller footprint's area) at which a model replaces
  /// a building.
  double minOverlap = 0.5;
  /// Used to re-finish models that were finished before matching and whose floors changed.
  FinishOptions finish;
};

struct MatchResult {
  std::uint64_t byId = 0;       ///< replaced by id
  std::uint64_t byOverlap = 0;  ///< replaced by footprint overlap
  std::uint64_t added = 0;      ///< new buildings
  [[nodiscard]] std::uint64_t replaced() const { return byId + byOverlap; }
};

/// Footprint overlap of two rings: intersection area / the smaller ring's area (0 .. 1).
double footprintOverlap(const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b);

/// Matches every model (see docs/lod2.md "Matching"): first by id (the model's id, or for cj:X and
/// obj:X ids the bare X, equals an existing id), then by footprint overlap >= minOverlap, the best
/// overlaps first, each existing building replaced at most once. A matched model takes the existing
/// id, replacesExisting = true and replacementAttributes(); models already replacing a building
/// (OSM parts) keep their id and count as replaced by id when that building is in `existing`, else
/// they become new buildings (replacesExisting = false). Models that were finished (skinned) before and whose floor
/// levels changed are finished again; a failure there is returned.
Result<MatchResult> matchModels(std::vector<Lod2Model>& models, const std::vector<ExistingBuilding>& existing,
                                const MatchOptions& options = {});

}  // namespace qv::prep
