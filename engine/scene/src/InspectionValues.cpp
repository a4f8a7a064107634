#include "qv/scene/InspectionValues.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace qv {
namespace {

constexpr double kMetresPerFoot = 0.3048;
constexpr double kMetresPerInch = 0.0254;

std::string printed(const char* fmt, double value, const char* unit) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value, unit);
  return buffer;
}

// -0 prints as "-0": a value that rounds to zero is shown without a sign.
double unsignedZero(double value, double resolution) {
  return std::abs(value) < 0.5 * resolution ? 0.0 : value;
}

}  // namespace

DisplayUnit displacementUnit(double metres, bool feet) {
  const double m = std::abs(metres);
  if (feet) {
    // Inches while the value, shown to one decimal, stays below a foot.
    if (std::isfinite(m) && m / kMetresPerInch < 11.95) return {"in", kMetresPerInch};
    return {"ft", kMetresPerFoot};
  }
  // Millimetres while the value, shown whole, stays below a metre.
  if (std::isfinite(m) && m * 1000.0 < 999.5) return {"mm", 0.001};
  return {"m", 1.0};
}

std::string displacementText(double metres, bool feet) {
  if (!std::isfinite(metres)) return "-";
  const DisplayUnit unit = displacementUnit(metres, feet);
  const double v = metres / unit.metresPerUnit;
  const double a = std::abs(v);
  if (feet) {
    if (unit.metresPerUnit == kMetresPerInch) {
      if (a < 0.995) return printed("%.2f %s", unsignedZero(v, 0.01), unit.name);
      return printed("%.1f %s", v, unit.name);
    }
    return printed("%.2f %s", v, unit.name);
  }
  if (unit.metresPerUnit == 0.001) {
    if (a == 0.0) return "0 mm";
    if (a < 9.95) return printed("%.1f %s", unsignedZero(v, 0.1), unit.name);
    return printed("%.0f %s", v, unit.name);
  }
  return printed("%.2f %s", v, unit.name);
}

std::string driftPercentText(double ratio) {
  if (!std::isfinite(ratio)) return "-";
  const double p = ratio * 100.0;
  if (p == 0.0) return "0.00 %";
  if (std::abs(p) < 0.0995) return printed("%.3f %s", unsignedZero(p, 0.001), "%");
  return printed("%.2f %s", p, "%");
}

std::vector<double> axisTicks(double low, double high, int maxTicks) {
  std::vector<double> ticks;
  if (!std::isfinite(low) || !std::isfinite(high) || !(high > low) || maxTicks < 1) return ticks;
  const double span = high - low;
  const double raw = span / static_cast<double>(maxTicks);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * p;
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * p >= raw * (1.0 - 1e-9)) {
      step = m * p;
      break;
    }
  }
  const double first = std::ceil(low / step - 1e-9);
  for (double k = first;; k += 1.0) {
    const double v = k * step;
    if (v > high + step * 1e-9) break;
    ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    if (ticks.size() > static_cast<std::size_t>(maxTicks) + 1) break;  // guards rounding
  }
  return ticks;
}

std::string tickLabel(double value, double step) {
  int decimals = 0;
  if (std::isfinite(step) && step > 0.0) {
    // Enough decimals for the step's leading digit ("0.25" for a step of 0.05 at 0.25 needs 2).
    decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
    if (std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-6) ++decimals;
  }
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, unsignedZero(value, std::pow(10.0, -decimals)));
  return buffer;
}

double storeyDriftScaleMax(const std::array<double, 4>& thresholds) {
  double top = 0.025;
  if (std::isfinite(thresholds[3])) top = std::max(top, thresholds[3]);
  return std::ceil(top / 0.005 - 1e-9) * 0.005;
}

double historyDriftErrorBound(double peakRoofDisplacementM, double storeyHeightM) {
  if (!(storeyHeightM > 0.0) || !std::isfinite(peakRoofDisplacementM)) return 0.0;
  return 2.0 * kHistoryRelativeErrorBound * std::abs(peakRoofDisplacementM) / storeyHeightM;
}

}  // namespace qv
