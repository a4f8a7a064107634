#include "qv/quality/FrameGovernor.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace qv {

DetailScale detailScaleForStep(int step) {
  const int s = std::max(step, 0);
  DetailScale scale;
  scale.screenSpaceError = static_cast<float>(std::pow(1.5, s));
  scale.drawTiles = static_cast<float>(std::pow(0.75, s));
  scale.animationRadius = static_cast<float>(std::pow(0.75, s));
  scale.animatedBuildings = static_cast<float>(std::pow(0.5, s));
  return scale;
}

FrameGovernor::FrameGovernor(FrameGovernorOptions options) : options_(options) {}

double FrameGovernor::medianMs() const {
  if (frames_.empty()) return 0.0;
  std::vector<double> sorted(frames_.begin(), frames_.end());
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  return *middle;
}

void FrameGovernor::change(int delta, GovernorReason reason, double medianMs) {
  step_ += delta;
  reason_ = reason;
  lastChangeMedianMs_ = medianMs;
  frames_.clear();
  windowMs_ = 0.0;
  if (delta > 0) {
    steppedDown_ = true;
    sinceStepDownMs_ = 0.0;
  }
}

int FrameGovernor::addFrame(double frameMs) {
  if (!std::isfinite(frameMs) || frameMs < 0.0) return step_;
  frames_.push_back(frameMs);
  windowMs_ += frameMs;
  sinceStepDownMs_ += frameMs;
  const double windowMs = options_.windowSeconds * 1000.0;
  // Keep just enough of the newest frames to span the window.
  while (frames_.size() > 1 && windowMs_ - frames_.front() >= windowMs) {
    windowMs_ -= frames_.front();
    frames_.pop_front();
  }
  if (windowMs_ < windowMs) return step_;

  const double median = medianMs();
  if (median > options_.slowFrameMs && step_ < options_.maxStep) {
    change(+1, GovernorReason::TooSlow, median);
  } else if (median < options_.fastFrameMs && step_ > 0 &&
             (!steppedDown_ || sinceStepDownMs_ >= options_.raiseHoldSeconds * 1000.0)) {
    change(-1, GovernorReason::Headroom, median);
  }
  return step_;
}

void FrameGovernor::reset() {
  frames_.clear();
  windowMs_ = 0.0;
  sinceStepDownMs_ = 0.0;
  steppedDown_ = false;
  step_ = 0;
  reason_ = GovernorReason::Steady;
  lastChangeMedianMs_ = 0.0;
}

}  // namespace qv
