// A small city built in memory with the real codecs (a coarse root over four leaves, with
// response summaries and histories, the search index and the response summary in its order),
// served by a fake fetcher: scene tests run natively and in WASM without files or a server.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "qv/core/Crc32.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/format/Tileset.h"
#include "qv/scene/Fetcher.h"

namespace qv::test {

/// Serves URLs from memory; completions arrive on poll(), as from a real network.
class FakeFetcher final : public Fetcher {
 public:
  std::map<std::string, std::vector<std::uint8_t>> files;
  std::map<std::string, int> statusOverride;  ///< url -> HTTP status to answer instead
  std::set<std::string> held;                 ///< urls not answered (yet): a slow server
  std::vector<std::string> requested;
  std::map<std::string, std::uint32_t> lastTimeoutMs;  ///< url -> the time limit of its last request

  RequestId fetch(const std::string& url, Done done, std::uint32_t timeoutMs) override {
    requested.push_back(url);
    lastTimeoutMs[url] = timeoutMs;
    const RequestId id = next_++;
    queue_.push_back({id, url, std::move(done)});
    return id;
  }
  void cancel(RequestId id) override {
    for (auto& q : queue_) {
      if (q.id == id) q.done = nullptr;
    }
  }
  void poll() override {
    std::vector<Queued> now;
    now.swap(queue_);
    for (Queued& q : now) {
      if (!q.done) continue;
      if (held.count(q.url) != 0) {
        queue_.push_back(std::move(q));
        continue;
      }
      FetchResponse r;
      const auto s = statusOverride.find(q.url);
      const auto f = files.find(q.url);
      if (s != statusOverride.end()) {
        r.status = s->second;
      } else if (f == files.end()) {
        r.status = 404;
      } else {
        r.status = 200;
        r.bytes = f->second;
      }
      q.done(std::move(r));
    }
  }
  [[nodiscard]] std::size_t count(const std::string& url) const {
    std::size_t n = 0;
    for (const auto& u : requested) n += u == url ? 1u : 0u;
    return n;
  }

 private:
  struct Queued {
    RequestId id;
    std::string url;
    Done done;
  };
  std::vector<Queued> queue_;
  RequestId next_ = 1;
};

struct MiniCity {
  static constexpr int kSide = 8;  ///< 8 × 8 buildings, 40 m apart, centred on the origin
  static constexpr int kStoreys = 5;
  static constexpr float kStoreyHeight = 3.5f;
  Tileset tileset;
  std::map<std::string, std::vector<std::uint8_t>> files;  ///< relative path -> bytes

  /// Roof amplitude (m) and period (s) of building (i, j): every building moves differently.
  static double amplitude(int i, int j) { return 0.05 + 0.01 * i + 0.002 * j; }
  static double period(int i, int j) { return 0.6 + 0.1 * j + 0.03 * i; }
  static double roofX(int i, int j, double t) {
    return amplitude(i, j) * std::sin(2.0 * 3.14159265358979 * t / period(i, j));
  }

  /// The building with a LOD2 model when `withLod2` (cell 0, 0): its 20 m square footprint carries
  /// a pyramid rising to kSpireTopM, far above the 17.5 m prism the footprint alone would give.
  static constexpr float kSpireTopM = 40.0f;
  static constexpr const char* kLod2Id = "s1";

  /// `rootLimit`: how many buildings the coarse root draws (the first ones of the first leaves), as
  /// a large city's coarse tiles hold only some of theirs. `heightsM`: cells (i, j) whose prism
  /// rises to another height than kStoreys x kStoreyHeight (towers; still kStoreys storeys).
  /// `withSeries`: the tile summaries carry the far view's drift series (DSER), made from the
  /// histories as quakeview-prep makes them (appendDriftSeries). `withLosses`: HAZUS losses
  /// (lossOf) laid out as quakeview-prep lays them out for a city with an index: in full in the
  /// index's summary (LOSS), as drawing probabilities only in the tile summaries (DPRB).
  explicit MiniCity(bool withResponse = true, bool withLod2 = false, std::size_t rootLimit = kSide * kSide,
                    std::map<std::pair<int, int>, float> heightsM = {}, bool withSeries = false,
                    bool withLosses = false)
      : withLod2_(withLod2), withSeries_(withSeries), withLosses_(withLosses), heightsM_(std::move(heightsM)) {
    const std::string prefix = "city/";
    tileset.generator = "test";
    tileset.originLon = -74.0;
    tileset.originLat = 40.7;
    tileset.maxHeightM = kStoreys * kStoreyHeight;
    for (const auto& [cell, h] : heightsM_) tileset.maxHeightM = std::max(tileset.maxHeightM, h);
    tileset.buildings = kSide * kSide;
    if (withResponse) {
      ResponseInfo r;
      r.motion = "test sines";
      r.method = "test";
      r.durationSeconds = 10.0;
      r.sampleRateHz = 50.0;
      r.buildingsRevision = 1;
      tileset.response = r;
    }
    // Leaves: quadrants of the grid; the root holds everything coarse.
    std::vector<std::vector<std::pair<int, int>>> quadrants(4);
    for (int i = 0; i < kSide; ++i) {
      for (int j = 0; j < kSide; ++j)
        quadrants[(j >= kSide / 2 ? 2u : 0u) + (i >= kSide / 2 ? 1u : 0u)].push_back({i, j});
    }
    std::vector<std::pair<int, int>> all;
    for (const auto& q : quadrants) all.insert(all.end(), q.begin(), q.end());
    const std::vector<std::pair<int, int>> inRoot(
        all.begin(), all.begin() + static_cast<std::ptrdiff_t>(std::min(rootLimit, all.size())));
    tileset.nodes.push_back(makeNode(0, 0, 0, inRoot, true, withResponse, prefix));
    for (int q = 0; q < 4; ++q) {
      tileset.nodes.push_back(makeNode(1, static_cast<std::uint32_t>(q % 2), static_cast<std::uint32_t>(q / 2),
                                       quadrants[static_cast<std::size_t>(q)], false, withResponse, prefix));
      tileset.nodes[0].children.push_back(static_cast<std::uint32_t>(q + 1));
    }
    tileset.nodes[0].subtreeBuildings = all.size();
    for (std::size_t q = 1; q < 5; ++q) tileset.nodes[0].bounds.expand(tileset.nodes[q].bounds);
    tileset.bounds = tileset.nodes[0].bounds;
    // The city-wide index, leaf by leaf, and the response summary in its order.
    std::vector<SearchEntry> index;
    ResponseSummaryTile summary;
    for (std::uint32_t q = 0; q < 4; ++q) {
      for (const auto& [i, j] : quadrants[q]) {
        SearchEntry e;
        e.id = idOf(i, j);
        e.name = "Building " + std::to_string(i) + "-" + std::to_string(j);
        e.use = "office";
        e.x = static_cast<float>(centreX(i));
        e.y = static_cast<float>(centreY(j));
        e.heightM = heightOf(i, j);
        e.storeys = kStoreys;
        e.lod = withLod2_ && i == 0 && j == 0 ? 2 : 1;
        e.leaf = q + 1;
        index.push_back(e);
        BuildingResponse r = responseOf(i, j);
        r.firstStorey = static_cast<std::uint32_t>(summary.storeyPeakDrift.size());
        for (int k = 0; k < kStoreys; ++k) summary.storeyPeakDrift.push_back(storeyDrift(r, k));
        summary.buildings.push_back(r);
        if (withResponse) summary.sites.push_back(siteOf(i, j));
        if (withResponse && withLosses_) summary.losses.push_back(lossOf(i, j));
      }
    }
    const auto indexBytes = encodeSearchIndex(index);
    tileset.search = CityFile{"search.qvi", indexBytes.size(), crc32(indexBytes)};
    files[prefix + "search.qvi"] = indexBytes;
    if (withResponse) {
      const auto summaryBytes = encodeResponseSummary(summary);
      tileset.response->summaryIndex = CityFile{"response/index.qvs", summaryBytes.size(), crc32(summaryBytes)};
      files[prefix + "response/index.qvs"] = summaryBytes;
    }
    const std::string json = tilesetToJson(tileset);
    files[prefix + "tileset.json"] = std::vector<std::uint8_t>(json.begin(), json.end());
  }

  void serve(FakeFetcher& f) const {
    for (const auto& [path, bytes] : files) f.files[path] = bytes;
  }

  static double centreX(int i) { return (i - kSide / 2 + 0.5) * 40.0; }
  static std::string idOf(int i, int j) { return "s" + std::to_string(i * kSide + j + 1); }
  static BuildingResponse responseOf(int i, int j) {
    BuildingResponse r;
    r.source = ResponseSource::Model;
    r.storeys = kStoreys;
    r.damage = static_cast<DamageState>((i + j) % 5);
    r.peakRoofDisplacementM = static_cast<float>(amplitude(i, j));
    r.peakDriftRatio = static_cast<float>(amplitude(i, j) / (kStoreys * kStoreyHeight));
    return r;
  }
  /// The ShakeMap's values at building (i, j): PGA 0.1 g + 0.01 g per cell from the corner; no MMI.
  static BuildingSite siteOf(int i, int j) {
    BuildingSite s;
    s.source = SiteSource::ShakeMap;
    s.pgaG = 0.1f + 0.01f * static_cast<float>(i + j);
    s.pgvCmS = 8.0f;
    s.psa03G = 2.0f * s.pgaG;
    s.psa10G = 0.5f * s.pgaG;
    s.psa30G = 0.1f * s.pgaG;
    s.vs30Mps = 400.0f;
    return s;
  }
  /// HAZUS losses of building (i, j): P(DS >= slight) from 0.103 up by 0.01 a building, repair cost
  /// 1000 USD times its number.
  static BuildingLoss lossOf(int i, int j) {
    const int n = i * kSide + j;
    const float a = 0.103f + 0.01f * static_cast<float>(n);  // P(DS >= moderate) never a whole percent
    BuildingLoss l;
    const float states[5] = {1.0f - a, 0.5f * a, 0.3f * a, 0.15f * a, 0.05f * a};
    for (int k = 0; k < 5; ++k) l.structural[k] = l.nonStructuralDrift[k] = l.nonStructuralAcceleration[k] = states[k];
    l.occupants = 10.0f;
    l.injuries[0] = 0.01f * a;
    l.replacementValueUsd = 1.0e6f;
    l.repairCostUsd = 1000.0f * static_cast<float>(n + 1);
    l.repairTimeDays = 10.0f * a;
    l.tag[0] = 1.0f - 0.5f * a;
    l.tag[1] = 0.3f * a;
    l.tag[2] = 0.2f * a;
    return l;
  }
  static float storeyDrift(const BuildingResponse& r, int storey) {
    return r.peakDriftRatio * (1.0f + 0.1f * static_cast<float>(storey));
  }
  static double centreY(int j) { return (j - kSide / 2 + 0.5) * 40.0; }
  /// Height of building (i, j)'s prism (metres).
  [[nodiscard]] float heightOf(int i, int j) const {
    const auto it = heightsM_.find({i, j});
    return it == heightsM_.end() ? kStoreys * kStoreyHeight : it->second;
  }

 private:
  TileNode makeNode(std::uint8_t level, std::uint32_t x, std::uint32_t y, const std::vector<std::pair<int, int>>& cells,
                    bool coarse, bool withResponse, const std::string& prefix) {
    CityTile tile;
    tile.coarse = coarse;
    double minX = 1e9, minY = 1e9, maxX = -1e9, maxY = -1e9;
    for (const auto& [i, j] : cells) {
      minX = std::min(minX, centreX(i) - 10);
      minY = std::min(minY, centreY(j) - 10);
      maxX = std::max(maxX, centreX(i) + 10);
      maxY = std::max(maxY, centreY(j) + 10);
    }
    tile.originX = minX;
    tile.originY = minY;
    tile.extent = static_cast<float>(std::max(maxX - minX, maxY - minY));
    ResponseSummaryTile summary;
    ResponseHistoryTile history;
    history.durationSeconds = 10.0f;
    for (const auto& [i, j] : cells) {
      const float cx = static_cast<float>(centreX(i) - minX), cy = static_cast<float>(centreY(j) - minY);
      tile.vertices.insert(tile.vertices.end(),
                           {{cx - 10, cy - 10}, {cx + 10, cy - 10}, {cx + 10, cy + 10}, {cx - 10, cy + 10}});
      tile.ringVertexCounts.push_back(4);
      tile.roofTriangles.insert(tile.roofTriangles.end(), {0, 1, 2, 0, 2, 3});
      TilePart part;
      part.ringCount = 1;
      part.triangleCount = 2;
      part.heightM = heightOf(i, j);
      tile.parts.push_back(part);
      TileBuilding b;
      b.partCount = 1;
      b.attributes.id = idOf(i, j);
      b.attributes.use = "office";
      b.attributes.heightM = part.heightM;
      b.attributes.storeys = kStoreys;
      b.attributes.footprintAreaM2 = 400.0f;
      b.attributes.centroidX = cx;
      b.attributes.centroidY = cy;
      if (withLod2_ && i == 0 && j == 0) {
        b.attributes.lod = 2;
        TileMesh m;
        m.building = static_cast<std::uint32_t>(tile.buildings.size());
        m.source = MeshSource::CityJson;
        m.storeys = kStoreys;
        m.verticesBefore = 5;
        m.topM = kSpireTopM;
        m.positions = {{cx - 10, cy - 10, 0},
                       {cx + 10, cy - 10, 0},
                       {cx + 10, cy + 10, 0},
                       {cx - 10, cy + 10, 0},
                       {cx, cy, kSpireTopM}};
        // Four walls (counter-clockwise from outside), then the two ground triangles.
        m.triangles = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 2, 1, 0, 3, 2};
        m.trianglesPerKind = {4, 0, 2, 0};
        m.farPositions = m.positions;
        m.farTriangles.assign(m.triangles.begin(), m.triangles.end());
        tile.meshes.push_back(std::move(m));
      }
      tile.buildings.push_back(b);

      BuildingResponse r = responseOf(i, j);
      r.firstStorey = static_cast<std::uint32_t>(summary.storeyPeakDrift.size());
      for (int s = 0; s < kStoreys; ++s) summary.storeyPeakDrift.push_back(storeyDrift(r, s));
      summary.buildings.push_back(r);
      // A slim tile (withLosses_) leaves the site and the losses to the index, as quakeview-prep does.
      if (!withLosses_) summary.sites.push_back(siteOf(i, j));
      if (withLosses_) summary.odds.push_back(BuildingDamageOdds::of(lossOf(i, j)));

      BuildingHistory h;
      h.floors = kStoreys;
      h.sampleRateHz = 50.0f;
      h.sampleCount = 501;
      h.x.modes = 1;
      h.x.scales = {static_cast<float>(amplitude(i, j) / 30000.0)};
      for (int f = 1; f <= kStoreys; ++f) h.x.shapes.push_back(static_cast<float>(f) / kStoreys);
      for (std::uint32_t s = 0; s < h.sampleCount; ++s) {
        h.x.coordinates.push_back(static_cast<std::int16_t>(
            std::lround(30000.0 * std::sin(2.0 * 3.14159265358979 * (s / 50.0) / period(i, j)))));
      }
      if (withSeries_) {
        if (summary.driftSeries.empty()) {
          summary.driftSeries.rateHz = kDriftSeriesRateHz;
          summary.driftSeries.fullScale = kDriftSeriesFullScale;
        }
        summary.driftSeries.spans.push_back(appendDriftSeries(h, kStoreyHeight, summary.driftSeries));
      }
      history.buildings.push_back(h);
    }
    TileNode n;
    n.level = level;
    n.x = x;
    n.y = y;
    n.bounds =
        Rect{static_cast<float>(minX), static_cast<float>(minY), static_cast<float>(maxX), static_cast<float>(maxY)};
    n.maxHeightM = kStoreys * kStoreyHeight;
    for (const auto& [i, j] : cells) n.maxHeightM = std::max(n.maxHeightM, heightOf(i, j));
    n.coarse = coarse;
    n.geometricErrorM = coarse ? 20.0f : 0.0f;
    n.buildings = static_cast<std::uint32_t>(cells.size());
    n.subtreeBuildings = cells.size();
    n.file = "tiles/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvt";
    const auto bytes = encodeCityTile(tile);
    n.bytes = bytes.size();
    n.crc32 = crc32(bytes);
    files[prefix + n.file] = bytes;
    if (withResponse) {
      TileResponseFiles rf;
      rf.summaryFile = "response/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvs";
      const auto sb = encodeResponseSummary(summary);
      rf.summaryBytes = sb.size();
      rf.summaryCrc32 = crc32(sb);
      files[prefix + rf.summaryFile] = sb;
      if (!coarse) {
        rf.historyFile =
            "response/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvh";
        const auto hb = encodeResponseHistory(history);
        rf.historyBytes = hb.size();
        rf.historyCrc32 = crc32(hb);
        files[prefix + rf.historyFile] = hb;
      }
      n.response = rf;
    }
    return n;
  }

  bool withLod2_ = false;
  bool withSeries_ = false;
  bool withLosses_ = false;
  std::map<std::pair<int, int>, float> heightsM_;
};

}  // namespace qv::test
