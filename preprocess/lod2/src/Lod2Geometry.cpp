// The CGAL translation unit of prep::lod2 (compiled without the conversion warnings CGAL's headers
// do not pass, see CMakeLists.txt). Every CGAL call is inside a try block: CGAL reports
// precondition failures and crossing constraints by throwing.
#include "qv/prep/Lod2Geometry.h"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <list>
#include <map>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "qv/prep/CdtDomains.h"
#include "qv/prep/Cleaning.h"
#include "qv/prep/Lod2Remesh.h"

namespace qv::prep {
namespace {

// ---- Constrained Delaunay triangulation of one face, in its plane -------------------------------
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;  // markNesting's depth: odd inside
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Epick>;
using FaceBase0 = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Epick>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Epick, FaceBase0>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Constraints that overlap along a stretch are allowed (no new points needed); constraints that
// cross would need new points off the face's vertex list and throw: such faces are reported.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Epick, Tds,
                                                       CGAL::No_constraint_intersection_requiring_constructions_tag>;

// ---- Boolean operations on footprints (exact constructions: intersection points are new) --------
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPolygon = CGAL::Polygon_2<Epeck>;
using ExactPolygonWithHoles = CGAL::Polygon_with_holes_2<Epeck>;

/// A simple counter-clockwise polygon from a ring, or false when the ring is degenerate or not simple.
bool makeExactPolygon(const std::vector<glm::dvec2>& ring, ExactPolygon& out) {
  std::vector<glm::dvec2> points;
  points.reserve(ring.size());
  for (const glm::dvec2& p : ring) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
    if (points.empty() || points.back() != p) points.push_back(p);
  }
  while (points.size() > 1 && points.back() == points.front()) points.pop_back();
  if (points.size() < 3) return false;
  ExactPolygon polygon;
  for (const glm::dvec2& p : points) polygon.push_back(Epeck::Point_2(p.x, p.y));
  if (!polygon.is_simple()) return false;
  const CGAL::Orientation orientation = polygon.orientation();
  if (orientation == CGAL::COLLINEAR) return false;
  if (orientation == CGAL::CLOCKWISE) polygon.reverse_orientation();
  out = polygon;  // CGAL 5.5 Polygon_2 copies: it has no move assignment
  return true;
}

std::vector<glm::dvec2> toRing(const ExactPolygon& polygon) {
  std::vector<glm::dvec2> ring;
  ring.reserve(polygon.size());
  for (auto it = polygon.vertices_begin(); it != polygon.vertices_end(); ++it) {
    ring.emplace_back(CGAL::to_double(it->x()), CGAL::to_double(it->y()));
  }
  return ring;
}

/// The cleaned outer ring of the largest piece of a union of counter-clockwise polygons.
std::vector<glm::dvec2> largestOuterRing(const std::vector<ExactPolygon>& polygons) {
  CGAL::Polygon_set_2<Epeck> set;
  set.join(polygons.begin(), polygons.end());
  std::vector<ExactPolygonWithHoles> pieces;
  set.polygons_with_holes(std::back_inserter(pieces));
  const ExactPolygonWithHoles* best = nullptr;
  double bestArea = 0.0;
  for (const ExactPolygonWithHoles& piece : pieces) {
    if (piece.is_unbounded()) continue;
    const double area = std::abs(CGAL::to_double(piece.outer_boundary().area()));
    if (area > bestArea) {
      bestArea = area;
      best = &piece;
    }
  }
  if (best == nullptr) return {};
  std::vector<glm::dvec2> ring = toRing(best->outer_boundary());
  // The union's boundary keeps every triangle corner it passes: clean collinear points with the
  // footprint rules of docs/attributes.md (1 mm).
  std::vector<glm::dvec2> cleaned = ring;
  std::vector<std::uint32_t> ringEnds{static_cast<std::uint32_t>(cleaned.size())};
  if (cleanPolygon(cleaned, ringEnds).empty() && ringEnds.size() == 1) return cleaned;
  if (signedRingArea(ring.data(), ring.size()) < 0.0) std::reverse(ring.begin(), ring.end());
  return ring;
}

double cross2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
}

using ProjectedTriangle = std::array<std::uint32_t, 3>;

ExactPolygon exactTriangle(const std::vector<glm::dvec2>& points, const ProjectedTriangle& t) {
  ExactPolygon triangle;
  for (std::uint32_t v : t) triangle.push_back(Epeck::Point_2(points[v].x, points[v].y));
  return triangle;
}

/// Adds the outlines of counter-clockwise projected triangles to a union: triangles joined by
/// consistently oriented shared edges form components (a roof plane, a whole roof) whose outer
/// boundary loops go to the union instead of their triangles, which makes the exact union far
/// cheaper. A component whose loops do not close or are not simple (a surface that folds over
/// itself in projection) adds its triangles instead, so the union stays exact.
void appendComponentOutlines(const std::vector<glm::dvec2>& points, const std::vector<ProjectedTriangle>& triangles,
                             std::vector<ExactPolygon>& out) {
  const auto key = [](std::uint32_t a, std::uint32_t b) { return (static_cast<std::uint64_t>(a) << 32) | b; };
  // Union-find over triangles across edges used once in each direction.
  std::vector<std::size_t> parent(triangles.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::unordered_map<std::uint64_t, std::size_t> directed;  // directed edge -> triangle
  std::unordered_map<std::uint64_t, int> uses;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t k = key(triangles[t][i], triangles[t][(i + 1) % 3]);
      directed.emplace(k, t);
      ++uses[k];
    }
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = triangles[t][i];
      const std::uint32_t b = triangles[t][(i + 1) % 3];
      const auto reverse = directed.find(key(b, a));
      if (reverse == directed.end() || uses[key(a, b)] != 1 || uses[key(b, a)] != 1) continue;
      parent[find(t)] = find(reverse->second);
    }
  }
  // Ordered maps: the same input gives the same loops in the same order on every platform.
  std::map<std::size_t, std::vector<std::size_t>> components;
  for (std::size_t t = 0; t < triangles.size(); ++t) components[find(t)].push_back(t);

  for (const auto& [root, members] : components) {
    // Boundary edges: directed edges of the component whose reverse is not in it.
    std::map<std::uint32_t, std::vector<std::uint32_t>> next;  // start -> ends
    std::size_t boundaryEdges = 0;
    for (std::size_t t : members) {
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t a = triangles[t][i];
        const std::uint32_t b = triangles[t][(i + 1) % 3];
        const auto reverse = directed.find(key(b, a));
        if (reverse != directed.end() && find(reverse->second) == root) continue;
        next[a].push_back(b);
        ++boundaryEdges;
      }
    }
    bool ok = true;
    std::vector<ExactPolygon> loops;
    std::size_t walked = 0;
    while (ok && walked < boundaryEdges) {
      auto start = next.begin();
      while (start != next.end() && start->second.empty()) ++start;
      if (start == next.end()) break;
      std::vector<glm::dvec2> ring;
      const std::uint32_t first = start->first;
      std::uint32_t at = first;
      do {
        std::vector<std::uint32_t>& ends = next[at];
        if (ends.empty() || ring.size() > boundaryEdges) {
          ok = false;  // an open chain: not a closed surface in projection
          break;
        }
        ring.push_back(points[at]);
        at = ends.back();
        ends.pop_back();
        ++walked;
      } while (at != first);
      if (!ok) break;
      if (signedRingArea(ring.data(), ring.size()) <= 0.0) continue;  // a hole: inside its outer loop
      ExactPolygon polygon;
      if (!makeExactPolygon(ring, polygon)) {
        ok = false;
        break;
      }
      loops.push_back(std::move(polygon));
    }
    if (ok && !loops.empty()) {
      for (ExactPolygon& loop : loops) out.push_back(std::move(loop));
    } else {
      for (std::size_t t : members) out.push_back(exactTriangle(points, triangles[t]));
    }
  }
}

}  // namespace

glm::dvec3 newellNormal(std::span<const glm::dvec3> ring) {
  glm::dvec3 n(0.0);
  if (ring.size() < 3) return n;
  // Relative to the first point: CityJSON coordinates are large (2.6e6 m in LV95).
  const glm::dvec3 origin = ring[0];
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec3 a = ring[i] - origin;
    const glm::dvec3 b = ring[(i + 1) % ring.size()] - origin;
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

bool triangulateFace(std::span<const glm::dvec3> points, std::span<const std::uint32_t> ringEnds,
                     std::vector<std::uint32_t>& out) {
  if (ringEnds.empty() || ringEnds.back() > points.size()) return false;
  const std::uint32_t outerEnd = ringEnds[0];
  if (outerEnd < 3) return false;
  glm::dvec3 normal = newellNormal(points.first(outerEnd));
  const double length = glm::length(normal);
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  normal /= length;
  if (ringEnds.size() == 1 && outerEnd == 3) {
    out.insert(out.end(), {0u, 1u, 2u});
    return true;
  }
  // An orthonormal basis (u, v) of the face's plane with u × v = normal, so counter-clockwise in
  // (u, v) is the face's own orientation.
  const glm::dvec3 u = glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(glm::dvec3(1.0, 0.0, 0.0), normal)
                                                               : glm::cross(glm::dvec3(0.0, 1.0, 0.0), normal));
  const glm::dvec3 v = glm::cross(normal, u);
  const glm::dvec3 origin = points[0];
  try {
    Cdt cdt;
    std::uint32_t begin = 0;
    for (std::uint32_t end : ringEnds) {
      if (end < begin + 3) {  // a degenerate hole adds nothing
        begin = end;
        continue;
      }
      std::vector<Cdt::Vertex_handle> ring;
      ring.reserve(end - begin);
      for (std::uint32_t i = begin; i < end; ++i) {
        const glm::dvec3 d = points[i] - origin;
        const std::size_t before = cdt.number_of_vertices();
        Cdt::Vertex_handle handle = cdt.insert(Epick::Point_2(glm::dot(d, u), glm::dot(d, v)));
        if (cdt.number_of_vertices() > before) handle->info() = i;  // a repeated point keeps its first index
        ring.push_back(handle);
      }
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Cdt::Vertex_handle& a = ring[i];
        const Cdt::Vertex_handle& b = ring[(i + 1) % ring.size()];
        if (a != b) cdt.insert_constraint(a, b);
      }
      begin = end;
    }
    markNesting(cdt);
    std::vector<std::uint32_t> triangles;
    appendInsideTriangles(cdt, triangles);
    if (triangles.empty()) return false;
    out.insert(out.end(), triangles.begin(), triangles.end());
    return true;
  } catch (...) {
    return false;  // crossing rings or a CGAL precondition: the caller counts the face as skipped
  }
}

std::vector<glm::dvec2> groundFootprint(const Lod2Mesh& mesh) {
  // Parts imported separately repeat their shared corners: weld them so roofs connect.
  const Lod2Mesh welded = weldVertices(mesh);
  std::vector<glm::dvec2> points;
  points.reserve(welded.positions.size());
  for (const glm::dvec3& p : welded.positions) points.emplace_back(p.x, p.y);
  try {
    // Faces looking up and faces looking down, each made counter-clockwise in projection; walls
    // (and slivers under 1 mm²) project to nothing.
    std::vector<ProjectedTriangle> up;
    std::vector<ProjectedTriangle> down;
    for (std::size_t t = 0; t + 2 < welded.triangles.size(); t += 3) {
      const std::uint32_t a = welded.triangles[t];
      const std::uint32_t b = welded.triangles[t + 1];
      const std::uint32_t c = welded.triangles[t + 2];
      const double twiceArea = cross2(points[a], points[b], points[c]);
      if (std::abs(twiceArea) < 2e-6) continue;
      if (twiceArea > 0.0)
        up.push_back({a, b, c});
      else
        down.push_back({a, c, b});
    }
    std::vector<ExactPolygon> polygons;
    appendComponentOutlines(points, up, polygons);
    appendComponentOutlines(points, down, polygons);
    if (polygons.empty()) return {};
    std::vector<glm::dvec2> ring = largestOuterRing(polygons);
    if (ring.size() >= 3) return ring;
  } catch (...) {
    // fall through to the convex hull
  }
  return convexHull(std::move(points));
}

std::vector<glm::dvec2> unionOuterRing(const std::vector<std::vector<glm::dvec2>>& rings) {
  std::vector<glm::dvec2> all;
  try {
    std::vector<ExactPolygon> polygons;
    for (const std::vector<glm::dvec2>& ring : rings) {
      all.insert(all.end(), ring.begin(), ring.end());
      ExactPolygon polygon;
      if (makeExactPolygon(ring, polygon)) polygons.push_back(std::move(polygon));
    }
    if (polygons.size() == 1) {
      std::vector<glm::dvec2> ring = toRing(polygons.front());
      return ring;
    }
    if (!polygons.empty()) {
      std::vector<glm::dvec2> ring = largestOuterRing(polygons);
      if (ring.size() >= 3) return ring;
    }
  } catch (...) {
    // fall through to the convex hull
  }
  return convexHull(std::move(all));
}

double intersectionAreaM2(const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b) {
  try {
    ExactPolygon pa;
    ExactPolygon pb;
    if (!makeExactPolygon(a, pa) || !makeExactPolygon(b, pb)) return 0.0;
    std::list<ExactPolygonWithHoles> pieces;
    CGAL::intersection(pa, pb, std::back_inserter(pieces));
    double area = 0.0;
    for (const ExactPolygonWithHoles& piece : pieces) {
      area += std::abs(CGAL::to_double(piece.outer_boundary().area()));
      for (auto hole = piece.holes_begin(); hole != piece.holes_end(); ++hole) {
        area -= std::abs(CGAL::to_double(hole->area()));
      }
    }
    return std::max(area, 0.0);
  } catch (...) {
    return 0.0;
  }
}

std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> points) {
  std::sort(points.begin(), points.end(),
            [](const glm::dvec2& p, const glm::dvec2& q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  const auto cross = [](const glm::dvec2& o, const glm::dvec2& p, const glm::dvec2& q) {
    return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x);
  };
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (const glm::dvec2& p : points) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace qv::prep
