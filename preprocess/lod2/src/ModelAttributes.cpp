#include <algorithm>
#include <cctype>
#include <cmath>

#include "qv/prep/Attributes.h"
#include "qv/prep/Cleaning.h"
#include "qv/prep/Lod2Attributes.h"

namespace qv::prep {
namespace {

/// A function/usage value in words ("office", "hospital"); CityGML code lists ("1000", "31001_1010")
/// say nothing the use table knows.
bool isWordValue(const std::string& text) {
  if (text.empty()) return false;
  return std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_' || c == ' ' || c == '-';
  });
}

/// The footprint's area and centroid (when it has three points or more).
void setFootprint(BuildingAttributes& a, const std::vector<glm::dvec2>& footprint) {
  if (footprint.size() < 3) return;
  const std::vector<std::uint32_t> ringEnds{static_cast<std::uint32_t>(footprint.size())};
  a.footprintAreaM2 = static_cast<float>(polygonArea(footprint, ringEnds));
  const glm::dvec2 centroid = polygonCentroid(footprint, ringEnds);
  a.centroidX = centroid.x;
  a.centroidY = centroid.y;
}

}  // namespace

BuildingAttributes newModelAttributes(const NewModelFacts& facts, const Lod2Mesh& mesh,
                                      const std::vector<glm::dvec2>& footprint) {
  BuildingAttributes a;
  a.id = facts.id;
  a.name = facts.name;
  a.use = isWordValue(facts.function) ? normalizeUse(facts.function, "") : "unknown";
  const HeightRange range = heightRange(mesh);
  HeightTags tags;
  tags.heightM = range.maxZ - std::min(range.minZ, 0.0);
  // A storey count is taken when it fits the bones (at most 255) and storeys of at least 1.5 m.
  if (facts.storeys && *facts.storeys >= 1.0 && *facts.storeys <= 255.0 && *tags.heightM / *facts.storeys >= 1.5)
    tags.levels = *facts.storeys;
  const ResolvedHeights heights = resolveHeights(tags, a.use);
  a.heightM = heights.heightM;
  a.minHeightM = 0.0f;
  a.storeys = heights.storeys;
  a.heightSource = ValueSource::Tagged;  // measured on the model
  a.storeysSource = heights.storeysSource;
  a.startYear = static_cast<std::int16_t>(facts.startYear);
  a.lod = 2;
  setFootprint(a, footprint);
  inferSeismicAttributes(a, facts.parts > 1);
  return a;
}

BuildingAttributes replacementAttributes(const BuildingAttributes& existing, double modelHeightM, bool hasParts,
                                         const std::vector<glm::dvec2>& footprint) {
  BuildingAttributes a = existing;
  a.lod = 2;
  setFootprint(a, footprint);
  if (modelHeightM > static_cast<double>(existing.heightM) + 0.01) {
    a.heightM = static_cast<float>(modelHeightM);
    a.heightSource = ValueSource::Tagged;
    if (existing.storeysSource != ValueSource::Tagged) {
      const double storeyHeight = storeyHeightForUse(a.use);
      const double storeys = std::round((modelHeightM - static_cast<double>(a.minHeightM)) / storeyHeight);
      a.storeys = static_cast<std::uint16_t>(std::clamp(storeys, 1.0, 300.0));
    }
    inferSeismicAttributes(a, hasParts);
  }
  return a;
}

}  // namespace qv::prep
