// The inside of a polygon with holes in a CGAL constrained triangulation of its rings (the CGAL
// manual's "Triangulating a Polygonal Domain" example, 2D Triangulations §8.4), shared by the roof
// triangulation (prep::tiling) and the LOD2 face triangulation (prep::lod2). Header-only templates:
// the includer brings CGAL and its own triangulation type, whose face info has an `int nesting`
// and whose vertex info is the vertex's index.
#pragma once

#include <cstdint>
#include <vector>

namespace qv::prep {

/// Sets every face's info().nesting to its depth: 0 for the faces reachable from the infinite face
/// without crossing a constrained edge, 1 beyond one constraint, and so on (odd: inside).
template <class Cdt>
void markNesting(Cdt& cdt) {
  for (auto f : cdt.all_face_handles()) f->info().nesting = -1;
  std::vector<typename Cdt::Edge> border;
  // Flood fill of one domain; the constrained edges met lead to the next level.
  auto fill = [&cdt, &border](typename Cdt::Face_handle start, int index) {
    if (start->info().nesting != -1) return;
    std::vector<typename Cdt::Face_handle> queue{start};  // order does not matter within a domain
    while (!queue.empty()) {
      typename Cdt::Face_handle fh = queue.back();
      queue.pop_back();
      if (fh->info().nesting != -1) continue;
      fh->info().nesting = index;
      for (int i = 0; i < 3; ++i) {
        const typename Cdt::Edge e(fh, i);
        typename Cdt::Face_handle n = fh->neighbor(i);
        if (n->info().nesting != -1) continue;
        if (cdt.is_constrained(e)) {
          border.push_back(e);
        } else {
          queue.push_back(n);
        }
      }
    }
  };
  fill(cdt.infinite_face(), 0);
  // Breadth-first over the borders (first in, first out), so each domain gets its nesting level.
  for (std::size_t next = 0; next < border.size(); ++next) {
    const typename Cdt::Edge e = border[next];
    typename Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) fill(n, e.first->info().nesting + 1);
  }
}

/// Appends the faces inside (odd nesting, after markNesting) as triples of their vertices' info().
template <class Cdt>
void appendInsideTriangles(const Cdt& cdt, std::vector<std::uint32_t>& out) {
  for (auto f : cdt.finite_face_handles()) {
    if (f->info().nesting % 2 != 1) continue;
    out.insert(out.end(), {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
}

}  // namespace qv::prep
