#include "qv/prep/Lod2Match.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>
#include <tuple>
#include <unordered_map>

#include <glm/common.hpp>

#include "qv/prep/Cleaning.h"
#include "qv/prep/Lod2Attributes.h"
#include "qv/prep/Lod2Geometry.h"
#include "qv/prep/Lod2Remesh.h"

namespace qv::prep {
namespace {

struct Bounds2 {
  glm::dvec2 min{std::numeric_limits<double>::max()};
  glm::dvec2 max{std::numeric_limits<double>::lowest()};
  void expand(const glm::dvec2& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  [[nodiscard]] bool intersects(const Bounds2& o) const {
    return !(o.min.x > max.x || o.max.x < min.x || o.min.y > max.y || o.max.y < min.y);
  }
};

Bounds2 boundsOf(const std::vector<glm::dvec2>& ring) {
  Bounds2 b;
  for (const glm::dvec2& p : ring) b.expand(p);
  return b;
}

std::vector<glm::dvec2> outerRing(const BuildingPart& part) {
  const std::size_t end = part.ringEnds.empty() ? part.points.size() : part.ringEnds.front();
  return {part.points.begin(), part.points.begin() + static_cast<std::ptrdiff_t>(end)};
}

bool sameFloors(const FloorLevels& a, const FloorLevels& b) {
  return a.storeys == b.storeys && a.baseM == b.baseM && a.storeyHeightM == b.storeyHeightM;
}

}  // namespace

std::vector<ExistingBuilding> existingBuildings(const CityModel& city) {
  std::vector<ExistingBuilding> out;
  out.reserve(city.buildings.size());
  for (const Building& building : city.buildings) {
    ExistingBuilding existing;
    existing.id = building.attributes.id;
    existing.attributes = building.attributes;
    if (building.parts.size() == 1) {
      existing.footprint = outerRing(building.parts.front());
    } else if (!building.parts.empty()) {
      std::vector<std::vector<glm::dvec2>> rings;
      for (const BuildingPart& part : building.parts) rings.push_back(outerRing(part));
      existing.footprint = unionOuterRing(rings);
    }
    out.push_back(std::move(existing));
  }
  return out;
}

double footprintOverlap(const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b) {
  if (a.size() < 3 || b.size() < 3) return 0.0;
  const double smaller =
      std::min(std::abs(signedRingArea(a.data(), a.size())), std::abs(signedRingArea(b.data(), b.size())));
  if (!(smaller > 0.0)) return 0.0;
  return std::clamp(intersectionAreaM2(a, b) / smaller, 0.0, 1.0);
}

Result<MatchResult> matchModels(std::vector<Lod2Model>& models, const std::vector<ExistingBuilding>& existing,
                                const MatchOptions& options) {
  MatchResult result;
  std::unordered_map<std::string, std::size_t> indexOf;
  for (std::size_t i = 0; i < existing.size(); ++i) indexOf.emplace(existing[i].id, i);
  std::vector<bool> taken(existing.size(), false);
  std::vector<std::optional<std::size_t>> assigned(models.size());

  // Models that already are a building of the city (OSM parts) keep it; one whose building is not
  // in this city is a new building with its own id.
  std::vector<bool> settled(models.size(), false);
  for (std::size_t m = 0; m < models.size(); ++m) {
    Lod2Model& model = models[m];
    if (!model.replacesExisting) continue;
    settled[m] = true;
    if (const auto it = indexOf.find(model.id); it != indexOf.end()) {
      taken[it->second] = true;
      ++result.byId;
    } else {
      model.replacesExisting = false;
      ++result.added;
    }
  }
  // 1. By id: the model's id or, for cj:X and obj:X, the bare X.
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (settled[m]) continue;
    const std::string& id = models[m].id;
    std::vector<std::string> candidates{id};
    for (const char* prefix : {"cj:", "obj:"}) {
      const std::string_view p(prefix);
      if (id.size() > p.size() && id.compare(0, p.size(), p) == 0) candidates.push_back(id.substr(p.size()));
    }
    for (const std::string& candidate : candidates) {
      const auto it = indexOf.find(candidate);
      if (it == indexOf.end() || taken[it->second]) continue;
      taken[it->second] = true;
      assigned[m] = it->second;
      ++result.byId;
      break;
    }
  }
  // 2. By footprint overlap, best pairs first.
  std::vector<Bounds2> existingBounds;
  existingBounds.reserve(existing.size());
  for (const ExistingBuilding& e : existing) existingBounds.push_back(boundsOf(e.footprint));
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // overlap, model, existing
  for (std::size_t m = 0; m < models.size(); ++m) {
    if (settled[m] || assigned[m] || models[m].footprint.size() < 3) continue;
    const Bounds2 bounds = boundsOf(models[m].footprint);
    for (std::size_t e = 0; e < existing.size(); ++e) {
      if (taken[e] || existing[e].footprint.size() < 3 || !bounds.intersects(existingBounds[e])) continue;
      const double overlap = footprintOverlap(models[m].footprint, existing[e].footprint);
      if (overlap >= options.minOverlap) pairs.emplace_back(overlap, m, e);
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  for (const auto& [overlap, m, e] : pairs) {
    if (assigned[m] || taken[e]) continue;
    taken[e] = true;
    assigned[m] = e;
    ++result.byOverlap;
  }

  for (std::size_t m = 0; m < models.size(); ++m) {
    Lod2Model& model = models[m];
    if (settled[m]) continue;
    if (!assigned[m]) {
      ++result.added;
      continue;
    }
    const ExistingBuilding& target = existing[*assigned[m]];
    const bool finished = model.skinned.finished;
    const FloorLevels before = floorLevels(model.attributes);
    const bool hasParts =
        ((model.attributes.importanceReasons | target.attributes.importanceReasons) & kReasonComplex) != 0;
    model.id = target.id;
    model.replacesExisting = true;
    model.attributes =
        replacementAttributes(target.attributes, heightRange(model.skinned.mesh).maxZ, hasParts, model.footprint);
    if (finished && !sameFloors(before, floorLevels(model.attributes))) {
      if (Status s = finishModel(model, options.finish); !s) return Error{s.error()};
    }
  }
  return result;
}

}  // namespace qv::prep
