#include "qv/scene/BuildingInfo.h"

#include <glm/geometric.hpp>

#include <cmath>

#include "qv/core/JsonWriter.h"

namespace qv {

std::string buildingInfoJson(const BuildingInfo& info) {
  const BuildingAttributes& a = info.attributes;
  JsonWriter w;
  w.beginObject();
  w.field("id", a.id).field("name", a.name).field("use", a.use).field("address", a.address);
  w.field("x", a.centroidX).field("y", a.centroidY);
  w.field("heightM", a.heightM).field("heightSource", valueSourceName(a.heightSource));
  w.field("storeys", static_cast<unsigned>(a.storeys)).field("storeysSource", valueSourceName(a.storeysSource));
  w.field("structuralType", structuralTypeCode(a.structuralType));
  w.field("codeEra", codeEraName(a.codeEra)).field("importance", importanceName(a.importance));
  w.field("lod", static_cast<unsigned>(a.lod));
  w.field("damageState", info.hasResponse ? damageStateName(info.response.damage) : std::string_view("no_result"));
  w.key("peakDriftRatio").beginArray();
  for (float d : info.storeyPeakDrift) w.value(d);
  w.endArray();
  if (info.hasResponse && info.response.source != ResponseSource::None) {
    w.field("peakRoofDisplacementM", info.response.peakRoofDisplacementM).field("pgaG", info.response.pgaG);
  } else {
    w.key("peakRoofDisplacementM").null().key("pgaG").null();
  }
  // Informative extras.
  w.field("minHeightM", a.minHeightM).field("footprintAreaM2", a.footprintAreaM2);
  w.field("structuralTypeDescription", structuralTypeDescription(a.structuralType));
  w.key("importanceReasons").beginArray();
  for (const std::string_view name : importanceReasonNames(a.importanceReasons)) w.value(name);
  w.endArray();
  w.field("startYear", static_cast<int>(a.startYear));
  w.field("responseSource", info.hasResponse ? responseSourceName(info.response.source) : std::string_view("none"));
  // Why there is no result (null with a result; "unknown" for responses that did not record it or
  // before the summary loaded), and whether the result is approximate.
  const bool hasResult = info.hasResponse && info.response.source != ResponseSource::None;
  if (hasResult) {
    w.key("noResultReason").null();
  } else {
    w.field("noResultReason",
            noResultReasonName(info.hasResponse ? info.response.noResultReason : NoResultReason::Unknown));
  }
  w.field("approximate", hasResult && info.response.approximate);
  w.field("unconvergedSteps", hasResult ? info.response.unconvergedSteps : 0u);
  w.field("worstResidualRatio", hasResult ? info.response.worstResidualRatio : 0.0f);
  if (!info.modelSource.empty()) {
    w.field("modelSource", info.modelSource);
    w.field("modelTriangles", info.modelTriangles);
  }
  w.field("detailed", info.detailed).field("tile", info.tile);
  if (hasResult && info.scaling) {
    w.key("spectralScaling").beginObject();
    for (int d = 0; d < 2; ++d) {
      w.key(d == 0 ? "x" : "y").beginObject();
      w.field("periodS", info.scaling->periodS[d]).field("targetSaG", info.scaling->targetSaG[d]);
      w.field("recordSaG", info.scaling->recordSaG[d]).field("scale", info.scaling->scale[d]).endObject();
    }
    w.endObject();
  }
  if (hasResult && info.spread) {
    w.key("suite").beginObject().field("records", static_cast<unsigned>(info.spread->records));
    w.field("shownRecord", static_cast<unsigned>(info.spread->shownRecord));
    w.field("driftBeta", info.spread->driftBeta).field("accelerationBeta", info.spread->accelerationBeta).endObject();
  }
  if (hasResult && info.loss) {
    static const char* const states[5] = {"none", "slight", "moderate", "extensive", "complete"};
    const BuildingLoss& l = *info.loss;
    w.key("damageProbabilities").beginObject();
    for (std::size_t k = 0; k < 5; ++k) w.field(states[k], l.structural[k]);
    w.endObject();
    w.field("collapseProbability", l.collapse).field("expectedDamageState", l.expectedState());
    std::size_t likely = 0;
    for (std::size_t k = 1; k < 5; ++k) {
      if (l.structural[k] > l.structural[likely]) likely = k;
    }
    w.field("mostLikelyDamageState", states[likely]);
    w.key("consequences").beginObject();
    w.field("occupants", l.occupants).field("occupantsInferred", (l.flags & kLossOccupantsInferred) != 0);
    w.key("injuries").beginArray();
    for (const float v : l.injuries) w.value(v);
    w.endArray();
    w.field("deaths", l.injuries[3]).field("replacementValueUsd", l.replacementValueUsd);
    w.field("valueInferred", (l.flags & kLossValueInferred) != 0).field("repairCostUsd", l.repairCostUsd);
    w.field("repairTimeDays", l.repairTimeDays);
    w.key("tags").beginObject().field("green", l.tag[0]).field("yellow", l.tag[1]).field("red", l.tag[2]).endObject();
    w.endObject();
  }
  w.endObject();
  return w.take();
}

std::optional<float> rayPrism(const float o[3], const float d[3], const PrismView& p) {
  float best = INFINITY;
  // Roof and floor planes: inside the polygon (even-odd over all rings) at z = maxZ / minZ.
  auto inside = [&](float x, float y) {
    bool in = false;
    std::uint32_t begin = 0;
    for (std::uint32_t r = 0; r < p.ringCount; ++r) {
      const std::uint32_t n = p.ringCounts[r];
      for (std::uint32_t i = 0, j = n - 1; i < n; j = i++) {
        const float xi = p.xy[2 * (begin + i)] + p.offsetX, yi = p.xy[2 * (begin + i) + 1] + p.offsetY;
        const float xj = p.xy[2 * (begin + j)] + p.offsetX, yj = p.xy[2 * (begin + j) + 1] + p.offsetY;
        if (((yi > y) != (yj > y)) && (x < (xj - xi) * (y - yi) / (yj - yi) + xi)) in = !in;
      }
      begin += n;
    }
    return in;
  };
  if (std::abs(d[2]) > 1e-9f) {
    for (float z : {p.maxZ, p.minZ}) {
      const float t = (z - o[2]) / d[2];
      if (t >= 0.0f && t < best && inside(o[0] + t * d[0], o[1] + t * d[1])) best = t;
    }
  }
  // Walls: the vertical quad of every ring edge.
  std::uint32_t begin = 0;
  for (std::uint32_t r = 0; r < p.ringCount; ++r) {
    const std::uint32_t n = p.ringCounts[r];
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t j = (i + 1) % n;
      const float ax = p.xy[2 * (begin + i)] + p.offsetX, ay = p.xy[2 * (begin + i) + 1] + p.offsetY;
      const float bx = p.xy[2 * (begin + j)] + p.offsetX, by = p.xy[2 * (begin + j) + 1] + p.offsetY;
      // Solve o + t d = a + s (b - a) in the plane: 2×2 system in (t, s).
      const float ex = bx - ax, ey = by - ay;
      const float det = d[0] * (-ey) - d[1] * (-ex);
      if (std::abs(det) < 1e-12f) continue;
      const float rx = ax - o[0], ry = ay - o[1];
      const float t = (rx * (-ey) - ry * (-ex)) / det;
      const float s = (d[0] * ry - d[1] * rx) / det;
      if (t < 0.0f || t >= best || s < 0.0f || s > 1.0f) continue;
      const float z = o[2] + t * d[2];
      if (z >= p.minZ && z <= p.maxZ) best = t;
    }
    begin += n;
  }
  if (!std::isfinite(best)) return std::nullopt;
  return best;
}

template <typename Index>
std::optional<float> rayTriangles(const float o[3], const float d[3], std::span<const glm::vec3> positions,
                                  std::span<const Index> triangles, const glm::vec3& offset) {
  // Möller–Trumbore, both faces.
  const glm::vec3 origin(o[0], o[1], o[2]), dir(d[0], d[1], d[2]);
  float best = INFINITY;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    if (triangles[t] >= positions.size() || triangles[t + 1] >= positions.size() ||
        triangles[t + 2] >= positions.size())
      continue;
    const glm::vec3 a = positions[triangles[t]] + offset;
    const glm::vec3 e1 = positions[triangles[t + 1]] + offset - a;
    const glm::vec3 e2 = positions[triangles[t + 2]] + offset - a;
    const glm::vec3 p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    const float inv = 1.0f / det;
    const glm::vec3 s = origin - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float hit = glm::dot(e2, q) * inv;
    if (hit >= 0.0f && hit < best) best = hit;
  }
  if (best == INFINITY) return std::nullopt;
  return best;
}

template std::optional<float> rayTriangles<std::uint32_t>(const float[3], const float[3], std::span<const glm::vec3>,
                                                          std::span<const std::uint32_t>, const glm::vec3&);
template std::optional<float> rayTriangles<std::uint16_t>(const float[3], const float[3], std::span<const glm::vec3>,
                                                          std::span<const std::uint16_t>, const glm::vec3&);

}  // namespace qv
