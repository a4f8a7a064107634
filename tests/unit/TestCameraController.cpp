#include <catch2/catch.hpp>

#include <cmath>

#include "qv/scene/CameraController.h"

using namespace qv;

TEST_CASE("Left drag pans, right drag orbits, wheel zooms", "[scene][camera]") {
  CameraState s{0.0, 0.0, 1000.0, 0.0, 60.0, 45.0};
  CameraController c(s);
  c.setViewport(1000.0, 800.0);

  // Dragging the ground downwards moves the looked-at point north (we pull the map towards us).
  c.pointerDown(0, 500.0, 400.0, false, false);
  c.pointerMove(500.0, 500.0);
  c.pointerUp(0);
  CHECK(s.y > 50.0);
  CHECK(std::abs(s.x) < 1.0);
  CHECK_FALSE(c.dragging());
  CHECK_FALSE(c.isClick());

  const double heading = s.headingDeg;
  c.pointerDown(2, 500.0, 400.0, false, false);
  c.pointerMove(540.0, 400.0);
  c.pointerUp(2);
  CHECK(s.headingDeg == Approx(heading + 10.0));

  // Shift + left drag orbits too (for one-button mice and trackpads).
  c.pointerDown(0, 500.0, 400.0, true, false);
  c.pointerMove(500.0, 380.0);
  c.pointerUp(0);
  CHECK(s.pitchDeg == Approx(55.0));

  const double distance = s.distance;
  c.wheel(500.0, 400.0, -100.0);
  CHECK(s.distance < distance);
  c.wheel(500.0, 400.0, 200.0);
  CHECK(s.distance > distance);
}

TEST_CASE("A press and release without motion is a click", "[scene][camera]") {
  CameraState s;
  CameraController c(s);
  c.setViewport(800.0, 600.0);
  c.pointerDown(0, 100.0, 100.0, false, false);
  c.pointerMove(101.0, 102.0);
  CHECK(c.isClick());
  c.pointerMove(120.0, 102.0);
  CHECK_FALSE(c.isClick());
}

TEST_CASE("Two-finger pinch zooms and one finger pans", "[scene][camera]") {
  CameraState s{0.0, 0.0, 1000.0, 0.0, 60.0, 45.0};
  CameraController c(s);
  c.setViewport(1000.0, 800.0);
  const TouchPoint start[] = {{1, 400.0, 400.0}, {2, 600.0, 400.0}};
  const TouchPoint spread[] = {{1, 300.0, 400.0}, {2, 700.0, 400.0}};
  c.touches(start);
  c.touches(spread);
  CHECK(s.distance == Approx(500.0).epsilon(0.01));
  c.touches({});
  CHECK_FALSE(c.dragging());
  const double y = s.y;
  const TouchPoint one[] = {{3, 500.0, 400.0}};
  const TouchPoint moved[] = {{3, 500.0, 450.0}};
  c.touches(one);
  c.touches(moved);
  CHECK(s.y > y);
}

TEST_CASE("One key press moves by a fixed step whatever the frame time, held keys then move steadily, R resets",
          "[scene][camera]") {
  CameraState s{0.0, 0.0, 1000.0, 0.0, 60.0, 45.0};
  CameraController c(s);
  c.setViewport(1000.0, 800.0);
  c.setHome(s);
  // The same press at 60 frames per second and at 5: the same step (a tenth of the distance).
  for (const double frame : {1.0 / 60.0, 0.2}) {
    c.reset();
    c.key(Key::Up, true);
    CHECK(c.update(frame));
    c.key(Key::Up, false);
    CHECK(s.y == Approx(100.0));
    CHECK_FALSE(c.update(frame));
  }
  // Q then E: back where it started (15° each), at any frame time.
  c.reset();
  c.key(Key::TurnRight, true);
  c.update(0.1);
  c.key(Key::TurnRight, false);
  CHECK(s.headingDeg == Approx(15.0));
  c.key(Key::TurnLeft, true);
  c.update(0.01);
  c.key(Key::TurnLeft, false);
  CHECK(s.headingDeg == Approx(0.0).margin(1e-9));
  // + and = are the same key: one press zooms in by e^0.2, another press the same again.
  c.key(Key::ZoomIn, true);
  c.key(Key::ZoomIn, false);
  CHECK(s.distance == Approx(1000.0 * std::exp(-0.2)));
  c.key(Key::ZoomIn, true);
  c.key(Key::ZoomIn, true);  // the browser's auto-repeat: no second step
  c.key(Key::ZoomIn, false);
  CHECK(s.distance == Approx(1000.0 * std::exp(-0.4)));
  // Held for 1.35 s in frames of 0.05 s: the step, then 1 s of steady motion at half the distance per second.
  c.reset();
  c.key(Key::Up, true);
  for (int i = 0; i < 27; ++i) c.update(0.05);
  c.key(Key::Up, false);
  CHECK(s.y == Approx(100.0 + 500.0));
  c.key(Key::Reset, true);
  CHECK(s.y == 0.0);
  CHECK(s.headingDeg == 0.0);
}
