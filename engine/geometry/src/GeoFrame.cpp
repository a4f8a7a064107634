#include "qv/geometry/GeoFrame.h"

#include <GeographicLib/TransverseMercator.hpp>

#include <cmath>

namespace qv {
namespace {

// Constructed once with the library's WGS84 constants: its constructor only throws for a
// non-positive radius or scale, which these are not.
const GeographicLib::TransverseMercator& projection() {
  static const GeographicLib::TransverseMercator tm(GeographicLib::Constants::WGS84_a(),
                                                    GeographicLib::Constants::WGS84_f(), 1.0);
  return tm;
}

}  // namespace

GeoFrame::GeoFrame(double originLon, double originLat) : originLon_(originLon), originLat_(originLat) {
  valid_ = std::isfinite(originLon) && std::isfinite(originLat) && std::abs(originLon) <= 180.0 &&
           std::abs(originLat) < 85.0;
  if (!valid_) return;
  double x = 0.0, y = 0.0;
  projection().Forward(originLon_, originLat_, originLon_, x, y);
  northingOfOrigin_ = y;
}

std::optional<glm::dvec2> GeoFrame::forward(LonLat p) const {
  if (!valid_ || !std::isfinite(p.lon) || !std::isfinite(p.lat) || std::abs(p.lat) >= 89.0 ||
      std::abs(p.lon - originLon_) > 60.0) {
    return std::nullopt;
  }
  double x = 0.0, y = 0.0;
  projection().Forward(originLon_, p.lat, p.lon, x, y);
  return glm::dvec2(x, y - northingOfOrigin_);
}

std::optional<LonLat> GeoFrame::reverse(glm::dvec2 m) const {
  if (!valid_ || !std::isfinite(m.x) || !std::isfinite(m.y) || std::abs(m.x) > 5.0e6 || std::abs(m.y) > 5.0e6) {
    return std::nullopt;
  }
  double lat = 0.0, lon = 0.0;
  projection().Reverse(originLon_, m.x, m.y + northingOfOrigin_, lat, lon);
  if (!std::isfinite(lat) || !std::isfinite(lon)) return std::nullopt;
  return LonLat{lon, lat};
}

}  // namespace qv
