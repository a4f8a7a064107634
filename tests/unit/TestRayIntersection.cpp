#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "qv/spatial/RayIntersection.h"

using namespace qv;

namespace {

// A 10 m x 10 m footprint from z = 0 to 20, with an optional 2 m x 2 m courtyard in its middle.
struct Footprint {
  std::vector<float> xy{0, 0, 10, 0, 10, 10, 0, 10};
  std::vector<std::uint16_t> rings{4};
  void addCourtyard() {
    xy.insert(xy.end(), {4, 4, 6, 4, 6, 6, 4, 6});
    rings.push_back(4);
  }
  [[nodiscard]] PrismView view(float offsetX = 0.0f, float offsetY = 0.0f) const {
    PrismView p;
    p.xy = xy.data();
    p.ringCounts = rings.data();
    p.ringCount = static_cast<std::uint32_t>(rings.size());
    p.offsetX = offsetX;
    p.offsetY = offsetY;
    p.minZ = 0.0f;
    p.maxZ = 20.0f;
    return p;
  }
};

std::optional<float> prismHit(const PrismView& p, std::array<float, 3> o, std::array<float, 3> d) {
  return rayPrism(o.data(), d.data(), p);
}

}  // namespace

TEST_CASE("A ray meets a building's prism on its roof, walls and floor at the nearest point", "[spatial][ray]") {
  const Footprint f;
  const PrismView p = f.view();
  SECTION("looking straight down onto the roof") {
    const auto t = prismHit(p, {5, 5, 100}, {0, 0, -1});
    REQUIRE(t);
    CHECK(*t == Approx(80.0f));
  }
  SECTION("level with the walls, from the west") {
    const auto t = prismHit(p, {-10, 5, 5}, {1, 0, 0});
    REQUIRE(t);
    CHECK(*t == Approx(10.0f));
  }
  SECTION("t is in units of an unnormalized direction") {
    const auto t = prismHit(p, {-10, 5, 5}, {2, 0, 0});
    REQUIRE(t);
    CHECK(*t == Approx(5.0f));
  }
  SECTION("a slanted ray through the roof edge's side hits the wall first") {
    // From (-5, 5, 24) towards +x and down 1 m per 1 m: the roof plane is crossed outside the
    // footprint (x = -1), and at x = 0 the ray is at z = 19, on the wall.
    const auto t = prismHit(p, {-5, 5, 24}, {1, 0, -1});
    REQUIRE(t);
    CHECK(*t == Approx(5.0f));
  }
  SECTION("from below, the floor") {
    const auto t = prismHit(p, {5, 5, -3}, {0, 0, 1});
    REQUIRE(t);
    CHECK(*t == Approx(3.0f));
  }
  SECTION("from inside, the roof above") {
    const auto t = prismHit(p, {5, 2, 10}, {0, 0, 1});
    REQUIRE(t);
    CHECK(*t == Approx(10.0f));
  }
  SECTION("misses: above the roof, beside it, and pointing away") {
    CHECK_FALSE(prismHit(p, {-10, 5, 25}, {1, 0, 0}));
    CHECK_FALSE(prismHit(p, {15, 5, 100}, {0, 0, -1}));
    CHECK_FALSE(prismHit(p, {-10, 5, 5}, {-1, 0, 0}));
  }
}

TEST_CASE("A prism's offset moves it, and its courtyard is empty space", "[spatial][ray]") {
  Footprint f;
  SECTION("offset") {
    const PrismView p = f.view(100.0f, -50.0f);
    const auto t = prismHit(p, {95, -45, 5}, {1, 0, 0});
    REQUIRE(t);
    CHECK(*t == Approx(5.0f));
    CHECK_FALSE(prismHit(p, {5, 5, 100}, {0, 0, -1}));
  }
  SECTION("courtyard") {
    f.addCourtyard();
    const PrismView p = f.view();
    // Straight down into the courtyard: no roof there, and the vertical ray runs along its walls.
    CHECK_FALSE(prismHit(p, {5, 5, 100}, {0, 0, -1}));
    // Beside the courtyard the roof is there.
    const auto roof = prismHit(p, {2, 2, 100}, {0, 0, -1});
    REQUIRE(roof);
    CHECK(*roof == Approx(80.0f));
    // Standing in the courtyard and looking east: the courtyard's wall at x = 6.
    const auto wall = prismHit(p, {5, 5, 10}, {1, 0, 0});
    REQUIRE(wall);
    CHECK(*wall == Approx(1.0f));
  }
}

TEMPLATE_TEST_CASE("A ray meets the nearest triangle of a model from either side", "[spatial][ray]", std::uint16_t,
                   std::uint32_t) {
  // Two stacked copies of a right triangle with legs of 10 m along x and y, at z = 0 and z = 2.
  const std::vector<glm::vec3> positions{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 2}, {10, 0, 2}, {0, 10, 2}};
  const std::vector<TestType> both{0, 1, 2, 3, 4, 5};
  const std::vector<TestType> lower{0, 1, 2};
  const glm::vec3 none(0.0f);
  auto hit = [&](const std::vector<TestType>& tris, std::array<float, 3> o, std::array<float, 3> d,
                 const glm::vec3& offset) {
    return rayTriangles<TestType>(o.data(), d.data(), positions, tris, offset);
  };
  SECTION("from above, the upper triangle") {
    const auto t = hit(both, {1, 1, 5}, {0, 0, -1}, none);
    REQUIRE(t);
    CHECK(*t == Approx(3.0f));
  }
  SECTION("from below, the lower triangle (back faces count)") {
    const auto t = hit(both, {1, 1, -5}, {0, 0, 1}, none);
    REQUIRE(t);
    CHECK(*t == Approx(5.0f));
  }
  SECTION("the offset moves the model") {
    const auto t = hit(lower, {101, 1, 5}, {0, 0, -1}, glm::vec3(100, 0, 0));
    REQUIRE(t);
    CHECK(*t == Approx(5.0f));
    CHECK_FALSE(hit(lower, {1, 1, 5}, {0, 0, -1}, glm::vec3(100, 0, 0)));
  }
  SECTION("misses: beyond the hypotenuse, behind the origin, parallel to the plane") {
    CHECK_FALSE(hit(both, {6, 6, 5}, {0, 0, -1}, none));
    CHECK_FALSE(hit(both, {1, 1, 5}, {0, 0, 1}, none));
    CHECK_FALSE(hit(lower, {-5, 1, 0}, {1, 0, 0}, none));
  }
  SECTION("a triangle with an index out of range, or incomplete, is skipped") {
    const std::vector<TestType> bad{0, 1, 7, 3, 4};
    CHECK_FALSE(hit(bad, {1, 1, 5}, {0, 0, -1}, none));
    const std::vector<TestType> badThenGood{0, 1, 7, 0, 1, 2};
    const auto t = hit(badThenGood, {1, 1, 5}, {0, 0, -1}, none);
    REQUIRE(t);
    CHECK(*t == Approx(5.0f));
  }
}
