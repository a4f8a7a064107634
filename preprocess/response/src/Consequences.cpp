#include "qv/prep/Consequences.h"

#include <simdjson.h>

#include <algorithm>
#include <cmath>

#include "qv/prep/Files.h"
#include "qv/prep/PointInRing.h"
#include "qv/prep/Simplify.h"

namespace qv::prep {
namespace {

constexpr std::size_t kMaxDistrictBytes = 64u << 20;
constexpr std::size_t kMaxDistricts = 10000;
constexpr std::size_t kMaxVertices = 1000000;

using simdjson::dom::array;
using simdjson::dom::element;

// Reads one polygon's rings ([[[lon, lat], ...], ...]).
Status readPolygon(array rings, Districts::Polygon& out, std::size_t& vertices, const std::string& where) {
  for (element ringElement : rings) {
    array ring;
    if (ringElement.get(ring) != simdjson::SUCCESS) return Error{where + ": a ring is not an array"};
    Districts::Ring points;
    for (element point : ring) {
      array pair;
      double lon = 0, lat = 0;
      if (point.get(pair) != simdjson::SUCCESS || pair.size() < 2 || pair.at(0).get_double().get(lon) ||
          pair.at(1).get_double().get(lat) || !std::isfinite(lon) || !std::isfinite(lat) || std::abs(lon) > 180.0 ||
          std::abs(lat) > 90.0) {
        return Error{where + ": a position is not [longitude, latitude] in degrees"};
      }
      points.push_back({lon, lat});
      if (++vertices > kMaxVertices) return Error{where + ": more than 1,000,000 vertices in the file"};
    }
    if (points.size() < 3) return Error{where + ": a ring has fewer than 3 positions"};
    out.push_back(std::move(points));
  }
  if (out.empty()) return Error{where + ": a polygon without rings"};
  return {};
}

}  // namespace

int Districts::find(double lon, double lat) const {
  for (std::size_t d = 0; d < areas.size(); ++d) {
    for (std::size_t k = 0; k < areas[d].size(); ++k) {
      const Polygon& polygon = areas[d][k];
      if (d < boxes.size() && k < boxes[d].size()) {
        const std::array<double, 4>& b = boxes[d][k];
        if (lon < b[0] || lat < b[1] || lon > b[2] || lat > b[3]) continue;
      }
      bool inside = false;
      for (const Ring& ring : polygon) inside ^= insideRing(ring, lon, lat);
      if (inside) return static_cast<int>(d);
    }
  }
  return -1;
}

Result<Districts> readDistricts(const std::string& path) {
  auto text = readTextFile(path, kMaxDistrictBytes);
  if (!text.ok()) return Error{text.error()};
  return parseDistricts(*text, path);
}

Result<Districts> parseDistricts(std::string_view json, const std::string& name) {
  simdjson::dom::parser parser;
  element root;
  if (auto error = parser.parse(json.data(), json.size()).get(root)) {
    return Error{name + ": not valid JSON (" + simdjson::error_message(error) + ")"};
  }
  array features;
  if (root["features"].get(features) != simdjson::SUCCESS) {
    return Error{name + ": not a GeoJSON FeatureCollection (no \"features\" array)"};
  }
  if (features.size() > kMaxDistricts) return Error{name + ": more than 10,000 districts"};
  Districts out;
  std::size_t vertices = 0, index = 0;
  for (element feature : features) {
    std::string where = name + ": feature " + std::to_string(index++);
    std::string_view districtName;
    if (feature["properties"]["name"].get(districtName) != simdjson::SUCCESS || districtName.empty()) {
      return Error{where + " has no \"name\" property (a district needs a name)"};
    }
    where += " (\"" + std::string(districtName) + "\")";
    std::string_view type;
    array coordinates;
    if (feature["geometry"]["type"].get(type) || feature["geometry"]["coordinates"].get(coordinates)) {
      return Error{where + " has no geometry"};
    }
    std::vector<Districts::Polygon> polygons;
    if (type == "Polygon") {
      Districts::Polygon polygon;
      if (Status s = readPolygon(coordinates, polygon, vertices, where); !s.ok()) return Error{s.error()};
      polygons.push_back(std::move(polygon));
    } else if (type == "MultiPolygon") {
      for (element part : coordinates) {
        array rings;
        if (part.get(rings) != simdjson::SUCCESS) return Error{where + ": a polygon is not an array"};
        Districts::Polygon polygon;
        if (Status s = readPolygon(rings, polygon, vertices, where); !s.ok()) return Error{s.error()};
        polygons.push_back(std::move(polygon));
      }
    } else {
      return Error{where + " is a " + std::string(type) + ", not a Polygon or MultiPolygon"};
    }
    std::vector<std::array<double, 4>> boxes;
    for (const Districts::Polygon& polygon : polygons) {
      std::array<double, 4> b{polygon[0][0][0], polygon[0][0][1], polygon[0][0][0], polygon[0][0][1]};
      for (const auto& p : polygon[0])
        b = {std::min(b[0], p[0]), std::min(b[1], p[1]), std::max(b[2], p[0]), std::max(b[3], p[1])};
      boxes.push_back(b);
    }
    out.names.emplace_back(districtName);
    out.areas.push_back(std::move(polygons));
    out.boxes.push_back(std::move(boxes));
  }
  if (out.names.empty()) return Error{name + ": no districts in the file"};
  // Optional members of the collection itself (what the districts are, a row for the rest).
  for (const auto& [key, text] :
       {std::pair<const char*, std::string*>{"source", &out.source}, {"outside", &out.outsideName}}) {
    simdjson::dom::element value;
    if (root[key].get(value) != simdjson::SUCCESS) continue;
    std::string_view v;
    if (value.get(v) != simdjson::SUCCESS || v.size() > 1000) {
      return Error{name + ": \"" + key + "\" must be a text of at most 1,000 bytes"};
    }
    *text = std::string(v);
  }
  simdjson::dom::element inferred;
  if (root["inferred"].get(inferred) == simdjson::SUCCESS && inferred.get(out.inferred) != simdjson::SUCCESS) {
    return Error{name + ": \"inferred\" must be true or false"};
  }
  return out;
}

std::vector<std::vector<std::array<double, 2>>> Districts::outline(std::size_t d) const {
  std::vector<std::vector<std::array<double, 2>>> out;
  if (d >= areas.size()) return out;
  // Local metres about the district's first point (equirectangular: enough to simplify a few km).
  double lon0 = 0, lat0 = 0;
  for (const Polygon& polygon : areas[d]) {
    if (!polygon.empty() && !polygon[0].empty()) {
      lon0 = polygon[0][0][0];
      lat0 = polygon[0][0][1];
      break;
    }
  }
  const double mx = 111320.0 * std::cos(lat0 * 3.14159265358979 / 180.0), my = 110540.0;
  for (double tolerance = 5.0; tolerance < 1e6; tolerance *= 2.0) {
    out.clear();
    std::size_t points = 0;
    for (const Polygon& polygon : areas[d]) {
      if (polygon.empty() || polygon[0].size() < 3) continue;
      std::vector<glm::dvec2> ring;
      for (const auto& p : polygon[0]) ring.emplace_back((p[0] - lon0) * mx, (p[1] - lat0) * my);
      if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();  // closed rings repeat the first point
      const std::vector<glm::dvec2> simple = simplifyRing(ring, tolerance);
      if (simple.size() < 3) continue;
      auto& kept = out.emplace_back();
      for (const glm::dvec2& q : simple) kept.push_back({lon0 + q.x / mx, lat0 + q.y / my});
      points += kept.size();
    }
    if (points <= 20000 && out.size() <= 1000) return out;
  }
  return {};
}

LossClass LossClass::of(const seismic::Exposure& exposure) {
  LossClass c;
  c.occupancy = exposure.occupancy;
  c.type = exposure.type;
  c.typeInferred = !exposure.typeMixture.empty();
  c.eraInferred = !exposure.eraKnown;
  c.useInferred = !exposure.useKnown;
  return c;
}

void addClassTotals(std::span<const seismic::BuildingLoss> losses, std::span<const LossClass> classes,
                    seismic::ConsequenceTotals& totals) {
  constexpr std::size_t kOccupancies = static_cast<std::size_t>(seismic::Occupancy::Count);
  constexpr std::size_t kTypes = static_cast<std::size_t>(StructuralType::Count);
  std::vector<seismic::ClassTotals> byOccupancy(kOccupancies), byStructure(kTypes);
  seismic::InferredCounts inferred;
  const auto add = [](seismic::ClassTotals& c, const seismic::BuildingLoss& b) {
    ++c.buildings;
    for (std::size_t k = 0; k < 5; ++k) c.damageStates[k] += b.structural.p[k];
    c.damaged += b.structural.p[2] + b.structural.p[3] + b.structural.p[4];
    c.collapsed += b.collapse;
    c.repairCostUsd += b.repairCostUsd;
    c.occupants += b.occupantsPresent;
    for (std::size_t k = 0; k < 4; ++k) c.injuries[k] += b.injuries[k];
  };
  for (std::size_t i = 0; i < losses.size() && i < classes.size(); ++i) {
    const LossClass& c = classes[i];
    add(byOccupancy[std::min(static_cast<std::size_t>(c.occupancy), kOccupancies - 1)], losses[i]);
    add(byStructure[std::min(static_cast<std::size_t>(c.type), kTypes - 1)], losses[i]);
    ++inferred.buildings;
    inferred.structuralType += c.typeInferred ? 1u : 0u;
    inferred.codeEra += c.eraInferred ? 1u : 0u;
    inferred.use += c.useInferred ? 1u : 0u;
    inferred.occupants += losses[i].occupantsInferred ? 1u : 0u;
    inferred.replacementValue += losses[i].valueInferred ? 1u : 0u;
  }
  totals.byOccupancy.clear();
  totals.byStructure.clear();
  for (std::size_t k = 0; k < kOccupancies; ++k) {
    if (byOccupancy[k].buildings == 0) continue;
    byOccupancy[k].key = std::string(seismic::occupancyCode(static_cast<seismic::Occupancy>(k)));
    totals.byOccupancy.push_back(std::move(byOccupancy[k]));
  }
  for (std::size_t k = 0; k < kTypes; ++k) {
    if (byStructure[k].buildings == 0) continue;
    byStructure[k].key = std::string(structuralTypeCode(static_cast<StructuralType>(k)));
    totals.byStructure.push_back(std::move(byStructure[k]));
  }
  totals.inferred = inferred;
}

BuildingLoss toSummaryLoss(const seismic::BuildingLoss& loss) {
  BuildingLoss out;
  for (std::size_t k = 0; k < 5; ++k) {
    out.structural[k] = static_cast<float>(loss.structural.p[k]);
    out.nonStructuralDrift[k] = static_cast<float>(loss.nonStructuralDrift.p[k]);
    out.nonStructuralAcceleration[k] = static_cast<float>(loss.nonStructuralAcceleration.p[k]);
  }
  out.collapse = static_cast<float>(loss.collapse);
  out.occupants = static_cast<float>(loss.occupantsPresent);
  for (std::size_t k = 0; k < 4; ++k) out.injuries[k] = static_cast<float>(loss.injuries[k]);
  out.replacementValueUsd = static_cast<float>(loss.replacementValueUsd);
  out.repairCostUsd = static_cast<float>(loss.repairCostUsd);
  out.repairTimeDays = static_cast<float>(loss.repairTimeDays);
  for (std::size_t k = 0; k < 3; ++k) out.tag[k] = static_cast<float>(loss.tag[k]);
  const seismic::LossSpread spread = seismic::lossSpread(loss);
  out.repairCostStdUsd = static_cast<float>(spread.repairCostUsd);
  for (std::size_t k = 0; k < 4; ++k) out.injuriesStd[k] = static_cast<float>(spread.injuries[k]);
  out.flags = static_cast<std::uint8_t>((loss.occupantsInferred ? kLossOccupantsInferred : 0) |
                                        (loss.valueInferred ? kLossValueInferred : 0));
  return out;
}

}  // namespace qv::prep
