#include "qv/prep/Projection.h"

#include <cassert>
#include <cmath>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/TransverseMercator.hpp>

namespace qv::prep {
namespace {

/// One transverse Mercator for every origin: the central meridian is an argument of Forward and
/// Reverse. WGS84 with k0 = 1 (true scale on the central meridian). The constructor throws only for
/// invalid ellipsoid parameters, which these constants are not.
const GeographicLib::TransverseMercator& wgs84TransverseMercator() {
  static const GeographicLib::TransverseMercator tm(GeographicLib::Constants::WGS84_a(),
                                                    GeographicLib::Constants::WGS84_f(), 1.0);
  return tm;
}

}  // namespace

bool validLonLat(double lon, double lat) {
  return std::isfinite(lon) && std::isfinite(lat) && std::abs(lat) <= 90.0 && std::abs(lon) <= 180.0;
}

CityProjection::CityProjection(double originLon, double originLat)
    : originLon_(originLon), originLat_(originLat), northingOfOriginM_(0.0) {
  assert(validLonLat(originLon, originLat) && std::abs(originLat) < 90.0);
  double x = 0.0;
  wgs84TransverseMercator().Forward(originLon_, originLat_, originLon_, x, northingOfOriginM_);
}

glm::dvec2 CityProjection::forward(double lon, double lat) const {
  double x = 0.0;
  double y = 0.0;
  wgs84TransverseMercator().Forward(originLon_, lat, lon, x, y);
  return {x, y - northingOfOriginM_};
}

std::array<double, 2> CityProjection::reverse(glm::dvec2 xy) const {
  double lat = 0.0;
  double lon = 0.0;
  wgs84TransverseMercator().Reverse(originLon_, xy.x, xy.y + northingOfOriginM_, lat, lon);
  return {lon, lat};
}

}  // namespace qv::prep
