// CityJSON through simdjson's DOM API, error codes only (never its exception API). The DOM suits
// CityJSON: geometries index into one shared vertex list and parts refer to their parents by id, so
// the reader needs random access to the whole document (files of a few MB).
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>

#include <simdjson.h>

#include <glm/geometric.hpp>

#include "qv/core/NumberFormat.h"
#include "qv/prep/Attributes.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/JsonSyntax.h"
#include "qv/prep/Lod2CityJson.h"
#include "qv/prep/Lod2Geometry.h"
#include "qv/prep/Lod2Georeference.h"

namespace qv::prep {
namespace {

namespace dom = simdjson::dom;
using simdjson::SUCCESS;

/// Kind code of a triangle whose kind comes from its normal (no semantics).
constexpr std::uint8_t kByNormal = 255;
constexpr std::size_t kMaxWarnings = 100;

SurfaceKind kindOfSemanticType(std::string_view type) {
  if (type == "RoofSurface") return SurfaceKind::Roof;
  if (type == "WallSurface") return SurfaceKind::Wall;
  if (type == "GroundSurface") return SurfaceKind::Ground;
  return SurfaceKind::Other;
}

/// Nesting levels above the surfaces of a geometry type's boundaries, 0 when not supported.
int surfaceDepth(std::string_view type) {
  if (type == "MultiSurface" || type == "CompositeSurface") return 1;
  if (type == "Solid") return 2;
  if (type == "MultiSolid" || type == "CompositeSolid") return 3;
  return 0;
}

bool supportedVersion(std::string_view version) {
  for (std::string_view known : {"1.0", "1.1", "2.0"}) {
    if (version == known) return true;
    if (version.size() > known.size() && version.substr(0, known.size()) == known && version[known.size()] == '.')
      return true;
  }
  return false;
}

// Strings are appended piece by piece here: GCC 12 at -O2 warns falsely (-Wrestrict) about
// "literal" + std::string temporaries.
std::string quoted(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  out.push_back('"');
  out.append(text);
  out.push_back('"');
  return out;
}

/// A geometry object of a CityObject, with its LOD as written and as a number.
struct GeometryRef {
  dom::element element;
  std::string_view type;
  std::string lodText;
  double lod = -1.0;  ///< -1: not given
  std::string_view objectId;
  std::size_t index = 0;  ///< position in the object's "geometry" array
};

struct ObjectRef {
  std::string_view id;
  std::string_view type;
  dom::element element;
  std::vector<std::string_view> parents;
  std::vector<std::string_view> children;
};

class CityJsonReader {
 public:
  CityJsonReader(std::string_view text, std::string name, const CityJsonOptions& options)
      : text_(text), name_(std::move(name)), options_(options) {}

  Result<CityJsonFile> read() {
    const simdjson::padded_string padded(text_);
    dom::element root;
    if (const simdjson::error_code e = parser_.parse(padded).get(root); e != SUCCESS) {
      if (const auto problem = findJsonSyntaxProblem(text_)) {
        return Error{name_ + ":" + lineColumn(text_, problem->offset) + ": malformed JSON: " + problem->what};
      }
      return Error{name_ + ": cannot parse JSON: " + simdjson::error_message(e)};
    }
    dom::object document;
    if (root.get_object().get(document) != SUCCESS)
      return fail("not a CityJSON document: the top level is not an object");
    std::string_view type;
    if (document["type"].get_string().get(type) != SUCCESS) return fail("not a CityJSON document: no \"type\" member");
    if (type != "CityJSON") return fail("not a CityJSON document: \"type\" is " + quoted(type));
    std::string_view version;
    if (document["version"].get_string().get(version) != SUCCESS)
      return fail("no CityJSON \"version\" (a string such as \"2.0\")");
    if (!supportedVersion(version))
      return fail("unsupported CityJSON version " + quoted(version) + " (supported: 1.0, 1.1, 2.0)");
    file_.version = std::string(version);

    if (Status s = readTransform(document); !s) return Error{s.error()};
    if (Status s = readVertices(document); !s) return Error{s.error()};
    readReferenceSystem(document);
    dom::object objects;
    if (document["CityObjects"].get_object().get(objects) != SUCCESS) return fail("no \"CityObjects\" object");
    if (Status s = readObjects(objects); !s) return Error{s.error()};
    return std::move(file_);
  }

 private:
  Error fail(const std::string& message) const { return Error{name_ + ": " + message}; }

  void warn(std::string message) {
    if (file_.warnings.size() < kMaxWarnings) file_.warnings.push_back(name_ + ": " + std::move(message));
  }

  static bool readNumber(dom::element element, double& out) {
    return element.get_double().get(out) == SUCCESS && std::isfinite(out);
  }

  Status readTransform(dom::object document) {
    dom::element transform;
    if (document["transform"].get(transform) != SUCCESS) return {};  // 1.0 files may store plain coordinates
    dom::array scale;
    dom::array translate;
    if (transform["scale"].get_array().get(scale) != SUCCESS || scale.size() != 3 ||
        transform["translate"].get_array().get(translate) != SUCCESS || translate.size() != 3)
      return fail("\"transform\" must have \"scale\" and \"translate\" arrays of 3 numbers");
    int i = 0;
    for (dom::element v : scale) {
      if (!readNumber(v, scale_[i++])) return fail("\"transform\".\"scale\" must hold 3 numbers");
    }
    i = 0;
    for (dom::element v : translate) {
      if (!readNumber(v, translate_[i++])) return fail("\"transform\".\"translate\" must hold 3 numbers");
    }
    return {};
  }

  Status readVertices(dom::object document) {
    dom::array vertices;
    if (document["vertices"].get_array().get(vertices) != SUCCESS) return fail("no \"vertices\" array");
    vertices_.reserve(vertices.size());
    for (dom::element vertex : vertices) {
      dom::array xyz;
      double c[3];
      int n = 0;
      bool ok = vertex.get_array().get(xyz) == SUCCESS && xyz.size() == 3;
      if (ok) {
        for (dom::element v : xyz) ok = ok && readNumber(v, c[n++]);
      }
      if (!ok) return fail("vertices[" + std::to_string(vertices_.size()) + "] is not an array of 3 numbers");
      vertices_.emplace_back(c[0] * scale_[0] + translate_[0], c[1] * scale_[1] + translate_[1],
                             c[2] * scale_[2] + translate_[2]);
    }
    return {};
  }

  void readReferenceSystem(dom::object document) {
    dom::element metadata;
    if (document["metadata"].get(metadata) != SUCCESS) return;
    std::string_view text;
    if (metadata["referenceSystem"].get_string().get(text) == SUCCESS) {
      file_.referenceSystem = std::string(text);
    } else {
      std::int64_t epsg = 0;  // early CityJSON 1.0: "crs": {"epsg": 7415}
      if (metadata["crs"]["epsg"].get_int64().get(epsg) == SUCCESS)
        file_.referenceSystem = "EPSG:" + std::to_string(epsg);
    }
    file_.crs = epsgFromReferenceSystem(file_.referenceSystem);
  }

  static std::vector<std::string_view> idList(dom::element object, const char* key) {
    std::vector<std::string_view> ids;
    dom::array array;
    if (object[key].get_array().get(array) != SUCCESS) return ids;
    for (dom::element e : array) {
      std::string_view id;
      if (e.get_string().get(id) == SUCCESS) ids.push_back(id);
    }
    return ids;
  }

  Status readObjects(dom::object objects) {
    std::vector<ObjectRef> refs;
    std::unordered_map<std::string_view, std::size_t> indexOf;
    for (dom::key_value_pair member : objects) {
      ObjectRef ref;
      ref.id = member.key;
      ref.element = member.value;
      if (member.value.type() != dom::element_type::OBJECT ||
          member.value["type"].get_string().get(ref.type) != SUCCESS)
        return fail("CityObjects[" + quoted(member.key) + "] has no \"type\"");
      ref.parents = idList(member.value, "parents");
      ref.children = idList(member.value, "children");
      indexOf.emplace(ref.id, refs.size());
      refs.push_back(std::move(ref));
    }
    // Parent links from both directions ("parents" of a part, "children" of its building).
    std::unordered_map<std::string_view, std::string_view> parentOf;
    for (const ObjectRef& ref : refs) {
      for (std::string_view child : ref.children) parentOf.emplace(child, ref.id);
    }
    for (const ObjectRef& ref : refs) {
      for (std::string_view parent : ref.parents) {
        if (indexOf.count(parent)) {
          parentOf[ref.id] = parent;
          break;
        }
      }
    }
    // Each BuildingPart goes to the Building above it; a part without one is a building itself.
    std::vector<std::vector<std::size_t>> partsOf(refs.size());
    std::vector<bool> isModelRoot(refs.size(), false);
    for (std::size_t i = 0; i < refs.size(); ++i) {
      const ObjectRef& ref = refs[i];
      if (ref.type == "Building") {
        isModelRoot[i] = true;
      } else if (ref.type == "BuildingPart") {
        std::optional<std::size_t> building;
        std::string_view at = ref.id;
        for (int depth = 0; depth < 64; ++depth) {  // bounded: a cycle of parents is not a hierarchy
          const auto parent = parentOf.find(at);
          if (parent == parentOf.end()) break;
          const auto index = indexOf.find(parent->second);
          if (index == indexOf.end()) break;
          if (refs[index->second].type == "Building") {
            building = index->second;
            break;
          }
          at = parent->second;
        }
        if (building) {
          partsOf[*building].push_back(i);
        } else {
          isModelRoot[i] = true;
          warn("BuildingPart " + quoted(ref.id) + " has no parent Building: imported as a building of its own");
        }
      } else {
        ++file_.skipped[std::string(ref.type)];
      }
    }
    for (std::size_t i = 0; i < refs.size(); ++i) {
      if (!isModelRoot[i]) continue;
      if (Status s = readBuilding(refs, i, partsOf[i]); !s) return s;
    }
    return {};
  }

  static std::string lodText(dom::element geometry, double& value) {
    dom::element lod;
    value = -1.0;
    if (geometry["lod"].get(lod) != SUCCESS) return "";
    std::string_view text;
    if (lod.get_string().get(text) == SUCCESS) {
      if (const auto parsed = parseDouble(text)) value = *parsed;
      return std::string(text);
    }
    double number = 0.0;
    if (lod.get_double().get(number) == SUCCESS && std::isfinite(number)) {  // CityJSON 1.0: a number
      value = number;
      return formatDouble(number);
    }
    return "";
  }

  void collectGeometries(const ObjectRef& ref, std::vector<GeometryRef>& out) {
    dom::array geometries;
    if (ref.element["geometry"].get_array().get(geometries) != SUCCESS) return;
    std::size_t index = 0;
    for (dom::element g : geometries) {
      GeometryRef geometry;
      geometry.element = g;
      geometry.objectId = ref.id;
      geometry.index = index++;
      if (g["type"].get_string().get(geometry.type) != SUCCESS) continue;
      if (surfaceDepth(geometry.type) == 0) {
        ++file_.skipped["geometry " + std::string(geometry.type)];
        continue;
      }
      geometry.lodText = lodText(g, geometry.lod);
      out.push_back(std::move(geometry));
    }
  }

  Status readBuilding(const std::vector<ObjectRef>& refs, std::size_t rootIndex,
                      const std::vector<std::size_t>& parts) {
    const ObjectRef& root = refs[rootIndex];
    std::vector<GeometryRef> geometries;
    collectGeometries(root, geometries);
    for (std::size_t part : parts) collectGeometries(refs[part], geometries);
    if (geometries.empty()) {
      ++file_.skipped["Building without geometry"];
      return {};
    }
    double chosen = -1.0;
    std::string chosenText;
    if (options_.lod.empty()) {
      for (const GeometryRef& g : geometries) {
        if (chosenText.empty() || g.lod > chosen) {
          chosen = g.lod;
          chosenText = g.lodText;
        }
      }
    } else {
      const auto wanted = parseDouble(options_.lod);
      for (const GeometryRef& g : geometries) {
        if ((wanted && g.lod >= 0.0 && std::abs(g.lod - *wanted) < 1e-9) || g.lodText == options_.lod) {
          chosen = g.lod;
          chosenText = g.lodText;
          break;
        }
      }
      if (chosenText.empty()) {
        ++file_.skipped["no LOD " + options_.lod];
        return {};
      }
    }

    building_ = CityJsonBuilding{};
    building_.objectId = std::string(root.id);
    building_.lod = chosenText;
    building_.parts = static_cast<std::uint32_t>(parts.size());
    localIndex_.clear();
    codes_.clear();
    for (const GeometryRef& g : geometries) {
      if (g.lodText != chosenText && !(g.lod >= 0.0 && std::abs(g.lod - chosen) < 1e-9)) continue;
      if (Status s = readGeometry(g); !s) return s;
      ++building_.geometries;
      ++file_.geometries[std::string(g.type)];
    }
    if (building_.triangles.empty()) {
      ++file_.skipped["Building without faces"];
      return {};
    }
    classifyByNormal();
    readAttributes(root.element);
    file_.partsMerged += parts.size();
    ++file_.lods[chosenText];
    file_.buildings.push_back(std::move(building_));
    return {};
  }

  /// The JSON path of a geometry for messages: CityObjects["id"].geometry[2].
  static std::string geometryPath(const GeometryRef& g) {
    return "CityObjects[" + quoted(g.objectId) + "].geometry[" + std::to_string(g.index) + "] (" + std::string(g.type) +
           ")";
  }

  Status readGeometry(const GeometryRef& g) {
    // Semantic surface kinds of this geometry (index -> kind).
    std::vector<SurfaceKind> semanticKinds;
    dom::element semantics;
    dom::element values;
    bool haveValues = false;
    if (g.element["semantics"].get(semantics) == SUCCESS) {
      dom::array surfaces;
      if (semantics["surfaces"].get_array().get(surfaces) == SUCCESS) {
        for (dom::element s : surfaces) {
          std::string_view type;
          semanticKinds.push_back(s["type"].get_string().get(type) == SUCCESS ? kindOfSemanticType(type)
                                                                              : SurfaceKind::Other);
        }
      }
      haveValues = semantics["values"].get(values) == SUCCESS;
    }
    dom::element boundaries;
    if (g.element["boundaries"].get(boundaries) != SUCCESS) return fail(geometryPath(g) + ": no \"boundaries\"");
    std::vector<std::size_t> path;
    return walk(g, boundaries, values, haveValues, surfaceDepth(g.type), semanticKinds, path);
  }

  static std::string indexPath(const std::vector<std::size_t>& path) {
    std::string text;
    for (std::size_t i : path) {
      text.push_back('[');
      text.append(std::to_string(i));
      text.push_back(']');
    }
    return text;
  }

  Status walk(const GeometryRef& g, dom::element boundaries, dom::element values, bool haveValues, int levels,
              const std::vector<SurfaceKind>& semanticKinds, std::vector<std::size_t>& path) {
    if (levels == 0) {
      std::uint8_t code = kByNormal;
      std::uint64_t surfaceIndex = 0;
      if (haveValues && values.get_uint64().get(surfaceIndex) == SUCCESS && surfaceIndex < semanticKinds.size())
        code = static_cast<std::uint8_t>(semanticKinds[surfaceIndex]);
      return readSurface(g, boundaries, code, path);
    }
    dom::array array;
    if (boundaries.get_array().get(array) != SUCCESS)
      return fail(geometryPath(g) + ": boundaries" + indexPath(path) + " is not an array");
    std::vector<dom::element> valueList;
    dom::array valueArray;
    if (haveValues && values.get_array().get(valueArray) == SUCCESS) {
      for (dom::element v : valueArray) valueList.push_back(v);
    }
    std::size_t i = 0;
    for (dom::element child : array) {
      path.push_back(i);
      const bool childHasValue = i < valueList.size();
      Status s =
          walk(g, child, childHasValue ? valueList[i] : dom::element(), childHasValue, levels - 1, semanticKinds, path);
      path.pop_back();
      if (!s) return s;
      ++i;
    }
    return {};
  }

  /// One surface: an array of rings (outer first), each an array of vertex indices.
  Status readSurface(const GeometryRef& g, dom::element surface, std::uint8_t code,
                     const std::vector<std::size_t>& path) {
    dom::array rings;
    if (surface.get_array().get(rings) != SUCCESS)
      return fail(geometryPath(g) + ": boundaries" + indexPath(path) + " is not an array of rings");
    facePoints_.clear();
    faceIds_.clear();
    ringEnds_.clear();
    std::size_t ringIndex = 0;
    for (dom::element ring : rings) {
      dom::array indices;
      if (ring.get_array().get(indices) != SUCCESS)
        return fail(geometryPath(g) + ": boundaries" + indexPath(path) + "[" + std::to_string(ringIndex) +
                    "] is not an array of vertex indices");
      const std::size_t ringBegin = faceIds_.size();
      std::size_t k = 0;
      for (dom::element v : indices) {
        std::uint64_t index = 0;
        if (v.get_uint64().get(index) != SUCCESS || index >= vertices_.size()) {
          std::int64_t shown = 0;
          const bool integer = v.get_int64().get(shown) == SUCCESS;
          return fail(geometryPath(g) + ": boundaries" + indexPath(path) + "[" + std::to_string(ringIndex) + "][" +
                      std::to_string(k) + "]: " +
                      (integer ? "vertex index " + std::to_string(shown) + " out of range (" +
                                     std::to_string(vertices_.size()) + " vertices)"
                               : std::string("not a vertex index")));
        }
        const auto id = static_cast<std::uint32_t>(index);
        // Repeated consecutive indices add nothing to a ring.
        if (faceIds_.size() == ringBegin || faceIds_.back() != id) faceIds_.push_back(id);
        ++k;
      }
      while (faceIds_.size() > ringBegin + 1 && faceIds_.back() == faceIds_[ringBegin]) faceIds_.pop_back();
      if (faceIds_.size() - ringBegin < 3) {
        faceIds_.resize(ringBegin);
        if (ringIndex == 0) {  // no outer ring: the whole face is degenerate
          skipFace(g, path, "its outer ring has fewer than 3 distinct vertices");
          return {};
        }
      } else {
        ringEnds_.push_back(static_cast<std::uint32_t>(faceIds_.size()));
      }
      ++ringIndex;
    }
    if (ringEnds_.empty()) {
      skipFace(g, path, "it has no rings");
      return {};
    }
    for (std::uint32_t id : faceIds_) facePoints_.push_back(vertices_[id]);
    faceTriangles_.clear();
    if (!triangulateFace(facePoints_, ringEnds_, faceTriangles_)) {
      skipFace(g, path, "it has no area or its rings cross");
      return {};
    }
    for (std::uint32_t local : faceTriangles_) building_.triangles.push_back(localVertex(faceIds_[local]));
    codes_.insert(codes_.end(), faceTriangles_.size() / 3, code);
    return {};
  }

  void skipFace(const GeometryRef& g, const std::vector<std::size_t>& path, const std::string& why) {
    ++file_.facesSkipped;
    warn(geometryPath(g) + ": face boundaries" + indexPath(path) + " skipped: " + why);
  }

  std::uint32_t localVertex(std::uint32_t global) {
    const auto [it, inserted] = localIndex_.emplace(global, static_cast<std::uint32_t>(building_.positions.size()));
    if (inserted) building_.positions.push_back(vertices_[global]);
    return it->second;
  }

  void classifyByNormal() {
    double minZ = building_.positions.front().z;
    for (const glm::dvec3& p : building_.positions) minZ = std::min(minZ, p.z);
    building_.kinds.resize(codes_.size());
    for (std::size_t t = 0; t < codes_.size(); ++t) {
      if (codes_[t] != kByNormal) {
        building_.kinds[t] = static_cast<SurfaceKind>(codes_[t]);
        continue;
      }
      const glm::dvec3& a = building_.positions[building_.triangles[3 * t]];
      const glm::dvec3& b = building_.positions[building_.triangles[3 * t + 1]];
      const glm::dvec3& c = building_.positions[building_.triangles[3 * t + 2]];
      const bool atBase = std::max({a.z, b.z, c.z}) - minZ <= 0.01;
      building_.kinds[t] = kindFromNormal(glm::cross(b - a, c - a), atBase);
    }
  }

  void readAttributes(dom::element object) {
    dom::object attributes;
    if (object["attributes"].get_object().get(attributes) != SUCCESS) return;
    std::string_view text;
    double number = 0.0;
    if (attributes["name"].get_string().get(text) == SUCCESS) building_.name = std::string(text);
    for (const char* key : {"function", "usage"}) {
      if (attributes[key].get_string().get(text) == SUCCESS) {
        building_.function = std::string(text);
        break;
      }
    }
    if (attributes["storeysAboveGround"].get_double().get(number) == SUCCESS && std::isfinite(number) && number >= 0.0)
      building_.storeysAboveGround = number;
    if (attributes["measuredHeight"].get_double().get(number) == SUCCESS && std::isfinite(number))
      building_.measuredHeightM = number;
    for (const char* key : {"yearOfConstruction", "oorspronkelijk_bouwjaar"}) {
      dom::element value;
      if (attributes[key].get(value) != SUCCESS) continue;
      if (value.get_double().get(number) == SUCCESS && number >= 1000.0 && number <= 2100.0) {
        building_.startYear = static_cast<int>(number);
        break;
      }
      if (value.get_string().get(text) == SUCCESS) {
        if (const auto year = parseStartYear(text)) {
          building_.startYear = *year;
          break;
        }
      }
    }
  }

  std::string_view text_;
  std::string name_;
  const CityJsonOptions& options_;
  dom::parser parser_;
  double scale_[3] = {1.0, 1.0, 1.0};
  double translate_[3] = {0.0, 0.0, 0.0};
  std::vector<glm::dvec3> vertices_;
  CityJsonFile file_;
  // The building being read, and scratch space reused across faces.
  CityJsonBuilding building_;
  std::unordered_map<std::uint32_t, std::uint32_t> localIndex_;
  std::vector<std::uint8_t> codes_;
  std::vector<glm::dvec3> facePoints_;
  std::vector<std::uint32_t> faceIds_;
  std::vector<std::uint32_t> ringEnds_;
  std::vector<std::uint32_t> faceTriangles_;
};

}  // namespace

Result<CityJsonFile> parseCityJson(std::string_view text, const std::string& name, const CityJsonOptions& options) {
  return CityJsonReader(text, name, options).read();
}

Result<CityJsonFile> readCityJson(const std::string& path, const CityJsonOptions& options) {
  Result<std::string> text = readTextFile(path, 2ull << 30);
  if (!text.ok()) return Error{text.error()};
  return parseCityJson(*text, path, options);
}

}  // namespace qv::prep
