#include "qv/prep/GroundTiler.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "GroundGeometry.h"
#include "qv/core/Crc32.h"
#include "qv/prep/Files.h"

namespace qv::prep {
namespace {

using ground::Box2;
using ground::Mesh;
using ground::Polyline;
using ground::Ring;

constexpr double kJoinToleranceM = 0.01;  // coastline ends this close are the same OSM node
constexpr double kClipMarginM = 0.01;     // beyond a ribbon's half width: its end caps fall outside the cell
constexpr double kMinStretchM = 40.0;     // a street label needs a straight stretch this long in the cell
constexpr double kLabelSpacingM = 150.0;  // the same name again closer than this in a cell is left out
constexpr double kMaxCoordinateM = 1e9;   // beyond, a point is not in any city (and would overflow clipping)
constexpr double kMaxWidthM = 500.0;
constexpr int kMaxLevels = 20;
constexpr std::uint8_t kUnsetRank = 128;      // GroundLine/GroundArea's default: the tiler's rank applies
constexpr std::uint8_t kUnsetPlaceRank = 64;  // GroundPlace's default

// A line, area or label point as validated from the input.
struct Line {
  GroundClass groundClass = GroundClass::Street;
  Polyline points;
  double widthM = 0.0;
  std::string text;  // cleaned; empty: no label
  GroundLabelKind kind = GroundLabelKind::Street;
  std::uint8_t rank = 0;
};
struct Area {
  GroundClass groundClass = GroundClass::Park;
  std::vector<Ring> rings;         // outer first
  std::vector<double> ringAreaM2;  // |area| of each ring
  double areaM2 = 0.0;             // outer minus holes
};
struct PointLabel {
  GroundLabelKind kind = GroundLabelKind::Neighbourhood;
  std::uint8_t rank = 0;
  glm::dvec2 position{0.0};
  std::string text;
  std::optional<std::uint32_t> area;  // an area's name: into Features::areas
  int firstLevel = 0;                 // labelled at this level and finer
};

struct Features {
  std::vector<Line> lines;
  std::vector<Area> areas;
  std::vector<PointLabel> points;
  std::vector<Ring> landRings;  // coastlines joined into rings, land inside (even-odd)
  std::vector<double> landRingAreaM2;
  std::map<std::string, std::uint64_t> counts;
  std::map<std::string, std::uint64_t> skipped;
  Box2 bounds = ground::boundsOf({});
};

// One level of the pyramid.
struct Level {
  int index = 0;
  double side = 0.0;     // cell side, metres
  double errorM = 0.0;   // geometric error: side / 256 for inner levels, 0 for leaves
  double minAreaM2 = 0;  // areas and rings smaller than this are left out (inner levels)
  bool leaf = false;
  int levels = 0;  // of the pyramid
};

// What a cell's subtree holds, clipped to the cell (lines to the cell widened by their ribbon's
// half width at its level), at full detail, in feature order.
struct LineClip {
  std::uint32_t feature = 0;
  std::vector<Polyline> pieces;
};
struct AreaClip {
  std::uint32_t feature = 0;
  std::vector<std::uint32_t> ringIndex;  // into the feature's rings (or Features::landRings)
  std::vector<Ring> rings;
};
struct CellInput {
  std::vector<LineClip> lines;
  std::vector<AreaClip> areas;
  AreaClip land;
  std::vector<std::uint32_t> points;  // into Features::points
  [[nodiscard]] bool empty() const { return lines.empty() && areas.empty() && land.rings.empty() && points.empty(); }
};

bool finitePoint(glm::dvec2 p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::abs(p.x) <= kMaxCoordinateM &&
         std::abs(p.y) <= kMaxCoordinateM;
}
bool allFinite(std::span<const glm::dvec2> points) {
  return std::all_of(points.begin(), points.end(), finitePoint);
}

// The points without consecutive repeats (and, for a ring, without the closing copy of the first).
Polyline withoutRepeats(std::span<const glm::dvec2> points, bool ring) {
  Polyline out;
  out.reserve(points.size());
  for (const glm::dvec2& p : points) {
    if (out.empty() || out.back() != p) out.push_back(p);
  }
  if (ring) {
    while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  }
  return out;
}

// Fewer than 3 points, or all on one line: no inside at all. (A zero signed area is not enough: a
// bow tie has two lobes of opposite winding.)
bool degenerateRing(std::span<const glm::dvec2> ring) {
  if (ring.size() < 3) return true;
  const glm::dvec2 o = ring[0];
  const auto second = std::find_if(ring.begin(), ring.end(), [o](glm::dvec2 p) { return p != o; });
  if (second == ring.end()) return true;
  const glm::dvec2 d = *second - o;
  return std::all_of(ring.begin(), ring.end(),
                     [&](glm::dvec2 p) { return d.x * (p.y - o.y) - d.y * (p.x - o.x) == 0.0; });
}

void unite(Box2& b, const Box2& other) {
  b.minX = std::min(b.minX, other.minX);
  b.minY = std::min(b.minY, other.minY);
  b.maxX = std::max(b.maxX, other.maxX);
  b.maxY = std::max(b.maxY, other.maxY);
}
bool emptyBox(const Box2& b) {
  return !(b.minX <= b.maxX && b.minY <= b.maxY);
}

std::uint8_t defaultRank(GroundLabelKind kind, GroundClass groundClass) {
  switch (kind) {
    case GroundLabelKind::Settlement:
      return 10;
    case GroundLabelKind::Neighbourhood:
      return 30;
    case GroundLabelKind::Water:
      return 50;
    case GroundLabelKind::Park:
      return 70;
    default:
      break;
  }
  switch (groundClass) {
    case GroundClass::Motorway:
      return 80;
    case GroundClass::Major:
      return 100;
    case GroundClass::Path:
      return 200;
    default:
      return 140;
  }
}

// The level from which a line's name is placed: streets and paths at the two finest levels,
// major roads, motorways and rivers one level coarser; railways are not named.
std::optional<int> lineLabelFirstLevel(GroundClass c, int levels) {
  switch (c) {
    case GroundClass::Street:
    case GroundClass::Path:
      return std::max(0, levels - 2);
    case GroundClass::Major:
    case GroundClass::Motorway:
    case GroundClass::Water:
      return std::max(0, levels - 3);
    default:
      return std::nullopt;
  }
}

bool lineDrawn(GroundClass c, const Level& level) {
  if (c == GroundClass::Street || c == GroundClass::Path) return level.index >= level.levels - 2;
  return true;
}

double halfWidth(const Line& line, const Level& level) {
  return 0.5 * (level.leaf ? line.widthM : std::max(line.widthM, 1.5 * level.errorM));
}

// Text cleaned for a label; counts "label-cleaned" when it had to change.
std::string labelText(const std::string& name, std::map<std::string, std::uint64_t>& skipped) {
  if (name.empty()) return {};
  std::string text = ground::cleanLabelText(name);
  if (text != name) ++skipped["label-cleaned"];
  return text;
}

// A point inside the area for its name: the centroid when it is inside, else the centroid of the
// largest triangle of the area's triangulation.
std::optional<glm::dvec2> areaLabelPoint(const Area& area) {
  const glm::dvec2 o = area.rings[0][0];  // relative coordinates: no cancellation
  double sumArea = 0.0;
  glm::dvec2 sum(0.0);
  for (std::size_t r = 0; r < area.rings.size(); ++r) {
    const Ring& ring = area.rings[r];
    const double ringSign = r == 0 ? 1.0 : -1.0;
    const double orientation = ground::signedArea(ring) >= 0.0 ? 1.0 : -1.0;
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
      const glm::dvec2 p = ring[i] - o, q = ring[(i + 1) % n] - o;
      const double c = (p.x * q.y - q.x * p.y) * orientation * ringSign;
      sumArea += c;
      sum += (p + q) * c;
    }
  }
  if (sumArea > 0.0) {
    const glm::dvec2 centroid = o + sum / (3.0 * sumArea);
    if (ground::insideEvenOdd(centroid, area.rings)) return centroid;
  }
  Mesh mesh;
  const Box2 box = ground::boundsOf(area.rings[0]).expanded(1.0);
  if (!ground::triangulateEvenOdd(area.rings, box, false, mesh)) return std::nullopt;
  double largest = 0.0;
  std::optional<glm::dvec2> best;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const glm::dvec2 a = mesh.vertices[mesh.triangles[t]], b = mesh.vertices[mesh.triangles[t + 1]],
                     c = mesh.vertices[mesh.triangles[t + 2]];
    const double size = std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    if (size > largest) {
      largest = size;
      best = (a + b + c) / 3.0;
    }
  }
  return best;
}

// Joins coastline ways end to start into closed rings (OSM: land on the left). A chain that does
// not close is left out and counted: guessing which side is sea would flood the land.
void joinCoastlines(const std::vector<std::vector<glm::dvec2>>& ways, Features& f) {
  std::vector<Polyline> valid;
  for (const auto& way : ways) {
    if (!allFinite(way)) {
      ++f.skipped["non-finite"];
      continue;
    }
    Polyline pts = withoutRepeats(way, false);
    if (pts.size() < 2) {
      ++f.skipped["degenerate"];
      continue;
    }
    valid.push_back(std::move(pts));
  }
  // Ways by the grid square (kJoinToleranceM wide) of their first and last points.
  using Key = std::pair<std::int64_t, std::int64_t>;
  auto keyOf = [](glm::dvec2 p) {
    return Key{static_cast<std::int64_t>(std::floor(p.x / kJoinToleranceM)),
               static_cast<std::int64_t>(std::floor(p.y / kJoinToleranceM))};
  };
  std::map<Key, std::vector<std::size_t>> byStart, byEnd;
  for (std::size_t i = 0; i < valid.size(); ++i) {
    byStart[keyOf(valid[i].front())].push_back(i);
    byEnd[keyOf(valid[i].back())].push_back(i);
  }
  std::vector<bool> used(valid.size(), false);
  auto near = [](glm::dvec2 a, glm::dvec2 b) {
    return std::abs(a.x - b.x) <= kJoinToleranceM && std::abs(a.y - b.y) <= kJoinToleranceM;
  };
  // The first unused way whose start (or end) is at p.
  auto find = [&](const std::map<Key, std::vector<std::size_t>>& index, glm::dvec2 p, bool start) {
    const Key k = keyOf(p);
    std::size_t found = std::numeric_limits<std::size_t>::max();
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = index.find({k.first + dx, k.second + dy});
        if (it == index.end()) continue;
        for (std::size_t w : it->second) {
          if (!used[w] && w < found && near(start ? valid[w].front() : valid[w].back(), p)) found = w;
        }
      }
    }
    return found;
  };
  for (std::size_t i = 0; i < valid.size(); ++i) {
    if (used[i]) continue;
    used[i] = true;
    Polyline chain = valid[i];
    bool closed = false;
    for (;;) {
      if (chain.size() > 2 && near(chain.front(), chain.back())) {
        closed = true;
        break;
      }
      const std::size_t next = find(byStart, chain.back(), true);
      if (next == std::numeric_limits<std::size_t>::max()) break;
      used[next] = true;
      chain.insert(chain.end(), valid[next].begin() + 1, valid[next].end());
    }
    if (!closed) {
      // Collect the rest of the open chain backwards, so that it is counted once.
      for (std::size_t previous = find(byEnd, chain.front(), false);
           previous != std::numeric_limits<std::size_t>::max(); previous = find(byEnd, chain.front(), false)) {
        used[previous] = true;
        chain.insert(chain.begin(), valid[previous].begin(), valid[previous].end() - 1);
      }
      ++f.skipped["unclosed-coastline"];
      continue;
    }
    chain.pop_back();  // the closing point
    Ring ring = withoutRepeats(chain, true);
    const double area = std::abs(ground::signedArea(ring));
    if (degenerateRing(ring)) {
      ++f.skipped["degenerate"];
      continue;
    }
    f.landRings.push_back(std::move(ring));
    f.landRingAreaM2.push_back(area);
  }
}

Features validate(const GroundFeatures& in) {
  Features f;
  auto count = [&f](GroundClass c) { ++f.counts[std::string(groundClassName(c))]; };
  for (const GroundLine& line : in.lines) {
    if (static_cast<unsigned>(line.groundClass) >= static_cast<unsigned>(GroundClass::Count)) {
      ++f.skipped["unknown-class"];
      continue;
    }
    count(line.groundClass);
    if (!allFinite(line.points) || !std::isfinite(line.widthM)) {
      ++f.skipped["non-finite"];
      continue;
    }
    Polyline pts = withoutRepeats(line.points, false);
    if (pts.size() < 2 || !(line.widthM > 0.0f)) {
      ++f.skipped["degenerate"];
      continue;
    }
    Line l;
    l.groundClass = line.groundClass;
    l.points = std::move(pts);
    l.widthM = std::min(static_cast<double>(line.widthM), kMaxWidthM);
    if (lineLabelFirstLevel(line.groundClass, kMaxLevels)) l.text = labelText(line.name, f.skipped);
    l.kind = line.groundClass == GroundClass::Water ? GroundLabelKind::Water : GroundLabelKind::Street;
    l.rank = line.rank != kUnsetRank ? line.rank : defaultRank(l.kind, line.groundClass);
    if (!l.text.empty()) ++f.counts["labels"];
    unite(f.bounds, ground::boundsOf(l.points));
    f.lines.push_back(std::move(l));
  }
  for (const GroundArea& area : in.areas) {
    if (static_cast<unsigned>(area.groundClass) >= static_cast<unsigned>(GroundClass::Count)) {
      ++f.skipped["unknown-class"];
      continue;
    }
    count(area.groundClass);
    if (!std::all_of(area.rings.begin(), area.rings.end(), [](const auto& r) { return allFinite(r); })) {
      ++f.skipped["non-finite"];
      continue;
    }
    Area a;
    a.groundClass = area.groundClass;
    for (std::size_t r = 0; r < area.rings.size(); ++r) {
      Ring ring = withoutRepeats(area.rings[r], true);
      const double ringArea = std::abs(ground::signedArea(ring));
      if (degenerateRing(ring)) {
        if (r == 0) break;          // no outer ring: the whole area goes
        ++f.skipped["degenerate"];  // a hole of nothing: left out
        continue;
      }
      a.rings.push_back(std::move(ring));
      a.ringAreaM2.push_back(ringArea);
      a.areaM2 += r == 0 ? ringArea : -ringArea;
    }
    if (a.rings.empty()) {
      ++f.skipped["degenerate"];
      continue;
    }
    a.areaM2 = std::max(a.areaM2, 0.0);
    unite(f.bounds, ground::boundsOf(a.rings[0]));
    if (area.groundClass == GroundClass::Water || area.groundClass == GroundClass::Park) {
      std::string text = labelText(area.name, f.skipped);
      if (!text.empty()) {
        if (const auto position = areaLabelPoint(a)) {
          PointLabel p;
          p.kind = area.groundClass == GroundClass::Water ? GroundLabelKind::Water : GroundLabelKind::Park;
          p.rank = area.rank != kUnsetRank ? area.rank : defaultRank(p.kind, area.groundClass);
          p.position = *position;
          p.text = std::move(text);
          p.area = static_cast<std::uint32_t>(f.areas.size());  // the area pushed below
          f.points.push_back(std::move(p));
          ++f.counts["labels"];
        }
      }
    }
    f.areas.push_back(std::move(a));
  }
  for (const GroundPlace& place : in.places) {
    if (static_cast<unsigned>(place.kind) >= static_cast<unsigned>(GroundLabelKind::Count)) {
      ++f.skipped["unknown-class"];
      continue;
    }
    if (!finitePoint(place.position)) {
      ++f.skipped["non-finite"];
      continue;
    }
    std::string text = labelText(place.name, f.skipped);
    if (text.empty()) continue;
    PointLabel p;
    p.kind = place.kind;
    p.rank = place.rank != kUnsetRank && place.rank != kUnsetPlaceRank ? place.rank
                                                                       : defaultRank(place.kind, GroundClass::Street);
    p.position = place.position;
    p.text = std::move(text);
    f.points.push_back(std::move(p));
    ++f.counts["labels"];
    unite(f.bounds, Box2{place.position.x, place.position.y, place.position.x, place.position.y});
  }
  joinCoastlines(in.coastlines, f);
  for (const Ring& ring : f.landRings) unite(f.bounds, ground::boundsOf(ring));
  if (!f.landRings.empty()) f.counts["land"] += f.landRings.size();
  return f;
}

// --- Cells -----------------------------------------------------------------------------------

Box2 cellBox(const GroundLayer& layer, const Level& level, std::uint32_t x, std::uint32_t y) {
  return {layer.minX + x * level.side, layer.minY + y * level.side, layer.minX + (x + 1) * level.side,
          layer.minY + (y + 1) * level.side};
}

// The cell of `level` holding p (cells are half-open, the last row and column closed).
std::pair<std::uint32_t, std::uint32_t> cellOf(const GroundLayer& layer, const Level& level, glm::dvec2 p) {
  const double cells = std::ldexp(1.0, level.index);
  auto index = [&](double v, double min) {
    return static_cast<std::uint32_t>(std::clamp(std::floor((v - min) / level.side), 0.0, cells - 1.0));
  };
  return {index(p.x, layer.minX), index(p.y, layer.minY)};
}

// `in` clipped to the cell (x, y) of `level`.
CellInput clipInput(const CellInput& in, const Features& f, const GroundLayer& layer, const Level& level,
                    std::uint32_t x, std::uint32_t y) {
  const Box2 box = cellBox(layer, level, x, y);
  CellInput out;
  for (const LineClip& line : in.lines) {
    const Box2 widened = box.expanded(halfWidth(f.lines[line.feature], level) + kClipMarginM);
    LineClip clip{line.feature, {}};
    for (const Polyline& piece : line.pieces) ground::clipPolyline(piece, widened, clip.pieces);
    if (!clip.pieces.empty()) out.lines.push_back(std::move(clip));
  }
  auto clipArea = [&box](const AreaClip& area, AreaClip& clip) {
    clip.feature = area.feature;
    for (std::size_t r = 0; r < area.rings.size(); ++r) {
      Ring ring = ground::clipRing(area.rings[r], box);
      if (ring.empty()) continue;
      clip.ringIndex.push_back(area.ringIndex[r]);
      clip.rings.push_back(std::move(ring));
    }
  };
  for (const AreaClip& area : in.areas) {
    AreaClip clip;
    clipArea(area, clip);
    if (!clip.rings.empty()) out.areas.push_back(std::move(clip));
  }
  clipArea(in.land, out.land);
  for (std::uint32_t p : in.points) {
    if (cellOf(layer, level, f.points[p].position) == std::pair{x, y}) out.points.push_back(p);
  }
  return out;
}

// Triangles of one feature in a cell.
struct Piece {
  GroundClass groundClass = GroundClass::Land;
  double importance = 0.0;  // length or area: the least important go first when a cell is too full
  Mesh mesh;
};

struct CellOutput {
  std::vector<std::uint8_t> bytes;  // empty: nothing to draw
  std::uint64_t triangles = 0;
  std::uint64_t labels = 0;
  std::map<std::string, std::uint64_t> skipped;
  std::array<std::optional<CellInput>, 4> children;  // SW, SE, NW, NE
};

double polylineLength(std::span<const Polyline> pieces) {
  double total = 0.0;
  for (const Polyline& p : pieces) {
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const glm::dvec2 d = p[i + 1] - p[i];
      total += std::sqrt(d.x * d.x + d.y * d.y);
    }
  }
  return total;
}

std::vector<GroundLabel> cellLabels(const CellInput& in, const Features& f, const Level& level, const Box2& box) {
  struct Candidate {
    GroundLabel label;
    glm::dvec2 position;
    double stretchM = 0.0;
  };
  std::vector<Candidate> streets;
  for (const LineClip& clip : in.lines) {
    const Line& line = f.lines[clip.feature];
    if (line.text.empty()) continue;
    const std::optional<int> first = lineLabelFirstLevel(line.groundClass, level.levels);
    if (!first || level.index < *first) continue;
    std::vector<Polyline> inCell;
    for (const Polyline& piece : clip.pieces) ground::clipPolyline(piece, box, inCell);
    const std::optional<ground::Stretch> stretch = ground::longestStretch(inCell);
    if (!stretch || stretch->lengthM < kMinStretchM) continue;
    GroundLabel label;
    label.kind = line.kind;
    label.rank = line.rank;
    label.angleRad = stretch->angleRad;
    // A river's name is drawn at a point (along the river's direction there): GroundLabel's
    // lengthM belongs to street labels only.
    label.lengthM = line.kind == GroundLabelKind::Street ? static_cast<float>(stretch->lengthM) : 0.0f;
    label.text = line.text;
    streets.push_back({std::move(label), stretch->middle, stretch->lengthM});
  }
  // One label per name within kLabelSpacingM: the longest stretch wins.
  std::stable_sort(streets.begin(), streets.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.label.rank, b.stretchM) < std::tie(b.label.rank, a.stretchM);
  });
  std::vector<GroundLabel> labels;
  std::unordered_map<std::string, std::vector<glm::dvec2>> placed;
  auto local = [&box](glm::dvec2 p) {
    const auto side = static_cast<float>(box.maxX - box.minX);
    return glm::vec2(std::clamp(static_cast<float>(p.x - box.minX), 0.0f, side),
                     std::clamp(static_cast<float>(p.y - box.minY), 0.0f, side));
  };
  for (Candidate& c : streets) {
    std::vector<glm::dvec2>& at = placed[c.label.text];
    const bool near = std::any_of(at.begin(), at.end(), [&c](glm::dvec2 p) {
      const glm::dvec2 d = p - c.position;
      return d.x * d.x + d.y * d.y < kLabelSpacingM * kLabelSpacingM;
    });
    if (near) continue;
    at.push_back(c.position);
    c.label.position = local(c.position);
    labels.push_back(std::move(c.label));
  }
  for (std::uint32_t index : in.points) {
    const PointLabel& p = f.points[index];
    if (level.index < p.firstLevel) continue;
    GroundLabel label;
    label.kind = p.kind;
    label.rank = p.rank;
    label.position = local(p.position);
    label.text = p.text;
    labels.push_back(std::move(label));
  }
  std::stable_sort(labels.begin(), labels.end(),
                   [](const GroundLabel& a, const GroundLabel& b) { return a.rank < b.rank; });
  return labels;
}

CellOutput processCell(const CellInput& in, const Features& f, const GroundLayer& layer, const Level& level,
                       const std::optional<Level>& childLevel, std::uint32_t x, std::uint32_t y) {
  CellOutput out;
  const Box2 box = cellBox(layer, level, x, y);
  std::vector<Piece> pieces;

  // Lines: ribbons of the (simplified) pieces, cut to the cell.
  for (const LineClip& clip : in.lines) {
    const Line& line = f.lines[clip.feature];
    if (!lineDrawn(line.groundClass, level)) continue;
    Mesh ribbon;
    const double hw = halfWidth(line, level);
    for (const Polyline& piece : clip.pieces) {
      if (level.leaf) {
        ground::appendRibbon(piece, hw, ribbon);
      } else {
        ground::appendRibbon(ground::simplifyPolyline(piece, level.errorM), hw, ribbon);
      }
    }
    Piece p{line.groundClass, polylineLength(clip.pieces), {}};
    ground::clipMesh(ribbon, box, p.mesh);
    if (!p.mesh.empty()) pieces.push_back(std::move(p));
  }

  // Rings of one area at this level: small holes and islands left out, simplified.
  auto levelRings = [&](const AreaClip& clip, const std::vector<double>& ringAreaM2, bool keepFirst) {
    std::vector<Ring> rings;
    for (std::size_t r = 0; r < clip.rings.size(); ++r) {
      const bool outer = keepFirst && clip.ringIndex[r] == 0;
      if (!level.leaf && !outer && ringAreaM2[clip.ringIndex[r]] < level.minAreaM2) continue;
      Ring ring = level.leaf ? clip.rings[r] : ground::simplifyClippedRing(clip.rings[r], box, level.errorM);
      if (ring.size() >= 3) rings.push_back(std::move(ring));
    }
    return rings;
  };
  for (const AreaClip& clip : in.areas) {
    const Area& area = f.areas[clip.feature];
    if (!level.leaf && area.areaM2 < level.minAreaM2) continue;
    const std::vector<Ring> rings = levelRings(clip, area.ringAreaM2, true);
    Piece p{area.groundClass, area.areaM2, {}};
    if (!ground::triangulateEvenOdd(rings, box, false, p.mesh)) {
      ++out.skipped["self-intersecting-area"];
      continue;
    }
    if (!p.mesh.empty()) pieces.push_back(std::move(p));
  }

  // Coast: land inside the land rings, sea the rest of the cell. Neither is ever dropped.
  if (!f.landRings.empty()) {
    const std::vector<Ring> rings = levelRings(in.land, f.landRingAreaM2, false);
    Piece land{GroundClass::Land, std::numeric_limits<double>::infinity(), {}};
    Piece sea{GroundClass::Water, std::numeric_limits<double>::infinity(), {}};
    if (ground::triangulateEvenOdd(rings, box, false, land.mesh) &&
        ground::triangulateEvenOdd(rings, box, true, sea.mesh)) {
      if (!land.mesh.empty()) pieces.push_back(std::move(land));
      if (!sea.mesh.empty()) pieces.push_back(std::move(sea));
    } else {
      ++out.skipped["self-intersecting-coastline"];
    }
  }

  // The codec's limits: the least important features go first.
  const GroundTileLimits limits;
  std::uint64_t vertexCount = 0, triangleCount = 0;
  for (const Piece& p : pieces) {
    vertexCount += p.mesh.vertices.size();
    triangleCount += p.mesh.triangles.size() / 3;
  }
  if (vertexCount > limits.maxVertices || triangleCount > limits.maxTriangles) {
    std::vector<std::size_t> order(pieces.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return pieces[a].importance < pieces[b].importance; });
    std::vector<bool> drop(pieces.size(), false);
    for (std::size_t i : order) {
      if (vertexCount <= limits.maxVertices && triangleCount <= limits.maxTriangles) break;
      drop[i] = true;
      vertexCount -= pieces[i].mesh.vertices.size();
      triangleCount -= pieces[i].mesh.triangles.size() / 3;
      ++out.skipped["cell-over-limit"];
    }
    std::vector<Piece> kept;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (!drop[i]) kept.push_back(std::move(pieces[i]));
    }
    pieces = std::move(kept);
  }

  GroundTile tile;
  tile.originX = box.minX;
  tile.originY = box.minY;
  tile.extent = static_cast<float>(level.side);
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const Piece& a, const Piece& b) { return a.groundClass < b.groundClass; });
  for (const Piece& p : pieces) {
    const auto first = static_cast<std::uint32_t>(tile.vertices.size());
    for (const glm::dvec2& v : p.mesh.vertices) {
      tile.vertices.emplace_back(std::clamp(static_cast<float>(v.x - box.minX), 0.0f, tile.extent),
                                 std::clamp(static_cast<float>(v.y - box.minY), 0.0f, tile.extent));
    }
    if (tile.runs.empty() || tile.runs.back().groundClass != p.groundClass) {
      tile.runs.push_back({p.groundClass, static_cast<std::uint32_t>(tile.triangles.size() / 3), 0});
    }
    for (std::uint32_t i : p.mesh.triangles) tile.triangles.push_back(first + i);
    tile.runs.back().triangleCount += static_cast<std::uint32_t>(p.mesh.triangles.size() / 3);
  }
  tile.labels = cellLabels(in, f, level, box);
  if (tile.labels.size() > limits.maxLabels) {
    out.skipped["cell-over-limit"] += tile.labels.size() - limits.maxLabels;
    tile.labels.resize(limits.maxLabels);
  }
  if (!tile.triangles.empty() || !tile.labels.empty()) {
    out.bytes = encodeGroundTile(tile);
    out.triangles = tile.triangles.size() / 3;
    out.labels = tile.labels.size();
  }

  if (childLevel) {
    for (std::uint32_t q = 0; q < 4; ++q) {
      const std::uint32_t cx = 2 * x + (q & 1u), cy = 2 * y + (q >> 1);
      CellInput child = clipInput(in, f, layer, *childLevel, cx, cy);
      // With a coastline every cell is land or sea: the whole pyramid has files.
      if (!child.empty() || !f.landRings.empty()) out.children[q] = std::move(child);
    }
  }
  return out;
}

struct WorkCell {
  std::uint32_t x = 0, y = 0;
  CellInput input;
};

}  // namespace

std::string groundFileName(int level, std::uint32_t x, std::uint32_t y) {
  return "ground/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvg";
}

Result<GroundTilerReport> writeGroundTiles(const GroundFeatures& features, const Rect& cityBounds,
                                           const std::string& cityDir, const GroundTilerOptions& options) {
  const unsigned threads = options.threads > 0 ? options.threads : usableCores();
  const double leafCellM =
      std::isfinite(options.leafCellM) && options.leafCellM > 0.0 ? options.leafCellM : GroundTilerOptions{}.leafCellM;
  GroundTilerReport report;
  GroundLayer& layer = report.layer;
  Features f = validate(features);
  layer.features = f.counts;
  layer.skipped = features.skipped;
  for (const auto& [reason, n] : f.skipped) layer.skipped[reason] += n;

  // 1. The pyramid: a square around the city and its features, the features clamped to 4 × the
  //    city's size (at least a leaf) around the city's centre.
  Box2 region = f.bounds;
  if (!cityBounds.empty()) {
    const Box2 city{cityBounds.minX, cityBounds.minY, cityBounds.maxX, cityBounds.maxY};
    const double size = std::max({city.maxX - city.minX, city.maxY - city.minY, leafCellM});
    const glm::dvec2 centre(0.5 * (city.minX + city.maxX), 0.5 * (city.minY + city.maxY));
    unite(region, city);
    region.minX = std::max(region.minX, centre.x - 2.0 * size);
    region.minY = std::max(region.minY, centre.y - 2.0 * size);
    region.maxX = std::min(region.maxX, centre.x + 2.0 * size);
    region.maxY = std::min(region.maxY, centre.y + 2.0 * size);
  }
  if (emptyBox(region) || f.lines.size() + f.areas.size() + f.points.size() + f.landRings.size() == 0) return report;
  double side = std::max(region.maxX - region.minX, region.maxY - region.minY);
  if (!(side > 0.0)) side = leafCellM;
  layer.minX = 0.5 * (region.minX + region.maxX) - 0.5 * side;
  layer.minY = 0.5 * (region.minY + region.maxY) - 0.5 * side;
  layer.size = side;
  int levels = 1;
  while (levels < kMaxLevels && std::ldexp(side, 1 - levels) > leafCellM) ++levels;
  layer.levels = static_cast<std::uint8_t>(levels);
  std::vector<Level> levelInfo(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l) {
    Level& level = levelInfo[static_cast<std::size_t>(l)];
    level.index = l;
    level.levels = levels;
    level.side = std::ldexp(side, -l);
    level.leaf = l == levels - 1;
    level.errorM = level.leaf ? 0.0 : level.side / 256.0;
    level.minAreaM2 = level.leaf ? 0.0 : (level.side / 128.0) * (level.side / 128.0);
  }
  // An area's name is placed from the first level that draws the area.
  for (PointLabel& p : f.points) {
    if (!p.area) continue;
    const Area& area = f.areas[*p.area];
    int first = levels - 1;
    while (first > 0 && area.areaM2 >= levelInfo[static_cast<std::size_t>(first - 1)].minAreaM2) --first;
    p.firstLevel = first;
  }

  if (const Status s = makeDirectories(cityDir + "/ground"); !s.ok()) return Error{s.error()};

  // 2. Level by level, every cell in parallel: its tile from its input, its children's inputs by
  //    clipping its own. A cell's bytes depend on its input only: the output does not depend on
  //    the number of threads.
  CellInput all;
  for (std::uint32_t i = 0; i < f.lines.size(); ++i) all.lines.push_back({i, {f.lines[i].points}});
  for (std::uint32_t i = 0; i < f.areas.size(); ++i) {
    AreaClip a{i, {}, f.areas[i].rings};
    for (std::uint32_t r = 0; r < a.rings.size(); ++r) a.ringIndex.push_back(r);
    all.areas.push_back(std::move(a));
  }
  all.land.rings = f.landRings;
  for (std::uint32_t r = 0; r < all.land.rings.size(); ++r) all.land.ringIndex.push_back(r);
  const Box2 root = cellBox(layer, levelInfo[0], 0, 0);
  for (std::uint32_t i = 0; i < f.points.size(); ++i) {
    if (root.contains(f.points[i].position)) all.points.push_back(i);
  }
  std::vector<WorkCell> cells;
  cells.push_back({0, 0, clipInput(all, f, layer, levelInfo[0], 0, 0)});
  all = CellInput{};

  std::mutex mutex;
  std::string firstError;
  std::set<std::tuple<int, std::uint32_t, std::uint32_t>> withFile;
  auto writeNode = [&](int level, std::uint32_t x, std::uint32_t y, const std::vector<std::uint8_t>& bytes) {
    GroundNode node;
    node.level = static_cast<std::uint8_t>(level);
    node.x = x;
    node.y = y;
    node.geometricErrorM = static_cast<float>(levelInfo[static_cast<std::size_t>(level)].errorM);
    node.file = groundFileName(level, x, y);
    node.bytes = bytes.size();
    node.crc32 = crc32(bytes);
    const Status s = writeStagedFile(cityDir + "/" + node.file, bytes);
    const std::lock_guard lock(mutex);
    if (!s.ok() && firstError.empty()) firstError = s.error();
    layer.bytes += node.bytes;
    layer.nodes.push_back(std::move(node));
    withFile.insert({level, x, y});
  };
  for (int l = 0; l < levels && !cells.empty(); ++l) {
    const Level& level = levelInfo[static_cast<std::size_t>(l)];
    const std::optional<Level> childLevel =
        level.leaf ? std::nullopt : std::optional<Level>(levelInfo[static_cast<std::size_t>(l + 1)]);
    std::vector<std::array<std::optional<CellInput>, 4>> children(cells.size());
    parallelFor(cells.size(), threads, [&](std::size_t i) {
      WorkCell& cell = cells[i];
      CellOutput out = processCell(cell.input, f, layer, level, childLevel, cell.x, cell.y);
      cell.input = CellInput{};
      children[i] = std::move(out.children);
      if (!out.bytes.empty()) writeNode(l, cell.x, cell.y, out.bytes);
      const std::lock_guard lock(mutex);
      for (const auto& [reason, n] : out.skipped) layer.skipped[reason] += n;
      report.triangles += out.triangles;
      report.labels += out.labels;
      if (level.leaf) {
        report.leafTriangles += out.triangles;
        if (!out.bytes.empty()) report.areaKm2 += level.side * level.side * 1e-6;
      }
    });
    if (interrupted()) return Error{"interrupted"};
    std::vector<WorkCell> next;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      for (std::uint32_t q = 0; q < 4; ++q) {
        if (!children[i][q]) continue;
        next.push_back({2 * cells[i].x + (q & 1u), 2 * cells[i].y + (q >> 1), std::move(*children[i][q])});
      }
    }
    cells = std::move(next);
  }
  if (!firstError.empty()) return Error{firstError};

  // 3. An inner cell that draws nothing over cells that do gets an empty file: the pyramid stays
  //    connected from its root, so a reader refines into every cell with a file.
  std::set<std::tuple<int, std::uint32_t, std::uint32_t>> ancestors;
  for (const auto& [level, x, y] : withFile) {
    for (int l = level - 1, shift = 1; l >= 0; --l, ++shift) {
      ancestors.insert({l, x >> shift, y >> shift});
    }
  }
  for (const auto& [level, x, y] : ancestors) {
    if (withFile.count({level, x, y}) != 0) continue;
    const Box2 box = cellBox(layer, levelInfo[static_cast<std::size_t>(level)], x, y);
    GroundTile tile;
    tile.originX = box.minX;
    tile.originY = box.minY;
    tile.extent = static_cast<float>(box.maxX - box.minX);
    writeNode(level, x, y, encodeGroundTile(tile));
  }
  if (!firstError.empty()) return Error{firstError};
  std::sort(layer.nodes.begin(), layer.nodes.end(), [](const GroundNode& a, const GroundNode& b) {
    return std::tie(a.level, a.y, a.x) < std::tie(b.level, b.y, b.x);
  });
  return report;
}

}  // namespace qv::prep
