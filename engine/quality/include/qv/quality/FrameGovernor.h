// The frame-time governor: when frames stay slow, the viewer draws less (a coarser level of
// detail, fewer tiles, a smaller animated area) one step at a time, and draws more again once
// there is headroom. Steps, not a continuous control: each change is visible and explained in the
// Performance panel, and the hysteresis keeps the picture from oscillating.
#pragma once

#include <cstdint>
#include <deque>

namespace qv {

struct FrameGovernorOptions {
  /// The frames judged together: those of the last `windowSeconds` of frame time.
  double windowSeconds = 2.0;
  /// Median frame time (ms) above which detail goes one step down (20 FPS).
  double slowFrameMs = 50.0;
  /// Median frame time (ms) below which detail goes one step back up (40 FPS): well under
  /// slowFrameMs, so that a step up which doubled the frame time does not come straight back.
  double fastFrameMs = 25.0;
  /// After a step down, no step up for this long (s): the cheaper step has to prove steady first.
  double raiseHoldSeconds = 10.0;
  /// Steps below the chosen preset: 0 (the preset as it is) .. maxStep.
  int maxStep = 3;
};

/// Why the step is what it is, for the Performance panel.
enum class GovernorReason : std::uint8_t {
  Steady,    ///< no change yet, or frames between the two thresholds
  TooSlow,   ///< the last change was a step down: the median frame time was above slowFrameMs
  Headroom,  ///< the last change was a step up: the median frame time was below fastFrameMs
};

/// What the detail settings are multiplied by at a governor step (see detailScaleForStep).
struct DetailScale {
  float screenSpaceError = 1.0f;  ///< allowed LOD error in pixels: larger is coarser
  float drawTiles = 1.0f;         ///< the draw-call budget for city tiles
  float animationRadius = 1.0f;   ///< the radius around the eye in which buildings move
  float animatedBuildings = 1.0f;
};

/// Step 0 is the preset unchanged; each further step allows 1.5× the screen-space error (about
/// half the triangles of the refined tiles), draws 3/4 of the tiles and animates within 3/4 of the
/// radius and 1/2 of the buildings. Negative steps are treated as 0.
[[nodiscard]] DetailScale detailScaleForStep(int step);

/// Feed it every frame's duration; it answers the step to draw at. Frame durations are wall-clock
/// milliseconds between frames (what the user sees), not engine CPU time. Not thread-safe.
class FrameGovernor {
 public:
  explicit FrameGovernor(FrameGovernorOptions options = {});

  /// Adds one frame (ms, >= 0; a negative or non-finite value is ignored) and returns the step
  /// to draw the next frame at. A change happens only when the frames kept span a full window;
  /// after a change the window starts empty, so each step is judged on its own frames.
  int addFrame(double frameMs);

  /// Back to step 0 with an empty window (the user chose a preset).
  void reset();

  [[nodiscard]] int step() const { return step_; }
  [[nodiscard]] GovernorReason reason() const { return reason_; }
  /// The median (ms) that caused the last change; 0 before any change.
  [[nodiscard]] double lastChangeMedianMs() const { return lastChangeMedianMs_; }
  /// The median (ms) of the frames in the current window; 0 when it is empty.
  [[nodiscard]] double medianMs() const;
  [[nodiscard]] const FrameGovernorOptions& options() const { return options_; }

 private:
  void change(int delta, GovernorReason reason, double medianMs);

  FrameGovernorOptions options_;
  std::deque<double> frames_;  // durations (ms) of the current window, oldest first
  double windowMs_ = 0.0;      // their sum
  double sinceStepDownMs_ = 0.0;
  bool steppedDown_ = false;
  int step_ = 0;
  GovernorReason reason_ = GovernorReason::Steady;
  double lastChangeMedianMs_ = 0.0;
};

}  // namespace qv
