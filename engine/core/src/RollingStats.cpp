#include "qv/core/RollingStats.h"

#include <algorithm>
#include <cmath>

namespace qv {

RollingStats::RollingStats(std::size_t capacity) : samples_(capacity > 0 ? capacity : 1, 0.0) {}

void RollingStats::add(double sample) {
  samples_[next_] = sample;
  next_ = (next_ + 1) % samples_.size();
  count_ = std::min(count_ + 1, samples_.size());
}

void RollingStats::clear() {
  next_ = 0;
  count_ = 0;
}

double RollingStats::percentile(double q) const {
  if (count_ == 0) return 0.0;
  std::vector<double> sorted;
  sorted.reserve(count_);
  // The kept samples are the last count_ written, ending just before next_.
  for (std::size_t i = 0; i < count_; ++i) {
    sorted.push_back(samples_[(next_ + samples_.size() - 1 - i) % samples_.size()]);
  }
  const double clamped = std::clamp(q, 0.0, 1.0);
  const auto rank = static_cast<std::size_t>(std::ceil(clamped * static_cast<double>(count_)));
  const std::size_t index = rank == 0 ? 0 : rank - 1;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(index), sorted.end());
  return sorted[index];
}

double RollingStats::last() const {
  if (count_ == 0) return 0.0;
  return samples_[(next_ + samples_.size() - 1) % samples_.size()];
}

}  // namespace qv
