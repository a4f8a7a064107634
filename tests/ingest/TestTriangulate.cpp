// Roof triangulation (qv/prep/Triangulate.h): convex rings take a fan, everything else CGAL's
// constrained Delaunay triangulation; either way the triangles cover exactly the polygon.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "qv/prep/Triangulate.h"

namespace {

using qv::prep::triangulatePolygon;

double ringArea(const std::vector<glm::dvec2>& p, std::uint32_t begin, std::uint32_t end) {
  double a = 0.0;
  for (std::uint32_t i = begin; i < end; ++i) {
    const glm::dvec2 u = p[i], v = p[i + 1 < end ? i + 1 : begin];
    a += u.x * v.y - v.x * u.y;
  }
  return 0.5 * a;
}

// Sum of the triangles' signed areas; every triangle must be counter-clockwise and non-degenerate.
double trianglesArea(const std::vector<glm::dvec2>& p, const std::vector<std::uint32_t>& t) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 2 < t.size(); i += 3) {
    const glm::dvec2 a = p[t[i]], b = p[t[i + 1]], c = p[t[i + 2]];
    const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    CHECK(area > 0.0);
    sum += area;
  }
  return sum;
}

}  // namespace

TEST_CASE("Convex rings of either winding become counter-clockwise triangles covering them", "[tiling][triangulate]") {
  for (const bool clockwise : {false, true}) {
    for (const std::uint32_t n : {3u, 4u, 7u, 40u}) {
      std::vector<glm::dvec2> ring;
      for (std::uint32_t i = 0; i < n; ++i) {
        const double angle = 2.0 * std::numbers::pi * i / n * (clockwise ? -1.0 : 1.0);
        ring.emplace_back(100.0 + 12.0 * std::cos(angle), -50.0 + 7.0 * std::sin(angle));
      }
      std::vector<std::uint32_t> triangles;
      const std::uint32_t end = n;
      REQUIRE(triangulatePolygon(ring, std::span(&end, 1), triangles));
      CHECK(triangles.size() == 3 * (n - 2));
      CHECK(trianglesArea(ring, triangles) == Approx(std::abs(ringArea(ring, 0, n))).epsilon(1e-12));
    }
  }
}

TEST_CASE("Concave rings and rings with holes are covered exactly, holes left open", "[tiling][triangulate]") {
  // An L-shape (concave) and a square courtyard block (outer CCW, hole CW).
  const std::vector<glm::dvec2> l{{0, 0}, {20, 0}, {20, 5}, {5, 5}, {5, 15}, {0, 15}};
  std::vector<std::uint32_t> triangles;
  const std::uint32_t lEnd = 6;
  REQUIRE(triangulatePolygon(l, std::span(&lEnd, 1), triangles));
  CHECK(trianglesArea(l, triangles) == Approx(20 * 5 + 5 * 10));

  const std::vector<glm::dvec2> block{{0, 0}, {30, 0}, {30, 30}, {0, 30}, {10, 10}, {10, 20}, {20, 20}, {20, 10}};
  const std::uint32_t ends[] = {4, 8};
  triangles.clear();
  REQUIRE(triangulatePolygon(block, ends, triangles));
  CHECK(trianglesArea(block, triangles) == Approx(900.0 - 100.0));
}

TEST_CASE("A self-crossing star is refused rather than fanned", "[tiling][triangulate]") {
  // A pentagram turns the same way at every corner, like a convex ring, but winds twice.
  std::vector<glm::dvec2> star;
  for (int i = 0; i < 5; ++i) {
    const double angle = 2.0 * std::numbers::pi * (2 * i % 5) / 5.0;
    star.emplace_back(10.0 * std::cos(angle), 10.0 * std::sin(angle));
  }
  std::vector<std::uint32_t> triangles{7, 7, 7};
  const std::uint32_t end = 5;
  CHECK_FALSE(triangulatePolygon(star, std::span(&end, 1), triangles));
  CHECK(triangles == std::vector<std::uint32_t>{7, 7, 7});
}
