// Decides what a touch gesture is: a tap (a press, as a mouse click), a one-finger drag (pan, or
// scroll over the UI) or a pinch (two or more fingers). The browser reports touch events with the
// full set of current touches; fed them in order, with their times, the classifier says what the
// gesture has become at each event. Pure: no browser API, tested natively.
//
// The rules (as in map apps):
//   - one finger that goes down and comes up without moving more than `slopCss` from where it
//     went down is a tap, at the point where it went down, however long it was held (unless
//     `maxTapSeconds` is set);
//   - one finger that moves more than `slopCss` is a drag from then on, until every finger is up;
//   - a second finger at any time makes the gesture a pinch until every finger is up: lifting
//     fingers never turns a pinch or a drag into a tap.
// Until a single finger has moved beyond the slop, nothing is decided (Pending): the caller
// should neither press the UI nor move the camera, so a tap does not also start a camera drag.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "qv/scene/CameraController.h"

namespace qv {

struct TapRules {
  /// Largest distance (CSS pixels) a finger may move from its start and still tap. Fingers
  /// wobble a few pixels on glass; 10 px is what Android's touch slop gives at 160 dpi scale.
  double slopCss = 10.0;
  /// Longest press that still counts as a tap, in seconds; infinity: any length.
  double maxTapSeconds = std::numeric_limits<double>::infinity();
};

enum class TouchGestureKind : std::uint8_t {
  None,     ///< no finger down, and the last gesture (if any) ended as a drag or pinch
  Pending,  ///< one finger down, not moved beyond the slop: not decided yet
  Drag,     ///< one finger down that moved beyond the slop (stays a drag until all are up)
  Pinch,    ///< two or more fingers down at some point of this gesture
  Tap,      ///< reported once, at the event on which the tapping finger came up
};

struct TouchGestureState {
  TouchGestureKind kind = TouchGestureKind::None;
  /// The gesture changed kind at this event (Pending -> Drag, Pending/Drag -> Pinch, -> Tap, ...).
  bool changed = false;
  /// Where the first finger went down (CSS pixels): the tap's point for Tap, the drag's start.
  double startX = 0.0, startY = 0.0;
  /// Seconds between the first finger down and this event.
  double heldSeconds = 0.0;
};

class TouchGestureClassifier {
 public:
  explicit TouchGestureClassifier(const TapRules& rules = {}) : rules_(rules) {}

  /// Feeds one touch event: `touches` is every finger down after it (empty when the last one
  /// came up), `timeSeconds` its time (any origin, non-decreasing). Returns what the gesture is now.
  TouchGestureState update(std::span<const TouchPoint> touches, double timeSeconds);

  /// The current gesture: as the last update returned it, except None after a Tap.
  [[nodiscard]] TouchGestureKind kind() const { return kind_; }

 private:
  TapRules rules_;
  TouchGestureKind kind_ = TouchGestureKind::None;
  std::int32_t fingerId_ = 0;
  double startX_ = 0.0, startY_ = 0.0, startSeconds_ = 0.0;
};

}  // namespace qv
