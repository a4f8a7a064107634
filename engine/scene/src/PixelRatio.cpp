#include "qv/scene/PixelRatio.h"

#include <algorithm>
#include <cmath>

namespace qv {

double PixelRatioGovernor::update(double deviceRatio, double cssWidth, double frameSeconds) {
  const double device = std::isfinite(deviceRatio) && deviceRatio > 0.0 ? deviceRatio : 1.0;
  if (frameSeconds > 0.0 && std::isfinite(frameSeconds) && last_ > 0.0) {
    window_[count_++] = frameSeconds;
    if (count_ == window_.size()) {
      std::array<double, kWindowFrames> sorted = window_;
      std::nth_element(sorted.begin(), sorted.begin() + kWindowFrames / 2, sorted.end());
      // Only a ratio above the floor can step down; from where it is now, not from the device's.
      if (sorted[kWindowFrames / 2] > rules_.slowFrameSeconds && last_ > rules_.minRatio) {
        slowCap_ = std::max(rules_.minRatio, last_ - rules_.stepDown);
      }
      count_ = 0;
    }
  }
  const double widthCap = cssWidth < rules_.narrowWidthCss ? rules_.narrowMaxRatio : rules_.maxRatio;
  last_ = std::min({device, widthCap, slowCap_});
  return last_;
}

}  // namespace qv
