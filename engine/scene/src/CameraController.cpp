#include "qv/scene/CameraController.h"

#include <algorithm>
#include <cmath>

namespace qv {

namespace {
constexpr double kClickTolerancePixels = 4.0;
}

CameraController::CameraController(CameraState& state, const CameraLimits& limits)
    : state_(state), home_(state), limits_(limits) {}

void CameraController::setViewport(double widthCss, double heightCss) {
  width_ = std::max(1.0, widthCss);
  height_ = std::max(1.0, heightCss);
}

CameraView CameraController::view() const {
  return CameraView(state_, static_cast<int>(std::lround(width_)), static_cast<int>(std::lround(height_)), shiftNdcX_);
}

void CameraController::pointerDown(int button, double x, double y, bool shift, bool ctrl) {
  if (mode_ == Mode::Touch) return;
  dragButton_ = button;
  mode_ = (button == 0 && !shift && !ctrl) ? Mode::Pan : Mode::Orbit;
  lastX_ = downX_ = x;
  lastY_ = downY_ = y;
  movedBeyondClick_ = false;
}

void CameraController::pointerMove(double x, double y) {
  if (mode_ == Mode::Pan) {
    camera_gestures::pan(state_, view(), {lastX_, lastY_}, {x, y});
  } else if (mode_ == Mode::Orbit) {
    camera_gestures::orbit(state_, x - lastX_, y - lastY_, limits_);
  }
  if (std::hypot(x - downX_, y - downY_) > kClickTolerancePixels) movedBeyondClick_ = true;
  lastX_ = x;
  lastY_ = y;
}

void CameraController::pointerUp(int button) {
  if (button == dragButton_ && mode_ != Mode::Touch) {
    mode_ = Mode::None;
    dragButton_ = -1;
  }
}

void CameraController::wheel(double x, double y, double deltaY) {
  if (!std::isfinite(deltaY) || deltaY == 0.0) return;
  // 100 px of scroll (one notch in most browsers) zooms by about 20 %.
  const double factor = std::exp(std::clamp(deltaY, -500.0, 500.0) * 0.0018);
  camera_gestures::zoomAt(state_, view(), {x, y}, factor, limits_);
}

void CameraController::touches(std::span<const TouchPoint> points) {
  const int count = static_cast<int>(std::min<std::size_t>(points.size(), 2));
  if (count == 0) {
    if (mode_ == Mode::Touch) mode_ = Mode::None;
    lastTouchCount_ = 0;
    return;
  }
  mode_ = Mode::Touch;
  if (count == lastTouchCount_) {
    const CameraView v = view();
    if (count == 1) {
      camera_gestures::pan(state_, v, {lastTouches_[0].x, lastTouches_[0].y}, {points[0].x, points[0].y});
    } else {
      const TouchPoint& a0 = lastTouches_[0];
      const TouchPoint& b0 = lastTouches_[1];
      const TouchPoint& a1 = points[0];
      const TouchPoint& b1 = points[1];
      const double d0 = std::hypot(b0.x - a0.x, b0.y - a0.y);
      const double d1 = std::hypot(b1.x - a1.x, b1.y - a1.y);
      const double cx = 0.5 * (a1.x + b1.x), cy = 0.5 * (a1.y + b1.y);
      if (d0 > 1.0 && d1 > 1.0) camera_gestures::zoomAt(state_, v, {cx, cy}, d0 / d1, limits_);
      const double angle0 = std::atan2(b0.y - a0.y, b0.x - a0.x);
      const double angle1 = std::atan2(b1.y - a1.y, b1.x - a1.x);
      double turn = (angle1 - angle0) * 180.0 / 3.14159265358979323846;
      if (turn > 180.0) turn -= 360.0;
      if (turn < -180.0) turn += 360.0;
      // Both fingers moving vertically together tilts (as in map apps).
      const double dy = 0.5 * ((a1.y - a0.y) + (b1.y - b0.y));
      camera_gestures::orbit(state_, -turn * 4.0, dy, limits_);
    }
  }
  for (int i = 0; i < count; ++i) lastTouches_[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(i)];
  lastTouchCount_ = count;
}

namespace {

// Per key: the step of one press and the rate while held (units of CameraController::applyKey).
struct KeyMotion {
  double step;
  double perSecond;
};
constexpr double kKeyHoldDelaySeconds = 0.35;
constexpr KeyMotion kPan{0.1, 0.5}, kTurn{15.0, 90.0}, kTilt{5.0, 40.0}, kZoom{0.2, 1.5};

KeyMotion motionOf(Key k) {
  switch (k) {
    case Key::Left:
    case Key::Right:
    case Key::Up:
    case Key::Down:
      return kPan;
    case Key::TurnLeft:
    case Key::TurnRight:
      return kTurn;
    case Key::TiltUp:
    case Key::TiltDown:
      return kTilt;
    case Key::ZoomIn:
    case Key::ZoomOut:
      return kZoom;
    default:
      return {0.0, 0.0};
  }
}

}  // namespace

void CameraController::applyKey(Key k, double amount) {
  const double h = state_.headingDeg * 3.14159265358979323846 / 180.0;
  const double fx = std::sin(h), fy = std::cos(h);   // forward on the ground
  const double rx = std::cos(h), ry = -std::sin(h);  // right on the ground
  const double d = state_.distance * amount;
  const auto pan = [this, d](double dx, double dy) {
    state_.x += dx * d;
    state_.y += dy * d;
  };
  switch (k) {
    case Key::Up:
      pan(fx, fy);
      break;
    case Key::Down:
      pan(-fx, -fy);
      break;
    case Key::Right:
      pan(rx, ry);
      break;
    case Key::Left:
      pan(-rx, -ry);
      break;
    // orbit() takes pixels of drag, a quarter of a degree each.
    case Key::TurnRight:
      camera_gestures::orbit(state_, 4.0 * amount, 0.0, limits_);
      break;
    case Key::TurnLeft:
      camera_gestures::orbit(state_, -4.0 * amount, 0.0, limits_);
      break;
    case Key::TiltUp:
      camera_gestures::orbit(state_, 0.0, 4.0 * amount, limits_);
      break;
    case Key::TiltDown:
      camera_gestures::orbit(state_, 0.0, -4.0 * amount, limits_);
      break;
    case Key::ZoomOut:
    case Key::ZoomIn: {
      const double sign = k == Key::ZoomOut ? 1.0 : -1.0;
      state_.distance = std::clamp(state_.distance * std::exp(sign * amount), limits_.minDistance, limits_.maxDistance);
      break;
    }
    default:
      break;
  }
}

void CameraController::key(Key k, bool down) {
  if (k == Key::Count) return;
  const auto i = static_cast<std::size_t>(k);
  if (down && !held_[i]) {
    heldSeconds_[i] = 0.0;
    if (k == Key::Reset) {
      reset();
    } else {
      applyKey(k, motionOf(k).step);
    }
    keyMoved_ = true;
  }
  held_[i] = down;
}

bool CameraController::update(double dt) {
  dt = std::clamp(dt, 0.0, 0.1);
  bool moved = keyMoved_;
  keyMoved_ = false;
  for (std::size_t i = 0; i < held_.size(); ++i) {
    if (!held_[i]) continue;
    // The part of this frame after the hold delay moves at the steady rate.
    const double before = heldSeconds_[i];
    heldSeconds_[i] += dt;
    const double steady = heldSeconds_[i] - std::max(before, kKeyHoldDelaySeconds);
    const Key k = static_cast<Key>(i);
    if (steady > 0.0 && motionOf(k).perSecond > 0.0) {
      applyKey(k, motionOf(k).perSecond * steady);
      moved = true;
    }
  }
  return moved;
}

}  // namespace qv
