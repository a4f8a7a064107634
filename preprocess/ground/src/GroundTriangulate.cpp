// triangulateEvenOdd (GroundGeometry.h): the one translation unit of prep::ground that includes CGAL.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <exception>
#include <limits>
#include <utility>
#include <vector>

#include "GroundGeometry.h"
#include "qv/prep/CdtDomains.h"

namespace qv::prep::ground {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;  // markNesting's depth: odd inside
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase0 = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBase0>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact predicates with intersections: map data crosses itself (broken multipolygons, and the
// simplification of inner levels may fold a thin shape), and the crossing points become vertices,
// so that the nesting is the even-odd rule of the arrangement instead of an exception.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

struct Segment {
  glm::dvec2 a, b;
};

// +1 / -1 when the ring is a strictly convex simple polygon (counter-clockwise / clockwise), else
// 0 (as in prep::tiling's Triangulate.cpp): every turn has the same sign and the edge directions
// go round once (x and y of the edges each change sign at most twice).
int convexWinding(std::span<const glm::dvec2> ring) {
  const std::size_t n = ring.size();
  if (n < 3) return 0;
  int turn = 0, xChanges = 0, yChanges = 0, lastX = 0, lastY = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 a = ring[i], b = ring[(i + 1) % n], c = ring[(i + 2) % n];
    const double cross = (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x);
    const int sign = cross > 0.0 ? 1 : cross < 0.0 ? -1 : 0;
    if (sign == 0 || (turn != 0 && sign != turn)) return 0;
    turn = sign;
    const int sx = b.x > a.x ? 1 : b.x < a.x ? -1 : 0;
    const int sy = b.y > a.y ? 1 : b.y < a.y ? -1 : 0;
    if (sx != 0) {
      if (lastX != 0 && sx != lastX) ++xChanges;
      lastX = sx;
    }
    if (sy != 0) {
      if (lastY != 0 && sy != lastY) ++yChanges;
      lastY = sy;
    }
  }
  return xChanges <= 2 && yChanges <= 2 ? turn : 0;
}

// The parts of a line covered an odd number of times by `intervals` ([lo, hi] along it): a point's
// coverage parity is the parity of the interval ends before it.
std::vector<std::pair<double, double>> oddCoverage(std::vector<std::pair<double, double>>& intervals) {
  std::vector<double> ends;
  ends.reserve(2 * intervals.size());
  for (const auto& [lo, hi] : intervals) ends.insert(ends.end(), {lo, hi});
  std::sort(ends.begin(), ends.end());
  std::vector<std::pair<double, double>> odd;
  bool inside = false;
  double start = 0.0;
  for (std::size_t i = 0; i < ends.size();) {
    std::size_t j = i;
    while (j < ends.size() && ends[j] == ends[i]) ++j;
    if ((j - i) % 2 == 1) {
      if (!inside) {
        start = ends[i];
      } else if (ends[i] > start) {
        odd.emplace_back(start, ends[i]);
      }
      inside = !inside;
    }
    i = j;
  }
  return odd;
}

}  // namespace

bool triangulateEvenOdd(std::span<const Ring> rings, const Box2& box, bool addBoxSides, Mesh& out) {
  // A convex ring alone (a rectangle, the whole cell) is its own fan.
  if (!addBoxSides && rings.size() == 1) {
    const int winding = convexWinding(rings[0]);
    if (winding != 0) {
      const auto first = static_cast<std::uint32_t>(out.vertices.size());
      const auto n = static_cast<std::uint32_t>(rings[0].size());
      out.vertices.insert(out.vertices.end(), rings[0].begin(), rings[0].end());
      for (std::uint32_t i = 1; i + 1 < n; ++i) {
        if (winding > 0) {
          out.triangles.insert(out.triangles.end(), {first, first + i, first + i + 1});
        } else {
          out.triangles.insert(out.triangles.end(), {first, first + i + 1, first + i});
        }
      }
      return true;
    }
  }

  // 1. The edges: those on a side of the box as intervals along it (summed modulo 2 below), the
  //    others as segments, in ring order (neighbours are close: cheap point location).
  std::array<std::vector<std::pair<double, double>>, 4> sides;  // x = minX, x = maxX (along y), y = minY, y = maxY
  std::vector<Segment> segments;
  for (const Ring& ring : rings) {
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
      const glm::dvec2 p = ring[i], q = ring[(i + 1) % n];
      if (p == q) continue;
      if (p.x == q.x && (p.x == box.minX || p.x == box.maxX)) {
        sides[p.x == box.minX ? 0 : 1].emplace_back(std::min(p.y, q.y), std::max(p.y, q.y));
      } else if (p.y == q.y && (p.y == box.minY || p.y == box.maxY)) {
        sides[p.y == box.minY ? 2 : 3].emplace_back(std::min(p.x, q.x), std::max(p.x, q.x));
      } else {
        segments.push_back({p, q});
      }
    }
  }
  if (addBoxSides) {
    sides[0].emplace_back(box.minY, box.maxY);
    sides[1].emplace_back(box.minY, box.maxY);
    sides[2].emplace_back(box.minX, box.maxX);
    sides[3].emplace_back(box.minX, box.maxX);
  }
  // The same segment twice (a shared edge of two rings) bounds nothing: both copies go.
  {
    auto key = [&segments](std::size_t i) {
      const Segment& s = segments[i];
      const bool forward = s.a.x < s.b.x || (s.a.x == s.b.x && s.a.y < s.b.y);
      const glm::dvec2 lo = forward ? s.a : s.b, hi = forward ? s.b : s.a;
      return std::array<double, 4>{lo.x, lo.y, hi.x, hi.y};
    };
    std::vector<std::size_t> order(segments.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    std::vector<bool> drop(segments.size(), false);
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i;
      while (j < order.size() && key(order[j]) == key(order[i])) ++j;
      for (std::size_t k = i; k < j - (j - i) % 2; ++k) drop[order[k]] = true;
      i = j;
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < segments.size(); ++i) {
      if (!drop[i]) segments[kept++] = segments[i];
    }
    segments.resize(kept);
  }
  for (int side = 0; side < 4; ++side) {
    for (const auto& [lo, hi] : oddCoverage(sides[side])) {
      switch (side) {
        case 0:
          segments.push_back({{box.minX, lo}, {box.minX, hi}});
          break;
        case 1:
          segments.push_back({{box.maxX, lo}, {box.maxX, hi}});
          break;
        case 2:
          segments.push_back({{lo, box.minY}, {hi, box.minY}});
          break;
        default:
          segments.push_back({{lo, box.maxY}, {hi, box.maxY}});
          break;
      }
    }
  }
  if (segments.empty()) return true;

  // 2. The constrained triangulation, in coordinates relative to the box's corner (small numbers
  //    keep the inexact intersection points close).
  const glm::dvec2 origin(box.minX, box.minY);
  try {
    Cdt cdt;
    Cdt::Face_handle hint;
    auto vertex = [&](glm::dvec2 p) {
      const glm::dvec2 local = p - origin;
      Cdt::Vertex_handle v = cdt.insert(Kernel::Point_2(local.x, local.y), hint);
      hint = v->face();
      return v;
    };
    for (const Segment& s : segments) {
      const Cdt::Vertex_handle a = vertex(s.a);
      const Cdt::Vertex_handle b = vertex(s.b);
      if (a != b) cdt.insert_constraint(a, b);
      // Inserting a constraint re-triangulates around it and may delete the hint's face; the
      // vertex stays and knows a face that exists.
      hint = b->face();
    }
    markNesting(cdt);
    // Every vertex (crossing points included) numbered, then only those of inside faces kept.
    std::vector<glm::dvec2> points;
    points.reserve(cdt.number_of_vertices());
    for (Cdt::Vertex_handle v : cdt.finite_vertex_handles()) {
      v->info() = static_cast<std::uint32_t>(points.size());
      points.emplace_back(v->point().x() + origin.x, v->point().y() + origin.y);
    }
    std::vector<std::uint32_t> triangles;
    appendInsideTriangles(cdt, triangles);
    std::vector<std::uint32_t> remap(points.size(), std::numeric_limits<std::uint32_t>::max());
    for (std::uint32_t& index : triangles) {
      if (remap[index] == std::numeric_limits<std::uint32_t>::max()) {
        remap[index] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(points[index]);
      }
      index = remap[index];
    }
    out.triangles.insert(out.triangles.end(), triangles.begin(), triangles.end());
    return true;
  } catch (const std::exception&) {
    return false;  // a CGAL precondition: the caller counts the area as skipped
  }
}

}  // namespace qv::prep::ground
