// RollingStats: median and 95th percentile of the most recent N samples (frame times, draw calls).
// Used for the figures `quakeview.stats()` reports, which must be robust to one slow frame.
#pragma once

#include <cstddef>
#include <vector>

namespace qv {

class RollingStats {
 public:
  /// capacity: number of most recent samples kept (> 0).
  explicit RollingStats(std::size_t capacity = 120);

  void add(double sample);
  void clear();

  [[nodiscard]] std::size_t count() const { return count_; }
  /// Median of the kept samples; 0 when there are none.
  [[nodiscard]] double median() const { return percentile(0.5); }
  /// q in [0, 1], nearest-rank percentile of the kept samples; 0 when there are none.
  [[nodiscard]] double percentile(double q) const;
  /// Most recent sample; 0 when there are none.
  [[nodiscard]] double last() const;

 private:
  std::vector<double> samples_;
  std::size_t next_ = 0;
  std::size_t count_ = 0;
};

}  // namespace qv
