#include "qv/geometry/GeoFrame.h"

#include <GeographicLib/TransverseMercator.hpp>

#include <cmath>

namespace qv {
namespace {

// One transverse Mercator for every origin (the central meridian is an argument of Forward and
// Reverse), constructed once with the library's WGS84 constants: its constructor only throws for
// a non-positive radius or scale, which these are not.
const GeographicLib::TransverseMercator& projection() {
  static const GeographicLib::TransverseMercator tm(GeographicLib::Constants::WGS84_a(),
                                                    GeographicLib::Constants::WGS84_f(), 1.0);
  return tm;
}

}  // namespace

GeoFrame::GeoFrame(double originLon, double originLat) : originLon_(originLon), originLat_(originLat) {
  const bool finite = std::isfinite(originLon) && std::isfinite(originLat) && std::abs(originLon) <= 180.0;
  valid_ = finite && std::abs(originLat) < 85.0;
  // The unchecked conversions accept origins up to the poles (quakeview-prep's own checks apply).
  if (!finite || !(std::abs(originLat) < 90.0)) return;
  double x = 0.0, y = 0.0;
  projection().Forward(originLon_, originLat_, originLon_, x, y);
  northingOfOrigin_ = y;
}

std::optional<glm::dvec2> GeoFrame::forward(LonLat p) const {
  if (!valid_ || !std::isfinite(p.lon) || !std::isfinite(p.lat) || std::abs(p.lat) >= 89.0 ||
      std::abs(p.lon - originLon_) > 60.0) {
    return std::nullopt;
  }
  return forwardUnchecked(p);
}

std::optional<LonLat> GeoFrame::reverse(glm::dvec2 m) const {
  if (!valid_ || !std::isfinite(m.x) || !std::isfinite(m.y) || std::abs(m.x) > 5.0e6 || std::abs(m.y) > 5.0e6) {
    return std::nullopt;
  }
  const LonLat p = reverseUnchecked(m);
  if (!std::isfinite(p.lat) || !std::isfinite(p.lon)) return std::nullopt;
  return p;
}

glm::dvec2 GeoFrame::forwardUnchecked(LonLat p) const {
  double x = 0.0, y = 0.0;
  projection().Forward(originLon_, p.lat, p.lon, x, y);
  return glm::dvec2(x, y - northingOfOrigin_);
}

LonLat GeoFrame::reverseUnchecked(glm::dvec2 m) const {
  double lat = 0.0, lon = 0.0;
  projection().Reverse(originLon_, m.x, m.y + northingOfOrigin_, lat, lon);
  return LonLat{lon, lat};
}

}  // namespace qv
