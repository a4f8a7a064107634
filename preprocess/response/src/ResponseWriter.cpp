#include "qv/prep/ResponseWriter.h"

#include <dirent.h>
#include <simdjson.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <set>

#include "qv/core/Crc32.h"
#include "qv/core/JsonWriter.h"
#include "qv/format/SearchIndex.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseCatalogue.h"

namespace qv::prep {
namespace {

std::string tileStem(const TileNode& n) {
  return std::to_string(n.level) + "-" + std::to_string(n.x) + "-" + std::to_string(n.y);
}

// Existing response-<n> folders of a city.
std::vector<std::pair<int, std::string>> responseFolders(const std::string& dir) {
  std::vector<std::pair<int, std::string>> out;
  DIR* d = opendir(dir.c_str());
  if (d == nullptr) return out;
  while (const dirent* e = readdir(d)) {
    const std::string name = e->d_name;
    if (name.rfind("response-", 0) != 0) continue;
    char* end = nullptr;
    const long n = std::strtol(name.c_str() + 9, &end, 10);
    if (end != nullptr && *end == '\0' && n > 0) out.emplace_back(static_cast<int>(n), name);
  }
  closedir(d);
  return out;
}

std::size_t damageIndex(DamageState s) {
  return s == DamageState::NoResult ? 5 : static_cast<std::size_t>(s);
}

NoResultReason reasonFromName(std::string_view name) {
  for (const NoResultReason r :
       {NoResultReason::ModelInvalid, NoResultReason::OutsideField, NoResultReason::SkippedByOption,
        NoResultReason::BaseAboveGround, NoResultReason::NotInImport}) {
    if (noResultReasonName(r) == name) return r;
  }
  return NoResultReason::Unknown;
}

// Lays buildings out in a summary tile (storey values after each other) and keeps an optional
// section only when some building has its value (the others then get zeros).
class SummaryBuilder {
 public:
  /// `withSeries`: the tile summaries carry the far view's drift series; the city-wide index does
  /// not (the viewer's list and filters do not need them). `slim`: a tile summary of a response
  /// with a city-wide index, which holds every building's full values: the tile keeps what drawing
  /// needs (RSUM, SDRF, SPEC, DSER, and the damage probabilities as DPRB), not SITE, SUIT, SSPR and
  /// LOSS (docs/formats.md).
  explicit SummaryBuilder(bool withSeries = true, bool slim = false) : withSeries_(withSeries), slim_(slim) {
    if (withSeries_) {
      tile_.driftSeries.rateHz = kDriftSeriesRateHz;
      tile_.driftSeries.fullScale = kDriftSeriesFullScale;
    }
  }
  /// `r` null: a building without a response (not in the results).
  void add(const BuildingResult* r) {
    if (withSeries_) {
      DriftSpan span;
      span.first = static_cast<std::uint32_t>(tile_.driftSeries.codes.size());
      if (r != nullptr && r->summary.source != ResponseSource::None && !r->driftCodes.empty()) {
        span.startSeconds = r->driftStartSeconds;
        span.count = static_cast<std::uint32_t>(r->driftCodes.size());
        tile_.driftSeries.codes.insert(tile_.driftSeries.codes.end(), r->driftCodes.begin(), r->driftCodes.end());
        hasSeries_ = true;
        ++seriesBuildings_;
      }
      tile_.driftSeries.spans.push_back(span);
    }
    BuildingResponse s = r != nullptr ? r->summary : BuildingResponse{};
    s.firstStorey = static_cast<std::uint32_t>(tile_.storeyPeakDrift.size());
    for (std::uint16_t k = 0; k < s.storeys; ++k) {
      tile_.storeyPeakDrift.push_back(k < r->storeyPeakDrift.size() ? r->storeyPeakDrift[k] : 0.0f);
      tile_.storeySpread.push_back(k < r->storeySpread.size() ? r->storeySpread[k] : StoreySpread{});
    }
    tile_.buildings.push_back(s);
    const bool result = r != nullptr && s.source != ResponseSource::None;
    // The site's shaking is known with or without a result (a building whose model is invalid).
    tile_.sites.push_back(r != nullptr && r->site ? *r->site : BuildingSite{});
    hasSites_ = hasSites_ || (r != nullptr && r->site && r->site->given());
    tile_.scaling.push_back(result && r->scaling ? *r->scaling : BuildingScaling{});
    tile_.spread.push_back(result && r->spread ? *r->spread : BuildingSpread{});
    tile_.losses.push_back(result && r->loss ? *r->loss : BuildingLoss{});
    hasScaling_ = hasScaling_ || (result && r->scaling);
    hasSpread_ = hasSpread_ || (result && r->spread);
    hasStoreySpread_ = hasStoreySpread_ || (result && !r->storeySpread.empty());
    hasLoss_ = hasLoss_ || (result && r->loss);
  }
  ResponseSummaryTile& finish() {
    if (!hasScaling_) tile_.scaling.clear();
    if (!hasSites_) tile_.sites.clear();
    if (!hasSpread_) tile_.spread.clear();
    if (!hasStoreySpread_) tile_.storeySpread.clear();
    if (!hasLoss_) tile_.losses.clear();
    if (!hasSeries_) tile_.driftSeries = DriftSeries{};
    if (slim_) {
      tile_.odds.clear();
      for (const BuildingLoss& l : tile_.losses) tile_.odds.push_back(BuildingDamageOdds::of(l));
      tile_.losses.clear();
      tile_.sites.clear();
      tile_.spread.clear();
      tile_.storeySpread.clear();
    }
    return tile_;
  }
  /// Bytes the drift series section takes in the encoded summary (0 without one).
  [[nodiscard]] std::uint64_t seriesBytes() const {
    return hasSeries_ ? 12 + 12 + 8 * tile_.driftSeries.spans.size() + tile_.driftSeries.codes.size() : 0;
  }
  [[nodiscard]] std::uint64_t seriesBuildings() const { return seriesBuildings_; }

 private:
  ResponseSummaryTile tile_;
  bool withSeries_ = true;
  bool slim_ = false;
  bool hasScaling_ = false, hasSites_ = false, hasSpread_ = false, hasStoreySpread_ = false, hasLoss_ = false,
       hasSeries_ = false;
  std::uint64_t seriesBuildings_ = 0;
};

}  // namespace

std::string responseNotesToJson(const ResponseNotes& notes) {
  JsonWriter w;
  w.beginObject();
  w.key("no_result").beginArray();
  for (const ResponseNotes::NoResult& n : notes.noResult) {
    w.beginObject().field("id", n.id).field("reason", noResultReasonName(n.reason)).field("detail", n.detail);
    w.endObject();
  }
  w.endArray();
  w.key("approximate").beginArray();
  for (const ResponseNotes::Approximate& a : notes.approximate) {
    w.beginObject().field("id", a.id).field("unconverged_steps", std::uint64_t{a.unconvergedSteps});
    w.field("worst_residual_ratio", a.worstResidualRatio).endObject();
  }
  w.endArray();
  w.endObject();
  return w.str() + "\n";
}

Result<ResponseNotes> parseResponseNotes(std::string_view json, const std::string& name) {
  simdjson::dom::parser parser;
  simdjson::dom::element root;
  if (parser.parse(json.data(), json.size()).get(root) != simdjson::SUCCESS) {
    return Error{name + ": not valid JSON"};
  }
  ResponseNotes notes;
  simdjson::dom::array list;
  if (root["no_result"].get(list) == simdjson::SUCCESS) {
    for (simdjson::dom::element e : list) {
      ResponseNotes::NoResult n;
      std::string_view id, reason, detail;
      if (e["id"].get(id) != simdjson::SUCCESS || e["reason"].get(reason) != simdjson::SUCCESS) {
        return Error{name + ": a no_result entry lacks \"id\" or \"reason\""};
      }
      if (e["detail"].get(detail) != simdjson::SUCCESS) detail = {};
      n.id = std::string(id);
      n.reason = reasonFromName(reason);
      n.detail = std::string(detail);
      notes.noResult.push_back(std::move(n));
    }
  }
  if (root["approximate"].get(list) == simdjson::SUCCESS) {
    for (simdjson::dom::element e : list) {
      ResponseNotes::Approximate a;
      std::string_view id;
      std::uint64_t steps = 0;
      double residual = 0.0;
      if (e["id"].get(id) != simdjson::SUCCESS || e["unconverged_steps"].get(steps) != simdjson::SUCCESS ||
          e["worst_residual_ratio"].get(residual) != simdjson::SUCCESS) {
        return Error{name + ": an approximate entry lacks \"id\", \"unconverged_steps\" or \"worst_residual_ratio\""};
      }
      a.id = std::string(id);
      a.unconvergedSteps = static_cast<std::uint32_t>(std::min<std::uint64_t>(steps, 0xFFFFFFFFu));
      a.worstResidualRatio = static_cast<float>(residual);
      notes.approximate.push_back(std::move(a));
    }
  }
  return notes;
}

Result<ResponseNotes> loadResponseNotes(const std::string& cityDir, const Tileset& tileset) {
  if (!tileset.response || !tileset.response->notes) return ResponseNotes{};
  const std::string path = cityDir + "/" + tileset.response->notes->file;
  auto text = readTextFile(path, 256ull << 20);
  if (!text.ok()) return Error{text.error()};
  return parseResponseNotes(*text, path);
}

ResponseWriter::ResponseWriter(std::string cityDir, Tileset tileset, std::string folder)
    : cityDir_(std::move(cityDir)), tileset_(std::move(tileset)), folder_(std::move(folder)) {}

ResponseWriter::~ResponseWriter() {
  if (!committed_) removeTree(cityDir_ + "/" + folder_);
}

Result<std::unique_ptr<ResponseWriter>> ResponseWriter::create(const std::string& cityDir, const Tileset& tileset) {
  int next = 1;
  std::vector<std::string> previous;
  for (const auto& [n, name] : responseFolders(cityDir)) {
    next = std::max(next, n + 1);
    previous.push_back(name);
  }
  // The next free number, taken by creating the folder (scenarios published at once on several
  // machines each get their own).
  std::string folder;
  for (int attempt = 0;; ++attempt, ++next) {
    folder = "response-" + std::to_string(next);
    if (::mkdir((cityDir + "/" + folder).c_str(), 0777) == 0) break;
    if (errno != EEXIST || attempt > 10000) {
      return Error{"cannot create directory " + cityDir + "/" + folder + ": " + std::strerror(errno)};
    }
  }
  std::unique_ptr<ResponseWriter> w(new ResponseWriter(cityDir, tileset, folder));
  w->previousFolders_ = std::move(previous);
  w->report_.folder = folder;
  return w;
}

std::string responseFolderOf(const std::string& manifestPath) {
  auto text = readTextFile(manifestPath, 256ull << 20);
  if (!text.ok()) return "";
  auto tileset = parseTileset(*text, manifestPath);
  if (!tileset.ok() || !tileset->response) return "";
  const ResponseInfo& r = *tileset->response;
  const std::string file = r.consequences ? r.consequences->file : r.notes ? r.notes->file : "";
  for (const TileNode& n : tileset->nodes) {
    const std::string& f = file.empty() && n.response ? n.response->summaryFile : file;
    const std::size_t slash = f.find('/');
    if (slash != std::string::npos && f.rfind("response-", 0) == 0) return f.substr(0, slash);
  }
  return "";
}

void ResponseWriter::setScenario(std::size_t index, std::vector<std::string> names) {
  scenario_ = index;
  scenarioNames_ = std::move(names);
}

Result<std::unique_ptr<ResponseWriter>> ResponseWriter::createPart(const std::string& cityDir, const Tileset& tileset,
                                                                   const std::string& folder) {
  if (const Status s = makeDirectories(cityDir + "/" + folder); !s.ok()) return Error{s.error()};
  std::unique_ptr<ResponseWriter> w(new ResponseWriter(cityDir, tileset, folder));
  w->part_ = true;
  w->report_.folder = folder;
  return w;
}

Status ResponseWriter::writeLeaf(std::uint32_t node, const CityTile& tile, std::vector<BuildingResult>& results) {
  if (node >= tileset_.nodes.size() || results.size() != tile.buildings.size()) {
    return Error{"internal: results do not match tile " + std::to_string(node)};
  }
  const TileNode& n = tileset_.nodes[node];
  SummaryBuilder summary(true, tileset_.search.has_value());
  ResponseHistoryTile history;
  history.durationSeconds = 0.0f;
  for (std::size_t b = 0; b < results.size(); ++b) {
    BuildingResult& r = results[b];
    if (r.summary.source == ResponseSource::None) {
      r.summary.storeys = 0;
      r.summary.damage = DamageState::NoResult;
    }
    // The far view's drift series from the stored history, with the storey height the viewer
    // colours the animated buildings' drift by (TileMeshBuilder).
    DriftSeries series;
    series.rateHz = kDriftSeriesRateHz;
    series.fullScale = kDriftSeriesFullScale;
    const DriftSpan span = appendDriftSeries(r.history, tile.buildings[b].attributes.storeyHeightM(), series);
    r.driftStartSeconds = span.startSeconds;
    r.driftCodes = std::move(series.codes);
    summary.add(&r);
    if (r.history.sampleCount > 0 && r.history.sampleRateHz > 0.0f) {
      history.durationSeconds =
          std::max(history.durationSeconds, static_cast<float>(r.history.sampleCount - 1) / r.history.sampleRateHz);
    }
    history.buildings.push_back(std::move(r.history));
  }
  const std::vector<std::uint8_t> summaryRaw = encodeResponseSummary(summary.finish());
  const std::vector<std::uint8_t> historyRaw = encodeResponseHistory(history);
  auto summaryStored = compressStoredFile(summaryRaw);
  if (!summaryStored.ok()) return Error{summaryStored.error()};
  auto historyStored = compressStoredFile(historyRaw);
  if (!historyStored.ok()) return Error{historyStored.error()};
  const std::vector<std::uint8_t>& summaryBytes = *summaryStored;
  const std::vector<std::uint8_t>& historyBytes = *historyStored;
  TileResponseFiles files;
  files.summaryFile = folder_ + "/" + tileStem(n) + ".qvs";
  files.summaryBytes = summaryBytes.size();
  files.summaryCrc32 = crc32(summaryBytes);
  files.historyFile = folder_ + "/" + tileStem(n) + ".qvh";
  files.historyBytes = historyBytes.size();
  files.historyCrc32 = crc32(historyBytes);
  if (Status s = writeFileAtomic(cityDir_ + "/" + files.summaryFile, summaryBytes); !s.ok()) return s;
  if (Status s = writeFileAtomic(cityDir_ + "/" + files.historyFile, historyBytes); !s.ok()) return s;
  const LeafStats stats{summaryRaw.size() + historyRaw.size(), summary.seriesBytes(), summary.seriesBuildings()};
  if (part_) {
    // Every section, for the merge to rebuild the results from (the leaf's own summary may be slim).
    SummaryBuilder full(true, false);
    for (const BuildingResult& r : results) full.add(&r);
    PartLeaf leaf{node, files, stats, encodeResponseSummary(full.finish())};
    const std::lock_guard lock(mutex_);
    partLeaves_.push_back(std::move(leaf));
  }
  remember(node, files, tile, results, stats, true);
  return {};
}

Status ResponseWriter::adoptLeaf(std::uint32_t node, const TileResponseFiles& files, const CityTile& tile,
                                 std::vector<BuildingResult>& results, const LeafStats& stats) {
  if (node >= tileset_.nodes.size() || results.size() != tile.buildings.size()) {
    return Error{"internal: results do not match tile " + std::to_string(node)};
  }
  const TileNode& n = tileset_.nodes[node];
  TileResponseFiles adopted = files;
  adopted.summaryFile = folder_ + "/" + tileStem(n) + ".qvs";
  adopted.historyFile = folder_ + "/" + tileStem(n) + ".qvh";
  if (Status s = linkOrCopyFile(cityDir_ + "/" + files.summaryFile, cityDir_ + "/" + adopted.summaryFile); !s.ok())
    return s;
  if (Status s = linkOrCopyFile(cityDir_ + "/" + files.historyFile, cityDir_ + "/" + adopted.historyFile); !s.ok())
    return s;
  remember(node, adopted, tile, results, stats, false);
  return {};
}

void ResponseWriter::addNotes(const ResponseNotes& notes) {
  const std::lock_guard lock(mutex_);
  notes_.noResult.insert(notes_.noResult.end(), notes.noResult.begin(), notes.noResult.end());
  notes_.approximate.insert(notes_.approximate.end(), notes.approximate.begin(), notes.approximate.end());
}

void ResponseWriter::remember(std::uint32_t node, const TileResponseFiles& files, const CityTile& tile,
                              std::vector<BuildingResult>& results, const LeafStats& stats, bool withNotes) {
  const std::lock_guard lock(mutex_);
  tileset_.nodes[node].response = files;
  report_.summaryBytes += files.summaryBytes;
  report_.historyBytes += files.historyBytes;
  report_.uncompressedBytes += stats.uncompressedBytes;
  report_.driftSeriesBytes += stats.driftSeriesBytes;
  report_.driftSeriesBuildings += stats.driftSeriesBuildings;
  for (std::size_t b = 0; b < tile.buildings.size(); ++b) {
    BuildingResult& r = results[b];
    const BuildingResponse& s = r.summary;
    ++report_.damage[damageIndex(s.damage)];
    const std::string& id = tile.buildings[b].attributes.id;
    if (s.source == ResponseSource::None) {
      const NoResultReason reason =
          s.noResultReason == NoResultReason::None ? NoResultReason::Unknown : s.noResultReason;
      ++report_.noResultReasons[reason];
      if (withNotes) notes_.noResult.push_back({id, reason, r.noResultDetail});
    } else if (s.approximate) {
      ++report_.approximate;
      if (withNotes) notes_.approximate.push_back({id, s.unconvergedSteps, s.worstResidualRatio});
    }
    // A part keeps its full summaries instead (partLeaves_): the merge's writer builds the inner
    // tiles.
    if (part_) continue;
    r.history = BuildingHistory{};
    byId_[id] = std::move(r);
  }
}

Result<CityFile> ResponseWriter::writeFile(const std::string& name, const std::string& text) {
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  CityFile f{folder_ + "/" + name, bytes.size(), crc32(bytes)};
  if (Status s = writeFileAtomic(cityDir_ + "/" + f.file, text); !s.ok()) return Error{s.error()};
  return f;
}

Result<ResponseWriteReport> ResponseWriter::commit(ResponseInfo info) {
  // Inner tiles: the same buildings as their leaves, found by id (the coarse tiles keep the ids).
  for (std::uint32_t i = 0; i < tileset_.nodes.size(); ++i) {
    TileNode& n = tileset_.nodes[i];
    if (n.children.empty()) {
      if (!n.response) return Error{"internal: leaf " + n.key() + " has no response"};
      continue;
    }
    auto bytes = readFile(cityDir_ + "/" + n.file);
    if (!bytes.ok()) return Error{bytes.error()};
    auto tile = decodeCityTile(*bytes, cityDir_ + "/" + n.file);
    if (!tile.ok()) return Error{tile.error()};
    SummaryBuilder summary(true, tileset_.search.has_value());
    for (const TileBuilding& b : tile->buildings) {
      const auto it = byId_.find(b.attributes.id);
      summary.add(it != byId_.end() ? &it->second : nullptr);
    }
    const auto raw = encodeResponseSummary(summary.finish());
    auto stored = compressStoredFile(raw);
    if (!stored.ok()) return Error{stored.error()};
    const std::vector<std::uint8_t>& encoded = *stored;
    report_.uncompressedBytes += raw.size();
    TileResponseFiles files;
    files.summaryFile = folder_ + "/" + tileStem(n) + ".qvs";
    files.summaryBytes = encoded.size();
    files.summaryCrc32 = crc32(encoded);
    if (Status s = writeFileAtomic(cityDir_ + "/" + files.summaryFile, encoded); !s.ok()) return Error{s.error()};
    n.response = files;
    report_.summaryBytes += encoded.size();
    report_.driftSeriesBytes += summary.seriesBytes();
    report_.driftSeriesBuildings += summary.seriesBuildings();
  }
  // The city-wide summary, in the search index's order (the viewer's list, filters and exports).
  if (tileset_.search) {
    const std::string path = cityDir_ + "/" + tileset_.search->file;
    auto bytes = readFile(path);
    if (!bytes.ok()) return Error{bytes.error()};
    auto index = decodeSearchIndex(*bytes, path);
    if (!index.ok()) return Error{index.error()};
    SummaryBuilder summary(false);
    for (const SearchEntry& e : *index) {
      const auto it = byId_.find(e.id);
      summary.add(it != byId_.end() ? &it->second : nullptr);
    }
    const auto raw = encodeResponseSummary(summary.finish());
    auto stored = compressStoredFile(raw);
    if (!stored.ok()) return Error{stored.error()};
    const std::vector<std::uint8_t>& encoded = *stored;
    report_.uncompressedBytes += raw.size();
    CityFile f{folder_ + "/index.qvs", encoded.size(), crc32(encoded)};
    if (Status s = writeFileAtomic(cityDir_ + "/" + f.file, encoded); !s.ok()) return Error{s.error()};
    info.summaryIndex = f;
    report_.summaryBytes += encoded.size();
  }
  {
    std::sort(notes_.noResult.begin(), notes_.noResult.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    std::sort(notes_.approximate.begin(), notes_.approximate.end(), [](const auto& a, const auto& b) {
      return a.worstResidualRatio != b.worstResidualRatio ? a.worstResidualRatio > b.worstResidualRatio : a.id < b.id;
    });
    const std::string json = responseNotesToJson(notes_);
    const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(json.data()), json.size());
    CityFile f{folder_ + "/notes.json", bytes.size(), crc32(bytes)};
    if (Status s = writeFileAtomic(cityDir_ + "/" + f.file, json); !s.ok()) return Error{s.error()};
    info.notes = f;
  }
  info.buildingsRevision = tileset_.buildingsRevision;
  for (int k = 0; k < 6; ++k) info.damageStates[k] = report_.damage[k];
  tileset_.response = info;
  if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
  const std::string manifest = tilesetToJson(tileset_);
  if (scenario_ == 0) {
    if (Status s = writeFileAtomic(cityDir_ + "/tileset.json", manifest); !s.ok()) return Error{s.error()};
    committed_ = true;
    // The previous response goes, but not the folders the city's scenarios show (scenarios.json).
    std::set<std::string> kept = {folder_};
    for (const std::string& m : scenarioManifestsOf(cityDir_)) kept.insert(responseFolderOf(cityDir_ + "/" + m));
    for (const std::string& old : previousFolders_) {
      if (kept.count(old) == 0) removeTree(cityDir_ + "/" + old);
    }
    return report_;
  }
  // A scenario of a catalogue: its own manifest, the city's default one for scenario 1, and the
  // list for the viewer; only this scenario's previous folder goes (the others' are theirs, some
  // perhaps being published right now on other machines).
  const std::string own = cityDir_ + "/" + scenarioManifestName(scenario_);
  std::set<std::string> replaced = {responseFolderOf(own)};
  if (scenario_ == 1) replaced.insert(responseFolderOf(cityDir_ + "/tileset.json"));
  if (Status s = writeFileAtomic(own, manifest); !s.ok()) return Error{s.error()};
  committed_ = true;
  if (scenario_ == 1) {
    if (Status s = writeFileAtomic(cityDir_ + "/tileset.json", manifest); !s.ok()) return Error{s.error()};
  }
  if (Status s = writeFileAtomic(cityDir_ + "/scenarios.json", scenariosToJson(scenarioNames_)); !s.ok()) {
    return Error{s.error()};
  }
  std::set<std::string> shown;
  for (const std::string& m : scenarioManifestsOf(cityDir_)) shown.insert(responseFolderOf(cityDir_ + "/" + m));
  shown.insert(responseFolderOf(cityDir_ + "/tileset.json"));
  for (const std::string& old : replaced) {
    if (!old.empty() && old != folder_ && shown.count(old) == 0) removeTree(cityDir_ + "/" + old);
  }
  return report_;
}

}  // namespace qv::prep
