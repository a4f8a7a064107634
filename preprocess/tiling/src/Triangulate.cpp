#include "qv/prep/Triangulate.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <list>
#include <utility>

namespace qv::prep {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;
  [[nodiscard]] bool inside() const { return nesting % 2 == 1; }
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using FaceBase0 = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBase0>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact predicates without intersection support: crossing constraints throw, and such polygons
// are reported as failures (cleaning drops self-intersecting rings before this point).
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;

// Flood-fills nesting levels from the infinite face across constrained edges (the CGAL manual's
// "Triangulating a Polygonal Domain" example, 2D Triangulations §8.4).
void markDomains(Cdt& cdt, Cdt::Face_handle start, int index, std::list<Cdt::Edge>& border) {
  if (start->info().nesting != -1) return;
  std::list<Cdt::Face_handle> queue;
  queue.push_back(start);
  while (!queue.empty()) {
    Cdt::Face_handle fh = queue.front();
    queue.pop_front();
    if (fh->info().nesting != -1) continue;
    fh->info().nesting = index;
    for (int i = 0; i < 3; ++i) {
      const Cdt::Edge e(fh, i);
      Cdt::Face_handle n = fh->neighbor(i);
      if (n->info().nesting == -1) {
        if (cdt.is_constrained(e))
          border.push_back(e);
        else
          queue.push_back(n);
      }
    }
  }
}

}  // namespace

bool triangulatePolygon(std::span<const glm::dvec2> points, std::span<const std::uint32_t> ringEnds,
                        std::vector<std::uint32_t>& out) {
  try {
    Cdt cdt;
    std::uint32_t begin = 0;
    for (std::uint32_t end : ringEnds) {
      if (end > points.size() || end < begin + 3) return false;
      std::vector<Cdt::Vertex_handle> ring;
      ring.reserve(end - begin);
      for (std::uint32_t i = begin; i < end; ++i) {
        Cdt::Vertex_handle v = cdt.insert(Kernel::Point_2(points[i].x, points[i].y));
        v->info() = i;
        ring.push_back(v);
      }
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto& a = ring[i];
        const auto& b = ring[(i + 1) % ring.size()];
        if (a != b) cdt.insert_constraint(a, b);
      }
      begin = end;
    }
    for (Cdt::Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
    std::list<Cdt::Edge> border;
    markDomains(cdt, cdt.infinite_face(), 0, border);
    while (!border.empty()) {
      const Cdt::Edge e = border.front();
      border.pop_front();
      Cdt::Face_handle n = e.first->neighbor(e.second);
      if (n->info().nesting == -1) markDomains(cdt, n, e.first->info().nesting + 1, border);
    }
    std::vector<std::uint32_t> triangles;
    for (Cdt::Face_handle f : cdt.finite_face_handles()) {
      if (!f->info().inside()) continue;
      triangles.insert(triangles.end(), {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    }
    if (triangles.empty()) return false;
    out.insert(out.end(), triangles.begin(), triangles.end());
    return true;
  } catch (const std::exception&) {
    return false;  // CGAL precondition or intersecting constraints: the caller counts the drop
  }
}

}  // namespace qv::prep
