#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "qv/scene/FlyToPose.h"

using namespace qv;

namespace {

Box prism(double cx, double cy, double halfSide, double height) {
  Box b;
  b.expand(static_cast<float>(cx - halfSide), static_cast<float>(cy - halfSide), 0.0f);
  b.expand(static_cast<float>(cx + halfSide), static_cast<float>(cy + halfSide), static_cast<float>(height));
  return b;
}

glm::dvec3 eyeOf(const CameraState& s) {
  const CameraView view(s, 1280, 720);
  return glm::dvec3(view.eye());
}

}  // namespace

TEST_CASE("Fly to keeps the view when nothing stands in front of the building", "[flyto]") {
  const CameraState current{500.0, 500.0, 2000.0, 30.0, 50.0, 45.0};
  const FlyToTarget target{0.0, 0.0, 0.0, 12.0, 400.0};
  const std::vector<Box> occluders{prism(0.0, 60.0, 10.0, 10.0)};  // a low neighbour behind it
  const FlyToPose pose = chooseFlyToPose(current, target, occluders);
  CHECK(pose.centreVisible);
  CHECK(pose.roofVisible);
  CHECK(pose.camera.headingDeg == Approx(30.0));
  CHECK(pose.camera.pitchDeg == Approx(50.0));
  CHECK(pose.camera.distance == Approx(150.0));
  CHECK(pose.camera.fovDeg == Approx(45.0));
  CHECK(pose.camera.x == 0.0);
}

TEST_CASE("Fly to turns to the side without towers in front of a low-rise building", "[flyto]") {
  const CameraState current{0.0, -1000.0, 2000.0, 0.0, 45.0, 45.0};  // looking north
  const FlyToTarget target{0.0, 0.0, 0.0, 10.0, 400.0};
  // 200 m towers south, west and east of it, 40 m apart; the north is open.
  std::vector<Box> towers;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{-40, -40}, {0, -40}, {40, -40}, {-40, 0}, {40, 0}})
    towers.push_back(prism(x, y, 12.0, 200.0));
  const glm::dvec3 centre(0.0, 0.0, 5.0);
  // Straight in (the current heading and pitch) a tower hides it.
  CameraState straight = current;
  straight.x = 0.0;
  straight.y = 0.0;
  straight.distance = flyToDistance(10.0, 400.0);
  CHECK(segmentBlocked(eyeOf(straight), centre, towers));

  const FlyToPose pose = chooseFlyToPose(current, target, towers);
  CHECK(pose.centreVisible);
  CHECK(pose.roofVisible);
  const glm::dvec3 eye = eyeOf(pose.camera);
  CHECK_FALSE(segmentBlocked(eye, centre, towers));
  CHECK(eye.y > 0.0);  // from the open north side
}

TEST_CASE("Fly to looks down when towers stand on every side", "[flyto]") {
  const CameraState current{0.0, 0.0, 2000.0, 0.0, 45.0, 45.0};
  const FlyToTarget target{0.0, 0.0, 0.0, 10.0, 400.0};
  std::vector<Box> towers;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      if (i != 0 || j != 0) towers.push_back(prism(30.0 * i, 30.0 * j, 12.0, 300.0));
    }
  }
  const FlyToPose pose = chooseFlyToPose(current, target, towers);
  CHECK(pose.centreVisible);
  CHECK(pose.camera.pitchDeg > 80.0);
  CHECK_FALSE(segmentBlocked(eyeOf(pose.camera), glm::dvec3(0.0, 0.0, 5.0), towers));
}

TEST_CASE("The framing distance grows with height and footprint", "[flyto]") {
  CHECK(flyToDistance(10.0, 400.0) == Approx(150.0));
  CHECK(flyToDistance(443.0, 8000.0) == Approx(443.0 * 2.5));
  CHECK(flyToDistance(20.0, 10000.0) == Approx(600.0));
}
