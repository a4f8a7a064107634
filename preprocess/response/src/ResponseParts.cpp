#include "qv/prep/ResponseParts.h"

#include <dirent.h>
#include <simdjson.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>

#include "ResponseFinish.h"
#include "ResponsePartFiles.h"
#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"
#include "qv/core/JsonWriter.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/StoredFile.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseCatalogue.h"

#ifndef QUAKEVIEW_VERSION
#define QUAKEVIEW_VERSION "unknown"
#endif

namespace qv::prep {

using detail::cityManifestIdentity;
using detail::describePart;
using detail::kPartManifest;
using detail::PartLeafEntry;
using detail::PartManifest;

namespace {

constexpr char kPartFormat[] = "quakeview-response-part";
constexpr int kPartVersion = 1;
constexpr std::uint32_t kResultsVersion = 1;
constexpr char kResultsFile[] = "results.qvp";
constexpr char kNotesFile[] = "notes.json";
constexpr char kInfoFile[] = "info.json";
constexpr char kDistrictsFile[] = "districts.geojson";

std::string hex32(std::uint32_t v) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%08x", v);
  return buffer;
}

std::string baseName(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// "name, N bytes, CRC-32 xxxxxxxx": a file by its name and content (not its path, which differs
// between machines).
Result<std::string> fileIdentity(const std::string& path) {
  auto bytes = readFile(path);
  if (!bytes.ok()) return Error{bytes.error()};
  return baseName(path) + ", " + std::to_string(bytes->size()) + " bytes, CRC-32 " + hex32(crc32(*bytes));
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace
namespace detail {

// The city's manifest without any response: what the parts were made from.
std::string cityManifestIdentity(const Tileset& tileset) {
  Tileset city = tileset;
  city.response.reset();
  for (TileNode& n : city.nodes) n.response.reset();
  const std::string json = tilesetToJson(city);
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(json.data()), json.size());
  return "manifest " + std::to_string(json.size()) + " bytes, CRC-32 " + hex32(crc32(bytes)) + ", buildings revision " +
         std::to_string(tileset.buildingsRevision);
}
}  // namespace detail
namespace {

// --- results.qvp ------------------------------------------------------------------------------

void writeProbabilities(ByteWriter& w, const seismic::DamageProbabilities& p) {
  for (const double v : p.p) w.f64(v);
}
void readProbabilities(ByteReader& r, seismic::DamageProbabilities& p) {
  for (double& v : p.p) v = r.f64("damage probability");
}
template <std::size_t N>
void writeArray(ByteWriter& w, const std::array<double, N>& a) {
  for (const double v : a) w.f64(v);
}
template <std::size_t N>
void readArray(ByteReader& r, std::array<double, N>& a, const char* what) {
  for (double& v : a) v = r.f64(what);
}

void writeLoss(ByteWriter& w, const seismic::BuildingLoss& l) {
  writeProbabilities(w, l.structural);
  writeProbabilities(w, l.nonStructuralDrift);
  writeProbabilities(w, l.nonStructuralAcceleration);
  w.f64(l.collapse);
  w.f64(l.occupantsPresent);
  writeArray(w, l.occupantsAt);
  w.u8(static_cast<std::uint8_t>((l.occupantsInferred ? 1 : 0) | (l.valueInferred ? 2 : 0)));
  writeArray(w, l.injuries);
  w.f64(l.replacementValueUsd);
  w.f64(l.repairCostUsd);
  w.f64(l.repairTimeDays);
  writeArray(w, l.tag);
  for (const auto& state : l.given.injuriesPerOccupant) writeArray(w, state);
  w.f64(l.given.collapseGivenComplete);
  writeArray(w, l.given.structuralCostUsd);
  writeArray(w, l.given.nsDriftCostUsd);
  writeArray(w, l.given.nsAccelerationCostUsd);
}

void readLoss(ByteReader& r, seismic::BuildingLoss& l) {
  readProbabilities(r, l.structural);
  readProbabilities(r, l.nonStructuralDrift);
  readProbabilities(r, l.nonStructuralAcceleration);
  l.collapse = r.f64("collapse");
  l.occupantsPresent = r.f64("occupants");
  readArray(r, l.occupantsAt, "occupants by time");
  const std::uint8_t flags = r.u8("loss flags");
  // Bits this version never writes mean the file was not written by it.
  if ((flags & ~3u) != 0) r.fail("a building's loss flags hold unknown bits");
  l.occupantsInferred = (flags & 1) != 0;
  l.valueInferred = (flags & 2) != 0;
  readArray(r, l.injuries, "injuries");
  l.replacementValueUsd = r.f64("replacement value");
  l.repairCostUsd = r.f64("repair cost");
  l.repairTimeDays = r.f64("repair time");
  readArray(r, l.tag, "tags");
  for (auto& state : l.given.injuriesPerOccupant) readArray(r, state, "injuries per occupant");
  l.given.collapseGivenComplete = r.f64("collapse given complete");
  readArray(r, l.given.structuralCostUsd, "structural cost");
  readArray(r, l.given.nsDriftCostUsd, "drift-sensitive cost");
  readArray(r, l.given.nsAccelerationCostUsd, "acceleration-sensitive cost");
}

// --- part.json --------------------------------------------------------------------------------

void cityFileJson(JsonWriter& w, const char* key, const CityFile& f) {
  w.key(key).beginObject();
  w.field("file", f.file).field("bytes", f.bytes).field("crc32", hex32(f.crc32));
  w.endObject();
}

std::string partManifestToJson(const PartManifest& m) {
  JsonWriter w;
  w.beginObject();
  w.field("format", std::string(kPartFormat)).field("version", std::uint64_t{kPartVersion});
  w.field("part", std::uint64_t{m.shard.part}).field("parts", std::uint64_t{m.shard.parts});
  w.field("created", m.created).field("host", m.host);
  w.field("scenario", std::uint64_t{m.scenario});
  w.key("scenarioNames").beginArray();
  for (const std::string& name : m.scenarioNames) w.value(name);
  w.endArray();
  w.key("run").beginObject();
  for (const auto& [key, value] : m.identity) w.field(key, value);
  w.endObject();
  w.key("leaves").beginArray();
  for (const PartLeafEntry& e : m.leaves) {
    w.beginObject().field("node", std::uint64_t{e.node});
    w.field("summary", e.files.summaryFile).field("summaryBytes", e.files.summaryBytes);
    w.field("summaryCrc32", hex32(e.files.summaryCrc32));
    w.field("history", e.files.historyFile).field("historyBytes", e.files.historyBytes);
    w.field("historyCrc32", hex32(e.files.historyCrc32));
    w.field("uncompressedBytes", e.stats.uncompressedBytes).field("driftSeriesBytes", e.stats.driftSeriesBytes);
    w.field("driftSeriesBuildings", e.stats.driftSeriesBuildings);
    w.field("rateSum", e.rate.sum).field("rateCount", e.rate.count);
    w.endObject();
  }
  w.endArray();
  cityFileJson(w, "results", m.results);
  cityFileJson(w, "notes", m.notes);
  cityFileJson(w, "info", m.info);
  if (m.districts) cityFileJson(w, "districts", *m.districts);
  w.key("population").beginObject();
  w.field("night", m.population.night).field("day", m.population.day).field("source", m.population.source);
  w.endObject();
  const ResponseRunReport& r = m.report;
  w.key("report").beginObject();
  w.field("buildings", r.buildings).field("seconds", r.seconds).field("solveSeconds", r.solveSeconds);
  w.field("passOneSeconds", r.passOneSeconds).field("passTwoSeconds", r.passTwoSeconds);
  w.field("encodeSeconds", r.encodeSeconds).field("lossSeconds", r.lossSeconds);
  w.field("storeySteps", r.storeySteps).field("nonConvergedSteps", r.nonConvergedSteps);
  w.field("encodingAttempts", r.encodingAttempts).field("outsideGrid", r.outsideGrid);
  w.field("worstRelativeError", r.worstRelativeError).field("p99RelativeError", r.p99RelativeError);
  w.field("scaling", r.scaling).field("frames", std::uint64_t{r.frames}).field("timeStepS", r.timeStepS);
  w.endObject();
  w.endObject();
  return w.str() + "\n";
}

// A small reader over simdjson objects that keeps the first error, naming the file and the key.
struct Fields {
  std::string name;
  std::string error;
  bool fail(const std::string& message) {
    if (error.empty()) error = name + ": " + message;
    return false;
  }
  bool u64(simdjson::dom::object o, const char* key, std::uint64_t& out) {
    if (o[key].get(out) != simdjson::SUCCESS) return fail(std::string("\"") + key + "\" is missing or not a count");
    return true;
  }
  bool f64(simdjson::dom::object o, const char* key, double& out) {
    if (o[key].get(out) == simdjson::SUCCESS) return true;
    std::int64_t i = 0;
    std::uint64_t u = 0;
    if (o[key].get(i) == simdjson::SUCCESS) {
      out = static_cast<double>(i);
      return true;
    }
    if (o[key].get(u) == simdjson::SUCCESS) {
      out = static_cast<double>(u);
      return true;
    }
    return fail(std::string("\"") + key + "\" is missing or not a number");
  }
  bool text(simdjson::dom::object o, const char* key, std::string& out) {
    std::string_view v;
    if (o[key].get(v) != simdjson::SUCCESS) return fail(std::string("\"") + key + "\" is missing or not text");
    out = std::string(v);
    return true;
  }
  bool crc(simdjson::dom::object o, const char* key, std::uint32_t& out) {
    std::string v;
    if (!text(o, key, v)) return false;
    char* end = nullptr;
    const unsigned long x = std::strtoul(v.c_str(), &end, 16);
    if (v.size() != 8 || end == nullptr || *end != '\0') return fail(std::string("\"") + key + "\" is not a CRC-32");
    out = static_cast<std::uint32_t>(x);
    return true;
  }
  bool file(simdjson::dom::object o, const char* key, CityFile& out) {
    simdjson::dom::object f;
    if (o[key].get(f) != simdjson::SUCCESS) return fail(std::string("\"") + key + "\" is missing");
    return text(f, "file", out.file) && u64(f, "bytes", out.bytes) && crc(f, "crc32", out.crc32);
  }
};

// A part's file names stay inside its folder.
bool plainName(const std::string& name) {
  return !name.empty() && name.find('/') == std::string::npos && name != "." && name != "..";
}

}  // namespace
namespace detail {

Result<PartManifest> parsePartManifest(std::string_view json, const std::string& name) {
  simdjson::dom::parser parser;
  simdjson::dom::object root;
  if (parser.parse(json.data(), json.size()).get(root) != simdjson::SUCCESS) {
    return Error{name + ": not valid JSON"};
  }
  Fields f{name, {}};
  PartManifest m;
  std::string format;
  std::uint64_t version = 0, part = 0, parts = 0;
  if (!f.text(root, "format", format) || !f.u64(root, "version", version)) return Error{f.error};
  if (format != kPartFormat) return Error{name + ": not a QuakeView response part (format \"" + format + "\")"};
  if (version != kPartVersion) {
    return Error{name + ": part format version " + std::to_string(version) + ", this tool reads version " +
                 std::to_string(kPartVersion) + " (re-run the part with this tool)"};
  }
  if (!f.u64(root, "part", part) || !f.u64(root, "parts", parts)) return Error{f.error};
  if (parts < 1 || parts > kMaxParts || part < 1 || part > parts) return Error{name + ": part numbers out of range"};
  m.shard = {static_cast<unsigned>(part), static_cast<unsigned>(parts)};
  std::uint64_t scenario = 0;
  if (!f.u64(root, "scenario", scenario)) return Error{f.error};
  simdjson::dom::array names;
  if (root["scenarioNames"].get(names) != simdjson::SUCCESS) return Error{name + ": \"scenarioNames\" is missing"};
  for (simdjson::dom::element e : names) {
    std::string_view v;
    if (e.get(v) != simdjson::SUCCESS) return Error{name + ": a scenario name is not text"};
    m.scenarioNames.emplace_back(v);
  }
  if (scenario > m.scenarioNames.size() || m.scenarioNames.size() > kMaxScenarios) {
    return Error{name + ": scenario " + std::to_string(scenario) + " of " + std::to_string(m.scenarioNames.size())};
  }
  m.scenario = static_cast<std::size_t>(scenario);
  f.text(root, "created", m.created);
  f.text(root, "host", m.host);
  simdjson::dom::object run;
  if (root["run"].get(run) != simdjson::SUCCESS) return Error{name + ": \"run\" is missing"};
  for (auto field : run) {
    std::string_view v;
    if (field.value.get(v) != simdjson::SUCCESS)
      return Error{name + ": run \"" + std::string(field.key) + "\" is not text"};
    m.identity.emplace_back(std::string(field.key), std::string(v));
  }
  simdjson::dom::array leaves;
  if (root["leaves"].get(leaves) != simdjson::SUCCESS) return Error{name + ": \"leaves\" is missing"};
  for (simdjson::dom::element e : leaves) {
    simdjson::dom::object o;
    if (e.get(o) != simdjson::SUCCESS) return Error{name + ": a leaf is not an object"};
    PartLeafEntry l;
    std::uint64_t node = 0;
    if (!f.u64(o, "node", node) || !f.text(o, "summary", l.files.summaryFile) ||
        !f.u64(o, "summaryBytes", l.files.summaryBytes) || !f.crc(o, "summaryCrc32", l.files.summaryCrc32) ||
        !f.text(o, "history", l.files.historyFile) || !f.u64(o, "historyBytes", l.files.historyBytes) ||
        !f.crc(o, "historyCrc32", l.files.historyCrc32) || !f.u64(o, "uncompressedBytes", l.stats.uncompressedBytes) ||
        !f.u64(o, "driftSeriesBytes", l.stats.driftSeriesBytes) ||
        !f.u64(o, "driftSeriesBuildings", l.stats.driftSeriesBuildings) || !f.f64(o, "rateSum", l.rate.sum) ||
        !f.u64(o, "rateCount", l.rate.count)) {
      return Error{f.error};
    }
    if (node > 0xFFFFFFFFu) return Error{name + ": a leaf's node is out of range"};
    if (!plainName(l.files.summaryFile) || !plainName(l.files.historyFile)) {
      return Error{name + ": a leaf's file names a path outside the part"};
    }
    l.node = static_cast<std::uint32_t>(node);
    m.leaves.push_back(std::move(l));
  }
  if (!f.file(root, "results", m.results) || !f.file(root, "notes", m.notes) || !f.file(root, "info", m.info)) {
    return Error{f.error};
  }
  simdjson::dom::object districts;
  if (root["districts"].get(districts) == simdjson::SUCCESS) {
    CityFile d;
    if (!f.file(root, "districts", d)) return Error{f.error};
    m.districts = d;
  }
  for (const CityFile* c : {&m.results, &m.notes, &m.info, m.districts ? &*m.districts : nullptr}) {
    if (c != nullptr && !plainName(c->file)) return Error{name + ": a file names a path outside the part"};
  }
  simdjson::dom::object population;
  if (root["population"].get(population) != simdjson::SUCCESS || !f.f64(population, "night", m.population.night) ||
      !f.f64(population, "day", m.population.day) || !f.text(population, "source", m.population.source)) {
    return Error{f.error.empty() ? name + ": \"population\" is missing" : f.error};
  }
  simdjson::dom::object report;
  if (root["report"].get(report) == simdjson::SUCCESS) {
    ResponseRunReport& r = m.report;
    f.u64(report, "buildings", r.buildings);
    f.f64(report, "seconds", r.seconds);
    f.f64(report, "solveSeconds", r.solveSeconds);
    f.f64(report, "passOneSeconds", r.passOneSeconds);
    f.f64(report, "passTwoSeconds", r.passTwoSeconds);
    f.f64(report, "encodeSeconds", r.encodeSeconds);
    f.f64(report, "lossSeconds", r.lossSeconds);
    f.u64(report, "storeySteps", r.storeySteps);
    f.u64(report, "nonConvergedSteps", r.nonConvergedSteps);
    f.u64(report, "encodingAttempts", r.encodingAttempts);
    f.u64(report, "outsideGrid", r.outsideGrid);
    f.f64(report, "worstRelativeError", r.worstRelativeError);
    f.f64(report, "p99RelativeError", r.p99RelativeError);
    std::uint64_t frames = 0;
    f.text(report, "scaling", r.scaling);
    f.u64(report, "frames", frames);
    f.f64(report, "timeStepS", r.timeStepS);
    r.frames = static_cast<std::size_t>(std::min<std::uint64_t>(frames, 1u << 30));
    if (!f.error.empty()) return Error{f.error};
  }
  return m;
}
}  // namespace detail
namespace {

std::string nowUtc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

std::string hostName() {
  char buffer[256] = {};
  if (gethostname(buffer, sizeof buffer - 1) != 0) return "";
  return buffer;
}

// Writes `bytes` as `name` in the part's folder and returns its entry (name relative to the folder).
Result<CityFile> writePartFile(const std::string& folder, const std::string& name,
                               std::span<const std::uint8_t> bytes) {
  if (Status s = writeFileAtomic(folder + "/" + name, bytes); !s.ok()) return Error{s.error()};
  return CityFile{name, bytes.size(), crc32(bytes)};
}
Result<CityFile> writePartFile(const std::string& folder, const std::string& name, const std::string& text) {
  return writePartFile(folder, name,
                       std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace
namespace detail {

// Why a part's file is not the one its manifest names.
std::string damagedPartFile(const std::string& part, const std::string& path, const FileDigest& got,
                            std::uint64_t bytes, std::uint32_t crc) {
  return part + " is damaged: " + path + " is not the file its part.json names (" + std::to_string(got.bytes) +
         " bytes, CRC-32 " + hex32(got.crc32) + "; expected " + std::to_string(bytes) + " bytes, CRC-32 " + hex32(crc) +
         "); re-run the part";
}

// Reads a part's file and checks it is the one the part's manifest names.
Result<std::vector<std::uint8_t>> readPartFile(const std::string& folder, const std::string& file, std::uint64_t bytes,
                                               std::uint32_t crc, const std::string& part) {
  const std::string path = folder + "/" + file;
  auto data = readFile(path);
  if (!data.ok()) return Error{part + " is incomplete: " + data.error()};
  const FileDigest got{data->size(), crc32(*data)};
  if (got.bytes != bytes || got.crc32 != crc) return Error{damagedPartFile(part, path, got, bytes, crc)};
  return data;
}

// The results of one building from a part's full summary of its leaf.
std::vector<BuildingResult> resultsFromSummary(const ResponseSummaryTile& t) {
  std::vector<BuildingResult> out(t.buildings.size());
  for (std::size_t b = 0; b < t.buildings.size(); ++b) {
    BuildingResult& r = out[b];
    r.summary = t.buildings[b];
    const std::uint32_t first = r.summary.firstStorey;
    for (std::uint16_t k = 0; k < r.summary.storeys; ++k) {
      if (first + k < t.storeyPeakDrift.size()) r.storeyPeakDrift.push_back(t.storeyPeakDrift[first + k]);
      if (!t.storeySpread.empty() && first + k < t.storeySpread.size())
        r.storeySpread.push_back(t.storeySpread[first + k]);
    }
    if (b < t.scaling.size()) r.scaling = t.scaling[b];
    if (b < t.sites.size()) r.site = t.sites[b];
    if (b < t.spread.size()) r.spread = t.spread[b];
    if (b < t.losses.size()) r.loss = t.losses[b];
    if (b < t.driftSeries.spans.size()) {
      const DriftSpan& span = t.driftSeries.spans[b];
      if (span.count > 0 && span.first + span.count <= t.driftSeries.codes.size()) {
        r.driftStartSeconds = span.startSeconds;
        r.driftCodes.assign(t.driftSeries.codes.begin() + span.first,
                            t.driftSeries.codes.begin() + span.first + span.count);
      }
    }
  }
  return out;
}

std::string describePart(const ShardSpec& s) {
  return "part " + std::to_string(s.part) + " of " + std::to_string(s.parts);
}
}  // namespace detail

std::optional<ShardSpec> parseShardSpec(std::string_view text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) return std::nullopt;
  const auto k = parseInteger(std::string(text.substr(0, slash)));
  const auto n = parseInteger(std::string(text.substr(slash + 1)));
  if (!k || !n || *n < 1 || *n > static_cast<std::int64_t>(kMaxParts) || *k < 1 || *k > *n) return std::nullopt;
  return ShardSpec{static_cast<unsigned>(*k), static_cast<unsigned>(*n)};
}

std::string partFolderName(const ShardSpec& shard) {
  return "part-" + std::to_string(shard.part) + "-of-" + std::to_string(shard.parts);
}

std::vector<std::vector<std::uint32_t>> assignParts(const Tileset& tileset, unsigned parts) {
  std::vector<std::uint32_t> leaves;
  for (std::uint32_t i = 0; i < tileset.nodes.size(); ++i) {
    if (tileset.nodes[i].children.empty()) leaves.push_back(i);
  }
  std::stable_sort(leaves.begin(), leaves.end(), [&](std::uint32_t a, std::uint32_t b) {
    return tileset.nodes[a].buildings > tileset.nodes[b].buildings;
  });
  std::vector<std::vector<std::uint32_t>> out(std::max(1u, parts));
  std::vector<std::uint64_t> load(out.size(), 0);
  for (const std::uint32_t leaf : leaves) {
    const std::size_t p = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    out[p].push_back(leaf);
    load[p] += tileset.nodes[leaf].buildings;
  }
  for (auto& part : out) std::sort(part.begin(), part.end());
  return out;
}

Result<RunIdentity> runIdentity(const Tileset& tileset, const ResponseRunOptions& o, unsigned parts) {
  RunIdentity id;
#ifdef QUAKEVIEW_WIDE_SIMD
  const char* kernel = "AVX2";
#else
  const char* kernel = "portable";
#endif
  id.emplace_back("tool", std::string("quakeview-prep ") + QUAKEVIEW_VERSION + ", solver kernel " + kernel);
  id.emplace_back("city", cityManifestIdentity(tileset));
  id.emplace_back("parts", std::to_string(parts));
  id.emplace_back(
      "scenario",
      o.scenarioIndex == 0
          ? std::string()
          : std::to_string(o.scenarioIndex) + " of " + std::to_string(o.scenarioNames.size()) + ": " +
                (o.scenarioIndex <= o.scenarioNames.size() ? o.scenarioNames[o.scenarioIndex - 1] : std::string()));
  std::string motions;
  if (!o.motions.empty()) {
    auto files = detail::expandMotionPaths(o.motions);
    if (!files.ok()) return Error{files.error()};
    for (const std::string& file : *files) {
      auto f = fileIdentity(file);
      if (!f.ok()) return Error{f.error()};
      motions += (motions.empty() ? "" : "; ") + *f;
    }
  }
  id.emplace_back("motion", motions);
  std::string motionY;
  if (!o.motionY.empty()) {
    auto f = fileIdentity(o.motionY);
    if (!f.ok()) return Error{f.error()};
    motionY = *f;
  }
  id.emplace_back("motion-y", motionY);
  std::string seeds;
  for (const std::uint64_t s : o.syntheticSeeds) seeds += (seeds.empty() ? "" : " ") + std::to_string(s);
  id.emplace_back("synthetic", seeds + (o.defaultSuite ? " (the built-in default suite)" : ""));
  id.emplace_back("dt", o.timeStepS ? number(*o.timeStepS) : "");
  id.emplace_back("units", o.units ? std::to_string(static_cast<int>(*o.units)) : "");
  id.emplace_back("pga", o.pgaG ? number(*o.pgaG) : "");
  std::string scenario;
  if (o.scenario) {
    const seismic::Scenario& s = *o.scenario;
    scenario = "M" + number(s.magnitude) + " at " + number(s.epicentreLongitudeDeg) + "," +
               number(s.epicentreLatitudeDeg) + " depth " + number(s.depthKm) + " km, vs30 " +
               number(s.vs30MetresPerSecond) + ", site factor " + number(s.siteFactor) + ", waves " +
               number(s.shearWaveSpeedKmPerS) + " km/s";
  }
  id.emplace_back("scenario", scenario);
  std::string shakemap;
  if (!o.shakemap.empty()) {
    auto f = fileIdentity(o.shakemap);
    if (!f.ok()) return Error{f.error()};
    shakemap = *f;
  }
  id.emplace_back("shakemap", shakemap);
  id.emplace_back("scale-by", o.scaleBy == ScaleBy::Pga ? "pga" : "sa");
  id.emplace_back("outside-grid", o.outsideGrid == OutsideGrid::Skip ? "skip" : "error");
  id.emplace_back("wave-speed", number(o.shearWaveSpeedKmPerS));
  id.emplace_back("time-of-day", std::string(seismic::timeOfDayName(o.timeOfDay)));
  std::string districts;
  if (!o.districts.empty()) {
    auto f = fileIdentity(o.districts);
    if (!f.ok()) return Error{f.error()};
    districts = *f;
  }
  id.emplace_back("districts", districts);
  id.emplace_back("population", o.population.given() ? number(o.population.night) + " night, " +
                                                           number(o.population.day) + " day, " + o.population.source
                                                     : "");
  id.emplace_back("history-tolerance", number(o.historyTolerance));
  return id;
}

std::vector<std::uint8_t> encodePartResults(const PartResults& results) {
  ByteWriter w;
  w.fourcc("QVPR");
  w.u32(kResultsVersion);
  w.u32(static_cast<std::uint32_t>(results.leafSummaries.size()));
  for (const auto& [node, bytes] : results.leafSummaries) {
    w.u32(node);
    w.u64(bytes.size());
    w.bytes(bytes);
  }
  w.u64(results.losses.size());
  for (const PartLoss& l : results.losses) {
    w.u64(l.key);
    w.i32(l.district);
    w.u8(static_cast<std::uint8_t>(l.lossClass.occupancy));
    w.u8(static_cast<std::uint8_t>(l.lossClass.type));
    w.u8(static_cast<std::uint8_t>((l.lossClass.typeInferred ? 1 : 0) | (l.lossClass.eraInferred ? 2 : 0) |
                                   (l.lossClass.useInferred ? 4 : 0)));
    writeLoss(w, l.loss);
  }
  return w.take();
}

Result<PartResults> decodePartResults(std::span<const std::uint8_t> bytes, std::string_view name) {
  ByteReader r(bytes);
  const std::string where(name);
  const auto magic = r.bytes(4, "magic");
  if (!r.ok() || std::memcmp(magic.data(), "QVPR", 4) != 0) return Error{where + ": not a part's results file"};
  const std::uint32_t version = r.u32("version");
  if (r.ok() && version != kResultsVersion) {
    return Error{where + ": results version " + std::to_string(version) + ", this tool reads version " +
                 std::to_string(kResultsVersion)};
  }
  PartResults out;
  const std::uint32_t leaves = r.u32("leaf count");
  for (std::uint32_t i = 0; i < leaves && r.ok(); ++i) {
    const std::uint32_t node = r.u32("leaf node");
    const std::uint64_t size = r.u64("summary size");
    if (size > r.remaining()) {
      r.fail("a leaf's summary runs past the end of the file");
      break;
    }
    const auto data = r.bytes(static_cast<std::size_t>(size), "summary");
    out.leafSummaries.emplace_back(node, std::vector<std::uint8_t>(data.begin(), data.end()));
  }
  const std::uint64_t count = r.ok() ? r.u64("loss count") : 0;
  // Each record is at least 8 + 4 + 3 bytes plus its numbers: no more records than bytes allow.
  if (r.ok() && count > r.remaining() / 100) r.fail("more losses than the file can hold");
  for (std::uint64_t i = 0; i < count && r.ok(); ++i) {
    PartLoss l;
    l.key = r.u64("loss key");
    l.district = r.i32("district");
    const std::uint8_t occupancy = r.u8("occupancy");
    const std::uint8_t type = r.u8("structural type");
    const std::uint8_t flags = r.u8("class flags");
    if (occupancy >= static_cast<std::uint8_t>(seismic::Occupancy::Count) ||
        type >= static_cast<std::uint8_t>(StructuralType::Count) || l.district < -1 || (flags & ~7u) != 0) {
      r.fail("a building's class, its flags or its district is out of range");
      break;
    }
    l.lossClass.occupancy = static_cast<seismic::Occupancy>(occupancy);
    l.lossClass.type = static_cast<StructuralType>(type);
    l.lossClass.typeInferred = (flags & 1) != 0;
    l.lossClass.eraInferred = (flags & 2) != 0;
    l.lossClass.useInferred = (flags & 4) != 0;
    readLoss(r, l.loss);
    out.losses.push_back(l);
  }
  if (!r.ok()) return Error{where + ": " + r.error()};
  if (r.remaining() != 0) return Error{where + ": " + std::to_string(r.remaining()) + " bytes after the last record"};
  return out;
}

// --- the part's side ---------------------------------------------------------------------------

Result<detail::PartRun> detail::PartRun::begin(const std::string& cityDir, const Tileset& tileset,
                                               const ResponseRunOptions& options, ShardSpec shard) {
  PartRun run;
  auto identity = runIdentity(tileset, options, shard.parts);
  if (!identity.ok()) return Error{identity.error()};
  run.identity_ = std::move(identity).value();
  run.cityDir_ = cityDir;
  run.shard_ = shard;
  run.tileset_ = tileset;
  run.districtsPath_ = options.districts;
  run.scenario_ = options.scenarioIndex;
  run.scenarioNames_ = options.scenarioNames;
  auto parts = assignParts(tileset, shard.parts);
  run.leaves_ = std::move(parts[shard.part - 1]);
  run.folder_ = stagingFolder(run.scenario_) + "/." + partFolderName(shard) + ".tmp-" + std::to_string(getpid());
  removeTree(cityDir + "/" + run.folder_);
  return run;
}

Status detail::PartRun::publish(ResponseWriter& writer, const FinishInputs& finish, const ResponseRunReport& report) {
  const std::string folder = cityDir_ + "/" + folder_;
  PartManifest m;
  m.shard = shard_;
  m.identity = identity_;
  m.scenario = scenario_;
  m.scenarioNames = scenarioNames_;
  m.created = nowUtc();
  m.host = hostName();
  m.population = finish.population;
  m.report = report;
  PartResults results;
  for (const ResponseWriter::PartLeaf& leaf : writer.partLeaves()) {
    PartLeafEntry e;
    e.node = leaf.node;
    e.files = leaf.files;
    e.files.summaryFile = baseName(e.files.summaryFile);
    e.files.historyFile = baseName(e.files.historyFile);
    e.stats = leaf.stats;
    e.rate = finish.leafRates[leaf.node];
    m.leaves.push_back(std::move(e));
    results.leafSummaries.emplace_back(leaf.node, leaf.fullSummary);
  }
  std::sort(m.leaves.begin(), m.leaves.end(), [](const auto& a, const auto& b) { return a.node < b.node; });
  std::sort(results.leafSummaries.begin(), results.leafSummaries.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  const RunLosses& l = finish.losses;
  results.losses.reserve(l.losses.size());
  for (std::size_t i = 0; i < l.losses.size(); ++i) {
    results.losses.push_back({l.key[i], i < l.district.size() ? l.district[i] : -1, l.classes[i], l.losses[i]});
  }
  // Zstandard's fastest level: the file lives only until the merge, which unpacks it once (level 3
  // took twice the CPU for 3 % fewer bytes on the synthetic city).
  auto stored = compressStoredFile(encodePartResults(results), 1);
  if (!stored.ok()) return Error{stored.error()};
  auto resultsFile = writePartFile(folder, kResultsFile, *stored);
  if (!resultsFile.ok()) return Error{resultsFile.error()};
  m.results = *resultsFile;
  auto notes = writePartFile(folder, kNotesFile, responseNotesToJson(writer.notes()));
  if (!notes.ok()) return Error{notes.error()};
  m.notes = *notes;
  // The run's description of the response, in the manifest's own form (the merge reads it back).
  Tileset described = tileset_;
  for (TileNode& n : described.nodes) n.response.reset();
  described.response = finish.info;
  auto info = writePartFile(folder, kInfoFile, tilesetToJson(described));
  if (!info.ok()) return Error{info.error()};
  m.info = *info;
  if (!districtsPath_.empty()) {
    auto bytes = readFile(districtsPath_);
    if (!bytes.ok()) return Error{bytes.error()};
    auto d = writePartFile(folder, kDistrictsFile, *bytes);
    if (!d.ok()) return Error{d.error()};
    m.districts = *d;
  }
  auto manifest = writePartFile(folder, kPartManifest, partManifestToJson(m));
  if (!manifest.ok()) return Error{manifest.error()};
  if (interrupted()) return Error{"interrupted; the part was not written"};
  // The commit point: the complete folder takes the part's name (an earlier attempt moved aside
  // first, then removed).
  const std::string target = cityDir_ + "/" + stagingFolder(scenario_) + "/" + partFolderName(shard_);
  const std::string aside = target + ".old-" + std::to_string(getpid());
  std::error_code ec;
  const bool earlier = std::filesystem::exists(target, ec);
  if (earlier && std::rename(target.c_str(), aside.c_str()) != 0) {
    return Error{"cannot move the earlier " + target + " aside: " + std::strerror(errno)};
  }
  if (std::rename(folder.c_str(), target.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    if (earlier) std::rename(aside.c_str(), target.c_str());
    return Error{"cannot rename " + folder + " to " + target + ": " + reason};
  }
  writer.keep();
  if (earlier) removeTree(aside);
  return {};
}

}  // namespace qv::prep
