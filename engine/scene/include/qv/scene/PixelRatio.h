// How many drawing-buffer pixels the canvas gets per CSS pixel. A phone reports a device pixel
// ratio of 3: its 390 x 844 CSS screen becomes a 1170 x 2532 buffer, 3 million pixels, and on a
// weak GPU (or software rendering) the frame time follows the pixels. The governor caps the ratio
// by screen width and steps it down while frames are slow. Pure: tested natively.
#pragma once

#include <array>
#include <cstddef>
#include <limits>

namespace qv {

struct PixelRatioRules {
  double maxRatio = 2.0;           ///< on any screen (beyond 2 the eye sees little difference)
  double narrowMaxRatio = 1.5;     ///< on narrow (phone) screens
  double narrowWidthCss = 600.0;   ///< a canvas narrower than this is a phone's
  double minRatio = 1.0;           ///< the governor never steps below this (nor above the device's)
  double slowFrameSeconds = 0.05;  ///< median frame interval above which the ratio steps down
  double stepDown = 0.25;          ///< each step down
};

class PixelRatioGovernor {
 public:
  /// Frames in the window whose median decides "slow" (about half a second at 60 FPS).
  static constexpr std::size_t kWindowFrames = 30;

  explicit PixelRatioGovernor(const PixelRatioRules& rules = {}) : rules_(rules) {}

  /// The ratio for this frame: the device's (a value <= 0 or not finite counts as 1), capped by
  /// the screen width's cap and by the governor's. `frameSeconds` is the interval since the last
  /// frame (<= 0 on the first). When the median of the last kWindowFrames intervals exceeds
  /// rules.slowFrameSeconds the governor's cap steps down (to at least minRatio) and a new window
  /// starts; the cap is never raised again, so the canvas does not resize back and forth.
  double update(double deviceRatio, double cssWidth, double frameSeconds);

  /// The governor's own cap so far (infinite until frames were slow).
  [[nodiscard]] double slowCap() const { return slowCap_; }

 private:
  PixelRatioRules rules_;
  std::array<double, kWindowFrames> window_{};
  std::size_t count_ = 0;
  double slowCap_ = std::numeric_limits<double>::infinity();
  double last_ = 0.0;  ///< the ratio returned last
};

}  // namespace qv
