#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "qv/geometry/OrbitCamera.h"
#include "qv/spatial/BoxTree.h"

using namespace qv;

namespace {

std::vector<Box> randomCity(std::uint32_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-3000.0f, 3000.0f), size(5.0f, 60.0f), height(3.0f, 300.0f);
  std::vector<Box> boxes(n);
  for (Box& b : boxes) {
    const float x = pos(rng), y = pos(rng), w = size(rng), d = size(rng);
    b = Box{x, y, 0.0f, x + w, y + d, height(rng)};
  }
  return boxes;
}

CameraState randomCamera(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(-3500.0, 3500.0), dist(50.0, 9000.0), heading(0.0, 360.0),
      pitch(5.0, 90.0);
  return CameraState{pos(rng), pos(rng), dist(rng), heading(rng), pitch(rng), 45.0};
}

}  // namespace

TEST_CASE("BoxTree visible ranges equal a brute-force frustum test on random cameras", "[spatial]") {
  const std::vector<Box> boxes = randomCity(5000, 7);
  BoxTree tree;
  tree.build(boxes);
  REQUIRE(tree.size() == boxes.size());
  std::mt19937 rng(11);
  std::vector<IndexRange> ranges;
  int nonTrivial = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const CameraView view(randomCamera(rng), 1280, 720);
    std::set<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      if (view.frustum().intersects(boxes[i])) expected.insert(i);
    }
    ranges.clear();
    tree.query(view.frustum(), ranges);
    std::set<std::uint32_t> got;
    std::uint32_t previousEnd = 0;
    for (const IndexRange& r : ranges) {
      REQUIRE(r.begin >= previousEnd);  // ascending, disjoint
      previousEnd = r.end;
      for (std::uint32_t p = r.begin; p < r.end; ++p) {
        got.insert(tree.order()[p]);
        if (r.inside) CHECK(view.frustum().classify(boxes[tree.order()[p]]) == Containment::Inside);
      }
    }
    REQUIRE(got == expected);
    CHECK(tree.countVisible(view.frustum()) == expected.size());
    if (!expected.empty() && expected.size() < boxes.size()) ++nonTrivial;
  }
  CHECK(nonTrivial > 50);  // the cameras really exercised partial views
}

TEST_CASE("BoxTree leaves out exactly the boxes smaller on screen than the size cut", "[spatial]") {
  // Boxes from 0.2 m to 60 m wide over 6 km, far cameras: many are under a few pixels.
  std::vector<Box> boxes = randomCity(5000, 9);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> tiny(0.2f, 3.0f);
  for (std::size_t i = 0; i < boxes.size(); i += 3) {
    boxes[i].maxX = boxes[i].minX + tiny(rng);
    boxes[i].maxY = boxes[i].minY + tiny(rng);
    boxes[i].maxZ = tiny(rng);
  }
  BoxTree tree;
  tree.build(boxes);
  std::vector<IndexRange> ranges;
  int dropped = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const CameraView view(randomCamera(rng), 1280, 720);
    const SizeCull size{view.eye(), 2.0f / view.pixelsPerMeterAt(1.0f)};  // two pixels
    std::set<std::uint32_t> expected;
    std::uint32_t inFrustum = 0;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      if (!view.frustum().intersects(boxes[i])) continue;
      ++inFrustum;
      const Box& b = boxes[i];
      const float d = std::hypot(std::max({b.minX - view.eye().x, 0.0f, view.eye().x - b.maxX}),
                                 std::max({b.minY - view.eye().y, 0.0f, view.eye().y - b.maxY}),
                                 std::max({b.minZ - view.eye().z, 0.0f, view.eye().z - b.maxZ}));
      const float diagonal = std::hypot(b.maxX - b.minX, b.maxY - b.minY, b.maxZ - b.minZ);
      if (diagonal >= size.minAngle * d) expected.insert(i);  // brute force: every box on its own
    }
    ranges.clear();
    tree.query(view.frustum(), ranges, size);
    std::set<std::uint32_t> got;
    for (const IndexRange& r : ranges) {
      for (std::uint32_t p = r.begin; p < r.end; ++p) got.insert(tree.order()[p]);
    }
    REQUIRE(got == expected);
    dropped += static_cast<int>(inFrustum - expected.size());
  }
  CHECK(dropped > 1000);  // the far cameras really left small boxes out
}

TEST_CASE("BoxTree ray hits are the boxes the ray enters, nearest first", "[spatial]") {
  const std::vector<Box> boxes = randomCity(2000, 3);
  BoxTree tree;
  tree.build(boxes);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    const CameraView view(randomCamera(rng), 800, 600);
    glm::vec3 origin, direction;
    view.ray(400.0, 300.0, origin, direction);
    std::vector<std::pair<float, std::uint32_t>> hits;
    tree.raycast(origin, direction, 1e6f, hits);
    const glm::vec3 inv(1.0f / direction.x, 1.0f / direction.y, 1.0f / direction.z);
    std::set<std::uint32_t> expected, got;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
      if (rayBoxEntry(origin, inv, boxes[i], 1e6f)) expected.insert(i);
    }
    for (std::size_t h = 0; h < hits.size(); ++h) {
      got.insert(tree.order()[hits[h].second]);
      if (h > 0) CHECK(hits[h].first >= hits[h - 1].first);
    }
    CHECK(got == expected);
  }
}

TEST_CASE("An empty BoxTree answers nothing", "[spatial]") {
  BoxTree tree;
  tree.build({});
  std::vector<IndexRange> ranges;
  tree.query(CameraView(CameraState{}, 100, 100).frustum(), ranges);
  CHECK(ranges.empty());
  CHECK(tree.size() == 0);
}
