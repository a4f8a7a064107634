// Turns pointer, wheel, touch and keyboard input into map-style camera motion:
//   mouse: left drag pans the ground, right (or middle, or shift/ctrl + left) drag orbits,
//          wheel zooms about the cursor;
//   touch: one finger pans, two fingers pinch to zoom and twist to turn, move both up/down to tilt;
//   keys:  arrows / WASD pan, Q / E turn, PageUp / PageDown tilt, + / - zoom, R or Home resets.
//          One press moves by a fixed step, whatever the frame rate (pan a tenth of the view
//          distance, turn 15°, tilt 5°, zoom by e^0.2 ≈ 1.22); a key held longer than 0.35 s then
//          moves at a steady rate (half the distance, 90°, 40°, e^1.5 per second).
// Coordinates are CSS pixels relative to the canvas's top-left corner; the controller is told
// the viewport in the same units.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "qv/geometry/OrbitCamera.h"

namespace qv {

struct TouchPoint {
  std::int32_t id = 0;
  double x = 0.0;
  double y = 0.0;
};

enum class Key : std::uint8_t {
  Left,
  Right,
  Up,
  Down,
  TurnLeft,
  TurnRight,
  TiltUp,
  TiltDown,
  ZoomIn,
  ZoomOut,
  Reset,
  Count
};

class CameraController {
 public:
  CameraController(CameraState& state, const CameraLimits& limits = {});

  void setViewport(double widthCss, double heightCss);
  /// The lens shift of the view (CameraView's shiftNdcX): gestures act on the picture as shown.
  void setLensShift(float shiftNdcX) { shiftNdcX_ = shiftNdcX; }
  void setHome(const CameraState& home) { home_ = home; }
  [[nodiscard]] const CameraState& home() const { return home_; }

  /// button: 0 left, 1 middle, 2 right.
  void pointerDown(int button, double x, double y, bool shift, bool ctrl);
  void pointerMove(double x, double y);
  void pointerUp(int button);
  /// deltaY > 0 zooms out (browser wheel convention); deltaY is in CSS pixels of scroll.
  void wheel(double x, double y, double deltaY);
  /// The full set of current touches after any touch event.
  void touches(std::span<const TouchPoint> points);
  /// A key went down or up. A key that goes down (and was not already held: the browser's
  /// auto-repeat is ignored) moves the camera by its step at once.
  void key(Key key, bool down);
  /// Applies held keys for a frame of dtSeconds (their steady motion, after the hold delay);
  /// returns true if the camera moved since the last update (key steps included).
  bool update(double dtSeconds);
  void reset() { state_ = home_; }

  [[nodiscard]] bool dragging() const { return mode_ != Mode::None; }
  /// True between pointerDown and pointerUp when the pointer moved less than a click tolerance.
  [[nodiscard]] bool isClick() const { return !movedBeyondClick_; }

 private:
  enum class Mode { None, Pan, Orbit, Touch };
  [[nodiscard]] CameraView view() const;
  /// Moves for key k by `amount`: a fraction of the view distance (pan), degrees (turn, tilt) or
  /// a natural-log zoom factor.
  void applyKey(Key k, double amount);

  CameraState& state_;
  CameraState home_;
  CameraLimits limits_;
  double width_ = 1.0;
  double height_ = 1.0;
  float shiftNdcX_ = 0.0f;
  Mode mode_ = Mode::None;
  int dragButton_ = -1;
  double lastX_ = 0.0, lastY_ = 0.0, downX_ = 0.0, downY_ = 0.0;
  bool movedBeyondClick_ = false;
  std::array<TouchPoint, 2> lastTouches_{};
  int lastTouchCount_ = 0;
  std::array<bool, static_cast<std::size_t>(Key::Count)> held_{};
  std::array<double, static_cast<std::size_t>(Key::Count)> heldSeconds_{};
  bool keyMoved_ = false;  ///< a key step since the last update
};

}  // namespace qv
