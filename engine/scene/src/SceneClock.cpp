#include "qv/scene/SceneClock.h"

#include <chrono>

namespace qv {

double SteadyClock::nowSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

SceneClock& steadyClock() {
  static SteadyClock clock;
  return clock;
}

}  // namespace qv
