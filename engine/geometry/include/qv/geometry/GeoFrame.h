// The city frame's link to the Earth: the transverse Mercator projection (WGS84, scale factor 1)
// centred on the tileset origin, as quakeview-prep projects the data (GeographicLib's Krüger
// series, accurate to nanometres within thousands of kilometres of the centre).
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
  /// every conversion returns nullopt).
  GeoFrame(double originLon, double originLat);

  [[nodiscard]] bool valid() const { return valid_; }
  /// Metres east/north of the origin for a point on the Earth; nullopt for invalid input.
  [[nodiscard]] std::optional<glm::dvec2> forward(LonLat point) const;
  /// The point on the Earth at metres east/north of the origin; nullopt for non-finite input or
  /// points more than 5000 km away (outside any city).
  [[nodiscard]] std::optional<LonLat> reverse(glm::dvec2 metres) const;

 private:
  double originLon_ = 0.0, originLat_ = 0.0;
  double northingOfOrigin_ = 0.0;
  bool valid_ = false;
};

}  // namespace qv
