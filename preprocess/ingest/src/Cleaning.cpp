#include "qv/prep/Cleaning.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace qv::prep {
namespace {

double cross(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}
double length(glm::dvec2 v) {
  return std::sqrt(v.x * v.x + v.y * v.y);
}

/// True when b is a degenerate corner of the triangle (a, b, c): the triangle's smallest altitude
/// (twice its area over its longest side) is within `tolerance`. That covers b on the line a–c
/// (collinear) and spikes (a–b–a' doubling back), whichever side is long.
bool degenerateCorner(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, double tolerance) {
  const double twiceArea = std::abs(cross(b - a, c - a));
  const double longest = std::max({length(b - a), length(c - b), length(c - a)});
  return twiceArea <= tolerance * longest;
}

bool near(glm::dvec2 a, glm::dvec2 b, double tolerance) {
  const glm::dvec2 d = b - a;
  return d.x * d.x + d.y * d.y <= tolerance * tolerance;
}

/// Closing point, duplicates, collinear vertices and spikes out of one ring (in place).
void cleanRing(std::vector<glm::dvec2>& ring, const CleanOptions& options) {
  const double dup = options.duplicateToleranceM;
  const double col = options.collinearToleranceM;
  std::size_t n = 0;  // ring[0, n) is the cleaned prefix (a stack)
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec2 p = ring[i];
    if (n > 0 && near(ring[n - 1], p, dup)) continue;
    ring[n++] = p;
    while (n >= 3 && degenerateCorner(ring[n - 3], ring[n - 2], ring[n - 1], col)) {
      ring[n - 2] = ring[n - 1];
      --n;
      if (n >= 2 && near(ring[n - 2], ring[n - 1], dup)) --n;
    }
  }
  ring.resize(n);
  // The seam: the closing point, then corners that wrap around the end.
  bool changed = true;
  while (changed && ring.size() >= 2) {
    changed = false;
    if (near(ring.back(), ring.front(), dup)) {
      ring.pop_back();
      changed = true;
      continue;
    }
    if (ring.size() < 3) break;
    const std::size_t m = ring.size();
    if (degenerateCorner(ring[m - 2], ring[m - 1], ring[0], col)) {
      ring.pop_back();
      changed = true;
    } else if (degenerateCorner(ring[m - 1], ring[0], ring[1], col)) {
      ring.erase(ring.begin());
      changed = true;
    }
  }
}

struct Box {
  double minX = std::numeric_limits<double>::infinity();
  double minY = std::numeric_limits<double>::infinity();
  double maxX = -std::numeric_limits<double>::infinity();
  double maxY = -std::numeric_limits<double>::infinity();
  void add(glm::dvec2 p) {
    minX = std::min(minX, p.x);
    minY = std::min(minY, p.y);
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  [[nodiscard]] bool overlaps(const Box& o) const {
    return minX <= o.maxX && o.minX <= maxX && minY <= o.maxY && o.minY <= maxY;
  }
};

Box ringBox(const std::vector<glm::dvec2>& ring) {
  Box box;
  for (const glm::dvec2& p : ring) box.add(p);
  return box;
}

// ---- Exact predicates on coordinates snapped to millimetres (relative to the outer ring's first
// point). |coordinate| <= 2^29 mm keeps every cross product below 2^62: int64 arithmetic is exact,
// so the topology decisions (crossing, touching, inside) cannot be flipped by rounding.
constexpr double kSnapPerMeter = 1000.0;
constexpr std::int64_t kSnapLimit = std::int64_t{1} << 29;

struct IPoint {
  std::int64_t x;
  std::int64_t y;
  bool operator==(const IPoint&) const = default;
};

int orient(IPoint a, IPoint b, IPoint c) {
  const std::int64_t v = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return (v > 0) - (v < 0);
}

/// p on segment a-b, given that the three are collinear.
bool withinBox(IPoint a, IPoint b, IPoint p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

enum class Contact : std::uint8_t { None, Touch, Cross, Overlap };

Contact segmentContact(IPoint p1, IPoint p2, IPoint q1, IPoint q2) {
  const int d1 = orient(q1, q2, p1);
  const int d2 = orient(q1, q2, p2);
  const int d3 = orient(p1, p2, q1);
  const int d4 = orient(p1, p2, q2);
  if (d1 * d2 < 0 && d3 * d4 < 0) return Contact::Cross;
  if (d1 == 0 && d2 == 0) {  // collinear: disjoint, one shared point, or overlapping
    const bool p1in = withinBox(q1, q2, p1);
    const bool p2in = withinBox(q1, q2, p2);
    const bool q1in = withinBox(p1, p2, q1);
    const bool q2in = withinBox(p1, p2, q2);
    const int inside = int{p1in} + int{p2in} + int{q1in} + int{q2in};
    if (inside == 0) return Contact::None;
    // Sharing exactly one endpoint and nothing else: a touch; any longer common stretch: overlap.
    const bool oneSharedEnd = inside == 2 && ((p1 == q1 || p1 == q2) != (p2 == q1 || p2 == q2));
    return oneSharedEnd ? Contact::Touch : Contact::Overlap;
  }
  if ((d1 == 0 && withinBox(q1, q2, p1)) || (d2 == 0 && withinBox(q1, q2, p2)) || (d3 == 0 && withinBox(p1, p2, q1)) ||
      (d4 == 0 && withinBox(p1, p2, q2)))
    return Contact::Touch;
  return Contact::None;
}

struct Segment {
  IPoint a;
  IPoint b;
  std::uint32_t ring;
  std::uint32_t index;  ///< index of `a` in its ring
  std::uint32_t ringSize;
};

bool adjacent(const Segment& s, const Segment& t) {
  if (s.ring != t.ring) return false;
  const std::uint32_t m = s.ringSize;
  return (s.index + 1) % m == t.index || (t.index + 1) % m == s.index;
}

/// Per-thread working memory of cleanPolygon: footprints are cleaned by the million, and a few
/// reused buffers beat a dozen allocations per footprint.
struct Scratch {
  std::vector<glm::dvec2> ring;    ///< the ring being cleaned
  std::vector<glm::dvec2> points;  ///< the kept rings, flat
  std::vector<std::uint32_t> ends;
  std::vector<IPoint> snapped;  ///< `points` snapped to millimetres
  std::vector<Segment> segments;
  std::vector<const Segment*> open;
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

/// Whether the rings are a valid polygon: no ring crosses or touches itself, no two rings cross or
/// share a stretch of boundary (touching in one point is allowed between rings, as in OGC simple
/// features). A sweep along x: segments sorted by their left end, each compared with the ones
/// still open.
bool ringsIntersect(const std::vector<IPoint>& points, const std::vector<std::uint32_t>& ends, Scratch& work) {
  std::vector<Segment>& segments = work.segments;
  segments.clear();
  std::uint32_t start = 0;
  for (std::uint32_t r = 0; r < ends.size(); ++r) {
    const std::uint32_t m = ends[r] - start;
    for (std::uint32_t i = 0; i < m; ++i) segments.push_back({points[start + i], points[start + (i + 1) % m], r, i, m});
    start = ends[r];
  }
  auto minX = [](const Segment& s) { return std::min(s.a.x, s.b.x); };
  auto maxX = [](const Segment& s) { return std::max(s.a.x, s.b.x); };
  std::sort(segments.begin(), segments.end(), [&](const Segment& s, const Segment& t) { return minX(s) < minX(t); });
  std::vector<const Segment*>& open = work.open;
  open.clear();
  for (const Segment& s : segments) {
    const std::int64_t left = minX(s);
    std::erase_if(open, [&](const Segment* t) { return maxX(*t) < left; });
    const std::int64_t sMinY = std::min(s.a.y, s.b.y);
    const std::int64_t sMaxY = std::max(s.a.y, s.b.y);
    for (const Segment* t : open) {
      if (std::max(t->a.y, t->b.y) < sMinY || std::min(t->a.y, t->b.y) > sMaxY) continue;
      if (adjacent(s, *t)) continue;
      const Contact contact = segmentContact(s.a, s.b, t->a, t->b);
      if (contact == Contact::None) continue;
      if (s.ring == t->ring || contact != Contact::Touch) return true;
    }
    open.push_back(&s);
  }
  return false;
}

enum class Side : std::uint8_t { Inside, Outside, Boundary };

/// Exact point-in-ring (crossing number with the half-open rule on y).
Side sideOfRing(IPoint p, const IPoint* ring, std::size_t m) {
  bool inside = false;
  for (std::size_t i = 0, j = m - 1; i < m; j = i++) {
    const IPoint a = ring[j];
    const IPoint b = ring[i];
    if (orient(a, b, p) == 0 && withinBox(a, b, p)) return Side::Boundary;
    if ((a.y > p.y) != (b.y > p.y)) {
      // p is left of the upward (or right of the downward) edge: the ray to +x crosses it.
      const int o = orient(a, b, p);
      if ((b.y > a.y) ? o > 0 : o < 0) inside = !inside;
    }
  }
  return inside ? Side::Inside : Side::Outside;
}

}  // namespace

double signedRingArea(const glm::dvec2* points, std::size_t count) {
  if (count < 3) return 0.0;
  // Shoelace relative to the first point: keeps precision for coordinates far from the origin.
  const glm::dvec2 o = points[0];
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < count; ++i) twice += cross(points[i] - o, points[i + 1] - o);
  return 0.5 * twice;
}

std::string cleanPolygon(std::vector<glm::dvec2>& points, std::vector<std::uint32_t>& ringEnds, DropCounts* ringDrops,
                         const CleanOptions& options) {
  if (ringEnds.empty() || points.empty()) return std::string(drop::kTooFewPoints);
  for (const glm::dvec2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::string(drop::kInvalidCoordinates);
  }
  Scratch& work = scratch();
  work.points.clear();
  work.ends.clear();
  auto takeRing = [&](std::size_t r) {
    const std::uint32_t begin = r == 0 ? 0 : ringEnds[r - 1];
    assert(ringEnds[r] >= begin && ringEnds[r] <= points.size());
    work.ring.assign(points.begin() + begin, points.begin() + ringEnds[r]);
    cleanRing(work.ring, options);
  };
  auto keepRing = [&] {
    work.points.insert(work.points.end(), work.ring.begin(), work.ring.end());
    work.ends.push_back(static_cast<std::uint32_t>(work.points.size()));
  };

  // The outer ring decides whether the polygon is kept.
  takeRing(0);
  if (work.ring.size() < 3) return std::string(drop::kTooFewPoints);
  const Box outerBox = ringBox(work.ring);
  if (outerBox.maxX - outerBox.minX > options.maxExtentM || outerBox.maxY - outerBox.minY > options.maxExtentM)
    return std::string(drop::kTooLarge);
  keepRing();

  auto dropHole = [&](std::string_view reason) {
    if (ringDrops != nullptr) ringDrops->add(std::string(reason));
  };
  for (std::size_t r = 1; r < ringEnds.size(); ++r) {
    takeRing(r);
    if (work.ring.size() < 3) {
      dropHole(drop::kDegenerateHole);
      continue;
    }
    const double area = signedRingArea(work.ring.data(), work.ring.size());
    if (std::abs(area) < options.minAreaM2) {
      dropHole(drop::kDegenerateHole);
      continue;
    }
    if (!ringBox(work.ring).overlaps(outerBox)) {
      dropHole(drop::kHoleOutsideOuter);
      continue;
    }
    if (area > 0.0) std::reverse(work.ring.begin(), work.ring.end());
    keepRing();
  }

  // Exact topology checks on millimetre-snapped copies.
  const glm::dvec2 origin = work.points[0];
  work.snapped.clear();
  for (const glm::dvec2& p : work.points) {
    const double sx = std::round((p.x - origin.x) * kSnapPerMeter);
    const double sy = std::round((p.y - origin.y) * kSnapPerMeter);
    if (std::abs(sx) > static_cast<double>(kSnapLimit) || std::abs(sy) > static_cast<double>(kSnapLimit))
      return std::string(drop::kTooLarge);
    work.snapped.push_back({static_cast<std::int64_t>(sx), static_cast<std::int64_t>(sy)});
  }
  if (ringsIntersect(work.snapped, work.ends, work)) return std::string(drop::kSelfIntersecting);
  // After the intersection test: a bow-tie's lobes cancel to zero signed area but it is
  // self-intersecting, not empty.
  const std::uint32_t outerEnd = work.ends[0];
  const double outerArea = signedRingArea(work.points.data(), outerEnd);
  if (std::abs(outerArea) < options.minAreaM2) return std::string(drop::kZeroArea);
  // A sliver (a way drawn out and back along one line, 1 cm apart) encloses a few square
  // centimetres over a long perimeter: its mean width, 2 x area / perimeter, says it is no building.
  double perimeter = 0.0;
  for (std::uint32_t i = 0; i < outerEnd; ++i) perimeter += length(work.points[(i + 1) % outerEnd] - work.points[i]);
  if (2.0 * std::abs(outerArea) < options.minMeanWidthM * perimeter) return std::string(drop::kZeroArea);
  if (outerArea < 0.0) {
    std::reverse(work.points.begin(), work.points.begin() + outerEnd);
    std::reverse(work.snapped.begin(), work.snapped.begin() + outerEnd);
  }

  // A hole that crosses nothing is either inside the outer ring or wholly outside it.
  points.clear();
  ringEnds.clear();
  std::uint32_t start = 0;
  for (std::size_t r = 0; r < work.ends.size(); ++r) {
    const std::uint32_t end = work.ends[r];
    bool keep = true;
    if (r > 0) {
      Side side = Side::Boundary;
      for (std::uint32_t i = start; i < end && side == Side::Boundary; ++i)
        side = sideOfRing(work.snapped[i], work.snapped.data(), outerEnd);
      keep = side != Side::Outside;
      if (!keep) dropHole(drop::kHoleOutsideOuter);
    }
    if (keep) {
      points.insert(points.end(), work.points.begin() + start, work.points.begin() + end);
      ringEnds.push_back(static_cast<std::uint32_t>(points.size()));
    }
    start = end;
  }
  return {};
}

double polygonArea(const std::vector<glm::dvec2>& points, const std::vector<std::uint32_t>& ringEnds) {
  double area = 0.0;
  std::uint32_t start = 0;
  for (std::size_t r = 0; r < ringEnds.size(); ++r) {
    const double a = std::abs(signedRingArea(points.data() + start, ringEnds[r] - start));
    area += r == 0 ? a : -a;
    start = ringEnds[r];
  }
  return std::max(0.0, area);
}

glm::dvec2 polygonCentroid(const std::vector<glm::dvec2>& points, const std::vector<std::uint32_t>& ringEnds) {
  if (points.empty() || ringEnds.empty()) return {0.0, 0.0};
  const glm::dvec2 o = points[0];
  double areaSum = 0.0;
  glm::dvec2 moment{0.0, 0.0};
  std::uint32_t start = 0;
  for (std::size_t r = 0; r < ringEnds.size(); ++r) {
    const std::uint32_t end = ringEnds[r];
    const double ringSigned = signedRingArea(points.data() + start, end - start);
    // Outer rings add, holes subtract, whatever their stored winding.
    const double sign = (r == 0) == (ringSigned >= 0.0) ? 1.0 : -1.0;
    for (std::uint32_t i = start; i < end; ++i) {
      const glm::dvec2 a = points[i] - o;
      const glm::dvec2 b = points[i + 1 < end ? i + 1 : start] - o;
      const double c = cross(a, b) * sign;
      areaSum += c;
      moment += (a + b) * c;
    }
    start = end;
  }
  if (std::abs(areaSum) < 1e-12) {
    glm::dvec2 mean{0.0, 0.0};
    for (std::uint32_t i = 0; i < ringEnds[0]; ++i) mean += points[i];
    return mean / static_cast<double>(std::max<std::uint32_t>(1, ringEnds[0]));
  }
  return o + moment / (3.0 * areaSum);
}

bool pointInPolygon(glm::dvec2 p, const std::vector<glm::dvec2>& points, const std::vector<std::uint32_t>& ringEnds) {
  bool inside = false;
  std::uint32_t start = 0;
  for (const std::uint32_t end : ringEnds) {
    for (std::uint32_t i = start, j = end - 1; i < end; j = i++) {
      const glm::dvec2 a = points[j];
      const glm::dvec2 b = points[i];
      if ((a.y > p.y) != (b.y > p.y)) {
        const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
        if (p.x < x) inside = !inside;
      }
    }
    start = end;
  }
  return inside;
}

std::optional<glm::dvec2> interiorPoint(const std::vector<glm::dvec2>& points,
                                        const std::vector<std::uint32_t>& ringEnds) {
  if (ringEnds.empty() || ringEnds[0] < 3) return std::nullopt;
  // Scan line: halfway between the two vertex ordinates closest to the middle of the outer ring's
  // bounds, so that it passes through no vertex (JTS InteriorPointArea does the same).
  double minY = std::numeric_limits<double>::infinity();
  double maxY = -std::numeric_limits<double>::infinity();
  for (std::uint32_t i = 0; i < ringEnds[0]; ++i) {
    minY = std::min(minY, points[i].y);
    maxY = std::max(maxY, points[i].y);
  }
  const double centre = 0.5 * (minY + maxY);
  double below = minY;
  double above = maxY;
  for (const glm::dvec2& p : points) {
    if (p.y <= centre) below = std::max(below, p.y);
    if (p.y > centre) above = std::min(above, p.y);
  }
  const double y = 0.5 * (below + above);
  std::vector<double> xs;
  std::uint32_t start = 0;
  for (const std::uint32_t end : ringEnds) {
    for (std::uint32_t i = start, j = end - 1; i < end; j = i++) {
      const glm::dvec2 a = points[j];
      const glm::dvec2 b = points[i];
      if ((a.y > y) != (b.y > y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    start = end;
  }
  std::sort(xs.begin(), xs.end());
  double bestWidth = 0.0;
  std::optional<glm::dvec2> best;
  for (std::size_t i = 0; i + 1 < xs.size(); i += 2) {
    const double width = xs[i + 1] - xs[i];
    if (width > bestWidth) {
      bestWidth = width;
      best = glm::dvec2{0.5 * (xs[i] + xs[i + 1]), y};
    }
  }
  return best;
}

}  // namespace qv::prep
