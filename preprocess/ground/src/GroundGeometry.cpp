#include "GroundGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "qv/core/Text.h"
#include "qv/prep/DouglasPeucker.h"

namespace qv::prep::ground {
namespace {

double cross(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}

void removeConsecutiveDuplicates(Ring& ring) {
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
}

bool onSide(glm::dvec2 p, const Box2& box) {
  return p.x == box.minX || p.x == box.maxX || p.y == box.minY || p.y == box.maxY;
}

glm::dvec2 rotate(glm::dvec2 v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// Sutherland–Hodgman against one side. `side`: 0 x >= minX, 1 x <= maxX, 2 y >= minY, 3 y <= maxY.
// The crossing point takes the side's coordinate exactly (points on a side are recognised by it).
void clipAgainstSide(const Ring& in, const Box2& box, int side, Ring& out) {
  out.clear();
  const std::size_t n = in.size();
  if (n == 0) return;
  auto inside = [&](glm::dvec2 p) {
    switch (side) {
      case 0:
        return p.x >= box.minX;
      case 1:
        return p.x <= box.maxX;
      case 2:
        return p.y >= box.minY;
      default:
        return p.y <= box.maxY;
    }
  };
  auto crossing = [&](glm::dvec2 s, glm::dvec2 e) {
    if (side < 2) {
      const double x = side == 0 ? box.minX : box.maxX;
      const double t = (x - s.x) / (e.x - s.x);
      return glm::dvec2(x, s.y == e.y ? s.y : s.y + t * (e.y - s.y));
    }
    const double y = side == 2 ? box.minY : box.maxY;
    const double t = (y - s.y) / (e.y - s.y);
    return glm::dvec2(s.x == e.x ? s.x : s.x + t * (e.x - s.x), y);
  };
  glm::dvec2 s = in[n - 1];
  bool sInside = inside(s);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 e = in[i];
    const bool eInside = inside(e);
    if (eInside != sInside) out.push_back(crossing(s, e));
    if (eInside) out.push_back(e);
    s = e;
    sInside = eInside;
  }
}

}  // namespace

Box2 boundsOf(std::span<const glm::dvec2> points) {
  Box2 b{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
         std::numeric_limits<double>::lowest()};
  for (const glm::dvec2& p : points) {
    b.minX = std::min(b.minX, p.x);
    b.minY = std::min(b.minY, p.y);
    b.maxX = std::max(b.maxX, p.x);
    b.maxY = std::max(b.maxY, p.y);
  }
  return b;
}

void clipPolyline(std::span<const glm::dvec2> line, const Box2& box, std::vector<Polyline>& out) {
  Polyline current;
  auto flush = [&] {
    if (current.size() >= 2) out.push_back(std::move(current));
    current.clear();
  };
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const glm::dvec2 a = line[i], b = line[i + 1];
    if (a == b) continue;
    // Liang–Barsky: the part t in [t0, t1] of a + t (b - a) inside each of the four half-planes.
    const glm::dvec2 d = b - a;
    double t0 = 0.0, t1 = 1.0;
    auto clip = [&](double p, double q) {  // keeps p t <= q
      if (p == 0.0) return q >= 0.0;
      const double r = q / p;
      if (p < 0.0) {
        if (r > t1) return false;
        t0 = std::max(t0, r);
      } else {
        if (r < t0) return false;
        t1 = std::min(t1, r);
      }
      return true;
    };
    if (!(clip(-d.x, a.x - box.minX) && clip(d.x, box.maxX - a.x) && clip(-d.y, a.y - box.minY) &&
          clip(d.y, box.maxY - a.y))) {
      flush();
      continue;
    }
    auto clamp = [&box](glm::dvec2 p) {
      return glm::dvec2(std::clamp(p.x, box.minX, box.maxX), std::clamp(p.y, box.minY, box.maxY));
    };
    const glm::dvec2 p0 = t0 == 0.0 ? a : clamp(a + d * t0);
    const glm::dvec2 p1 = t1 == 1.0 ? b : clamp(a + d * t1);
    if (p0 == p1) continue;
    if (current.empty() || current.back() != p0) {
      flush();
      current.push_back(p0);
    }
    current.push_back(p1);
    if (t1 != 1.0) flush();  // the line leaves the box here
  }
  flush();
}

Ring clipRing(std::span<const glm::dvec2> ring, const Box2& box) {
  const Box2 b = boundsOf(ring);
  if (ring.size() < 3 || !box.intersects(b)) return {};
  Ring current(ring.begin(), ring.end());
  if (b.minX < box.minX || b.maxX > box.maxX || b.minY < box.minY || b.maxY > box.maxY) {
    Ring next;
    for (int side = 0; side < 4 && !current.empty(); ++side) {
      clipAgainstSide(current, box, side, next);
      current.swap(next);
    }
  }
  removeConsecutiveDuplicates(current);
  if (current.size() < 3) return {};
  return current;
}

Polyline simplifyPolyline(std::span<const glm::dvec2> line, double toleranceM) {
  if (line.size() <= 2 || !(toleranceM > 0.0)) return {line.begin(), line.end()};
  std::vector<bool> keep(line.size(), false);
  keep.front() = keep.back() = true;
  douglasPeucker(line, 0, line.size() - 1, toleranceM, keep);
  Polyline out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (keep[i]) out.push_back(line[i]);
  }
  return out;
}

Ring simplifyClippedRing(std::span<const glm::dvec2> ring, const Box2& box, double toleranceM) {
  const std::size_t n = ring.size();
  if (n < 3) return {};
  if (!(toleranceM > 0.0) || n <= 4) return {ring.begin(), ring.end()};
  std::vector<std::size_t> anchors;
  for (std::size_t i = 0; i < n; ++i) {
    if (onSide(ring[i], box)) anchors.push_back(i);
  }
  if (anchors.size() < 2) {
    // A ring inside the cell (or touching it once): the classic ring split, at a point and the
    // point farthest from it.
    const std::size_t start = anchors.empty() ? 0 : anchors[0];
    std::size_t far = start;
    double farthest = -1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 d = ring[i] - ring[start];
      if (d.x * d.x + d.y * d.y > farthest) {
        farthest = d.x * d.x + d.y * d.y;
        far = i;
      }
    }
    anchors = {std::min(start, far), std::max(start, far)};
    if (anchors[0] == anchors[1]) return {ring.begin(), ring.end()};
  }
  // The ring rotated to start at the first anchor and closed again, so every chain between two
  // consecutive anchors is a contiguous range.
  Ring closed;
  closed.reserve(n + 1);
  for (std::size_t i = 0; i <= n; ++i) closed.push_back(ring[(anchors[0] + i) % n]);
  std::vector<bool> keep(n + 1, false);
  for (std::size_t k = 0; k < anchors.size(); ++k) {
    const std::size_t a = anchors[k] - anchors[0];
    const std::size_t b = k + 1 < anchors.size() ? anchors[k + 1] - anchors[0] : n;
    keep[a] = keep[b] = true;
    douglasPeucker(closed, a, b, toleranceM, keep);
  }
  Ring out;
  for (std::size_t i = 0; i < n; ++i) {
    if (keep[i]) out.push_back(closed[i]);
  }
  if (out.size() < 3) return {};
  return out;
}

void appendRibbon(std::span<const glm::dvec2> line, double halfWidthM, Mesh& out) {
  Polyline pts;
  pts.reserve(line.size());
  for (const glm::dvec2& p : line) {
    if (pts.empty() || pts.back() != p) pts.push_back(p);
  }
  if (pts.size() < 2 || !(halfWidthM > 0.0)) return;
  auto vertex = [&out](glm::dvec2 p) {
    out.vertices.push_back(p);
    return static_cast<std::uint32_t>(out.vertices.size() - 1);
  };
  auto triangle = [&out](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const double turn = cross(out.vertices[b] - out.vertices[a], out.vertices[c] - out.vertices[a]);
    if (turn > 0.0) out.triangles.insert(out.triangles.end(), {a, b, c});
    if (turn < 0.0) out.triangles.insert(out.triangles.end(), {a, c, b});
  };
  // A fan around `centre` from centre + start, turning by `angle` (signed) in `steps`.
  auto fan = [&](glm::dvec2 centre, glm::dvec2 start, double angle, int steps) {
    const std::uint32_t c = vertex(centre);
    std::uint32_t previous = vertex(centre + start);
    for (int k = 1; k <= steps; ++k) {
      const std::uint32_t next = vertex(centre + rotate(start, angle * k / steps));
      triangle(c, previous, next);
      previous = next;
    }
  };
  constexpr double kQuarterPi = std::numbers::pi / 4.0;
  std::vector<glm::dvec2> normals(pts.size() - 1);
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const glm::dvec2 d = pts[i + 1] - pts[i];
    const double len = std::sqrt(d.x * d.x + d.y * d.y);
    normals[i] = glm::dvec2(-d.y, d.x) * (halfWidthM / len);
    const std::uint32_t v0 = vertex(pts[i] - normals[i]), v1 = vertex(pts[i + 1] - normals[i]);
    const std::uint32_t v2 = vertex(pts[i + 1] + normals[i]), v3 = vertex(pts[i] + normals[i]);
    triangle(v0, v1, v2);
    triangle(v0, v2, v3);
  }
  // Bends: the wedge between the two quads on the outer side (the inner sides overlap).
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const glm::dvec2 n0 = normals[i - 1], n1 = normals[i];
    const double turn = std::atan2(cross(n0, n1), n0.x * n1.x + n0.y * n1.y);  // left turn > 0
    if (std::abs(turn) < 1e-6) continue;
    const int steps = std::clamp(static_cast<int>(std::ceil(std::abs(turn) / kQuarterPi)), 1, 4);
    fan(pts[i], turn > 0.0 ? -n0 : n0, turn, steps);
  }
  // Ends: half-discs behind the first point and beyond the last.
  fan(pts.front(), normals.front(), std::numbers::pi, 4);
  fan(pts.back(), -normals.back(), std::numbers::pi, 4);
}

void clipMesh(const Mesh& mesh, const Box2& box, Mesh& out) {
  constexpr double kMinAreaM2 = 1e-9;
  std::vector<std::uint32_t> kept(mesh.vertices.size(), std::numeric_limits<std::uint32_t>::max());
  auto keep = [&](std::uint32_t i) {
    if (kept[i] == std::numeric_limits<std::uint32_t>::max()) {
      kept[i] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(mesh.vertices[i]);
    }
    return kept[i];
  };
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const std::uint32_t ia = mesh.triangles[t], ib = mesh.triangles[t + 1], ic = mesh.triangles[t + 2];
    const glm::dvec2 a = mesh.vertices[ia], b = mesh.vertices[ib], c = mesh.vertices[ic];
    if (box.contains(a) && box.contains(b) && box.contains(c)) {
      out.triangles.insert(out.triangles.end(), {keep(ia), keep(ib), keep(ic)});
      continue;
    }
    const glm::dvec2 corners[3] = {a, b, c};
    const Ring piece = clipRing(corners, box);
    if (piece.size() < 3 || signedArea(piece) < kMinAreaM2) continue;
    const auto first = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), piece.begin(), piece.end());
    for (std::uint32_t k = 1; k + 1 < piece.size(); ++k) {
      if (cross(piece[k] - piece[0], piece[k + 1] - piece[0]) <= 0.0) continue;
      out.triangles.insert(out.triangles.end(), {first, first + k, first + k + 1});
    }
  }
}

double signedArea(std::span<const glm::dvec2> ring) {
  if (ring.size() < 3) return 0.0;
  // Relative to the first point: city coordinates of tens of kilometres would cancel otherwise.
  const glm::dvec2 o = ring[0];
  double a = 0.0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) a += cross(ring[i] - o, ring[i + 1] - o);
  return 0.5 * a;
}

bool insideEvenOdd(glm::dvec2 p, std::span<const Ring> rings) {
  bool inside = false;
  for (const Ring& ring : rings) {
    const std::size_t n = ring.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const glm::dvec2 a = ring[i], b = ring[j];
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
    }
  }
  return inside;
}

std::optional<Stretch> longestStretch(std::span<const Polyline> pieces) {
  constexpr double kStraightRad = 20.0 * std::numbers::pi / 180.0;
  std::optional<Stretch> best;
  for (const Polyline& piece : pieces) {
    // The piece without repeated points, and each segment's direction and length.
    Polyline pts;
    for (const glm::dvec2& p : piece) {
      if (pts.empty() || pts.back() != p) pts.push_back(p);
    }
    if (pts.size() < 2) continue;
    const std::size_t segments = pts.size() - 1;
    std::vector<double> direction(segments), length(segments);
    for (std::size_t i = 0; i < segments; ++i) {
      const glm::dvec2 d = pts[i + 1] - pts[i];
      direction[i] = std::atan2(d.y, d.x);
      length[i] = std::sqrt(d.x * d.x + d.y * d.y);
    }
    for (std::size_t i = 0; i < segments;) {
      std::size_t j = i + 1;
      double total = length[i];
      while (j < segments &&
             std::abs(std::remainder(direction[j] - direction[i], 2.0 * std::numbers::pi)) <= kStraightRad) {
        total += length[j];
        ++j;
      }
      if (!best || total > best->lengthM) {
        // The point halfway along segments [i, j).
        double remaining = 0.5 * total;
        std::size_t k = i;
        while (k + 1 < j && remaining > length[k]) remaining -= length[k++];
        const double t = length[k] > 0.0 ? std::clamp(remaining / length[k], 0.0, 1.0) : 0.0;
        const glm::dvec2 chord = pts[j] - pts[i];
        best = Stretch{pts[k] + (pts[k + 1] - pts[k]) * t, textAngle(chord.x, chord.y), total};
      }
      i = j;
    }
  }
  return best;
}

float textAngle(double dx, double dy) {
  constexpr double kHalfPi = std::numbers::pi / 2.0;
  double a = std::atan2(dy, dx);
  if (a > kHalfPi) a -= std::numbers::pi;
  if (a <= -kHalfPi) a += std::numbers::pi;
  // In float, -pi/2 rounds to -float(pi/2), which the range excludes: it reads the same as +pi/2.
  const float halfPi = static_cast<float>(kHalfPi);
  float f = static_cast<float>(a);
  if (!(f > -halfPi) || f > halfPi) f = halfPi;
  return f;
}

std::string cleanLabelText(std::string_view text) {
  constexpr std::size_t kMaxBytes = 255;
  const std::string valid = toValidUtf8(text);
  std::string out;
  out.reserve(valid.size());
  for (std::size_t i = 0; i < valid.size();) {
    const auto b = static_cast<unsigned char>(valid[i]);
    const std::size_t len = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : 4;
    if (b < 0x20 || b == 0x7F) {
      if (b == '\t' || b == '\n' || b == '\r' || b == '\v' || b == '\f') out += ' ';
      ++i;
      continue;
    }
    // C1 controls U+0080..U+009F are 0xC2 0x80..0x9F in UTF-8.
    if (b == 0xC2 && i + 1 < valid.size() && static_cast<unsigned char>(valid[i + 1]) <= 0x9F) {
      i += 2;
      continue;
    }
    out.append(valid, i, len);
    i += len;
  }
  auto trim = [&out] {
    const std::size_t first = out.find_first_not_of(' ');
    if (first == std::string::npos) {
      out.clear();
      return;
    }
    out.erase(0, first);
    out.erase(out.find_last_not_of(' ') + 1);
  };
  trim();
  if (out.size() > kMaxBytes) {
    std::size_t cut = kMaxBytes;
    while (cut > 0 && (static_cast<unsigned char>(out[cut]) & 0xC0) == 0x80) --cut;
    out.resize(cut);
    trim();
  }
  return out;
}

}  // namespace qv::prep::ground
