#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "qv/geometry/OrbitCamera.h"

using namespace qv;

TEST_CASE("The looked-at point projects to the viewport centre", "[geometry][camera]") {
  const CameraState s{120.0, -40.0, 800.0, 30.0, 45.0, 45.0};
  const CameraView view(s, 1280, 720);
  const auto p = view.project(glm::vec3(120.0f, -40.0f, 0.0f));
  REQUIRE(p.has_value());
  CHECK(p->x == Approx(640.0f).margin(0.5f));
  CHECK(p->y == Approx(360.0f).margin(0.5f));
  const auto g = view.groundPoint(640.0, 360.0);
  REQUIRE(g.has_value());
  CHECK(g->x == Approx(120.0).margin(0.05));
  CHECK(g->y == Approx(-40.0).margin(0.05));
  CHECK(glm::length(view.eye() - glm::vec3(120.0f, -40.0f, 0.0f)) == Approx(800.0f).epsilon(1e-4));
}

TEST_CASE("Heading 0 looks north, 90 looks east, pitch 90 looks straight down", "[geometry][camera]") {
  CameraState s{0.0, 0.0, 100.0, 0.0, 0.0, 45.0};
  CHECK(CameraView(s, 100, 100).forward().y == Approx(1.0f));
  s.headingDeg = 90.0;
  CHECK(CameraView(s, 100, 100).forward().x == Approx(1.0f));
  s.pitchDeg = 90.0;
  const CameraView down(s, 100, 100);
  CHECK(down.forward().z == Approx(-1.0f));
  CHECK(down.eye().z == Approx(100.0f));
  // Looking down with heading 90 (east up on screen), a point to the east is above the centre.
  const auto p = down.project(glm::vec3(10.0f, 0.0f, 0.0f));
  REQUIRE(p.has_value());
  CHECK(p->y < 50.0f);
  CHECK(p->x == Approx(50.0f).margin(0.01f));
}

TEST_CASE("Frustum keeps what is in front and culls what is behind", "[geometry][camera]") {
  const CameraState s{0.0, 0.0, 500.0, 0.0, 30.0, 45.0};
  const CameraView view(s, 800, 600);
  CHECK(view.frustum().intersects(Box{-10, -10, 0, 10, 10, 50}));
  // Far behind the eye (the eye is south of the target, looking north).
  CHECK_FALSE(view.frustum().intersects(Box{-10, -2000, 0, 10, -1900, 50}));
  // Far to the side.
  CHECK_FALSE(view.frustum().intersects(Box{5000, 0, 0, 5100, 100, 50}));
}

TEST_CASE("Zooming about a point keeps that ground point under the cursor", "[geometry][camera]") {
  CameraState s{0.0, 0.0, 1000.0, 20.0, 50.0, 45.0};
  const glm::dvec2 cursor(900.0, 200.0);
  const auto before = CameraView(s, 1280, 720).groundPoint(cursor.x, cursor.y);
  REQUIRE(before.has_value());
  camera_gestures::zoomAt(s, CameraView(s, 1280, 720), cursor, 0.5);
  CHECK(s.distance == Approx(500.0));
  const auto after = CameraView(s, 1280, 720).groundPoint(cursor.x, cursor.y);
  REQUIRE(after.has_value());
  CHECK(after->x == Approx(before->x).margin(0.5));
  CHECK(after->y == Approx(before->y).margin(0.5));
}

TEST_CASE("Panning drags the ground with the cursor", "[geometry][camera]") {
  CameraState s{0.0, 0.0, 1000.0, 0.0, 60.0, 45.0};
  const CameraView view(s, 1000, 800);
  const auto grabbed = view.groundPoint(500.0, 400.0);
  camera_gestures::pan(s, view, {500.0, 400.0}, {600.0, 450.0});
  const auto under = CameraView(s, 1000, 800).groundPoint(600.0, 450.0);
  REQUIRE(grabbed.has_value());
  REQUIRE(under.has_value());
  CHECK(under->x == Approx(grabbed->x).margin(1.0));
  CHECK(under->y == Approx(grabbed->y).margin(1.0));
}

TEST_CASE("sanitizeCamera replaces non-finite values and clamps absurd ones", "[geometry][camera]") {
  const CameraState fallback{1.0, 2.0, 300.0, 10.0, 40.0, 45.0};
  CameraState s{std::numeric_limits<double>::quiet_NaN(), 5.0, -10.0, 725.0, 200.0,
                std::numeric_limits<double>::infinity()};
  CHECK_FALSE(sanitizeCamera(s, fallback));
  CHECK(s.x == 1.0);
  CHECK(s.y == 5.0);
  CHECK(s.distance == CameraLimits{}.minDistance);
  CHECK(s.headingDeg == Approx(5.0));
  CHECK(s.pitchDeg == 90.0);
  CHECK(s.fovDeg == 45.0);
  CameraState good = fallback;
  CHECK(sanitizeCamera(good, fallback));
}
