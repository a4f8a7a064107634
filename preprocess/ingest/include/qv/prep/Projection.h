// The city frame for quakeview-prep: the viewer's projection (qv::GeoFrame, engine/geometry:
// transverse Mercator on WGS84, k0 = 1, central meridian through the origin; x east, y north, in
// metres from the origin) with preprocess's contract: input validated by the caller, so no
// optional results. Also a fast grid of it for the many points of one city.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/geometry/GeoFrame.h"

namespace qv::prep {

class CityProjection {
 public:
  /// Origin in degrees. Precondition: finite, |originLat| < 90, |originLon| <= 180 (asserted;
  /// callers validate user input first).
  CityProjection(double originLon, double originLat);

  [[nodiscard]] double originLon() const { return frame_.originLon(); }
  [[nodiscard]] double originLat() const { return frame_.originLat(); }

  /// Degrees (WGS84) to metres east/north of the origin (GeoFrame::forwardUnchecked). Accurate to
  /// nanometres within a few thousand kilometres of the central meridian.
  [[nodiscard]] glm::dvec2 forward(double lon, double lat) const { return frame_.forwardUnchecked({lon, lat}); }
  /// Metres of the city frame to {lon, lat} in degrees (GeoFrame::reverseUnchecked).
  [[nodiscard]] std::array<double, 2> reverse(glm::dvec2 xy) const;

 private:
  GeoFrame frame_;
};

/// CityProjection::forward for the many points of one city, fast: the exact values at the nodes of
/// a grid of kStepDegrees, bilinear interpolation in between (one exact projection costs about
/// 0.4 µs, an interpolation a few ns). The error of bilinear interpolation is at most h²/8 times
/// the second derivatives along lon and lat (the cross term is interpolated exactly), which on
/// WGS84 within 10° of the central meridian stay below about 1,000 m per square degree: 0.13 mm at
/// h = 0.001°, a tenth of the tiles' finest quantization step. make() measures the error at cell
/// centres and refuses a grid whose error exceeds kMaxErrorM.
class ProjectionGrid {
 public:
  static constexpr double kStepDegrees = 0.001;
  static constexpr double kMaxErrorM = 0.001;

  /// A grid covering [minLon, maxLon] × [minLat, maxLat] (degrees, valid), or nullopt when it would
  /// need more than `maxNodes` nodes or its measured error exceeds kMaxErrorM. Builds on up to
  /// `threads` threads.
  static std::optional<ProjectionGrid> make(const CityProjection& projection, double minLon, double minLat,
                                            double maxLon, double maxLat, std::size_t maxNodes, unsigned threads = 1);

  /// As CityProjection::forward, within the grid's box (points outside are extrapolated from the
  /// nearest cell: callers stay inside).
  [[nodiscard]] glm::dvec2 forward(double lon, double lat) const;
  /// The largest difference from the exact projection found at construction, metres.
  [[nodiscard]] double measuredErrorM() const { return measuredErrorM_; }
  [[nodiscard]] std::size_t nodes() const { return nodes_.size(); }

 private:
  ProjectionGrid() = default;
  double lon0_ = 0.0, lat0_ = 0.0;
  int columns_ = 0, rows_ = 0;
  std::vector<glm::dvec2> nodes_;  // row-major, row j at lat0_ + j × step
  double measuredErrorM_ = 0.0;
};

/// True for finite WGS84 degrees: |lat| <= 90 and |lon| <= 180.
bool validLonLat(double lon, double lat);

}  // namespace qv::prep
