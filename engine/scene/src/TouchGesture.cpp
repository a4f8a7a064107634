#include "qv/scene/TouchGesture.h"

#include <cmath>

namespace qv {

TouchGestureState TouchGestureClassifier::update(std::span<const TouchPoint> touches, double timeSeconds) {
  const TouchGestureKind before = kind_;
  const bool starting = before == TouchGestureKind::None;
  if (touches.empty()) {
    // The last finger came up: a pending single finger that stayed put is a tap.
    const bool tap = before == TouchGestureKind::Pending && timeSeconds - startSeconds_ <= rules_.maxTapSeconds;
    kind_ = tap ? TouchGestureKind::Tap : TouchGestureKind::None;
  } else if (starting) {
    fingerId_ = touches[0].id;
    startX_ = touches[0].x;
    startY_ = touches[0].y;
    startSeconds_ = timeSeconds;
    kind_ = touches.size() > 1 ? TouchGestureKind::Pinch : TouchGestureKind::Pending;
  } else if (touches.size() > 1) {
    kind_ = TouchGestureKind::Pinch;
  } else if (before == TouchGestureKind::Pending) {
    // The same finger (a different id means the first came up and another went down in one
    // event: no longer a tap at the first finger's place).
    const TouchPoint& t = touches[0];
    const bool moved = t.id != fingerId_ || std::hypot(t.x - startX_, t.y - startY_) > rules_.slopCss;
    if (moved) kind_ = TouchGestureKind::Drag;
  }
  TouchGestureState state;
  state.kind = kind_;
  state.changed = kind_ != before || (starting && !touches.empty());
  state.startX = startX_;
  state.startY = startY_;
  state.heldSeconds = timeSeconds - startSeconds_;
  // A tap is reported once; the next event starts from nothing.
  if (kind_ == TouchGestureKind::Tap) kind_ = TouchGestureKind::None;
  return state;
}

}  // namespace qv
