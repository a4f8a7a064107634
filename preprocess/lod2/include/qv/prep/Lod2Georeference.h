// Georeferencing of LOD2 models: a model's coordinate reference system (CityJSON's
// metadata.referenceSystem) is transformed to WGS84 longitude/latitude with PROJ (its C API, every
// call checked) and from there into the city frame (CityProjection). Heights are not transformed:
// each model's ground is its lowest vertex (docs/lod2.md "Heights").
//
// A placement (`--place LON,LAT[,ROTATION_DEG]`) instead puts a model set's footprint centre at a
// point of the city, rotated clockwise from north; it is how models of another city, or without
// a CRS, are brought into a city.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>

#include "qv/core/Result.h"

namespace qv::prep {

/// Where to put a model set: its footprint centre at (lon, lat) degrees WGS84, turned by
/// rotationDeg clockwise (seen from above) about that point, so the model's north points to
/// rotationDeg from true north.
struct Placement {
  double lon = 0.0;
  double lat = 0.0;
  double rotationDeg = 0.0;
};

/// Parses "LON,LAT" or "LON,LAT,ROTATION_DEG" (WGS84 degrees; rotation finite). Nullopt otherwise.
std::optional<Placement> parsePlacement(std::string_view text);

/// "EPSG:<code>" from the forms CityJSON files use for their CRS:
/// "https://www.opengis.net/def/crs/EPSG/0/7415" (1.1, 2.0; also http://), "urn:ogc:def:crs:EPSG::7415"
/// and "urn:ogc:def:crs:EPSG:6.18:3:7415" (1.0), "EPSG:7415". Empty when the text names no EPSG code.
std::string epsgFromReferenceSystem(std::string_view text);

/// Rotates (x, y) clockwise by degrees (north (0, 1) turned by 90 degrees points east (1, 0)).
glm::dvec2 rotateClockwise(glm::dvec2 xy, double degrees);

/// A horizontal transformation from one CRS to WGS84 longitude/latitude through PROJ. A compound
/// CRS (e.g. EPSG:7415 = RD New + NAP height) is split and only its horizontal part is used.
/// Not copyable; one instance is not thread-safe (it owns a PROJ context).
class CrsToLonLat {
 public:
  /// Creates the transformation for a CRS PROJ knows ("EPSG:28992", a WKT, ...). The error says the
  /// CRS and PROJ's reason.
  static Result<CrsToLonLat> create(const std::string& crs);

  CrsToLonLat(CrsToLonLat&&) noexcept;
  CrsToLonLat& operator=(CrsToLonLat&&) noexcept;
  ~CrsToLonLat();

  /// (easting, northing) or (lon, lat) of the source CRS, in its units, to {lon, lat} degrees.
  /// Nullopt when PROJ cannot transform the point (outside the CRS's domain, non-finite input).
  [[nodiscard]] std::optional<glm::dvec2> toLonLat(double x, double y) const;

  [[nodiscard]] bool geographic() const { return geographic_; }  ///< source axes are angles
  /// Metres per unit of the source's horizontal axes (projected CRS; 1 for geographic ones).
  [[nodiscard]] double horizontalMetresPerUnit() const { return horizontalMetresPerUnit_; }
  /// Metres per unit of heights: the vertical part of a compound CRS, else the horizontal unit of a
  /// projected CRS, else 1.
  [[nodiscard]] double verticalMetresPerUnit() const { return verticalMetresPerUnit_; }
  [[nodiscard]] const std::string& name() const { return name_; }  ///< PROJ's name of the CRS

 private:
  struct Impl;
  explicit CrsToLonLat(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  bool geographic_ = false;
  double horizontalMetresPerUnit_ = 1.0;
  double verticalMetresPerUnit_ = 1.0;
  std::string name_;
};

}  // namespace qv::prep
