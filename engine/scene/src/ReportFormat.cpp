#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ReportParts.h"
#include "qv/core/Text.h"

namespace qv::report {

std::string esc(std::string_view raw) {
  const std::string text = isValidUtf8(raw) ? std::string(raw) : toValidUtf8(raw);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        // Control characters (other than tab and newline) are not text.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
          out += ' ';
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string fmt(const char* format, double value) {
  const int size = std::snprintf(nullptr, 0, format, value);
  if (size <= 0) return {};
  std::string out(static_cast<std::size_t>(size) + 1, '\0');
  std::snprintf(out.data(), out.size(), format, value);
  out.pop_back();
  return out;
}

/// Whole numbers with thousands separators ("12,345").
std::string grouped(double value) {
  if (!std::isfinite(value)) return "n/a";
  if (std::abs(value) >= 1e15) return fmt("%.3g", value);  // no file holds that many; say it, do not overflow
  const long long n = std::llround(value);
  std::string digits = std::to_string(n < 0 ? -n : n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return (n < 0 ? "-" : "") + out;
}

/// An expected count of buildings or people: one decimal under 10, whole numbers above.
std::string count(double value) {
  if (!std::isfinite(value)) return "n/a";
  if (std::abs(value) < 0.05) return "0";
  if (std::abs(value) < 10) return fmt("%.1f", value);
  return grouped(value);
}

std::string money(double usd) {
  if (!std::isfinite(usd)) return "n/a";
  if (usd >= 1e9) return fmt("$%.2f bn", usd / 1e9);
  if (usd >= 1e6) return fmt("$%.1f M", usd / 1e6);
  if (usd >= 1e3) return fmt("$%.0f k", usd / 1e3);
  return fmt("$%.0f", usd);
}

std::string percent(double p) {
  if (!std::isfinite(p)) return "n/a";
  if (p > 0 && p < 0.001) return "&lt;0.1 %";
  return fmt(p < 0.1 ? "%.1f %%" : "%.0f %%", 100 * p);
}

std::string range(const seismic::Estimate& e, bool isMoney) {
  if (!std::isfinite(e.low) || !std::isfinite(e.high)) return "not computed";
  return isMoney ? money(e.low) + " &ndash; " + money(e.high) : count(e.low) + " &ndash; " + count(e.high);
}

std::string hexColor(Rgb c) {
  const auto byte = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buffer;
}

/// P(structural DS = k), k 0..4, of the building at `i` (nullopt without probabilities).
std::optional<std::array<double, 5>> structuralOf(const ResponseSummaryTile* summary, std::size_t i) {
  if (summary == nullptr) return std::nullopt;
  if (i < summary->losses.size()) {
    const BuildingLoss& l = summary->losses[i];
    if (i < summary->buildings.size() && summary->buildings[i].damage == DamageState::NoResult) return std::nullopt;
    return std::array<double, 5>{l.structural[0], l.structural[1], l.structural[2], l.structural[3], l.structural[4]};
  }
  if (i < summary->odds.size()) {
    if (i < summary->buildings.size() && summary->buildings[i].damage == DamageState::NoResult) return std::nullopt;
    const BuildingDamageOdds& o = summary->odds[i];
    std::array<double, 5> p{};
    p[0] = 1.0 - o.atLeast[0];
    for (std::size_t k = 1; k < 4; ++k) p[k] = o.atLeast[k - 1] - o.atLeast[k];
    p[4] = o.atLeast[3];
    for (double& v : p) v = std::max(v, 0.0);
    return p;
  }
  return std::nullopt;
}

}  // namespace qv::report
