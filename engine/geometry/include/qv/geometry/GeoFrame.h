// The city frame's link to the Earth: the transverse Mercator projection (WGS84, scale factor 1)
// centred on the tileset origin (GeographicLib's Krüger series of order 6, accurate to nanometres
// within thousands of kilometres of the central meridian). Near the city distances are true
// metres (plain Web Mercator would stretch them by 1/cos(latitude), 1.32 in New York). x points
// east, y north, in metres, (0, 0) is the origin; double precision throughout. The one
// implementation of the projection: the viewer uses it, and quakeview-prep through
// qv::prep::CityProjection.
#pragma once

#include <optional>

#include <glm/vec2.hpp>

namespace qv {

struct LonLat {
  double lon = 0.0;  ///< degrees east
  double lat = 0.0;  ///< degrees north
};

class GeoFrame {
 public:
  /// Precondition checked: |originLon| <= 180, |originLat| < 85 (else the frame is invalid and
  /// every checked conversion returns nullopt).
  GeoFrame(double originLon, double originLat);

  [[nodiscard]] bool valid() const { return valid_; }
  [[nodiscard]] double originLon() const { return originLon_; }
  [[nodiscard]] double originLat() const { return originLat_; }

  /// Metres east/north of the origin for a point on the Earth; nullopt for invalid input.
  [[nodiscard]] std::optional<glm::dvec2> forward(LonLat point) const;
  /// The point on the Earth at metres east/north of the origin; nullopt for non-finite input or
  /// points more than 5000 km away (outside any city).
  [[nodiscard]] std::optional<LonLat> reverse(glm::dvec2 metres) const;

  /// forward and reverse without their range checks, for callers that validated their input
  /// (quakeview-prep). Preconditions: a finite origin with |originLon| <= 180 and |originLat| < 90
  /// (the origins up to 85° that valid() requires, and beyond); finite arguments. Outside them the
  /// results are unspecified (NaN).
  [[nodiscard]] glm::dvec2 forwardUnchecked(LonLat point) const;
  [[nodiscard]] LonLat reverseUnchecked(glm::dvec2 metres) const;

 private:
  double originLon_ = 0.0, originLat_ = 0.0;
  double northingOfOrigin_ = 0.0;  ///< the TM northing of the origin (y is measured from it)
  bool valid_ = false;
};

}  // namespace qv
