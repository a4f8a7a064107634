// The map features of a city's input (streets, railways, water, parks, open land, coastline and
// place names) in the city frame, as the readers (OSM, synth-city) hand them to the ground tiler
// (qv/prep/GroundTiler.h). No geometry is cleaned here: the tiler validates, clips and skips
// (with a count by reason) what it cannot use.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/format/GroundTile.h"

namespace qv::prep {

/// A street, railway, river or path: a polyline drawn as a ribbon `widthM` wide.
struct GroundLine {
  GroundClass groundClass = GroundClass::Street;
  std::vector<glm::dvec2> points;  ///< city frame, metres; at least 2
  float widthM = 6.0f;             ///< full width on the ground
  std::string name;                ///< "" when unnamed (no label)
  std::uint8_t rank = 128;         ///< label importance (GroundLabel::rank)
};

/// A water body, park or open land: rings, the first the outer boundary (any orientation, closed
/// implicitly: the last point is not a copy of the first), then its holes.
struct GroundArea {
  GroundClass groundClass = GroundClass::Park;
  std::vector<std::vector<glm::dvec2>> rings;
  std::string name;
  std::uint8_t rank = 128;
};

/// A named place (OSM place=* node, or an area's label point).
struct GroundPlace {
  GroundLabelKind kind = GroundLabelKind::Neighbourhood;
  glm::dvec2 position{0.0};
  std::string name;
  std::uint8_t rank = 64;
};

/// An area the input draws as a boundary that may serve as a district (an administrative boundary,
/// a place's area): one outer ring and its holes, as GroundArea. Areas of several outer rings are
/// several boundaries of the same name and source. Not drawn on the map.
struct GroundBoundary {
  std::string name;
  /// What kind of boundary: "boundary=administrative admin_level=10", "place=neighbourhood", ...
  /// Boundaries of one source make one set of districts (prep::chooseDistricts).
  std::string source;
  /// How fine the source divides (larger: finer): admin_level, or the place's equivalent
  /// (city/town/village 8, borough 9, suburb 10, quarter 11, neighbourhood 12).
  int fineness = 0;
  std::vector<std::vector<glm::dvec2>> rings;
};

struct GroundFeatures {
  std::vector<GroundLine> lines;
  std::vector<GroundArea> areas;
  std::vector<GroundPlace> places;
  std::vector<GroundBoundary> boundaries;
  /// natural=coastline ways as read, land on their left (OSM's convention), in no particular
  /// order; the tiler joins them into land polygons. Empty when the input has no coastline.
  std::vector<std::vector<glm::dvec2>> coastlines;
  /// Objects the reader saw but could not use, by reason ("broken-multipolygon" -> 3).
  std::map<std::string, std::uint64_t> skipped;
  [[nodiscard]] bool empty() const { return lines.empty() && areas.empty() && places.empty() && coastlines.empty(); }
};

}  // namespace qv::prep
