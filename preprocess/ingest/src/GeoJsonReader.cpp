// GeoJSON FeatureCollections of Polygon / MultiPolygon footprints through simdjson's On-Demand API,
// used with error codes only (never its exception API). On-Demand parses lazily and reports where
// it stopped but not always why the text is broken, so on any error the text is run through a small
// syntax checker that finds the first offending byte: messages say "file:line:column: what".
#include <optional>
#include <string_view>
#include <utility>

#include <simdjson.h>

#include "RawCity.h"
#include "qv/core/NumberFormat.h"
#include "qv/prep/JsonSyntax.h"
#include "qv/prep/Projection.h"

namespace qv::prep::detail {
namespace {

namespace od = simdjson::ondemand;

std::string_view trimRight(std::string_view text) {
  while (!text.empty() && (text.back() == ' ' || text.back() == '\n' || text.back() == '\r' || text.back() == '\t'))
    text.remove_suffix(1);
  return text;
}

bool tagSet(const std::string& value) {
  return !value.empty() && value != "no";
}

class GeoJsonReader {
 public:
  GeoJsonReader(const std::string& path, const IngestOptions& options, LengthUnit plainUnit, std::size_t ordinal,
                RawCity& city, IngestStats& stats)
      : path_(path), options_(options), plainUnit_(plainUnit), ordinal_(ordinal), city_(city), stats_(stats) {}

  Status run() {
    if (const simdjson::error_code e = simdjson::padded_string::load(path_).get(json_); e != simdjson::SUCCESS) {
      return Error{path_ + ": cannot read: " + simdjson::error_message(e)};
    }
    simdjson::error_code e = parser_.iterate(json_).get(doc_);
    if (e != simdjson::SUCCESS) return jsonError(e, "not valid JSON");
    iterating_ = true;
    od::json_type rootType{};
    if ((e = doc_.type().get(rootType)) != simdjson::SUCCESS) return jsonError(e, "not valid JSON");
    if (rootType != od::json_type::object) {
      return errorAt(firstTokenOffset(),
                     "expected a GeoJSON FeatureCollection (an object), found " + std::string(typeName(rootType)));
    }
    od::object root;
    if ((e = doc_.get_object().get(root)) != simdjson::SUCCESS) return jsonError(e, "not valid JSON");
    bool sawType = false;
    bool sawFeatures = false;
    for (auto fieldResult : root) {
      od::field field;
      std::string_view key;
      if ((e = std::move(fieldResult).get(field)) != simdjson::SUCCESS ||
          (e = field.unescaped_key().get(key)) != simdjson::SUCCESS)
        return jsonError(e, "in the top-level object");
      if (key == "type") {
        const std::size_t at = currentOffset();
        std::string_view type;
        if ((e = field.value().get_string().get(type)) != simdjson::SUCCESS)
          return jsonError(e, "the top-level \"type\" must be a string");
        if (type != "FeatureCollection") {
          return errorAt(
              at, "top-level \"type\" is \"" + std::string(type) + "\": expected a GeoJSON \"FeatureCollection\"");
        }
        sawType = true;
      } else if (key == "features") {
        if (Status s = readFeatures(field.value()); !s) return s;
        sawFeatures = true;
      } else if (key == "crs") {
        if (Status s = checkCrs(field.value()); !s) return s;
      }
    }
    if (!sawType) return Error{path_ + ": no top-level \"type\": not a GeoJSON FeatureCollection"};
    if (!sawFeatures) return Error{path_ + ": the FeatureCollection has no \"features\" array"};
    return {};
  }

 private:
  static std::string_view typeName(od::json_type type) {
    switch (type) {
      case od::json_type::array:
        return "an array";
      case od::json_type::object:
        return "an object";
      case od::json_type::number:
        return "a number";
      case od::json_type::string:
        return "a string";
      case od::json_type::boolean:
        return "a boolean";
      case od::json_type::null:
        return "null";
    }
    return "a value";
  }

  std::size_t firstTokenOffset() const {
    std::size_t i = 0;
    const std::string_view text(json_.data(), json_.size());
    while (i < text.size() && (text[i] == ' ' || text[i] == '\n' || text[i] == '\r' || text[i] == '\t')) ++i;
    return i;
  }

  std::size_t currentOffset() {
    // Before iterate() succeeded the document has no token buffer: current_location() would read
    // through a null pointer.
    if (!iterating_) return 0;
    const char* location = nullptr;
    if (doc_.current_location().get(location) != simdjson::SUCCESS || location == nullptr) return json_.size();
    return static_cast<std::size_t>(location - json_.data());
  }

  std::string position(std::size_t offset) const {
    return lineColumn(std::string_view(json_.data(), json_.size()), offset);
  }

  Error errorAt(std::size_t offset, const std::string& message) const {
    return Error{path_ + ":" + position(offset) + ": " + message};
  }

  /// An error simdjson reported: a syntax error wherever the checker finds one, else the place
  /// On-Demand stopped with simdjson's reason.
  Error jsonError(simdjson::error_code code, const std::string& context) {
    if (const auto problem = findJsonSyntaxProblem(std::string_view(json_.data(), json_.size())))
      return errorAt(problem->offset, "malformed JSON: " + problem->what);
    return errorAt(currentOffset(), context + ": " + simdjson::error_message(code));
  }

  Status checkCrs(od::value& value) {
    const std::size_t at = currentOffset();
    std::string_view name;
    auto crsName = value["properties"]["name"];
    if (crsName.get_string().get(name) != simdjson::SUCCESS) return {};  // unknown CRS form: assume WGS84
    if (name.find("CRS84") != std::string_view::npos || name.find("4326") != std::string_view::npos) return {};
    return errorAt(at, "the file declares CRS \"" + std::string(name) +
                           "\": footprints must be WGS84 longitude/latitude (reproject with "
                           "`ogr2ogr -t_srs EPSG:4326`)");
  }

  Status readFeatures(od::value& value) {
    od::array features;
    simdjson::error_code e = value.get_array().get(features);
    if (e != simdjson::SUCCESS) return jsonError(e, "\"features\" must be an array");
    std::size_t index = 0;
    for (auto featureResult : features) {
      od::value feature;
      if ((e = featureResult.get(feature)) != simdjson::SUCCESS) return jsonError(e, featureName(index));
      if (Status s = readFeature(feature, index); !s) return s;
      ++index;
    }
    return {};
  }

  static std::string featureName(std::size_t index) { return "feature " + std::to_string(index); }

  /// A property or id value as text: strings as they are, numbers as written, booleans as yes/no.
  /// False for null, objects and arrays (left unread).
  bool readScalar(od::value& value, std::string& out, simdjson::error_code& e) {
    od::json_type type{};
    if ((e = value.type().get(type)) != simdjson::SUCCESS) return false;
    std::string_view text;
    switch (type) {
      case od::json_type::string:
        if ((e = value.get_string().get(text)) != simdjson::SUCCESS) return false;
        out.assign(text);
        return true;
      case od::json_type::number:
        out.assign(trimRight(value.raw_json_token()));
        return true;
      case od::json_type::boolean: {
        bool flag = false;
        if ((e = value.get_bool().get(flag)) != simdjson::SUCCESS) return false;
        out = flag ? "yes" : "no";
        return true;
      }
      default:
        return false;
    }
  }

  std::string* propertySlot(std::string_view key, RawTags& tags, std::string& idValue) const {
    // The configurable names first: they may shadow an OSM key ("height" vs "heightroof").
    if (key == options_.idProperty) return &idValue;
    if (key == options_.heightProperty) return &tags.height;
    if (key == options_.levelsProperty) return &tags.levels;
    if (key == options_.minHeightProperty) return &tags.minHeight;
    if (key == options_.yearProperty) return &tags.startDate;
    if (key == options_.useProperty) return &tags.building;
    if (key == options_.nameProperty) return &tags.name;
    if (key == options_.occupantsProperty) return &tags.occupants;
    if (key == options_.valueProperty) return &tags.replacementValue;
    if (key == "building:part") return &tags.buildingPart;
    if (key == "building:min_level") return &tags.minLevel;
    if (key == "building:material") return &tags.material;
    if (key == "building:structure") return &tags.structure;
    if (key == "roof:shape") return &tags.roofShape;
    if (key == "roof:height") return &tags.roofHeight;
    if (key == "amenity") return &tags.amenity;
    if (key == "emergency") return &tags.emergency;
    if (key == "healthcare") return &tags.healthcare;
    if (key == "social_facility") return &tags.socialFacility;
    if (key == "power") return &tags.power;
    if (key == "shop") return &tags.shop;
    if (key == "industrial") return &tags.industrial;
    if (key == "addr:housenumber") return &tags.houseNumber;
    if (key == "addr:street") return &tags.street;
    if (key == "addr:postcode") return &tags.postcode;
    if (key == "addr:city") return &tags.city;
    if (key == "location") return &tags.location;
    if (key == "layer") return &tags.layer;
    return nullptr;
  }

  Status readProperties(od::value& value, std::size_t index, RawTags& tags, std::string& idValue) {
    od::object properties;
    simdjson::error_code e = value.get_object().get(properties);
    if (e != simdjson::SUCCESS) return jsonError(e, featureName(index) + ": \"properties\" must be an object or null");
    for (auto fieldResult : properties) {
      od::field field;
      std::string_view key;
      if ((e = std::move(fieldResult).get(field)) != simdjson::SUCCESS ||
          (e = field.unescaped_key().get(key)) != simdjson::SUCCESS)
        return jsonError(e, featureName(index) + " properties");
      std::string* slot = propertySlot(key, tags, idValue);
      if (slot == nullptr) continue;
      if (!readScalar(field.value(), *slot, e) && e != simdjson::SUCCESS)
        return jsonError(e, featureName(index) + " property \"" + std::string(key) + "\"");
    }
    return {};
  }

  /// Appends the rings of one GeoJSON Polygon's coordinates (an array of rings of positions).
  Status readPolygon(od::value& value, std::size_t index, RawFeature& feature) {
    od::array rings;
    simdjson::error_code e = value.get_array().get(rings);
    if (e != simdjson::SUCCESS) return jsonError(e, featureName(index) + ": polygon coordinates must be an array");
    for (auto ringResult : rings) {
      od::array ring;
      if ((e = ringResult.get_array().get(ring)) != simdjson::SUCCESS)
        return jsonError(e, featureName(index) + ": a polygon ring must be an array of positions");
      for (auto positionResult : ring) {
        od::array position;
        if ((e = positionResult.get_array().get(position)) != simdjson::SUCCESS)
          return jsonError(e, featureName(index) + ": a position must be an array [longitude, latitude]");
        const std::size_t at = currentOffset();
        double lonLat[2] = {0.0, 0.0};
        std::size_t n = 0;
        for (auto coordinate : position) {
          double v = 0.0;
          if ((e = coordinate.get_double().get(v)) != simdjson::SUCCESS)
            return jsonError(e, featureName(index) + ": a coordinate must be a number");
          if (n < 2) lonLat[n] = v;
          ++n;
        }
        if (n < 2) return errorAt(at, featureName(index) + ": a position needs longitude and latitude");
        if (!validLonLat(lonLat[0], lonLat[1])) {
          const std::string text = "[" + formatDouble(lonLat[0], 10) + ", " + formatDouble(lonLat[1], 10) + "]";
          return errorAt(at, featureName(index) + ": position " + text +
                                 " is not WGS84 longitude/latitude in degrees (reproject the file to EPSG:4326)");
        }
        feature.points.push_back(city_.points.add({lonLat[0], lonLat[1]}));
      }
      // GeoJSON repeats the first position at the end; rings are closed implicitly from here on.
      const std::size_t ringStart = feature.ringEnds.empty() ? 0 : feature.ringEnds.back();
      const std::vector<glm::dvec2>& table = city_.points.points;
      if (feature.points.size() >= ringStart + 2 && table[feature.points.back()] == table[feature.points[ringStart]]) {
        feature.points.pop_back();
        city_.points.points.pop_back();  // the repeated position was the last one added
      }
      feature.ringEnds.push_back(static_cast<std::uint32_t>(feature.points.size()));
    }
    const auto ringCount = static_cast<std::uint32_t>(feature.ringEnds.size());
    if (feature.polygonEnds.empty() ? ringCount > 0 : ringCount > feature.polygonEnds.back())
      feature.polygonEnds.push_back(ringCount);
    return {};
  }

  /// Reads the geometry into `feature`; `kind` becomes "Polygon"/"MultiPolygon" or the other type.
  Status readGeometry(od::value& value, std::size_t index, RawFeature& feature, std::string& kind) {
    od::object geometry;
    simdjson::error_code e = value.get_object().get(geometry);
    if (e != simdjson::SUCCESS) return jsonError(e, featureName(index) + ": \"geometry\" must be an object or null");
    std::string_view type;
    if ((e = geometry["type"].get_string().get(type)) != simdjson::SUCCESS)
      return jsonError(e, featureName(index) + ": the geometry has no \"type\" string");
    kind.assign(type);
    if (kind != "Polygon" && kind != "MultiPolygon") return {};
    od::value coordinates;
    if ((e = geometry["coordinates"].get(coordinates)) != simdjson::SUCCESS)
      return jsonError(e, featureName(index) + ": the " + kind + " has no \"coordinates\"");
    if (kind == "Polygon") return readPolygon(coordinates, index, feature);
    od::array polygons;
    if ((e = coordinates.get_array().get(polygons)) != simdjson::SUCCESS)
      return jsonError(e, featureName(index) + ": MultiPolygon coordinates must be an array of polygons");
    for (auto polygonResult : polygons) {
      od::value polygon;
      if ((e = polygonResult.get(polygon)) != simdjson::SUCCESS) return jsonError(e, featureName(index));
      if (Status s = readPolygon(polygon, index, feature); !s) return s;
    }
    return {};
  }

  Status readFeature(od::value& value, std::size_t index) {
    const std::size_t at = currentOffset();
    od::object object;
    simdjson::error_code e = value.get_object().get(object);
    if (e != simdjson::SUCCESS) return jsonError(e, featureName(index) + " must be an object");
    RawFeature feature;
    feature.plainUnit = plainUnit_;
    feature.propertyNames = &options_;
    std::string propertyId;
    std::string featureId;
    std::string geometryKind;
    for (auto fieldResult : object) {
      od::field field;
      std::string_view key;
      if ((e = std::move(fieldResult).get(field)) != simdjson::SUCCESS ||
          (e = field.unescaped_key().get(key)) != simdjson::SUCCESS)
        return jsonError(e, featureName(index));
      if (key == "type") {
        std::string type;
        if (!readScalar(field.value(), type, e) || type != "Feature") {
          if (e != simdjson::SUCCESS) return jsonError(e, featureName(index));
          return errorAt(at, featureName(index) + ": \"type\" is \"" + type + "\", expected \"Feature\"");
        }
      } else if (key == "id") {
        if (!readScalar(field.value(), featureId, e) && e != simdjson::SUCCESS) return jsonError(e, featureName(index));
      } else if (key == "properties") {
        bool isNull = false;
        if ((e = field.value().is_null().get(isNull)) != simdjson::SUCCESS) return jsonError(e, featureName(index));
        if (!isNull) {
          if (Status s = readProperties(field.value(), index, feature.tags, propertyId); !s) return s;
        }
      } else if (key == "geometry") {
        bool isNull = false;
        if ((e = field.value().is_null().get(isNull)) != simdjson::SUCCESS) return jsonError(e, featureName(index));
        if (!isNull) {
          if (Status s = readGeometry(field.value(), index, feature, geometryKind); !s) return s;
        }
      }
    }
    ++stats_.geojsonFeatures;
    if (geometryKind.empty()) {
      city_.drops.add("no-geometry");
      return {};
    }
    if (geometryKind != "Polygon" && geometryKind != "MultiPolygon") {
      city_.drops.add("not-a-polygon");
      return {};
    }
    if (feature.polygonEnds.empty()) {
      city_.drops.add("too-few-points");
      return {};
    }
    if (!propertyId.empty()) {
      feature.id = "g:" + propertyId;
    } else if (!featureId.empty()) {
      feature.id = "g:" + featureId;
    } else {
      feature.id = "g:" + (ordinal_ > 0 ? std::to_string(ordinal_) + "." : std::string()) + std::to_string(index);
    }
    const bool isPart = tagSet(feature.tags.buildingPart) && feature.tags.building.empty();
    if (!isPart && feature.tags.building == "no") {
      city_.drops.add("not-a-building");
      return {};
    }
    feature.kind = isPart ? FeatureKind::Part : FeatureKind::Building;
    city_.features.push_back(std::move(feature));
    return {};
  }

  const std::string& path_;
  const IngestOptions& options_;
  LengthUnit plainUnit_;
  std::size_t ordinal_;
  RawCity& city_;
  IngestStats& stats_;
  simdjson::padded_string json_;
  od::parser parser_;
  od::document doc_;
  bool iterating_ = false;  ///< doc_ comes from a successful iterate()
};

}  // namespace

Status readGeoJsonFile(const std::string& path, const IngestOptions& options, LengthUnit plainUnit, std::size_t ordinal,
                       RawCity& city, IngestStats& stats) {
  GeoJsonReader reader{path, options, plainUnit, ordinal, city, stats};
  return reader.run();
}

}  // namespace qv::prep::detail
