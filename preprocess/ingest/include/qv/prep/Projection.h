// The city frame: GeographicLib's transverse Mercator on WGS84 with scale k0 = 1 and its central
// meridian through the origin, so distances near the city are true metres (plain Web Mercator
// would stretch them by 1/cos(latitude), 1.32 in New York). x points east, y north, in metres,
// (0, 0) is the origin. Double precision throughout.
#pragma once

#include <array>

#include <glm/vec2.hpp>

namespace qv::prep {

class CityProjection {
 public:
  /// Origin in degrees. Precondition: finite, |originLat| < 90, |originLon| <= 180 (asserted;
  /// callers validate user input first).
  CityProjection(double originLon, double originLat);

  [[nodiscard]] double originLon() const { return originLon_; }
  [[nodiscard]] double originLat() const { return originLat_; }

  /// Degrees (WGS84) to metres east/north of the origin. Accurate to nanometres within a few
  /// thousand kilometres of the central meridian (GeographicLib's Krüger series of order 6).
  [[nodiscard]] glm::dvec2 forward(double lon, double lat) const;
  /// Metres of the city frame to {lon, lat} in degrees.
  [[nodiscard]] std::array<double, 2> reverse(glm::dvec2 xy) const;

 private:
  double originLon_;
  double originLat_;
  double northingOfOriginM_;  ///< the TM northing of the origin (y is measured from it)
};

/// True for finite WGS84 degrees: |lat| <= 90 and |lon| <= 180.
bool validLonLat(double lon, double lat);

}  // namespace qv::prep
