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
#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string_view>
#include <system_error>

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
  OsmReader(const std::string& path, RawCity& city, IngestStats& stats) : path_(path), city_(city), stats_(stats) {}

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
            case osmium::item_type::node:
              ++stats_.osmNodes;
              locations.node(static_cast<const osmium::Node&>(item));
              break;
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
    if (!isBuilding && !isPart) return;
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
    if (!tagIs(type, "multipolygon")) return;  // type=site, route, ...: not buildings
    const bool isBuilding = tagSet(tags.get_value_by_key("building"));
    const bool isPart = !isBuilding && tagSet(tags.get_value_by_key("building:part"));
    if (!isBuilding && !isPart) return;
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
      const std::string id = "r" + std::to_string(relation.id());
      const bool isBuilding = tagSet(relation.tags().get_value_by_key("building"));
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

  const std::string& path_;
  RawCity& city_;
  IngestStats& stats_;
  MissingNodes missing_;
  std::vector<osmium::memory::Buffer> wayBuffers_;  ///< input buffers holding ways, kept for the relations
  std::vector<std::pair<osmium::object_id_type, const osmium::Way*>> ways_;
  osmium::memory::Buffer relationStore_{1 << 16, osmium::memory::Buffer::auto_grow::yes};
};

}  // namespace

Status readOsmFile(const std::string& path, RawCity& city, IngestStats& stats) {
  OsmReader reader{path, city, stats};
  return reader.run();
}

}  // namespace qv::prep::detail
