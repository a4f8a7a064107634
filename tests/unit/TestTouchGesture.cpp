#include <catch2/catch.hpp>

#include <vector>

#include "qv/scene/TouchGesture.h"

using namespace qv;

namespace {

// One touch event: the fingers down after it and its time.
struct Event {
  std::vector<TouchPoint> touches;
  double timeSeconds = 0.0;
};

// Feeds a sequence of events; returns the kind after each.
std::vector<TouchGestureKind> classify(const std::vector<Event>& events, const TapRules& rules = {}) {
  TouchGestureClassifier classifier(rules);
  std::vector<TouchGestureKind> kinds;
  for (const Event& e : events) kinds.push_back(classifier.update(e.touches, e.timeSeconds).kind);
  return kinds;
}

using K = TouchGestureKind;

}  // namespace

TEST_CASE("A finger that goes down and up in place is a tap at the point it went down", "[scene][touch]") {
  TouchGestureClassifier c;
  const TouchPoint down[] = {{7, 120.0, 300.0}};
  TouchGestureState s = c.update(down, 1.0);
  CHECK(s.kind == K::Pending);
  CHECK(s.changed);
  const TouchPoint wobble[] = {{7, 123.0, 304.0}};  // 5 px: a finger's wobble, within the slop
  s = c.update(wobble, 1.05);
  CHECK(s.kind == K::Pending);
  CHECK_FALSE(s.changed);
  s = c.update({}, 1.1);
  CHECK(s.kind == K::Tap);
  CHECK(s.changed);
  CHECK(s.startX == 120.0);
  CHECK(s.startY == 300.0);
  CHECK(s.heldSeconds == Approx(0.1));
  CHECK(c.kind() == K::None);  // reported once
}

TEST_CASE("Taps of any length count unless a longest tap is set", "[scene][touch]") {
  const std::vector<Event> longPress = {{{{1, 50.0, 50.0}}, 0.0}, {{}, 3.0}};
  CHECK(classify(longPress) == std::vector<K>{K::Pending, K::Tap});
  TapRules quick;
  quick.maxTapSeconds = 0.5;
  CHECK(classify(longPress, quick) == std::vector<K>{K::Pending, K::None});
  const std::vector<Event> shortPress = {{{{1, 50.0, 50.0}}, 0.0}, {{}, 0.2}};
  CHECK(classify(shortPress, quick) == std::vector<K>{K::Pending, K::Tap});
}

TEST_CASE("A finger that moves beyond the slop drags until it comes up, and is no tap", "[scene][touch]") {
  const std::vector<Event> events = {
      {{{1, 100.0, 100.0}}, 0.0},
      {{{1, 106.0, 100.0}}, 0.02},  // 6 px: still pending
      {{{1, 115.0, 100.0}}, 0.04},  // 15 px: a drag
      {{{1, 101.0, 100.0}}, 0.06},  // back near the start: still a drag
      {{}, 0.08},
  };
  CHECK(classify(events) == std::vector<K>{K::Pending, K::Pending, K::Drag, K::Drag, K::None});
  TapRules wide;
  wide.slopCss = 20.0;
  CHECK(classify(events, wide) == std::vector<K>{K::Pending, K::Pending, K::Pending, K::Pending, K::Tap});
}

TEST_CASE("A second finger makes a pinch, and lifting fingers never turns it into a tap", "[scene][touch]") {
  const std::vector<Event> events = {
      {{{1, 100.0, 100.0}}, 0.0},
      {{{1, 100.0, 100.0}, {2, 200.0, 100.0}}, 0.05},
      {{{1, 90.0, 100.0}, {2, 210.0, 100.0}}, 0.1},
      {{{2, 210.0, 100.0}}, 0.15},  // the first finger up
      {{}, 0.2},
  };
  CHECK(classify(events) == std::vector<K>{K::Pending, K::Pinch, K::Pinch, K::Pinch, K::None});
  // Two fingers landing in the same event, and a drag that gains a finger.
  CHECK(classify({{{{1, 0.0, 0.0}, {2, 50.0, 0.0}}, 0.0}, {{}, 0.1}}) == std::vector<K>{K::Pinch, K::None});
  CHECK(
      classify({{{{1, 0.0, 0.0}}, 0.0}, {{{1, 40.0, 0.0}}, 0.1}, {{{1, 40.0, 0.0}, {2, 90.0, 0.0}}, 0.2}, {{}, 0.3}}) ==
      std::vector<K>{K::Pending, K::Drag, K::Pinch, K::None});
}

TEST_CASE("Each gesture starts afresh: a tap after a drag, a drag after a tap", "[scene][touch]") {
  const std::vector<Event> events = {
      {{{1, 0.0, 0.0}}, 0.0},
      {{{1, 0.0, 80.0}}, 0.1},
      {{}, 0.2},  // drag
      {{{2, 10.0, 10.0}}, 1.0},
      {{}, 1.1},  // tap
      {{{3, 300.0, 10.0}}, 2.0},
      {{{3, 300.0, 40.0}}, 2.1},
      {{}, 2.2}  // drag
  };
  CHECK(classify(events) ==
        std::vector<K>{K::Pending, K::Drag, K::None, K::Pending, K::Tap, K::Pending, K::Drag, K::None});
  TouchGestureClassifier c;
  for (std::size_t i = 0; i < 4; ++i) c.update(events[i].touches, events[i].timeSeconds);
  const TouchGestureState tap = c.update({}, 1.1);
  CHECK(tap.startX == 10.0);  // the second gesture's start, not the first's
  CHECK(tap.heldSeconds == Approx(0.1));
}

TEST_CASE("A finger replaced by another in one event is not a tap where the first went down", "[scene][touch]") {
  CHECK(classify({{{{1, 0.0, 0.0}}, 0.0}, {{{2, 3.0, 0.0}}, 0.1}, {{}, 0.2}}) ==
        std::vector<K>{K::Pending, K::Drag, K::None});
}
