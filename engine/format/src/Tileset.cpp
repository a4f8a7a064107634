#include "qv/format/Tileset.h"

#include <simdjson.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <tuple>

#include "qv/core/JsonWriter.h"
#include "qv/core/NumberFormat.h"

namespace qv {
namespace {

/// Heights beyond this are not buildings (and would not fit the float the tiles keep).
constexpr double kMaxHeightM = 1.0e5;
/// Positions and sizes in the city frame lie within this of its origin (as the tiles' origins).
constexpr double kMaxCoordinateM = 1.0e7;
/// The ground pyramid: a level-0 square of at most the ground tiles' largest extent, at most 24
/// levels (a 40,000 km square still has 2.4 m leaves) and a million cells with a file.
constexpr double kMaxGroundSizeM = 1.0e8;
constexpr std::uint64_t kMaxGroundLevels = 24;
constexpr std::size_t kMaxGroundNodes = 1000000;
constexpr const char* kDamageKeys[6] = {"none", "slight", "moderate", "extensive", "complete", "no_result"};

std::string hex32(std::uint32_t v) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%08x", v);
  return buffer;
}

void writeRect(JsonWriter& w, const Rect& r) {
  w.beginArray().value(r.minX).value(r.minY).value(r.maxX).value(r.maxY).endArray();
}

void writeCityFile(JsonWriter& w, const char* key, const CityFile& f) {
  w.key(key).beginObject();
  w.field("file", f.file).field("bytes", f.bytes).field("crc32", hex32(f.crc32));
  w.endObject();
}

void writeCounts(JsonWriter& w, const char* key, const std::map<std::string, std::uint64_t>& counts) {
  w.key(key).beginObject();
  for (const auto& [what, n] : counts) w.field(what, n);
  w.endObject();
}

void writeGround(JsonWriter& w, const GroundLayer& g) {
  w.key("ground").beginObject();
  w.field("minX", g.minX).field("minY", g.minY).field("size", g.size);
  w.field("levels", static_cast<unsigned>(g.levels)).field("bytes", g.bytes);
  if (!g.features.empty()) writeCounts(w, "features", g.features);
  if (!g.skipped.empty()) writeCounts(w, "skipped", g.skipped);
  w.key("nodes").beginArray();
  for (const GroundNode& n : g.nodes) {
    w.breakLine();
    w.beginObject();
    w.field("level", static_cast<unsigned>(n.level)).field("x", n.x).field("y", n.y);
    w.field("geometricError", n.geometricErrorM);
    w.field("file", n.file).field("bytes", n.bytes).field("crc32", hex32(n.crc32));
    w.endObject();
  }
  w.endArray();
  w.endObject();
}

void writeNode(JsonWriter& w, const Tileset& t, std::uint32_t index, int depth) {
  const TileNode& n = t.nodes[index];
  w.beginObject();
  w.field("level", static_cast<unsigned>(n.level)).field("x", n.x).field("y", n.y);
  w.key("bounds");
  writeRect(w, n.bounds);
  w.field("maxHeight", n.maxHeightM);
  w.field("coarse", n.coarse);
  w.field("geometricError", n.geometricErrorM);
  w.field("buildings", n.buildings);
  w.field("subtreeBuildings", n.subtreeBuildings);
  w.field("file", n.file).field("bytes", n.bytes).field("crc32", hex32(n.crc32));
  if (n.response) {
    w.key("response").beginObject();
    w.field("summary", n.response->summaryFile).field("summaryBytes", n.response->summaryBytes);
    w.field("summaryCrc32", hex32(n.response->summaryCrc32));
    if (!n.response->historyFile.empty()) {
      w.field("history", n.response->historyFile).field("historyBytes", n.response->historyBytes);
      w.field("historyCrc32", hex32(n.response->historyCrc32));
    }
    w.endObject();
  }
  if (!n.children.empty() && depth < 64) {
    w.key("children").beginArray();
    for (std::uint32_t c : n.children) {
      w.breakLine();
      writeNode(w, t, c, depth + 1);
    }
    w.endArray();
  }
  w.endObject();
}

// --- parsing ---------------------------------------------------------------------------------

using simdjson::dom::element;
using simdjson::dom::object;

struct Parser {
  std::string prefix;
  std::string error;

  bool fail(const std::string& what) {
    if (error.empty()) error = prefix + what;
    return false;
  }
  bool number(const object& o, const char* key, double& out, const std::string& where) {
    element e;
    if (o[key].get(e) != simdjson::SUCCESS) return fail(where + ": missing \"" + key + "\"");
    if (e.get_double().get(out) != simdjson::SUCCESS || !std::isfinite(out)) {
      return fail(where + ": \"" + key + "\" is not a number");
    }
    return true;
  }
  bool unsignedNumber(const object& o, const char* key, std::uint64_t& out, const std::string& where) {
    double v = 0;
    if (!number(o, key, v, where)) return false;
    if (v < 0 || v > 9.0e15 || std::floor(v) != v) return fail(where + ": \"" + key + "\" is not a count");
    out = static_cast<std::uint64_t>(v);
    return true;
  }
  bool text(const object& o, const char* key, std::string& out, const std::string& where, bool required = true) {
    std::string_view v;
    const auto r = o[key].get(v);
    if (r == simdjson::NO_SUCH_FIELD && !required) return true;
    if (r != simdjson::SUCCESS) return fail(where + ": \"" + key + "\" missing or not a string");
    out = std::string(v);
    return true;
  }
  bool hex(const object& o, const char* key, std::uint32_t& out, const std::string& where) {
    std::string s;
    if (!text(o, key, s, where)) return false;
    // Digits only: strtoul alone would also take " 1", "+1", "-1" (as 0xffffffff) and "0x1".
    if (s.empty() || s.size() > 8 || s.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) {
      return fail(where + ": \"" + key + "\" is not hex");
    }
    out = static_cast<std::uint32_t>(std::strtoul(s.c_str(), nullptr, 16));
    return true;
  }
  /// A file size: the binary formats store their own size in 32 bits.
  bool fileSize(const object& o, const char* key, std::uint64_t& out, const std::string& where) {
    if (!unsignedNumber(o, key, out, where)) return false;
    if (out > 0xFFFFFFFFull) return fail(where + ": \"" + key + "\" is larger than a QuakeView file can be (4 GiB)");
    return true;
  }
  bool rect(const object& o, const char* key, Rect& out, const std::string& where) {
    simdjson::dom::array a;
    if (o[key].get(a) != simdjson::SUCCESS || a.size() != 4)
      return fail(where + ": \"" + key + "\" must be [minX, minY, maxX, maxY]");
    double v[4];
    std::size_t i = 0;
    for (element e : a) {
      if (e.get_double().get(v[i]) != simdjson::SUCCESS || !std::isfinite(v[i]) || std::abs(v[i]) > 1e7) {
        return fail(where + ": \"" + key + "\" holds a non-number");
      }
      ++i;
    }
    out = Rect{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]), static_cast<float>(v[3])};
    if (out.minX > out.maxX || out.minY > out.maxY) return fail(where + ": \"" + key + "\" has min > max");
    return true;
  }
  // Relative paths only: a manifest must not point the viewer or tools outside its directory.
  bool relativePath(const std::string& path, const std::string& where) {
    if (path.empty() || path[0] == '/' || path.find("..") != std::string::npos || path.find(':') != std::string::npos ||
        path.find('\\') != std::string::npos) {
      return fail(where + ": file \"" + path + "\" is not a relative path inside the city directory");
    }
    return true;
  }

  /// An optional object of counts by name (a ground layer's "features" and "skipped").
  bool counts(const object& o, const char* key, std::map<std::string, std::uint64_t>& out, const std::string& where) {
    element e;
    if (o[key].get(e) != simdjson::SUCCESS) return true;
    object counts;
    if (e.get(counts) != simdjson::SUCCESS) return fail(where + ": \"" + key + "\" must be an object of counts");
    for (auto field : counts) {
      std::uint64_t n = 0;
      const std::string what(field.key);
      if (!unsignedNumber(counts, what.c_str(), n, where + " " + key)) return false;
      out[what] = n;
    }
    return true;
  }

  bool cityFile(const object& o, CityFile& f, const std::string& where) {
    return text(o, "file", f.file, where) && fileSize(o, "bytes", f.bytes, where) && hex(o, "crc32", f.crc32, where) &&
           relativePath(f.file, where);
  }

  /// The ground layer (docs/formats.md "Ground tile"): the pyramid's square, its levels and the
  /// cells that have a file, each inside the pyramid and listed once.
  bool ground(const object& o, GroundLayer& g) {
    const std::string where = "ground";
    std::uint64_t levels = 0;
    if (!number(o, "minX", g.minX, where) || !number(o, "minY", g.minY, where) || !number(o, "size", g.size, where) ||
        !unsignedNumber(o, "levels", levels, where) || !unsignedNumber(o, "bytes", g.bytes, where)) {
      return false;
    }
    if (std::abs(g.minX) > kMaxCoordinateM || std::abs(g.minY) > kMaxCoordinateM) {
      return fail(where + ": \"minX\" and \"minY\" must lie within 1e7 m of the origin");
    }
    if (!(g.size > 0.0 && g.size <= kMaxGroundSizeM)) {
      return fail(where + ": \"size\" must be a positive number of metres, at most 1e8");
    }
    if (levels < 1 || levels > kMaxGroundLevels) {
      return fail(where + ": \"levels\" must be 1 to " + std::to_string(kMaxGroundLevels) + ", not " +
                  std::to_string(levels));
    }
    g.levels = static_cast<std::uint8_t>(levels);
    if (!counts(o, "features", g.features, where) || !counts(o, "skipped", g.skipped, where)) return false;
    simdjson::dom::array nodes;
    if (o["nodes"].get(nodes) != simdjson::SUCCESS) return fail(where + ": \"nodes\" missing or not an array");
    if (nodes.size() > kMaxGroundNodes) return fail(where + ": more than a million \"nodes\"");
    std::set<std::tuple<std::uint64_t, std::uint64_t, std::uint64_t>> cells;
    for (element e : nodes) {
      const std::string at = "ground node " + std::to_string(g.nodes.size());
      object n;
      if (e.get(n) != simdjson::SUCCESS) return fail(at + ": a ground node must be an object");
      GroundNode node;
      std::uint64_t level = 0, x = 0, y = 0;
      double geometricError = 0;
      if (!unsignedNumber(n, "level", level, at) || !unsignedNumber(n, "x", x, at) || !unsignedNumber(n, "y", y, at) ||
          !number(n, "geometricError", geometricError, at) || !text(n, "file", node.file, at) ||
          !fileSize(n, "bytes", node.bytes, at) || !hex(n, "crc32", node.crc32, at)) {
        return false;
      }
      if (level >= levels) {
        return fail(at + ": \"level\" " + std::to_string(level) + " is not below \"levels\" " + std::to_string(levels));
      }
      if (x >= (1ull << level) || y >= (1ull << level)) {
        return fail(at + ": \"x\" " + std::to_string(x) + " and \"y\" " + std::to_string(y) + " must be below 2^" +
                    std::to_string(level) + " at level " + std::to_string(level));
      }
      if (!(geometricError >= 0.0 && geometricError <= kMaxCoordinateM)) {
        return fail(at + ": \"geometricError\" must be 0 to 1e7 m");
      }
      if (!relativePath(node.file, at)) return false;
      if (!cells.emplace(level, x, y).second) {
        return fail(at + ": cell " + std::to_string(level) + "/" + std::to_string(x) + "/" + std::to_string(y) +
                    " is listed twice");
      }
      node.level = static_cast<std::uint8_t>(level);
      node.x = static_cast<std::uint32_t>(x);
      node.y = static_cast<std::uint32_t>(y);
      node.geometricErrorM = static_cast<float>(geometricError);
      g.nodes.push_back(std::move(node));
    }
    return true;
  }

  bool node(const element& e, Tileset& t, int depth, const std::string& where) {
    if (depth > 40) return fail(where + ": tile tree deeper than 40 levels");
    if (t.nodes.size() >= 1000000) return fail("more than a million tiles");
    object o;
    if (e.get(o) != simdjson::SUCCESS) return fail(where + ": a tile must be an object");
    TileNode n;
    std::uint64_t level = 0, x = 0, y = 0, buildings = 0, bytes = 0;
    double maxHeight = 0, geometricError = 0;
    if (!unsignedNumber(o, "level", level, where) || !unsignedNumber(o, "x", x, where) ||
        !unsignedNumber(o, "y", y, where) || !rect(o, "bounds", n.bounds, where) ||
        !number(o, "maxHeight", maxHeight, where) || !unsignedNumber(o, "buildings", buildings, where) ||
        !unsignedNumber(o, "subtreeBuildings", n.subtreeBuildings, where) || !text(o, "file", n.file, where) ||
        !fileSize(o, "bytes", bytes, where) || !hex(o, "crc32", n.crc32, where)) {
      return false;
    }
    if (level > 30 || x >= (1ull << level) || y >= (1ull << level)) return fail(where + ": invalid level/x/y");
    if (std::abs(maxHeight) > kMaxHeightM) return fail(where + ": \"maxHeight\" out of range");
    if (buildings > 0xFFFFFFFFull) return fail(where + ": too many buildings");
    if (!relativePath(n.file, where)) return false;
    n.level = static_cast<std::uint8_t>(level);
    n.x = static_cast<std::uint32_t>(x);
    n.y = static_cast<std::uint32_t>(y);
    n.buildings = static_cast<std::uint32_t>(buildings);
    n.bytes = bytes;
    n.maxHeightM = static_cast<float>(maxHeight);
    bool coarse = false;
    if (o["coarse"].get(coarse) == simdjson::SUCCESS) n.coarse = coarse;
    if (o["geometricError"].get_double().get(geometricError) == simdjson::SUCCESS && std::isfinite(geometricError) &&
        std::abs(geometricError) <= 1e7) {
      n.geometricErrorM = static_cast<float>(geometricError);
    }
    object r;
    if (o["response"].get(r) == simdjson::SUCCESS) {
      TileResponseFiles files;
      const std::string rw = where + " response";
      if (!text(r, "summary", files.summaryFile, rw) || !fileSize(r, "summaryBytes", files.summaryBytes, rw) ||
          !hex(r, "summaryCrc32", files.summaryCrc32, rw) || !relativePath(files.summaryFile, rw)) {
        return false;
      }
      if (r["history"].error() == simdjson::SUCCESS) {
        if (!text(r, "history", files.historyFile, rw) || !fileSize(r, "historyBytes", files.historyBytes, rw) ||
            !hex(r, "historyCrc32", files.historyCrc32, rw) || !relativePath(files.historyFile, rw)) {
          return false;
        }
      }
      n.response = files;
    }
    const auto index = static_cast<std::uint32_t>(t.nodes.size());
    t.nodes.push_back(n);
    simdjson::dom::array children;
    if (o["children"].get(children) == simdjson::SUCCESS) {
      if (children.size() > 4) return fail(where + ": a quadtree tile has at most 4 children");
      std::vector<std::uint32_t> childIndices;
      for (element c : children) {
        const auto childIndex = static_cast<std::uint32_t>(t.nodes.size());
        if (!node(c, t, depth + 1, where + "/" + std::to_string(childIndices.size()))) return false;
        const TileNode& child = t.nodes[childIndex];
        if (child.level != n.level + 1 || child.x / 2 != n.x || child.y / 2 != n.y) {
          return fail(where + ": child " + child.key() + " is not a quadtree child of " + n.key());
        }
        childIndices.push_back(childIndex);
      }
      t.nodes[index].children = std::move(childIndices);
    }
    return true;
  }
};

}  // namespace

std::string TileNode::key() const {
  return std::to_string(level) + "/" + std::to_string(x) + "/" + std::to_string(y);
}

std::string tilesetToJson(const Tileset& t) {
  JsonWriter w;
  w.beginObject();
  w.field("format", kTilesetFormat).field("version", t.version);
  w.field("generator", t.generator);
  if (!t.name.empty()) w.field("name", t.name);
  w.key("origin").beginArray().value(t.originLon).value(t.originLat).endArray();
  w.key("projection").beginObject();
  w.field("type", t.projection).field("ellipsoid", "WGS84").field("centralMeridian", t.originLon);
  w.field("latitudeOfOrigin", t.originLat).field("scaleFactor", 1.0).field("units", "m");
  w.endObject();
  w.key("bounds");
  writeRect(w, t.bounds);
  w.field("maxHeight", t.maxHeightM);
  w.field("buildings", t.buildings);
  w.field("buildingsRevision", t.buildingsRevision);
  w.key("sources").beginArray();
  for (const std::string& s : t.sources) w.value(s);
  w.endArray();
  if (!t.excluded.empty()) {
    w.key("excluded").beginObject();
    for (const auto& [reason, n] : t.excluded) w.field(reason, n);
    w.endObject();
  }
  if (t.response) {
    const ResponseInfo& r = *t.response;
    w.key("response").beginObject();
    w.field("motion", r.motion).field("scenario", r.scenario).field("method", r.method);
    w.field("durationSeconds", r.durationSeconds).field("sampleRateHz", r.sampleRateHz);
    w.field("buildingsRevision", r.buildingsRevision);
    w.key("damageStates").beginObject();
    for (int i = 0; i < 6; ++i) w.field(kDamageKeys[i], r.damageStates[i]);
    w.endObject();
    if (!r.motionPreviewG.empty()) {
      w.field("motionPreviewRateHz", r.motionPreviewRateHz);
      w.key("motionPreviewG").beginArray();
      for (float v : r.motionPreviewG) w.value(v);
      w.endArray();
    }
    if (r.summaryIndex) writeCityFile(w, "summaryIndex", *r.summaryIndex);
    if (r.notes) writeCityFile(w, "notes", *r.notes);
    if (!r.eventType.empty()) w.field("eventType", r.eventType);
    if (!r.shakingField.empty()) w.field("shakingField", r.shakingField);
    if (!r.scaling.empty()) w.field("scaling", r.scaling);
    if (r.shakemap) {
      const ResponseInfo::ShakeMap& m = *r.shakemap;
      w.key("shakemap").beginObject();
      w.field("eventId", m.eventId).field("version", m.version).field("processTimestamp", m.processTimestamp);
      w.field("eventTimestamp", m.eventTimestamp).field("description", m.description).field("source", m.source);
      w.field("magnitude", m.magnitude).field("depthKm", m.depthKm);
      w.field("latitude", m.latitudeDeg).field("longitude", m.longitudeDeg);
      w.endObject();
    }
    if (!r.records.empty()) {
      w.key("records").beginArray();
      for (const std::string& s : r.records) w.value(s);
      w.endArray();
    }
    if (!r.timeOfDay.empty()) w.field("timeOfDay", r.timeOfDay);
    if (r.consequences) writeCityFile(w, "consequences", *r.consequences);
    w.endObject();
  }
  if (t.search) writeCityFile(w, "search", *t.search);
  if (t.ground) writeGround(w, *t.ground);
  if (t.districts) {
    const DistrictsInfo& d = *t.districts;
    w.key("districts").beginObject();
    w.field("file", d.file.file).field("bytes", d.file.bytes).field("crc32", hex32(d.file.crc32));
    w.field("count", d.count).field("source", d.source).field("inferred", d.inferred).field("coverage", d.coverage);
    w.endObject();
  }
  if (!t.nodes.empty()) {
    w.key("root");
    writeNode(w, t, 0, 0);
  }
  w.endObject();
  std::string out = w.take();
  out += '\n';
  return out;
}

Result<Tileset> parseTileset(std::string_view json, std::string_view name) {
  Parser p;
  p.prefix = std::string(name) + ": ";
  if (json.size() > (256u << 20)) return Error{p.prefix + "manifest larger than 256 MB"};
  simdjson::dom::parser parser;
  element doc;
  const simdjson::padded_string padded(json.data(), json.size());
  if (const auto err = parser.parse(padded).get(doc); err != simdjson::SUCCESS) {
    return Error{p.prefix + "not valid JSON (" + simdjson::error_message(err) + ")"};
  }
  object root;
  if (doc.get(root) != simdjson::SUCCESS) return Error{p.prefix + "the manifest must be a JSON object"};
  Tileset t;
  std::string format;
  if (!p.text(root, "format", format, "manifest")) return Error{p.error};
  if (format != kTilesetFormat) return Error{p.prefix + "not a QuakeView tileset (format \"" + format + "\")"};
  double version = 0;
  if (!p.number(root, "version", version, "manifest")) return Error{p.error};
  if (version != kTilesetVersion) {
    // Printed as written: a hostile version (1e300) must not reach an integer conversion.
    return Error{p.prefix + "manifest: unsupported tileset version " + formatDouble(version, 10) +
                 " (this build reads version " + std::to_string(kTilesetVersion) + ")"};
  }
  t.version = kTilesetVersion;
  p.text(root, "generator", t.generator, "manifest", false);
  if (!p.text(root, "name", t.name, "manifest", false)) return Error{p.error};
  simdjson::dom::array origin;
  if (root["origin"].get(origin) != simdjson::SUCCESS || origin.size() != 2) {
    return Error{p.prefix + "\"origin\" must be [lon, lat]"};
  }
  if (origin.at(0).get_double().get(t.originLon) != simdjson::SUCCESS ||
      origin.at(1).get_double().get(t.originLat) != simdjson::SUCCESS || !(std::abs(t.originLon) <= 180.0) ||
      !(std::abs(t.originLat) <= 85.0)) {
    return Error{p.prefix + "\"origin\" must hold a longitude in [-180, 180] and a latitude in [-85, 85]"};
  }
  object projection;
  if (root["projection"].get(projection) == simdjson::SUCCESS)
    p.text(projection, "type", t.projection, "projection", false);
  double maxHeight = 0;
  std::uint64_t revision = 1;
  if (!p.rect(root, "bounds", t.bounds, "manifest") || !p.number(root, "maxHeight", maxHeight, "manifest") ||
      !p.unsignedNumber(root, "buildings", t.buildings, "manifest")) {
    return Error{p.error};
  }
  if (root["buildingsRevision"].error() == simdjson::SUCCESS &&
      !p.unsignedNumber(root, "buildingsRevision", revision, "manifest")) {
    return Error{p.error};
  }
  if (std::abs(maxHeight) > kMaxHeightM) return Error{p.prefix + "manifest: \"maxHeight\" out of range"};
  t.buildingsRevision = revision;
  t.maxHeightM = static_cast<float>(maxHeight);
  simdjson::dom::array sources;
  if (root["sources"].get(sources) == simdjson::SUCCESS) {
    for (element s : sources) {
      std::string_view v;
      if (s.get(v) == simdjson::SUCCESS) t.sources.emplace_back(v);
    }
  }
  object excluded;
  if (root["excluded"].get(excluded) == simdjson::SUCCESS) {
    for (auto field : excluded) {
      std::uint64_t n = 0;
      const std::string reason(field.key);
      if (!p.unsignedNumber(excluded, reason.c_str(), n, "excluded")) return Error{p.error};
      t.excluded[reason] = n;
    }
  }
  object response;
  if (root["response"].get(response) == simdjson::SUCCESS) {
    ResponseInfo r;
    std::uint64_t rev = 0;
    if (!p.text(response, "motion", r.motion, "response") || !p.text(response, "scenario", r.scenario, "response") ||
        !p.text(response, "method", r.method, "response") ||
        !p.number(response, "durationSeconds", r.durationSeconds, "response") ||
        !p.number(response, "sampleRateHz", r.sampleRateHz, "response") ||
        !p.unsignedNumber(response, "buildingsRevision", rev, "response")) {
      return Error{p.error};
    }
    r.buildingsRevision = rev;
    object states;
    if (response["damageStates"].get(states) != simdjson::SUCCESS)
      return Error{p.prefix + "response: missing damageStates"};
    for (int i = 0; i < 6; ++i) {
      if (!p.unsignedNumber(states, kDamageKeys[i], r.damageStates[i], "response damageStates")) return Error{p.error};
    }
    simdjson::dom::array preview;
    if (response["motionPreviewG"].get(preview) == simdjson::SUCCESS) {
      if (preview.size() > 100000) return Error{p.prefix + "response: motionPreviewG is too long"};
      if (!p.number(response, "motionPreviewRateHz", r.motionPreviewRateHz, "response") ||
          !(r.motionPreviewRateHz > 0.0 && r.motionPreviewRateHz <= 1000.0)) {
        return Error{p.prefix + "response: motionPreviewRateHz must be in (0, 1000]"};
      }
      for (element e : preview) {
        double v = 0;
        if (e.get_double().get(v) != simdjson::SUCCESS || !std::isfinite(v) || std::abs(v) > 100.0) {
          return Error{p.prefix + "response: motionPreviewG holds a non-number"};
        }
        r.motionPreviewG.push_back(static_cast<float>(v));
      }
    }
    object summaryIndex;
    if (response["summaryIndex"].get(summaryIndex) == simdjson::SUCCESS) {
      CityFile f;
      if (!p.cityFile(summaryIndex, f, "response summaryIndex")) return Error{p.error};
      r.summaryIndex = f;
    }
    object notes;
    if (response["notes"].get(notes) == simdjson::SUCCESS) {
      CityFile f;
      if (!p.cityFile(notes, f, "response notes")) return Error{p.error};
      r.notes = f;
    }
    if (!p.text(response, "eventType", r.eventType, "response", false) ||
        !p.text(response, "shakingField", r.shakingField, "response", false) ||
        !p.text(response, "scaling", r.scaling, "response", false) ||
        !p.text(response, "timeOfDay", r.timeOfDay, "response", false)) {
      return Error{p.error};
    }
    if (!r.eventType.empty() && r.eventType != "SCENARIO" && r.eventType != "ACTUAL") {
      return Error{p.prefix + "response: eventType must be \"SCENARIO\" or \"ACTUAL\", not \"" + r.eventType + "\""};
    }
    object shakemap;
    if (response["shakemap"].get(shakemap) == simdjson::SUCCESS) {
      ResponseInfo::ShakeMap m;
      const std::string where = "response shakemap";
      if (!p.text(shakemap, "eventId", m.eventId, where) || !p.text(shakemap, "version", m.version, where, false) ||
          !p.text(shakemap, "processTimestamp", m.processTimestamp, where, false) ||
          !p.text(shakemap, "eventTimestamp", m.eventTimestamp, where, false) ||
          !p.text(shakemap, "description", m.description, where, false) ||
          !p.text(shakemap, "source", m.source, where, false) || !p.number(shakemap, "magnitude", m.magnitude, where) ||
          !p.number(shakemap, "depthKm", m.depthKm, where) || !p.number(shakemap, "latitude", m.latitudeDeg, where) ||
          !p.number(shakemap, "longitude", m.longitudeDeg, where)) {
        return Error{p.error};
      }
      r.shakemap = m;
    }
    simdjson::dom::array records;
    if (response["records"].get(records) == simdjson::SUCCESS) {
      if (records.size() > 1000) return Error{p.prefix + "response: more than 1000 records"};
      for (element e : records) {
        std::string_view v;
        if (e.get_string().get(v) != simdjson::SUCCESS) return Error{p.prefix + "response: records holds a non-string"};
        r.records.emplace_back(v);
      }
    }
    object consequences;
    if (response["consequences"].get(consequences) == simdjson::SUCCESS) {
      CityFile f;
      if (!p.cityFile(consequences, f, "response consequences")) return Error{p.error};
      r.consequences = f;
    }
    t.response = r;
  }
  object search;
  if (root["search"].get(search) == simdjson::SUCCESS) {
    CityFile f;
    if (!p.cityFile(search, f, "search")) return Error{p.error};
    t.search = f;
  }
  // Absent in manifests written before the ground layer and in cities made with --no-ground.
  element groundValue;
  if (root["ground"].get(groundValue) == simdjson::SUCCESS) {
    object groundObject;
    if (groundValue.get(groundObject) != simdjson::SUCCESS) return Error{p.prefix + "\"ground\" must be an object"};
    GroundLayer g;
    if (!p.ground(groundObject, g)) return Error{p.error};
    t.ground = std::move(g);
  }
  // Absent in manifests written before districts by default, and for inputs that name none.
  object districts;
  if (root["districts"].get(districts) == simdjson::SUCCESS) {
    DistrictsInfo d;
    bool inferred = false;
    if (!p.cityFile(districts, d.file, "districts") || !p.unsignedNumber(districts, "count", d.count, "districts") ||
        !p.text(districts, "source", d.source, "districts") ||
        !p.number(districts, "coverage", d.coverage, "districts")) {
      return Error{p.error};
    }
    if (districts["inferred"].get(inferred) != simdjson::SUCCESS) {
      return Error{p.prefix + "districts: \"inferred\" must be true or false"};
    }
    if (!(d.coverage >= 0.0 && d.coverage <= 1.0)) return Error{p.prefix + "districts: \"coverage\" must be 0 to 1"};
    if (d.count < 1 || d.count > 10000) return Error{p.prefix + "districts: \"count\" must be 1 to 10000"};
    d.inferred = inferred;
    t.districts = std::move(d);
  }
  element rootTile;
  if (root["root"].get(rootTile) != simdjson::SUCCESS) return Error{p.prefix + "missing \"root\" tile"};
  if (!p.node(rootTile, t, 0, "tile 0/0/0")) return Error{p.error};
  return t;
}

}  // namespace qv
