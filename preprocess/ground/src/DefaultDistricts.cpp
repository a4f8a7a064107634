#include "qv/prep/DefaultDistricts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <tuple>

#include "qv/core/JsonWriter.h"
#include "qv/prep/PointInRing.h"

namespace qv::prep {
namespace {

/// A set of boundaries must hold at least this share of the buildings to be the city's districts.
constexpr double kMinCoverage = 0.9;
/// At most this many named places become districts (the nearest-name cells cost n² clips).
constexpr std::size_t kMaxPlaces = 2000;
/// The cells of the nearest-name districts cover the buildings' box grown by this much.
constexpr double kCellMarginM = 50.0;

using Ring = std::vector<glm::dvec2>;
using Polygon = std::vector<Ring>;

struct Box {
  double minX = std::numeric_limits<double>::infinity(), minY = minX;
  double maxX = -std::numeric_limits<double>::infinity(), maxY = maxX;
  void add(glm::dvec2 p) {
    minX = std::min(minX, p.x);
    minY = std::min(minY, p.y);
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  [[nodiscard]] bool contains(glm::dvec2 p) const { return p.x >= minX && p.y >= minY && p.x <= maxX && p.y <= maxY; }
};

bool inside(const Polygon& polygon, const Box& box, glm::dvec2 p) {
  if (!box.contains(p)) return false;
  bool in = false;
  for (const Ring& ring : polygon) in ^= insideRing(ring, p.x, p.y);
  return in;
}

/// Counts each building in the first district (in the file's order, as the response finds it)
/// that holds it; returns the buildings inside any.
std::uint64_t countBuildings(std::vector<DefaultDistricts::District>& districts,
                             std::span<const glm::dvec2> buildings) {
  std::vector<std::vector<Box>> boxes(districts.size());
  for (std::size_t d = 0; d < districts.size(); ++d) {
    for (const Polygon& polygon : districts[d].polygons) {
      Box b;
      for (const glm::dvec2& p : polygon.front()) b.add(p);
      boxes[d].push_back(b);
    }
  }
  std::uint64_t covered = 0;
  for (const glm::dvec2& p : buildings) {
    bool found = false;
    for (std::size_t d = 0; d < districts.size() && !found; ++d) {
      for (std::size_t k = 0; k < districts[d].polygons.size(); ++k) {
        if (inside(districts[d].polygons[k], boxes[d][k], p)) {
          ++districts[d].buildings;
          found = true;
          break;
        }
      }
    }
    covered += found ? 1 : 0;
  }
  return covered;
}

/// The boundaries of one source as districts (one per name, its polygons together), by name.
std::vector<DefaultDistricts::District> districtsOf(const GroundFeatures& ground, const std::string& source) {
  std::map<std::string, DefaultDistricts::District> byName;
  for (const GroundBoundary& b : ground.boundaries) {
    if (b.source != source || b.rings.empty() || b.rings.front().size() < 3) continue;
    DefaultDistricts::District& d = byName[b.name];
    d.name = b.name;
    d.polygons.push_back(b.rings);
  }
  std::vector<DefaultDistricts::District> out;
  for (auto& [name, d] : byName) out.push_back(std::move(d));
  return out;
}

/// The part of convex polygon `cell` where dot(p, n) <= c (Sutherland-Hodgman against one line).
Ring clip(const Ring& cell, glm::dvec2 n, double c) {
  Ring out;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    const glm::dvec2 a = cell[i];
    const glm::dvec2 b = cell[(i + 1) % cell.size()];
    const double da = a.x * n.x + a.y * n.y - c;
    const double db = b.x * n.x + b.y * n.y - c;
    if (da <= 0.0) out.push_back(a);
    if ((da < 0.0) != (db < 0.0) && da != db) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

std::string placeSourceText(const std::string& origin, bool neighbourhoods) {
  const bool osm = origin == "OpenStreetMap";
  return "each building to its nearest " + origin +
         (neighbourhoods
              ? std::string(" neighbourhood name") + (osm ? " (place=neighbourhood, quarter, suburb, borough)" : "")
              : std::string(" town or village name") + (osm ? " (place=city, town, village, hamlet)" : "")) +
         "; the input draws no boundaries that divide the city";
}

}  // namespace

std::optional<DefaultDistricts> chooseDistricts(const GroundFeatures& ground, std::span<const glm::dvec2> buildings,
                                                const std::string& origin) {
  if (buildings.empty()) return std::nullopt;
  const auto total = static_cast<double>(buildings.size());

  // 1. Drawn boundaries: the sources, finest first (then by name, for a deterministic choice).
  std::vector<std::pair<int, std::string>> sources;
  for (const GroundBoundary& b : ground.boundaries) sources.emplace_back(b.fineness, b.source);
  std::sort(sources.begin(), sources.end(),
            [](const auto& a, const auto& b) { return std::tie(b.first, a.second) < std::tie(a.first, b.second); });
  sources.erase(std::unique(sources.begin(), sources.end()), sources.end());
  for (const auto& [fineness, source] : sources) {
    std::vector<DefaultDistricts::District> districts = districtsOf(ground, source);
    const std::uint64_t covered = countBuildings(districts, buildings);
    std::erase_if(districts, [](const DefaultDistricts::District& d) { return d.buildings == 0; });
    if (districts.size() < 2 || static_cast<double>(covered) < kMinCoverage * total) continue;
    DefaultDistricts out;
    out.districts = std::move(districts);
    out.source = origin + " " + source + " areas";
    out.coverage = static_cast<double>(covered) / total;
    return out;
  }

  // 2. Named places: neighbourhoods, else settlements, near the buildings (their box grown by a
  // quarter of its size: a name just beyond the last building still names the edge).
  Box box;
  for (const glm::dvec2& p : buildings) box.add(p);
  const double grow = 0.25 * std::max(box.maxX - box.minX, box.maxY - box.minY) + kCellMarginM;
  const Box near{box.minX - grow, box.minY - grow, box.maxX + grow, box.maxY + grow};
  for (const GroundLabelKind kind : {GroundLabelKind::Neighbourhood, GroundLabelKind::Settlement}) {
    std::vector<const GroundPlace*> places;
    for (const GroundPlace& place : ground.places) {
      if (place.kind == kind && !place.name.empty() && near.contains(place.position)) places.push_back(&place);
    }
    // One site per position (a place's node and its area's centroid may coincide), in a fixed order.
    std::sort(places.begin(), places.end(), [](const GroundPlace* a, const GroundPlace* b) {
      return std::tie(a->position.x, a->position.y, a->name) < std::tie(b->position.x, b->position.y, b->name);
    });
    places.erase(std::unique(places.begin(), places.end(),
                             [](const GroundPlace* a, const GroundPlace* b) { return a->position == b->position; }),
                 places.end());
    if (places.size() > kMaxPlaces) places.resize(kMaxPlaces);
    std::map<std::string, std::size_t> names;
    for (const GroundPlace* p : places) names.emplace(p->name, 0);
    if (names.size() < 2) continue;

    // Each building to its nearest place.
    std::vector<std::uint64_t> count(places.size(), 0);
    for (const glm::dvec2& b : buildings) {
      std::size_t best = 0;
      double bestD = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < places.size(); ++i) {
        const glm::dvec2 d = places[i]->position - b;
        const double d2 = d.x * d.x + d.y * d.y;
        if (d2 < bestD) {
          bestD = d2;
          best = i;
        }
      }
      ++count[best];
    }
    // The places' cells over the buildings' box (grown a little), relative to its centre.
    const glm::dvec2 centre{0.5 * (box.minX + box.maxX), 0.5 * (box.minY + box.maxY)};
    const double hx = 0.5 * (box.maxX - box.minX) + kCellMarginM;
    const double hy = 0.5 * (box.maxY - box.minY) + kCellMarginM;
    std::map<std::string, DefaultDistricts::District> byName;
    for (std::size_t i = 0; i < places.size(); ++i) {
      if (count[i] == 0) continue;
      const glm::dvec2 si = places[i]->position - centre;
      Ring cell{{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
      for (std::size_t j = 0; j < places.size() && cell.size() >= 3; ++j) {
        if (j == i) continue;
        const glm::dvec2 sj = places[j]->position - centre;
        // Nearer to si than to sj: dot(p, sj - si) <= (|sj|² - |si|²) / 2.
        const glm::dvec2 n = sj - si;
        cell = clip(cell, n, 0.5 * ((sj.x * sj.x + sj.y * sj.y) - (si.x * si.x + si.y * si.y)));
      }
      if (cell.size() < 3) continue;
      for (glm::dvec2& p : cell) p += centre;
      DefaultDistricts::District& d = byName[places[i]->name];
      d.name = places[i]->name;
      d.polygons.push_back({std::move(cell)});
      d.buildings += count[i];
    }
    if (byName.size() < 2) continue;
    DefaultDistricts out;
    for (auto& [name, d] : byName) out.districts.push_back(std::move(d));
    out.source = placeSourceText(origin, kind == GroundLabelKind::Neighbourhood);
    out.inferred = true;
    std::uint64_t covered = 0;
    for (const auto& d : out.districts) covered += d.buildings;
    out.coverage = static_cast<double>(covered) / total;
    return out;
  }
  return std::nullopt;
}

std::string districtsGeoJson(const DefaultDistricts& districts, const GeoFrame& frame) {
  // Positions with 7 decimals (about a centimetre), written by hand: JsonWriter's shortest
  // round-trip form would keep the projection's noise in every coordinate.
  auto position = [&](std::string& out, glm::dvec2 p) {
    const LonLat ll = frame.reverseUnchecked(p);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "[%.7f,%.7f]", ll.lon, ll.lat);
    out += buffer;
  };
  // The collection's own members (Consequences.h parseDistricts): what the districts are, and a
  // row for the buildings outside them where some are.
  std::string out = "{\"type\":\"FeatureCollection\",\"source\":";
  JsonWriter::appendQuoted(out, districts.source);
  out += std::string(",\"inferred\":") + (districts.inferred ? "true" : "false");
  if (districts.coverage < 1.0) out += ",\"outside\":\"Outside the districts\"";
  out += ",\"features\":[";
  bool firstFeature = true;
  for (const DefaultDistricts::District& d : districts.districts) {
    out += firstFeature ? "\n" : ",\n";
    firstFeature = false;
    out += "{\"type\":\"Feature\",\"properties\":{\"name\":";
    JsonWriter::appendQuoted(out, d.name);
    out +=
        ",\"buildings\":" + std::to_string(d.buildings) + "},\"geometry\":{\"type\":\"MultiPolygon\",\"coordinates\":[";
    for (std::size_t k = 0; k < d.polygons.size(); ++k) {
      out += k ? ",[" : "[";
      for (std::size_t r = 0; r < d.polygons[k].size(); ++r) {
        const Ring& ring = d.polygons[k][r];
        out += r ? ",[" : "[";
        for (const glm::dvec2& p : ring) {
          position(out, p);
          out += ',';
        }
        position(out, ring.front());  // GeoJSON rings repeat their first position
        out += ']';
      }
      out += ']';
    }
    out += "]}}";
  }
  out += "\n]}\n";
  return out;
}

}  // namespace qv::prep
