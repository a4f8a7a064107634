#include "qv/prep/Triangulate.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <utility>
#include <vector>

#include "qv/prep/CdtDomains.h"

namespace qv::prep {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;  // markNesting's depth: odd inside
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase0 = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBase0>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact predicates without intersection support: crossing constraints throw, and such polygons
// are reported as failures (cleaning drops self-intersecting rings before this point).
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;

// +1 or -1 when the ring is a strictly convex simple polygon wound counter-clockwise or clockwise,
// 0 otherwise. Every turn has the same sign, and the edge directions go round once: x and y of the
// edge vectors each change sign at most twice (which rules out stars such as the pentagram).
int convexWinding(std::span<const glm::dvec2> ring) {
  const std::size_t n = ring.size();
  if (n < 3) return 0;
  int turn = 0;
  int xChanges = 0, yChanges = 0;
  int lastX = 0, lastY = 0;
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

}  // namespace

bool triangulatePolygon(std::span<const glm::dvec2> points, std::span<const std::uint32_t> ringEnds,
                        std::vector<std::uint32_t>& out, bool* usedConstrained) {
  if (usedConstrained != nullptr) *usedConstrained = false;
  // Most footprints are one convex ring (rectangles above all): a fan is their triangulation, and
  // costs nothing next to building a Delaunay triangulation.
  if (ringEnds.size() == 1 && ringEnds[0] <= points.size()) {
    const std::uint32_t n = ringEnds[0];
    const int winding = convexWinding(points.first(n));
    if (winding != 0) {
      out.reserve(out.size() + 3 * (n - 2));
      for (std::uint32_t i = 1; i + 1 < n; ++i) {
        if (winding > 0)
          out.insert(out.end(), {0, i, i + 1});
        else
          out.insert(out.end(), {0, i + 1, i});
      }
      return true;
    }
  }
  if (usedConstrained != nullptr) *usedConstrained = true;
  try {
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> ring;
    std::uint32_t begin = 0;
    for (std::uint32_t end : ringEnds) {
      if (end > points.size() || end < begin + 3) return false;
      ring.clear();
      // Each vertex is located from the previous one (ring neighbours are close): no walk from
      // an arbitrary face.
      Cdt::Face_handle hint;
      for (std::uint32_t i = begin; i < end; ++i) {
        Cdt::Vertex_handle v = cdt.insert(Kernel::Point_2(points[i].x, points[i].y), hint);
        v->info() = i;
        hint = v->face();
        ring.push_back(v);
      }
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto& a = ring[i];
        const auto& b = ring[(i + 1) % ring.size()];
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
  } catch (const std::exception&) {
    return false;  // CGAL precondition or intersecting constraints: the caller counts the drop
  }
}

}  // namespace qv::prep
