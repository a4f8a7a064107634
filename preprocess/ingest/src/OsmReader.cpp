// OpenStreetMap input through libosmium, in one pass over the file.
//
// libosmium's usual multipolygon recipe (MultipolygonManager) reads the file twice: relations
// first, then nodes and ways. Parsing dominates the cost (XML especially), so this reader reads the
// file once instead: node locations go into a FlexMem index and are written into the ways as they
// stream past (NodeLocationsForWays), the input buffers that hold ways are kept (the relations come
// last and may use any way as a member; node-only buffers are released), and the building
// multipolygon relations are assembled at the end with the same libosmium area Assembler the
// manager would call, given the member ways looked up by id. Building and building:part ways are
// turned into features immediately.
//
// The map under the buildings (docs/attributes.md "Ground features") comes from the same pass when
// IngestOptions::ground is on: place nodes, street, railway and river ways, closed ways of water,
// parks and open land, and their multipolygons, assembled at the end like the buildings'. A ground
// object that cannot be used (a tunnel, a multipolygon whose rings do not close, a way of one
// node) is counted by reason in RawGround::skipped, never an error: it touches no building.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>

#include <osmium/area/assembler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/osm/area.hpp>
#include <osmium/osm/relation.hpp>
#include <osmium/osm/way.hpp>

#include "RawCity.h"

namespace qv::prep::detail {
namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;

constexpr std::size_t kMissingIdsShown = 5;

bool tagIs(const char* value, const char* wanted) {
  return value != nullptr && std::strcmp(value, wanted) == 0;
}
bool tagSet(const char* value) {
  return value != nullptr && std::strcmp(value, "no") != 0;
}

/// The kept tags (docs/attributes.md "Tag streamlining"); everything else is dropped here.
void keepTags(const osmium::TagList& tags, RawTags& out) {
  for (const osmium::Tag& tag : tags) {
    const std::string_view key = tag.key();
    const char* value = tag.value();
    std::string* slot = nullptr;
    switch (key.empty() ? '\0' : key.front()) {
      case 'a':
        if (key == "amenity") {
          slot = &out.amenity;
        } else if (key.starts_with("addr:")) {
          const std::string_view part = key.substr(5);
          if (part == "housenumber") slot = &out.houseNumber;
          if (part == "street") slot = &out.street;
          if (part == "postcode") slot = &out.postcode;
          if (part == "city") slot = &out.city;
        }
        break;
      case 'b':
        if (key == "building") slot = &out.building;
        if (key == "building:part") slot = &out.buildingPart;
        if (key == "building:levels") slot = &out.levels;
        if (key == "building:min_level") slot = &out.minLevel;
        if (key == "building:material") slot = &out.material;
        if (key == "building:structure") slot = &out.structure;
        break;
      case 'e':
        if (key == "emergency") slot = &out.emergency;
        break;
      case 'h':
        if (key == "height") slot = &out.height;
        if (key == "healthcare") slot = &out.healthcare;
        break;
      case 'i':
        if (key == "industrial") slot = &out.industrial;
        break;
      case 'p':
        if (key == "power") slot = &out.power;
        break;
      case 'l':
        if (key == "location") slot = &out.location;
        if (key == "layer") slot = &out.layer;
        break;
      case 'm':
        if (key == "min_height") slot = &out.minHeight;
        if (key == "man_made") slot = &out.manMade;
        break;
      case 'n':
        if (key == "name") slot = &out.name;
        break;
      case 'r':
        if (key == "roof:shape") slot = &out.roofShape;
        if (key == "roof:height") slot = &out.roofHeight;
        break;
      case 't':
        if (key == "tower:type") slot = &out.towerType;
        break;
      case 's':
        if (key == "start_date") slot = &out.startDate;
        if (key == "shop") slot = &out.shop;
        if (key == "social_facility") slot = &out.socialFacility;
        break;
      default:
        break;
    }
    if (slot != nullptr) slot->assign(value);
  }
}

glm::dvec2 lonLat(const osmium::Location& location) {
  return {location.lon_without_check(), location.lat_without_check()};
}

/// Appends a closed ring without its repeated last node (rings are closed implicitly from here on,
/// and one point fewer is one projection fewer).
template <typename TRing>
void appendRing(const TRing& ring, PointTable& table, RawFeature& feature) {
  auto end = ring.end();
  if (ring.size() > 1 && ring.front().location() == ring.back().location()) --end;
  for (auto it = ring.begin(); it != end; ++it) {
    const osmium::Location location = it->location();
    feature.points.push_back(table.addLocation(location.x(), location.y(), lonLat(location)));
  }
  feature.ringEnds.push_back(static_cast<std::uint32_t>(feature.points.size()));
}

// ---- Ground features (docs/attributes.md "Ground features").

/// The values of the keys the ground reads, found in one pass over a tag list (null when absent).
struct GroundTags {
  const char* highway = nullptr;
  const char* railway = nullptr;
  const char* waterway = nullptr;
  const char* natural = nullptr;
  const char* landuse = nullptr;
  const char* leisure = nullptr;
  const char* place = nullptr;
  const char* name = nullptr;
  const char* width = nullptr;
  const char* tunnel = nullptr;
  const char* area = nullptr;
  const char* boundary = nullptr;
  const char* adminLevel = nullptr;

  static GroundTags read(const osmium::TagList& tags) {
    static constexpr std::pair<std::string_view, const char * GroundTags::*> kKeys[] = {
        {"highway", &GroundTags::highway},
        {"railway", &GroundTags::railway},
        {"waterway", &GroundTags::waterway},
        {"natural", &GroundTags::natural},
        {"landuse", &GroundTags::landuse},
        {"leisure", &GroundTags::leisure},
        {"place", &GroundTags::place},
        {"name", &GroundTags::name},
        {"width", &GroundTags::width},
        {"tunnel", &GroundTags::tunnel},
        {"area", &GroundTags::area},
        {"boundary", &GroundTags::boundary},
        {"admin_level", &GroundTags::adminLevel},
    };
    GroundTags t;
    for (const osmium::Tag& tag : tags) {
      const std::string_view key = tag.key();
      for (const auto& [wanted, member] : kKeys) {
        if (key == wanted) {
          t.*member = tag.value();
          break;
        }
      }
    }
    return t;
  }
  [[nodiscard]] bool underground() const { return tagSet(tunnel); }
  [[nodiscard]] std::string nameText() const { return name != nullptr ? std::string(name) : std::string(); }
};

/// How a street, railway or river is drawn: class, default width and label rank.
struct LineStyle {
  GroundClass groundClass;
  float widthM;
  std::uint8_t rank;
};

/// A value of a key and what it draws.
template <typename T>
struct StyleRow {
  std::string_view value;
  T style;
};

constexpr StyleRow<LineStyle> kHighways[] = {
    {"motorway", {GroundClass::Motorway, 20.0f, 16}},
    {"motorway_link", {GroundClass::Motorway, 20.0f, 112}},
    {"trunk", {GroundClass::Major, 14.0f, 24}},
    {"trunk_link", {GroundClass::Major, 14.0f, 112}},
    {"primary", {GroundClass::Major, 14.0f, 32}},
    {"primary_link", {GroundClass::Major, 14.0f, 112}},
    {"secondary", {GroundClass::Major, 12.0f, 48}},
    {"secondary_link", {GroundClass::Major, 12.0f, 120}},
    {"tertiary", {GroundClass::Street, 10.0f, 64}},
    {"tertiary_link", {GroundClass::Street, 10.0f, 128}},
    {"residential", {GroundClass::Street, 8.0f, 96}},
    {"unclassified", {GroundClass::Street, 8.0f, 104}},
    {"living_street", {GroundClass::Street, 8.0f, 104}},
    {"service", {GroundClass::Street, 5.0f, 176}},
    {"pedestrian", {GroundClass::Path, 3.0f, 136}},
    {"footway", {GroundClass::Path, 3.0f, 192}},
    {"path", {GroundClass::Path, 3.0f, 200}},
    {"cycleway", {GroundClass::Path, 3.0f, 192}},
    {"steps", {GroundClass::Path, 3.0f, 224}},
    {"track", {GroundClass::Path, 3.0f, 208}},
};
constexpr StyleRow<LineStyle> kRailways[] = {
    {"rail", {GroundClass::Rail, 4.0f, 160}},
    {"light_rail", {GroundClass::Rail, 4.0f, 168}},
    {"narrow_gauge", {GroundClass::Rail, 4.0f, 168}},
    {"tram", {GroundClass::Rail, 4.0f, 184}},
};
constexpr StyleRow<LineStyle> kWaterways[] = {
    {"river", {GroundClass::Water, 30.0f, 40}},
    {"canal", {GroundClass::Water, 15.0f, 80}},
    {"stream", {GroundClass::Water, 4.0f, 152}},
};

template <typename T, std::size_t N>
std::optional<T> lookUp(const StyleRow<T> (&rows)[N], const char* value) {
  if (value == nullptr) return std::nullopt;
  for (const StyleRow<T>& row : rows) {
    if (row.value == value) return row.style;
  }
  return std::nullopt;
}

/// Label ranks of areas by class (areas are labelled by their names: lakes and parks).
std::uint8_t areaRank(GroundClass c) {
  switch (c) {
    case GroundClass::Water:
      return 56;
    case GroundClass::Park:
      return 112;
    case GroundClass::Forest:
      return 160;
    default:
      return 176;
  }
}

/// The area class of a closed way or multipolygon from its tags, or nullopt. Water first (a lake
/// in a park is water), then parks, forest and open land.
std::optional<GroundClass> areaClass(const GroundTags& t) {
  auto in = [](const char* value, std::initializer_list<std::string_view> values) {
    return value != nullptr && std::find(values.begin(), values.end(), std::string_view(value)) != values.end();
  };
  if (in(t.natural, {"water"}) || in(t.waterway, {"riverbank", "dock"}) || in(t.landuse, {"reservoir", "basin"}))
    return GroundClass::Water;
  if (in(t.leisure, {"park", "garden", "playground", "nature_reserve"})) return GroundClass::Park;
  if (in(t.landuse, {"forest"}) || in(t.natural, {"wood", "scrub"})) return GroundClass::Forest;
  if (in(t.landuse, {"grass", "meadow", "recreation_ground", "cemetery", "village_green"}) ||
      in(t.leisure, {"pitch", "golf_course"}))
    return GroundClass::Green;
  return std::nullopt;
}

/// The kind and label rank of place=*, or nullopt for the values the map does not name.
std::optional<std::pair<GroundLabelKind, std::uint8_t>> placeKind(const char* place) {
  static constexpr StyleRow<std::pair<GroundLabelKind, std::uint8_t>> kPlaces[] = {
      {"city", {GroundLabelKind::Settlement, 4}},        {"town", {GroundLabelKind::Settlement, 20}},
      {"village", {GroundLabelKind::Settlement, 44}},    {"hamlet", {GroundLabelKind::Settlement, 72}},
      {"borough", {GroundLabelKind::Neighbourhood, 36}}, {"suburb", {GroundLabelKind::Neighbourhood, 52}},
      {"quarter", {GroundLabelKind::Neighbourhood, 68}}, {"neighbourhood", {GroundLabelKind::Neighbourhood, 84}},
  };
  return lookUp(kPlaces, place);
}

/// What an area of these tags is as a district (GroundBoundary::source and fineness), or nullopt:
/// an administrative boundary with its admin_level, a place's area, a boundary=place without
/// place=* (a neighbourhood's outline). Unnamed areas are none.
std::optional<std::pair<std::string, int>> districtSource(const GroundTags& t) {
  if (t.name == nullptr || *t.name == '\0') return std::nullopt;
  if (tagIs(t.boundary, "administrative") && t.adminLevel != nullptr) {
    int level = 0;
    const std::string_view text(t.adminLevel);
    const auto [at, ec] = std::from_chars(text.data(), text.data() + text.size(), level);
    if (ec != std::errc() || at != text.data() + text.size() || level < 1 || level > 12) return std::nullopt;
    return std::pair{"boundary=administrative admin_level=" + std::to_string(level), level};
  }
  static constexpr StyleRow<int> kPlaceFineness[] = {
      {"city", 8}, {"town", 8}, {"village", 8}, {"borough", 9}, {"suburb", 10}, {"quarter", 11}, {"neighbourhood", 12},
  };
  if (const auto fineness = lookUp(kPlaceFineness, t.place))
    return std::pair{"place=" + std::string(t.place), *fineness};
  if (tagIs(t.boundary, "place") && t.place == nullptr) return std::pair{std::string("boundary=place"), 12};
  return std::nullopt;
}

/// width=* in metres when it is a plain number (a trailing " m" or "m" allowed) from 1 to 100;
/// anything else (feet, "3,5", "narrow", typos) leaves the class's width.
std::optional<float> widthTag(const char* value) {
  if (value == nullptr) return std::nullopt;
  std::string_view text(value);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.ends_with("m")) text.remove_suffix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  double v = 0.0;
  const auto [at, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || at != text.data() + text.size() || !std::isfinite(v) || v < 1.0 || v > 100.0)
    return std::nullopt;
  return static_cast<float>(v);
}

/// The area-weighted centroid of a ring in degrees (an affine map of the city frame's over a
/// city's extent, so the same point), or its mean where it encloses nothing.
glm::dvec2 ringCentroid(const std::vector<glm::dvec2>& ring, double& twiceArea) {
  glm::dvec2 sum{0.0};
  twiceArea = 0.0;
  if (ring.empty()) return sum;
  const glm::dvec2 o = ring.front();  // relative to the first point: fewer cancellations
  glm::dvec2 weighted{0.0};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const glm::dvec2 p = ring[i] - o;
    const glm::dvec2 q = ring[(i + 1) % ring.size()] - o;
    const double c = p.x * q.y - q.x * p.y;
    twiceArea += c;
    weighted += (p + q) * c;
    sum += ring[i];
  }
  if (std::abs(twiceArea) > 1e-18) return o + weighted / (3.0 * twiceArea);
  return sum / static_cast<double>(ring.size());
}

/// Node references whose node is not in the file, for one error message per file.
struct MissingNodes {
  std::uint64_t count = 0;
  std::uint64_t objects = 0;
  std::string firstIds;
  std::size_t shown = 0;

  /// Records the missing nodes of `way` (used by `user`, "w12" or "r34"); false when none.
  bool check(const osmium::Way& way, const std::string& user) {
    bool any = false;
    for (const osmium::NodeRef& node : way.nodes()) {
      if (node.location().valid()) continue;
      any = true;
      ++count;
      if (shown < kMissingIdsShown) {
        if (!firstIds.empty()) firstIds += ", ";
        firstIds += "n" + std::to_string(node.ref()) + " in " + user;
        ++shown;
      }
    }
    if (any) ++objects;
    return any;
  }
};

class OsmReader {
 public:
  OsmReader(const std::string& path, const IngestOptions& options, RawCity& city, IngestStats& stats)
      : path_(path), ground_(options.ground), city_(city), stats_(stats) {}

  Status run() {
    std::unique_ptr<osmium::io::Reader> reader;
    try {
      const osmium::io::File file{path_};
      if (file.format() == osmium::io::file_format::unknown)
        return fail(path_ + ": not an OSM file name (expected .osm, .osm.bz2, .osm.gz or .osm.pbf)");
      // Nodes, ways and relations without their metadata (versions, timestamps, users: unused here),
      // which libosmium then does not decode.
      reader = std::make_unique<osmium::io::Reader>(file, osmium::osm_entity_bits::nwr, osmium::io::read_meta::no);
      LocationIndex index;
      osmium::handler::NodeLocationsForWays<LocationIndex> locations{index};
      locations.ignore_errors();  // missing nodes leave invalid locations; counted below
      while (osmium::memory::Buffer buffer = reader->read()) {
        bool hasWays = false;
        for (osmium::memory::Item& item : buffer) {
          switch (item.type()) {
            case osmium::item_type::node: {
              ++stats_.osmNodes;
              const auto& node = static_cast<const osmium::Node&>(item);
              locations.node(node);
              if (ground_ && !node.tags().empty()) takeGroundNode(node);
              break;
            }
            case osmium::item_type::way: {
              auto& way = static_cast<osmium::Way&>(item);
              locations.way(way);
              ways_.emplace_back(way.id(), &way);
              takeWay(way);
              hasWays = true;
              break;
            }
            case osmium::item_type::relation:
              takeRelation(static_cast<const osmium::Relation&>(item));
              break;
            default:
              break;
          }
        }
        // Relations come last and may use any way as a member: buffers holding ways are kept (their
        // memory does not move when the Buffer object does), node-only buffers are released.
        if (hasWays) wayBuffers_.push_back(std::move(buffer));
      }
      reader->close();
      assembleRelations();
      city_.points.endFile();
    } catch (const osmium::xml_error& e) {
      if (e.line > 0)
        return fail(path_ + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) +
                    ": not valid OSM XML: " + e.error_string);
      return fail(path_ + ": not valid OSM XML: " + e.what());
    } catch (const osmium::opl_error& e) {
      return fail(path_ + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) + ": " + e.what());
    } catch (const osmium::pbf_error& e) {
      return fail(path_ + ": corrupt or truncated PBF " + where(reader.get()) + ": " + e.what());
    } catch (const std::system_error& e) {
      return fail(path_ + ": cannot read: " + e.code().message());
    } catch (const std::bad_alloc&) {
      return fail(path_ + ": out of memory while reading " + where(reader.get()));
    } catch (const std::exception& e) {
      return fail(path_ + ": cannot read " + where(reader.get()) + ": " + e.what());
    }
    if (missing_.count > 0) {
      return fail(path_ + ": " + std::to_string(missing_.count) + " node reference" + (missing_.count == 1 ? "" : "s") +
                  " of " + std::to_string(missing_.objects) +
                  " building way(s) point to nodes missing from the file (first: " + missing_.firstIds +
                  "); the extract is incomplete: cut it with `osmium extract --strategy complete_ways`");
    }
    return {};
  }

 private:
  static Error fail(std::string message) { return Error{std::move(message)}; }

  static std::string where(const osmium::io::Reader* reader) {
    if (reader == nullptr || reader->file_size() == 0) return "(at the start)";
    return "(near byte " + std::to_string(reader->offset()) + " of " + std::to_string(reader->file_size()) + ")";
  }

  void takeWay(const osmium::Way& way) {
    const osmium::TagList& tags = way.tags();
    const bool isBuilding = tagSet(tags.get_value_by_key("building"));
    const bool isPart = !isBuilding && tagSet(tags.get_value_by_key("building:part"));
    if (!isBuilding && !isPart) {
      if (ground_ && !tags.empty()) takeGroundWay(way);
      return;
    }
    if (isBuilding) {
      ++stats_.osmWays;
    } else {
      ++stats_.osmPartObjects;
    }
    const std::string id = "w" + std::to_string(way.id());
    if (missing_.check(way, id)) return;
    // libosmium's is_closed() reads the last node: undefined for a way without nodes.
    if (way.nodes().empty()) {
      city_.drops.add("too-few-points");
      return;
    }
    if (!way.is_closed()) {
      city_.drops.add("not-closed");
      return;
    }
    if (way.nodes().size() < 4) {
      city_.drops.add("too-few-points");
      return;
    }
    RawFeature feature;
    feature.id = id;
    feature.kind = isBuilding ? FeatureKind::Building : FeatureKind::Part;
    keepTags(tags, feature.tags);
    feature.points.reserve(way.nodes().size() - 1);
    appendRing(way.nodes(), city_.points, feature);
    feature.polygonEnds.push_back(1);
    city_.features.push_back(std::move(feature));
  }

  void takeRelation(const osmium::Relation& relation) {
    const osmium::TagList& tags = relation.tags();
    const char* type = tags.get_value_by_key("type");
    if (tagIs(type, "building")) {
      ++stats_.osmTypeBuildingRelations;
      BuildingGroup group;
      group.relationId = "r" + std::to_string(relation.id());
      for (const osmium::RelationMember& member : relation.members()) {
        if (member.type() != osmium::item_type::way && member.type() != osmium::item_type::relation) continue;
        std::string memberId = (member.type() == osmium::item_type::way ? "w" : "r") + std::to_string(member.ref());
        if (std::strcmp(member.role(), "outline") == 0 && group.outlineId.empty())
          group.outlineId = std::move(memberId);
        else if (std::strcmp(member.role(), "part") == 0)
          group.partIds.push_back(std::move(memberId));
      }
      city_.groups.push_back(std::move(group));
      return;
    }
    const bool multipolygon = tagIs(type, "multipolygon");
    const bool isBuilding = multipolygon && tagSet(tags.get_value_by_key("building"));
    const bool isPart = multipolygon && !isBuilding && tagSet(tags.get_value_by_key("building:part"));
    if (!isBuilding && !isPart) {
      // Water, parks and open land are multipolygons; a place's area may be a boundary relation too
      // (type=boundary, boundary=place). Routes, sites and the rest are not ground.
      if (ground_ && (multipolygon || tagIs(type, "boundary"))) {
        const GroundTags t = GroundTags::read(tags);
        if ((multipolygon && areaClass(t)) || (t.name != nullptr && placeKind(t.place)) || districtSource(t)) {
          relationStore_.add_item(relation);
          relationStore_.commit();
        }
      }
      return;
    }
    if (isBuilding) {
      ++stats_.osmRelations;
    } else {
      ++stats_.osmPartObjects;
    }
    relationStore_.add_item(relation);
    relationStore_.commit();
  }

  const osmium::Way* findWay(osmium::object_id_type id) const {
    const auto it = std::lower_bound(ways_.begin(), ways_.end(), id,
                                     [](const auto& entry, osmium::object_id_type key) { return entry.first < key; });
    if (it == ways_.end() || it->first != id) return nullptr;
    return it->second;
  }

  void assembleRelations() {
    // Sorted files (the norm: osmium, planet extracts) are already in id order.
    auto byId = [](const auto& a, const auto& b) { return a.first < b.first; };
    if (!std::is_sorted(ways_.begin(), ways_.end(), byId)) std::stable_sort(ways_.begin(), ways_.end(), byId);
    osmium::area::AssemblerConfig config;
    config.create_way_polygons = false;
    config.create_empty_areas = false;  // a failed assembly returns false instead of an empty area
    std::vector<const osmium::Way*> members;
    for (const osmium::Relation& relation : relationStore_.select<osmium::Relation>()) {
      const bool isBuilding = tagSet(relation.tags().get_value_by_key("building"));
      if (!isBuilding && !tagSet(relation.tags().get_value_by_key("building:part"))) {
        assembleGroundRelation(relation, config);
        continue;
      }
      const std::string id = "r" + std::to_string(relation.id());
      members.clear();
      std::size_t missingWays = 0;
      std::size_t outers = 0;
      std::size_t outersThatAreBuildings = 0;
      bool missingNodes = false;
      for (const osmium::RelationMember& member : relation.members()) {
        if (member.type() != osmium::item_type::way) continue;
        const osmium::Way* way = findWay(member.ref());
        if (way == nullptr) {
          ++missingWays;
          continue;
        }
        members.push_back(way);
        missingNodes = missing_.check(*way, id) || missingNodes;
        if (std::strcmp(member.role(), "inner") != 0) {
          ++outers;
          if (!way->nodes().empty() && way->is_closed() && tagSet(way->tags().get_value_by_key("building"))) {
            ++outersThatAreBuildings;
          }
        }
      }
      if (missingNodes) continue;
      if (missingWays > 0 || members.empty()) {
        city_.drops.add("incomplete-relation");
        city_.warnings.add("multipolygon with member ways missing from the file",
                           id + ": " + std::to_string(missingWays) + " member way(s) missing from the file; skipped");
        continue;
      }
      // A building multipolygon whose every outer ring is already a building way of its own (one
      // building mapped twice): the ways carry the details, the relation adds nothing but a copy.
      if (isBuilding && outers > 0 && outersThatAreBuildings == outers) {
        city_.drops.add("duplicate-outline");
        continue;
      }
      osmium::memory::Buffer areaBuffer{1024, osmium::memory::Buffer::auto_grow::yes};
      osmium::area::Assembler assembler{config};
      const bool ok = assembler(relation, members, areaBuffer);
      if (!ok || areaBuffer.committed() == 0) {
        city_.drops.add("invalid-multipolygon");
        continue;
      }
      const osmium::Area& area = areaBuffer.get<const osmium::Area>(0);
      RawFeature feature;
      feature.id = id;
      feature.kind = isBuilding ? FeatureKind::Building : FeatureKind::Part;
      keepTags(relation.tags(), feature.tags);
      for (const osmium::OuterRing& outer : area.outer_rings()) {
        appendRing(outer, city_.points, feature);
        for (const osmium::InnerRing& inner : area.inner_rings(outer)) appendRing(inner, city_.points, feature);
        feature.polygonEnds.push_back(static_cast<std::uint32_t>(feature.ringEnds.size()));
      }
      if (feature.polygonEnds.empty()) {
        city_.drops.add("invalid-multipolygon");
        continue;
      }
      city_.features.push_back(std::move(feature));
    }
  }

  // ---- Ground features.

  void skipGround(const char* reason) { ++city_.ground.skipped[reason]; }

  void takeGroundNode(const osmium::Node& node) {
    const GroundTags t = GroundTags::read(node.tags());
    const auto kind = placeKind(t.place);
    if (!kind) return;
    if (t.name == nullptr || *t.name == '\0') {
      skipGround("unnamed-place");
      return;
    }
    if (!node.location().valid()) {
      skipGround("invalid-coordinates");
      return;
    }
    city_.ground.places.push_back({kind->first, kind->second, t.nameText(), lonLat(node.location())});
  }

  /// Appends the located nodes of `way` to the ground's points; false (and nothing appended) when
  /// one of them is missing from the file.
  bool appendGroundRing(const osmium::WayNodeList& nodes, bool dropLastRepeat) {
    RawGround& g = city_.ground;
    const std::size_t start = g.points.size();
    std::size_t n = nodes.size();
    if (dropLastRepeat && n > 1 && nodes.front().location() == nodes.back().location()) --n;
    for (std::size_t i = 0; i < n; ++i) {
      const osmium::Location location = nodes[i].location();
      if (!location.valid()) {
        g.points.resize(start);
        return false;
      }
      g.points.push_back(lonLat(location));
    }
    return true;
  }

  /// A polyline of a way: one piece per run of nodes present in the file (an extract cuts roads at
  /// its edge); `add(begin, end)` takes each piece of at least 2 distinct points. A way with
  /// missing nodes is counted as "missing-nodes", one that leaves no piece otherwise as
  /// "too-few-points".
  template <typename Add>
  void addLinePieces(const osmium::WayNodeList& nodes, Add add) {
    RawGround& g = city_.ground;
    bool missing = false;
    std::size_t pieces = 0;
    std::size_t begin = g.points.size();
    auto flush = [&] {
      if (g.points.size() - begin >= 2) {
        add(static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(g.points.size()));
        ++pieces;
      } else {
        g.points.resize(begin);
      }
      begin = g.points.size();
    };
    for (const osmium::NodeRef& node : nodes) {
      if (!node.location().valid()) {
        missing = true;
        flush();
        continue;
      }
      const glm::dvec2 p = lonLat(node.location());
      if (g.points.size() > begin && g.points.back() == p) continue;  // a node repeated in place
      g.points.push_back(p);
    }
    flush();
    if (missing) {
      skipGround("missing-nodes");
    } else if (pieces == 0) {
      skipGround("too-few-points");
    }
  }

  void addPlaceAt(const GroundTags& t, const std::vector<glm::dvec2>& ring) {
    const auto kind = placeKind(t.place);
    if (!kind || t.name == nullptr || *t.name == '\0') return;
    double twiceArea = 0.0;
    city_.ground.places.push_back({kind->first, kind->second, t.nameText(), ringCentroid(ring, twiceArea)});
  }

  void takeGroundWay(const osmium::Way& way) {
    const GroundTags t = GroundTags::read(way.tags());
    const osmium::WayNodeList& nodes = way.nodes();
    // is_closed() reads the last node: undefined for a way without nodes.
    const bool closed = nodes.size() >= 4 && way.is_closed();
    RawGround& g = city_.ground;
    if (t.place != nullptr && closed && placeKind(t.place) && t.name != nullptr) {
      std::vector<glm::dvec2> ring;
      for (const osmium::NodeRef& node : nodes) {
        if (node.location().valid()) ring.push_back(lonLat(node.location()));
      }
      if (ring.size() >= 3) addPlaceAt(t, ring);
    }
    if (closed) {
      if (const auto district = districtSource(t)) {
        const auto begin = static_cast<std::uint32_t>(g.points.size());
        if (appendGroundRing(nodes, true)) {
          g.boundaries.push_back(
              {t.nameText(), district->first, district->second, begin, {static_cast<std::uint32_t>(g.points.size())}});
        } else {
          skipGround("missing-nodes");
        }
      }
    }
    if (tagIs(t.natural, "coastline")) {
      addLinePieces(nodes, [&](std::uint32_t begin, std::uint32_t end) { g.coastlines.emplace_back(begin, end); });
      return;
    }
    std::optional<LineStyle> style = lookUp(kHighways, t.highway);
    if (!style) style = lookUp(kRailways, t.railway);
    if (!style) style = lookUp(kWaterways, t.waterway);
    const bool subway = tagIs(t.railway, "subway");
    if (style || subway) {
      if (subway || t.underground()) {
        skipGround("tunnel");
        return;
      }
      // A pedestrian square or a footway drawn as its outline (area=yes): the surface, not a line.
      if (t.highway != nullptr && style->groundClass == GroundClass::Path && tagIs(t.area, "yes")) {
        if (!closed) {
          skipGround("unclosed-area");
          return;
        }
        addGroundArea(way, GroundClass::Path, style->rank, t);
        return;
      }
      if (t.highway != nullptr && tagIs(t.area, "yes")) return;  // a parking lot's or a plaza's outline
      const float widthM = widthTag(t.width).value_or(style->widthM);
      addLinePieces(nodes, [&](std::uint32_t begin, std::uint32_t end) {
        g.lines.push_back({style->groundClass, widthM, style->rank, t.nameText(), begin, end});
      });
      return;
    }
    const std::optional<GroundClass> area = areaClass(t);
    if (!area) return;
    if (!closed) {
      skipGround(nodes.size() < 4 && !nodes.empty() && way.is_closed() ? "too-few-points" : "unclosed-area");
      return;
    }
    addGroundArea(way, *area, areaRank(*area), t);
  }

  void addGroundArea(const osmium::Way& way, GroundClass groundClass, std::uint8_t rank, const GroundTags& t) {
    RawGround& g = city_.ground;
    const auto begin = static_cast<std::uint32_t>(g.points.size());
    if (!appendGroundRing(way.nodes(), true)) {
      skipGround("missing-nodes");
      return;
    }
    RawGround::Area area;
    area.groundClass = groundClass;
    area.rank = rank;
    area.name = t.nameText();
    area.begin = begin;
    area.ringEnds.push_back(static_cast<std::uint32_t>(g.points.size()));
    g.areas.push_back(std::move(area));
  }

  /// A water, park or open-land multipolygon, or a place's area (its label at the centroid of its
  /// largest outer ring). Never fails the file: a relation that cannot be assembled is counted.
  void assembleGroundRelation(const osmium::Relation& relation, const osmium::area::AssemblerConfig& config) {
    const GroundTags t = GroundTags::read(relation.tags());
    const std::optional<GroundClass> area =
        tagIs(relation.tags().get_value_by_key("type"), "multipolygon") ? areaClass(t) : std::optional<GroundClass>();
    const auto district = districtSource(t);
    // A boundary cut by the extract is common (an area larger than the extract): counted apart from
    // the broken or cut areas the map would draw.
    const char* incomplete = area || placeKind(t.place) ? "incomplete-multipolygon" : "incomplete-boundary";
    const char* broken = area || placeKind(t.place) ? "broken-multipolygon" : "broken-boundary";
    std::vector<const osmium::Way*> members;
    for (const osmium::RelationMember& member : relation.members()) {
      if (member.type() != osmium::item_type::way) continue;
      const osmium::Way* way = findWay(member.ref());
      bool located = way != nullptr;
      for (std::size_t i = 0; located && i < way->nodes().size(); ++i) located = way->nodes()[i].location().valid();
      if (!located) {
        // Cut by the extract: libosmium's manager skips such relations too.
        skipGround(incomplete);
        return;
      }
      members.push_back(way);
    }
    if (members.empty()) {
      skipGround(incomplete);
      return;
    }
    osmium::memory::Buffer areaBuffer{1024, osmium::memory::Buffer::auto_grow::yes};
    try {
      osmium::area::Assembler assembler{config};
      if (!assembler(relation, members, areaBuffer) || areaBuffer.committed() == 0) {
        skipGround(broken);
        return;
      }
    } catch (const std::exception&) {
      skipGround(broken);
      return;
    }
    RawGround& g = city_.ground;
    const osmium::Area& assembled = areaBuffer.get<const osmium::Area>(0);
    std::vector<glm::dvec2> ring;
    std::vector<glm::dvec2> largest;
    double largestArea = -1.0;
    auto readRing = [&](const auto& nodes) {
      ring.clear();
      auto end = nodes.end();
      if (nodes.size() > 1 && nodes.front().location() == nodes.back().location()) --end;
      for (auto it = nodes.begin(); it != end; ++it) ring.push_back(lonLat(it->location()));
    };
    std::size_t outers = 0;
    for (const osmium::OuterRing& outer : assembled.outer_rings()) {
      ++outers;
      readRing(outer);
      double twiceArea = 0.0;
      ringCentroid(ring, twiceArea);
      if (std::abs(twiceArea) > largestArea) {
        largestArea = std::abs(twiceArea);
        largest = ring;
      }
      if (!area && !district) continue;
      // The outer ring and its holes, once in the points (shared by the area and the boundary).
      const auto begin = static_cast<std::uint32_t>(g.points.size());
      std::vector<std::uint32_t> ringEnds;
      g.points.insert(g.points.end(), ring.begin(), ring.end());
      ringEnds.push_back(static_cast<std::uint32_t>(g.points.size()));
      for (const osmium::InnerRing& inner : assembled.inner_rings(outer)) {
        readRing(inner);
        g.points.insert(g.points.end(), ring.begin(), ring.end());
        ringEnds.push_back(static_cast<std::uint32_t>(g.points.size()));
      }
      if (area) {
        RawGround::Area a;
        a.groundClass = *area;
        a.rank = areaRank(*area);
        a.name = t.nameText();
        a.begin = begin;
        a.ringEnds = ringEnds;
        g.areas.push_back(std::move(a));
      }
      if (district) g.boundaries.push_back({t.nameText(), district->first, district->second, begin, ringEnds});
    }
    if (outers == 0) {
      skipGround(broken);
      return;
    }
    if (largest.size() >= 3) addPlaceAt(t, largest);
  }

  const std::string& path_;
  const bool ground_;
  RawCity& city_;
  IngestStats& stats_;
  MissingNodes missing_;
  std::vector<osmium::memory::Buffer> wayBuffers_;  ///< input buffers holding ways, kept for the relations
  std::vector<std::pair<osmium::object_id_type, const osmium::Way*>> ways_;
  osmium::memory::Buffer relationStore_{1 << 16, osmium::memory::Buffer::auto_grow::yes};
};

}  // namespace

Status readOsmFile(const std::string& path, const IngestOptions& options, RawCity& city, IngestStats& stats) {
  OsmReader reader{path, options, city, stats};
  return reader.run();
}

}  // namespace qv::prep::detail
