// Footprint cleaning: closing, duplicates, collinear points, winding, and the drop reasons.
#include <catch2/catch.hpp>

#include <vector>

#include "qv/prep/Cleaning.h"

using namespace qv::prep;
using Points = std::vector<glm::dvec2>;
using RingEnds = std::vector<std::uint32_t>;

namespace {

double ringArea(const Points& points, std::uint32_t begin, std::uint32_t end) {
  return signedRingArea(points.data() + begin, end - begin);
}

}  // namespace

TEST_CASE("Cleaning drops the closing point, duplicates and collinear vertices", "[ingest][cleaning]") {
  // A 10 x 10 m square, closed, with a duplicated corner, a point in the middle of an edge, a point
  // 0.5 mm off an edge and a spike.
  Points points{{0, 0}, {5, 0}, {10, 0}, {10, 0}, {10.0005, 5}, {10, 10}, {10, 12}, {10, 10}, {0, 10}, {0, 0}};
  RingEnds ends{static_cast<std::uint32_t>(points.size())};
  DropCounts holes;
  REQUIRE(cleanPolygon(points, ends, &holes).empty());
  REQUIRE(ends == RingEnds{4});
  CHECK(points == Points{{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  CHECK(holes.total() == 0);
}

TEST_CASE("Cleaning makes outer rings counter-clockwise and holes clockwise", "[ingest][cleaning]") {
  // Outer clockwise, hole counter-clockwise: both reversed.
  Points points{{0, 0}, {0, 10}, {10, 10}, {10, 0}, {2, 2}, {8, 2}, {8, 8}, {2, 8}};
  RingEnds ends{4, 8};
  REQUIRE(cleanPolygon(points, ends).empty());
  REQUIRE(ends == RingEnds{4, 8});
  CHECK(ringArea(points, 0, 4) == Approx(100.0));
  CHECK(ringArea(points, 4, 8) == Approx(-36.0));
  CHECK(polygonArea(points, ends) == Approx(64.0));
  const glm::dvec2 c = polygonCentroid(points, ends);
  CHECK(c.x == Approx(5.0));
  CHECK(c.y == Approx(5.0));
}

TEST_CASE("Cleaning drops bad polygons with a reason", "[ingest][cleaning]") {
  struct Row {
    const char* name;
    Points points;
    std::string_view reason;
  };
  const Row rows[] = {
      {"bow-tie", {{0, 0}, {10, 10}, {10, 0}, {0, 10}}, drop::kSelfIntersecting},
      {"ring touching itself", {{0, 0}, {10, 0}, {10, 10}, {5, 0}, {0, 10}}, drop::kSelfIntersecting},
      {"zero area (tiny triangle)", {{0, 0}, {0.1, 0}, {0, 0.1}}, drop::kZeroArea},
      // Out and back along a line 1.5 cm apart (like w249664916 in Lower Manhattan): 0.19 m2, but
      // a mean width of 8 mm.
      {"sliver", {{0, 0}, {23, 0}, {15, 0.012}, {10, 0.015}}, drop::kZeroArea},
      {"a 20 cm wall is kept as a footprint", {{0, 0}, {50, 0}, {50, 0.2}, {0, 0.2}}, ""},
      {"all collinear", {{0, 0}, {5, 0}, {10, 0}, {5, 0}}, drop::kTooFewPoints},
      {"two points", {{0, 0}, {5, 0}}, drop::kTooFewPoints},
      {"wider than 2 km", {{0, 0}, {2500, 0}, {2500, 10}, {0, 10}}, drop::kTooLarge},
      {"not finite", {{0, 0}, {10, 0}, {10, std::numeric_limits<double>::quiet_NaN()}}, drop::kInvalidCoordinates},
  };
  for (const Row& row : rows) {
    INFO(row.name);
    Points points = row.points;
    RingEnds ends{static_cast<std::uint32_t>(points.size())};
    CHECK(cleanPolygon(points, ends) == row.reason);
  }
  SECTION("a hole crossing the outer ring") {
    Points points{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {5, 5}, {15, 5}, {15, 6}, {5, 6}};
    RingEnds ends{4, 8};
    CHECK(cleanPolygon(points, ends) == drop::kSelfIntersecting);
  }
}

TEST_CASE("Cleaning removes holes outside their outer ring and degenerate holes, and keeps the polygon",
          "[ingest][cleaning]") {
  // An L-shaped outer ring; hole 1 sits in the notch of the L (inside the bounds, outside the ring),
  // hole 2 is far away, hole 3 is a sliver, hole 4 is a real hole.
  Points points{{0, 0},     {20, 0},    {20, 10},       {10, 10}, {10, 20}, {0, 20},  // outer
                {12, 12},   {18, 12},   {18, 18},       {12, 18},                     // in the notch
                {100, 100}, {101, 100}, {101, 101},                                   // far away
                {2, 2},     {8, 2},     {5, 2.0000001},                               // sliver
                {2, 12},    {2, 18},    {8, 18},        {8, 12}};                     // inside
  RingEnds ends{6, 10, 13, 16, 20};
  DropCounts holes;
  REQUIRE(cleanPolygon(points, ends, &holes).empty());
  CHECK(ends == RingEnds{6, 10});
  CHECK(holes.byReason[std::string(drop::kHoleOutsideOuter)] == 2);
  CHECK(holes.byReason[std::string(drop::kDegenerateHole)] == 1);
  CHECK(polygonArea(points, ends) == Approx(300.0 - 36.0));
}

TEST_CASE("A hole touching the outer ring in one point is kept", "[ingest][cleaning]") {
  Points points{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 5}, {4, 3}, {4, 7}};
  RingEnds ends{4, 7};
  // The outer ring has no vertex at (0, 5): the hole's corner lies on its edge.
  REQUIRE(cleanPolygon(points, ends).empty());
  CHECK(ends.size() == 2);
}

TEST_CASE("Interior points lie inside concave footprints", "[ingest][cleaning]") {
  // A U shape: its centroid is in the empty middle, the interior point is not.
  const Points u{{0, 0}, {30, 0}, {30, 30}, {20, 30}, {20, 10}, {10, 10}, {10, 30}, {0, 30}};
  const RingEnds ends{8};
  const glm::dvec2 centroid = polygonCentroid(u, ends);
  CHECK_FALSE(pointInPolygon(centroid, u, ends));
  const auto inside = interiorPoint(u, ends);
  REQUIRE(inside.has_value());
  CHECK(pointInPolygon(*inside, u, ends));
  // A square with a hole in the middle: the interior point avoids the hole.
  const Points holed{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {2, 2}, {2, 8}, {8, 8}, {8, 2}};
  const RingEnds holedEnds{4, 8};
  const auto p = interiorPoint(holed, holedEnds);
  REQUIRE(p.has_value());
  CHECK(pointInPolygon(*p, holed, holedEnds));
}
