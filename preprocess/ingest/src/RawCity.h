// Internal to prep::ingest: what the readers hand to the city builder. Features keep only the tags
// the product uses (docs/attributes.md "Tag streamlining") and their rings in degrees; the builder
// projects, cleans, attaches parts and infers attributes. The map under the buildings (streets,
// water, parks, place names: RawGround) is read beside them, in degrees too, and projected with
// the buildings' projection.
#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/core/Result.h"
#include "qv/prep/Attributes.h"
#include "qv/prep/CityModel.h"
#include "qv/prep/Ingest.h"

namespace qv::prep::detail {

/// The kept tags (raw text; parsed by the builder so that every garbage value is warned once, in
/// one place, whatever the input format).
struct RawTags {
  std::string building;      ///< building=* (OSM) or the use property (GeoJSON)
  std::string buildingPart;  ///< building:part=*
  std::string name;
  std::string height;
  std::string minHeight;
  std::string levels;
  std::string minLevel;
  std::string roofShape;
  std::string roofHeight;
  std::string material;
  std::string structure;
  std::string startDate;
  std::string amenity;
  std::string emergency;       ///< emergency=* (ambulance_station; folded into the amenity, normalizeFacility)
  std::string healthcare;      ///< healthcare=*
  std::string socialFacility;  ///< social_facility=*
  std::string power;           ///< power=* (plant, substation)
  std::string shop;            ///< shop=* (mall)
  std::string industrial;      ///< industrial=* (chemical, refinery, oil)
  std::string manMade;         ///< man_made=* (a part that is a mast, antenna or tower: not storeys)
  std::string towerType;       ///< tower:type=* (communication)
  std::string houseNumber;
  std::string street;
  std::string postcode;
  std::string city;
  std::string location;          ///< location=* ("underground")
  std::string layer;             ///< layer=* (negative: below ground)
  std::string occupants;         ///< GeoJSON occupants property (no OSM key)
  std::string replacementValue;  ///< GeoJSON replacement value property, USD (no OSM key)
};

enum class FeatureKind : std::uint8_t { Building, Part };

struct RawFeature {
  std::string id;  ///< w…, r…, g:…
  FeatureKind kind = FeatureKind::Building;
  LengthUnit plainUnit = LengthUnit::Meters;  ///< unit of plain numbers in height values
  /// GeoJSON features: the property names the values came from (for warnings); null for OSM.
  const IngestOptions* propertyNames = nullptr;
  RawTags tags;
  /// Rings of every polygon, outer ring first then its holes, as indices into RawCity::points
  /// (rings do not repeat their first point). ringEnds as in BuildingPart; polygonEnds[k] is one
  /// past the last ring of polygon k (an OSM multipolygon may have several outer rings).
  std::vector<std::uint32_t> points;
  std::vector<std::uint32_t> ringEnds;
  std::vector<std::uint32_t> polygonEnds;
};

/// A type=building relation: an outline and the parts it groups.
struct BuildingGroup {
  std::string relationId;
  std::string outlineId;
  std::vector<std::string> partIds;
};

/// Warnings with a per-kind count; the first kMaxMessages messages are kept verbatim.
struct WarningLog {
  static constexpr std::size_t kMaxMessages = 1000;
  std::vector<std::string> messages;
  std::map<std::string, std::uint64_t> counts;
  std::uint64_t total = 0;

  void add(const std::string& kind, std::string message) {
    ++counts[kind];
    ++total;
    if (messages.size() < kMaxMessages) messages.push_back(std::move(message));
  }
  void append(const WarningLog& other) {
    for (const auto& [kind, n] : other.counts) counts[kind] += n;
    total += other.total;
    for (const std::string& m : other.messages) {
      if (messages.size() >= kMaxMessages) break;
      messages.push_back(m);
    }
  }
};

/// Every footprint vertex once: lon/lat degrees as read, metres of the city frame after projection.
/// An OSM node shared by several rings (party walls of neighbours, parts on their outline: 226,098
/// references to 141,239 nodes in Lower Manhattan) is stored, and projected, once.
class PointTable {
 public:
  /// The index of the OSM location (x, y in units of 1e-7 degrees), added on first use.
  std::uint32_t addLocation(std::int32_t x, std::int32_t y, glm::dvec2 lonLat) {
    if (2 * (used_ + 1) > keys_.size()) grow();
    const std::uint64_t key = (std::uint64_t{static_cast<std::uint32_t>(x)} << 32) | static_cast<std::uint32_t>(y);
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t slot = hash(key) & mask;; slot = (slot + 1) & mask) {
      if (values_[slot] == kEmpty) {
        keys_[slot] = key;
        values_[slot] = add(lonLat);
        ++used_;
        return values_[slot];
      }
      if (keys_[slot] == key) return values_[slot];
    }
  }
  /// A point of its own (GeoJSON: no sharing is looked for).
  std::uint32_t add(glm::dvec2 lonLat) {
    points.push_back(lonLat);
    return static_cast<std::uint32_t>(points.size() - 1);
  }
  /// Forgets the lookup (the points stay): an OSM file's locations are not matched across files.
  void endFile() {
    keys_.clear();
    values_.clear();
    used_ = 0;
  }

  std::vector<glm::dvec2> points;

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;
  static std::size_t hash(std::uint64_t key) { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20); }
  void grow() {
    std::vector<std::uint64_t> keys = std::move(keys_);
    std::vector<std::uint32_t> values = std::move(values_);
    const std::size_t size = std::max<std::size_t>(1u << 16, keys.size() * 2);
    keys_.assign(size, 0);
    values_.assign(size, kEmpty);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (values[i] == kEmpty) continue;
      for (std::size_t slot = hash(keys[i]) & (size - 1);; slot = (slot + 1) & (size - 1)) {
        if (values_[slot] == kEmpty) {
          keys_[slot] = keys[i];
          values_[slot] = values[i];
          break;
        }
      }
    }
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t used_ = 0;
};

/// The ground features of the OSM inputs (docs/attributes.md "Ground features"), as GroundFeatures
/// holds them but in degrees: the builder projects them with the buildings' projection, which
/// they must not move (their points are kept apart from the buildings' PointTable). Empty when
/// IngestOptions::ground is off.
struct RawGround {
  struct Line {
    GroundClass groundClass = GroundClass::Street;
    float widthM = 6.0f;
    std::uint8_t rank = 128;
    std::string name;
    std::uint32_t begin = 0, end = 0;  ///< [begin, end) in points
  };
  struct Area {
    GroundClass groundClass = GroundClass::Park;
    std::uint8_t rank = 128;
    std::string name;
    std::uint32_t begin = 0;              ///< the first ring's first point
    std::vector<std::uint32_t> ringEnds;  ///< one past each ring's last point (outer ring, then holes)
  };
  struct Place {
    GroundLabelKind kind = GroundLabelKind::Neighbourhood;
    std::uint8_t rank = 64;
    std::string name;
    glm::dvec2 lonLat{0.0};
  };
  std::vector<glm::dvec2> points;  ///< degrees {lon, lat}, the shapes' points one after another
  std::vector<Line> lines;
  std::vector<Area> areas;
  std::vector<Place> places;
  struct Boundary {  ///< GroundBoundary in degrees
    std::string name;
    std::string source;
    int fineness = 0;
    std::uint32_t begin = 0;
    std::vector<std::uint32_t> ringEnds;
  };
  std::vector<Boundary> boundaries;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> coastlines;  ///< [begin, end) in points
  std::map<std::string, std::uint64_t> skipped;                     ///< as GroundFeatures::skipped
};

struct RawCity {
  PointTable points;
  std::deque<RawFeature> features;  ///< a deque: features never move once read
  std::vector<BuildingGroup> groups;
  DropCounts drops;
  WarningLog warnings;
  RawGround ground;
};

/// OSM XML / PBF (any libosmium input format) into `city`: buildings, and the ground features when
/// `options.ground` is on. Errors name the file and position; a broken ground feature is never an
/// error (it is counted in city.ground.skipped).
Status readOsmFile(const std::string& path, const IngestOptions& options, RawCity& city, IngestStats& stats);

/// A GeoJSON FeatureCollection into `city`. `ordinal` counts GeoJSON inputs from 0: index-based
/// ids of the second and later files are "g:<ordinal>.<index>" so merged files never collide.
Status readGeoJsonFile(const std::string& path, const IngestOptions& options, LengthUnit plainUnit, std::size_t ordinal,
                       RawCity& city, IngestStats& stats);

}  // namespace qv::prep::detail
