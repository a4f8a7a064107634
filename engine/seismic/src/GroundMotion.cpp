#include "qv/seismic/GroundMotion.h"

#include <cmath>

namespace qv::seismic {

double metresPerSecond2Per(AccelerationUnit unit) {
  switch (unit) {
    case AccelerationUnit::G:
      return kGravityMps2;
    case AccelerationUnit::MetresPerSecond2:
      return 1.0;
    case AccelerationUnit::CentimetresPerSecond2:
      return 0.01;
  }
  return 1.0;
}

std::string_view accelerationUnitName(AccelerationUnit unit) {
  switch (unit) {
    case AccelerationUnit::G:
      return "g";
    case AccelerationUnit::MetresPerSecond2:
      return "m/s2";
    case AccelerationUnit::CentimetresPerSecond2:
      return "cm/s2";
  }
  return "?";
}

std::optional<AccelerationUnit> parseAccelerationUnit(std::string_view text) {
  if (text == "g" || text == "G") return AccelerationUnit::G;
  if (text == "m/s2" || text == "m/s^2" || text == "mps2") return AccelerationUnit::MetresPerSecond2;
  if (text == "cm/s2" || text == "cm/s^2" || text == "gal") return AccelerationUnit::CentimetresPerSecond2;
  return std::nullopt;
}

double GroundMotion::accelerationAt(double timeS) const {
  if (!(timeS > 0.0) || !(timeStepS > 0.0)) return 0.0;
  const double position = timeS / timeStepS;  // sample index in the 1-based convention
  const double n = static_cast<double>(size());
  if (position >= n + 1.0) return 0.0;
  const double below = std::floor(position);
  const double fraction = position - below;
  const auto k = static_cast<std::size_t>(below);  // a(k·dt): 0 at k = 0, sample k-1 (0-based) after
  const double left = k == 0 || k > size() ? 0.0 : accelerationMps2[k - 1];
  const double right = k >= size() ? 0.0 : accelerationMps2[k];
  return left + fraction * (right - left);
}

double GroundMotion::peakAbsMps2() const {
  double peak = 0.0;
  for (const double a : accelerationMps2) peak = std::fmax(peak, std::fabs(a));
  return peak;
}

std::size_t GroundMotion::peakIndex() const {
  std::size_t best = 0;
  for (std::size_t i = 1; i < size(); ++i) {
    if (std::fabs(accelerationMps2[i]) > std::fabs(accelerationMps2[best])) best = i;
  }
  return best;
}

}  // namespace qv::seismic
