#include "qv/scene/CityScene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "qv/anim/FloorDisplacements.h"
#include "qv/anim/HistorySampling.h"
#include "qv/core/Crc32.h"
#include "qv/scene/BuildingTable.h"
#include "qv/scene/TileMeshBuilder.h"
#include "qv/spatial/BoxTree.h"

namespace qv {
namespace {

double msSince(const SceneClock& clock, double startSeconds) {
  return (clock.nowSeconds() - startSeconds) * 1000.0;
}

// Rows of the GPU tables: capacity of the index spaces (the device grows textures on demand).
constexpr std::uint32_t kNotAnimated = UINT32_MAX;

// The loader's options from the scene's (which the viewer may change between frames).
FileLoaderOptions loaderOptions(const CitySceneOptions& options) {
  return {options.maxRequestsInFlight, options.requestTimeoutMs, options.slowestBytesPerSecond};
}

}  // namespace

struct CityScene::LoadedTile : TileContent {
  explicit LoadedTile(TileContent content) : TileContent(std::move(content)) {}
  MeshHandle mesh;
  std::uint32_t slotBase = 0;
  std::uint64_t cpuBytes = 0;
  std::uint64_t gpuBytes = 0;
};

struct CityScene::TileRuntime {
  FileLoad tile;                    // the tile's file; its state is the node's
  std::vector<std::uint8_t> bytes;  // arrived, waiting to be decoded
  std::unique_ptr<LoadedTile> loaded;
  std::uint64_t lastUsed = 0;
  std::vector<IndexRange> visible;  // this frame's culling result (positions)

  FileLoad summaryLoad;
  std::unique_ptr<ResponseSummaryTile> summary;
  FileLoad historyLoad;
  std::unique_ptr<ResponseHistoryTile> history;
  std::uint64_t historyBytes = 0;
  std::uint64_t historyUsed = 0;
  /// Per building of the loaded tile: its index in animated_, or kNotAnimated.
  std::vector<std::uint32_t> animatedIndex;
};

struct CityScene::Animated {
  BuildingRef ref;
  std::uint32_t slot = 0;
  std::uint32_t floorBase = 0;
  std::uint32_t rows = 0;     // storeys + 1
  std::uint64_t choice = 0;   // the last choice (chooseAnimated) that kept it
  bool peaksWritten = false;  // its peak drifts are in its floor rows
};

CityScene::CityScene(RenderDevice& device, Fetcher& fetcher, std::string manifestUrl, CitySceneOptions options,
                     ErrorSink onError)
    : device_(device),
      fetcher_(fetcher),
      manifestUrl_(std::move(manifestUrl)),
      options_(options),
      onError_(std::move(onError)),
      clock_(options.clock != nullptr ? *options.clock : steadyClock()),
      loader_(fetcher_, clock_, [this](const LoadError& e) { onError_(e); }),
      index_(loader_, manifestUrl_) {
  if (const std::string problem = dataUrlProblem(manifestUrl_); !problem.empty()) {
    manifestFailed_ = true;  // refused before any request: settled, with the message
    reportCityError("The city could not be loaded from " + manifestUrl_.substr(0, 200) + ": " + problem);
    return;
  }
  if (const std::string problem = dataOriginProblem(options_.origin); !problem.empty()) {
    manifestFailed_ = true;  // refused before any request, as above
    reportCityError(problem);
    return;
  }
  loader_.options() = loaderOptions(options_);
  manifestRequest_ = loader_.fetch(
      manifestUrl_, [this](FetchResponse r) { onManifest(std::move(r)); }, options_.requestTimeoutMs);
}

CityScene::~CityScene() {
  if (manifestRequest_ != 0) fetcher_.cancel(manifestRequest_);
  for (const auto& t : tiles_) {
    if (t && t->loaded && t->loaded->mesh) device_.destroyMesh(t->loaded->mesh);
    if (!t) continue;
    for (FileLoad* load : {&t->tile, &t->summaryLoad, &t->historyLoad}) loader_.cancel(*load);
  }
}

void CityScene::reportCityError(std::string message) {
  onError_(LoadError{FileKind::Manifest, {}, std::move(message)});
}

void CityScene::onManifest(FetchResponse response) {
  manifestRequest_ = 0;
  if (!response.ok()) {
    manifestFailed_ = true;
    std::string why = responseProblem(response);
    if (response.status == 0 && isAbsoluteHttpUrl(manifestUrl_)) {
      why +=
          " (a server on another site must also allow this page to read its files: "
          "Access-Control-Allow-Origin)";
    }
    reportCityError("The city could not be loaded from " + manifestUrl_ + ": " + why);
    return;
  }
  const std::string_view text(reinterpret_cast<const char*>(response.bytes.data()), response.bytes.size());
  Result<Tileset> parsed = parseTileset(text, manifestUrl_);
  if (!parsed.ok()) {
    manifestFailed_ = true;
    reportCityError("The city could not be loaded: " + parsed.error());
    return;
  }
  tileset_ = std::move(parsed).value();
  index_.open(*tileset_);
  tiles_.resize(tileset_->nodes.size());
  for (auto& t : tiles_) t = std::make_unique<TileRuntime>();
  states_.assign(tileset_->nodes.size(), TileState::Unloaded);
  nodeBytes_.assign(tileset_->nodes.size(), 0);
  nodeBytesMeasured_.assign(tileset_->nodes.size(), false);
  wasLoaded_ = std::make_unique<bool[]>(tileset_->nodes.size());
  if (tileset_->responseOutOfDate()) {
    reportCityError(
        "The response results are older than the buildings of this city (run quakeview-prep response "
        "again); colours and motion may not match the buildings.");
  }
}

double CityScene::duration() const {
  return tileset_ && tileset_->response ? tileset_->response->durationSeconds : 0.0;
}

CameraState CityScene::overviewCamera(double fovDeg) const {
  CameraState c;
  c.fovDeg = fovDeg;
  c.headingDeg = 0.0;
  c.pitchDeg = 50.0;
  if (!tileset_) return c;
  const Rect& b = tileset_->bounds;
  c.x = b.centerX();
  c.y = b.centerY();
  const double size = std::max({static_cast<double>(b.width()), static_cast<double>(b.height()), 200.0});
  c.distance = size * 0.5 / std::tan(fovDeg * 3.14159265358979 / 360.0) * 1.15;
  return c;
}

TileCounts CityScene::tileCounts() const {
  TileCounts c;
  for (const auto& t : tiles_) {
    if (t->tile.state == TileState::Loaded)
      ++c.loaded;
    else if (t->tile.state == TileState::Failed)
      ++c.failed;
    else if (t->tile.state == TileState::Loading)
      ++c.pending;
    // Response tiers on their way count too: the view is not complete without them.
    if (t->summaryLoad.state == TileState::Loading) ++c.pending;
    if (t->historyLoad.state == TileState::Loading) ++c.pending;
  }
  c.pending += index_.pendingFiles();
  // Tiles the view wants but has not requested yet (the request limit) are pending as well.
  for (std::uint32_t i : selection_.wanted) {
    if (tiles_[i]->tile.state == TileState::Unloaded) ++c.pending;
  }
  return c;
}

std::uint64_t CityScene::tileBytes(std::uint32_t node) const {
  const TileRuntime& t = *tiles_[node];
  std::uint64_t total = t.bytes.size() + t.historyBytes;
  if (t.loaded) total += t.loaded->cpuBytes + t.loaded->gpuBytes;
  if (t.summary) {
    total += t.summary->buildings.size() * sizeof(BuildingResponse) + t.summary->storeyPeakDrift.size() * sizeof(float);
  }
  return total;
}

std::uint64_t CityScene::memoryBytes() const {
  std::uint64_t total = index_.bytes();
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) total += tileBytes(i);
  return total;
}

void CityScene::updateNodeBytes() {
  // Resident bytes per file byte, as measured on the tiles loaded so far; before any, what the
  // synthetic and OSM cities measure natively (coarse tiles about 9, leaves about 17: a leaf's
  // mesh has a ring of vertices per floor).
  constexpr double kDefaultRatio[2] = {17.0, 9.0};
  double ratio[2];
  for (int k = 0; k < 2; ++k) {
    ratio[k] = fileOfResident_[k] > 0
                   ? static_cast<double>(residentOfFile_[k]) / static_cast<double>(fileOfResident_[k])
                   : kDefaultRatio[k];
  }
  for (std::uint32_t i = 0; i < nodeBytes_.size(); ++i) {
    if (tiles_[i]->tile.state == TileState::Loaded) {
      // Histories come and go with the animation radius: the tile's own bytes, measured.
      nodeBytes_[i] = tileBytes(i) - tiles_[i]->historyBytes;
      nodeBytesMeasured_[i] = true;
      wasLoaded_[i] = true;
    } else if (!nodeBytesMeasured_[i]) {
      const TileNode& n = tileset_->nodes[i];
      nodeBytes_[i] = static_cast<std::uint64_t>(static_cast<double>(n.bytes) * ratio[n.children.empty() ? 0 : 1]);
    }
  }
}

FileSpec CityScene::tileSpec(std::uint32_t node) const {
  const TileNode& n = tileset_->nodes[node];
  return FileSpec{FileKind::Tile, resolveUrl(manifestUrl_, n.file), n.bytes, n.crc32, n.key()};
}

FileSpec CityScene::summarySpec(std::uint32_t node) const {
  const TileResponseFiles& r = *tileset_->nodes[node].response;
  return FileSpec{
      FileKind::ResponseSummary, resolveUrl(manifestUrl_, r.summaryFile), r.summaryBytes, r.summaryCrc32, {}};
}

FileSpec CityScene::historySpec(std::uint32_t node) const {
  const TileResponseFiles& r = *tileset_->nodes[node].response;
  return FileSpec{
      FileKind::ResponseHistory, resolveUrl(manifestUrl_, r.historyFile), r.historyBytes, r.historyCrc32, {}};
}

void CityScene::request(std::uint32_t node) {
  // Verified bytes wait for the frame's decoding budget (finishTile).
  const bool started =
      loader_.start(tiles_[node]->tile, tileSpec(node), [this, node](std::vector<std::uint8_t>& bytes) {
        tiles_[node]->bytes = std::move(bytes);
        decodeQueue_.push_back(node);
        return Verdict::later();
      });
  // Its response summary travels alongside (it colours the tile's first frame): both downloads
  // overlap instead of the summary waiting for the tile to arrive and be decoded.
  if (started) requestSummary(node);
}

void CityScene::finishTile(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  const TileNode& n = tileset_->nodes[node];
  const FileSpec spec = tileSpec(node);
  const std::string& url = spec.url;
  std::vector<std::uint8_t> bytes = std::move(t.bytes);
  t.bytes.clear();
  Result<CityTile> decoded = decodeCityTile(bytes, url);
  if (!decoded.ok()) {
    loader_.fail(t.tile, spec, decoded.error(), false);
    return;
  }
  if (decoded->buildings.size() != n.buildings) {
    loader_.fail(t.tile, spec,
                 url + ": " + std::to_string(decoded->buildings.size()) + " buildings, the manifest says " +
                     std::to_string(n.buildings),
                 false);
    return;
  }
  auto tile = std::make_unique<LoadedTile>(indexTile(std::move(decoded).value()));
  const auto count = tile->buildingCount();
  const auto slotBase = table_.reserveBuildings(count);
  if (!slotBase) {
    loader_.fail(t.tile, spec, "too many buildings loaded at once", true);
    return;
  }
  tile->slotBase = *slotBase;
  initialBuildingRows(*tile, tileset_->nodes[node].response.has_value(), table_.edit(tile->slotBase, count));
  const MeshData mesh = buildTileMesh(*tile, tile->slotBase);
  tile->mesh = device_.createMesh(mesh);
  tile->gpuBytes = meshGpuBytes(mesh);
  tile->cpuBytes = tileCpuBytes(*tile);
  {
    const int kind = tileset_->nodes[node].children.empty() ? 0 : 1;
    residentOfFile_[kind] += tile->cpuBytes + tile->gpuBytes;
    fileOfResident_[kind] += tileset_->nodes[node].bytes;
  }
  t.loaded = std::move(tile);
  ++residencyGeneration_;
  t.lastUsed = frame_;
  loader_.succeed(t.tile, spec);  // an error it had shown is withdrawn
  applyFlags(node);
  // The summary was requested with the tile and may be here already (or may have failed).
  if (t.summary)
    applySummary(node);
  else if (t.summaryLoad.state == TileState::Failed)
    markNoResult(node);
  if (tileset_->nodes[node].response) requestSummary(node);
}

void CityScene::requestSummary(std::uint32_t node) {
  if (!tileset_->nodes[node].response) return;
  const FileSpec spec = summarySpec(node);
  loader_.start(
      tiles_[node]->summaryLoad, spec,
      [this, node, url = spec.url](std::vector<std::uint8_t>& bytes) {
        auto decoded = decodeResponseSummary(bytes, url);
        if (!decoded.ok()) return Verdict::rejected(decoded.error(), false);
        if (decoded->buildings.size() != tileset_->nodes[node].buildings) {
          return Verdict::rejected(url + ": building count differs from the city tile", false);
        }
        tiles_[node]->summary = std::make_unique<ResponseSummaryTile>(std::move(decoded).value());
        applySummary(node);
        return Verdict::loaded();
      },
      [this, node] { markNoResult(node); });  // its buildings are hatched: no result
}

void CityScene::markNoResult(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded) return;
  const LoadedTile& tile = *t.loaded;
  for (BuildingGpuRecord& row : table_.edit(tile.slotBase, tile.buildingCount())) row.damageState = -1.0f;
}

void CityScene::applySummary(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded || !t.summary) return;
  const LoadedTile& tile = *t.loaded;
  for (std::size_t b = 0; b < t.summary->buildings.size() && b < tile.positionOf.size(); ++b) {
    const BuildingResponse& r = t.summary->buildings[b];
    BuildingGpuRecord& row = table_.row(tile.slotBase + tile.positionOf[b]);
    row.peakValue = r.peakDriftRatio;
    row.damageState = r.damage == DamageState::NoResult ? -1.0f : static_cast<float>(r.damage);
  }
  table_.changed(tile.slotBase, tile.buildingCount());
  applyFlags(node);  // damage filters need the summary
}

void CityScene::requestHistory(std::uint32_t node) {
  const TileNode& n = tileset_->nodes[node];
  if (!n.response || n.response->historyFile.empty()) return;
  const FileSpec spec = historySpec(node);
  loader_.start(tiles_[node]->historyLoad, spec, [this, node, url = spec.url](std::vector<std::uint8_t>& bytes) {
    auto decoded = decodeResponseHistory(bytes, url);
    if (!decoded.ok()) return Verdict::rejected(decoded.error(), false);
    if (decoded->buildings.size() != tileset_->nodes[node].buildings) {
      return Verdict::rejected(url + ": building count differs from the city tile", false);
    }
    TileRuntime& t = *tiles_[node];
    t.history = std::make_unique<ResponseHistoryTile>(std::move(decoded).value());
    std::uint64_t historyBytes = 0;
    for (const BuildingHistory& h : t.history->buildings) {
      historyBytes += sizeof(BuildingHistory) + (h.x.coordinates.size() + h.y.coordinates.size()) * 2 +
                      (h.x.shapes.size() + h.y.shapes.size()) * 4;
    }
    t.historyBytes = historyBytes;
    ++residencyGeneration_;
    return Verdict::loaded();
  });
}

void CityScene::reindexAnimated() {
  for (std::size_t k = 0; k < animated_.size(); ++k) {
    TileRuntime& t = *tiles_[animated_[k]->ref.node];
    if (animated_[k]->ref.index < t.animatedIndex.size()) {
      t.animatedIndex[animated_[k]->ref.index] = static_cast<std::uint32_t>(k);
    }
  }
}

void CityScene::evict(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  ++residencyGeneration_;
  if (t.loaded) {
    // Buildings of this tile stop animating first (they hold floor rows).
    for (auto& a : animated_) {
      if (a && a->ref.node == node) {
        table_.releaseFloors(a->floorBase, a->rows);
        a.reset();
      }
    }
    animated_.erase(std::remove(animated_.begin(), animated_.end(), nullptr), animated_.end());
    t.animatedIndex.clear();
    reindexAnimated();
    if (t.loaded->mesh) device_.destroyMesh(t.loaded->mesh);
    table_.releaseBuildings(t.loaded->slotBase, t.loaded->buildingCount());
    t.loaded.reset();
  }
  t.summary.reset();
  t.summaryLoad.state = TileState::Unloaded;
  t.history.reset();
  t.historyBytes = 0;
  t.historyLoad.state = TileState::Unloaded;
  t.tile.state = TileState::Unloaded;
}

void CityScene::enforceMemoryBudget() {
  std::uint64_t total = memoryBytes();
  if (total <= options_.memoryBudgetBytes) return;
  // Histories outside the animation radius go first (re-fetched when needed), then whole tiles,
  // least recently used first; nothing the current frame uses is evicted.
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    if (tiles_[i]->history && tiles_[i]->historyUsed < frame_) {
      total -= tiles_[i]->historyBytes;
      tiles_[i]->history.reset();
      ++residencyGeneration_;
      tiles_[i]->historyBytes = 0;
      tiles_[i]->historyLoad.state = TileState::Unloaded;
      if (total <= options_.memoryBudgetBytes) return;
    }
    if (tiles_[i]->loaded && tiles_[i]->lastUsed < frame_) candidates.push_back(i);
  }
  std::sort(candidates.begin(), candidates.end(),
            [&](std::uint32_t a, std::uint32_t b) { return tiles_[a]->lastUsed < tiles_[b]->lastUsed; });
  for (std::uint32_t i : candidates) {
    if (total <= options_.memoryBudgetBytes) break;
    const std::uint64_t bytes = tileBytes(i);
    evict(i);
    total -= std::min(total, bytes);
  }
  if (total <= options_.memoryBudgetBytes) return;
  // Still over: the coarse tiles this frame replaced by their children, largest first. The
  // selector passes through an evicted tile to its children instead of loading it again.
  candidates.clear();
  for (std::uint32_t i : selection_.replaced) {
    if (tiles_[i]->loaded && std::find(detailWanted_.begin(), detailWanted_.end(), i) == detailWanted_.end())
      candidates.push_back(i);
  }
  std::sort(candidates.begin(), candidates.end(), [&](std::uint32_t a, std::uint32_t b) {
    const std::uint64_t ba = tileBytes(a), bb = tileBytes(b);
    return ba != bb ? ba > bb : a < b;
  });
  for (std::uint32_t i : candidates) {
    if (total <= options_.memoryBudgetBytes) break;
    const std::uint64_t bytes = tileBytes(i);
    evict(i);
    total -= std::min(total, bytes);
  }
}

void CityScene::update(const CameraView& view, double timeSeconds, FrameTimesMs& times, FrameCounts& counts,
                       std::vector<DrawItem>& items) {
  ++frame_;
  const double frameStart = clock_.nowSeconds();
  loader_.options() = loaderOptions(options_);
  fetcher_.poll();
  if (!tileset_) {
    settled_ = manifestFailed_;
    return;
  }

  // Decode and mesh what arrived, within the time budget (at least one tile per frame), before
  // choosing tiles: a tile decoded now lets its children be requested in this same frame. When
  // frames are slow anyway (a software renderer drawing a million triangles), the budget grows
  // with the frame interval, so loading is not held back by drawing.
  double t0 = clock_.nowSeconds();
  const double intervalMs = lastUpdate_ ? (frameStart - *lastUpdate_) * 1000.0 : 0.0;
  lastUpdate_ = frameStart;
  const double budgetMs = std::max(options_.workBudgetMs, std::min(0.5 * intervalMs, 200.0));
  while (!decodeQueue_.empty()) {
    const std::uint32_t node = decodeQueue_.front();
    decodeQueue_.erase(decodeQueue_.begin());
    finishTile(node);
    if (msSince(clock_, t0) > budgetMs) break;
  }
  const double streamingMs = msSince(clock_, t0);

  // LOD: which tiles to draw and to load.
  t0 = clock_.nowSeconds();
  TileSelectorOptions selectorOptions;
  selectorOptions.maxScreenSpaceError = options_.maxScreenSpaceError;
  selectorOptions.maxDrawTiles = options_.maxDrawTiles;
  selectorOptions.detailRadiusM = options_.animationRadiusM;
  // The tiles drawn and wanted get what the city index and the animated buildings' histories leave
  // of the budget (at least an eighth of it: something must be drawn).
  updateNodeBytes();
  std::uint64_t histories = 0;
  for (const auto& t : tiles_) histories += t->historyBytes;
  const std::uint64_t budget = options_.memoryBudgetBytes;
  selectorOptions.nodeBytes = nodeBytes_;
  selectorOptions.wasLoaded = std::span<const bool>(wasLoaded_.get(), nodeBytes_.size());
  selectorOptions.memoryBudgetBytes =
      std::max<std::uint64_t>({1, budget / 8, budget - std::min(budget, index_.bytes() + histories)});
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) states_[i] = tiles_[i]->tile.state;
  selectTiles(*tileset_, states_, view, selectorOptions, selection_);
  for (std::uint32_t i : selection_.used) tiles_[i]->lastUsed = frame_;
  for (std::uint32_t i : selection_.wanted) tiles_[i]->lastUsed = frame_;
  for (std::uint32_t i : selection_.wanted) {
    if (!loader_.hasRoom()) break;
    if (tiles_[i]->tile.state == TileState::Unloaded) request(i);
  }
  // The selected building's leaf, wherever the camera is (inspection needs its attributes and
  // history).
  for (std::uint32_t i : detailWanted_) {
    tiles_[i]->lastUsed = frame_;
    if (tiles_[i]->tile.state == TileState::Unloaded) request(i);
  }
  detailWanted_.erase(std::remove_if(detailWanted_.begin(), detailWanted_.end(),
                                     [&](std::uint32_t i) {
                                       const TileState state = tiles_[i]->tile.state;
                                       return state == TileState::Loaded || state == TileState::Failed;
                                     }),
                      detailWanted_.end());
  // Once the view has everything it asked for, the search index comes in the background (names
  // and addresses for search, the inspection window and exports).
  if (loader_.inFlight() == 0 && decodeQueue_.empty()) index_.request();
  index_.retry();
  // Failed tiles (and their response summaries) the view still uses are retried with backoff
  // (the server may recover).
  for (std::uint32_t i : selection_.used) {
    if (tiles_[i]->summaryLoad.state == TileState::Failed && tiles_[i]->loaded) requestSummary(i);
  }
  for (std::uint32_t i : selection_.used) {
    if (!loader_.hasRoom()) break;
    if (tiles_[i]->tile.state == TileState::Failed) request(i);  // once its backoff has passed
  }
  times.lod += msSince(clock_, t0);

  // Cull: tile boxes first, then the buildings of partly visible tiles.
  t0 = clock_.nowSeconds();
  const Frustum& frustum = view.frustum();
  std::uint32_t visibleBuildings = 0;
  for (std::uint32_t i : selection_.draw) {
    TileRuntime& t = *tiles_[i];
    t.visible.clear();
    if (!t.loaded) continue;
    const auto n = static_cast<std::uint32_t>(t.loaded->positionOf.size());
    const Containment c = frustum.classify(nodeBox(tileset_->nodes[i]));
    if (c == Containment::Outside) continue;
    if (c == Containment::Inside)
      t.visible.push_back(IndexRange{0, n, true});
    else
      t.loaded->tree.query(frustum, t.visible);
    for (const IndexRange& r : t.visible) visibleBuildings += r.end - r.begin;
    items.push_back(DrawItem{t.loaded->mesh, t.loaded->origin});
  }
  // Damage states in view (for the panel), from the summaries of the drawn tiles: counted again
  // only when the visible sets or the summaries behind them changed.
  std::uint64_t viewSignature = 1469598103934665603ull;  // FNV-1a
  auto mix = [&viewSignature](std::uint64_t v) {
    viewSignature ^= v;
    viewSignature *= 1099511628211ull;
  };
  for (std::uint32_t i : selection_.draw) {
    const TileRuntime& t = *tiles_[i];
    if (!t.loaded) continue;
    mix(i);
    mix(reinterpret_cast<std::uintptr_t>(t.summary.get()));
    mix(t.visible.size());
    for (const IndexRange& r : t.visible) mix((static_cast<std::uint64_t>(r.begin) << 32) | r.end);
  }
  mix(residencyGeneration_);
  const bool viewChanged = viewSignature != viewSignature_;
  viewSignature_ = viewSignature;
  if (viewChanged) {
    damageInView_.fill(0);
    for (std::uint32_t i : selection_.draw) {
      const TileRuntime& t = *tiles_[i];
      if (!t.loaded) continue;
      for (const IndexRange& r : t.visible) {
        for (std::uint32_t p = r.begin; p < r.end; ++p) {
          const std::uint32_t b = t.loaded->tree.order()[p];
          const DamageState d =
              t.summary && b < t.summary->buildings.size() ? t.summary->buildings[b].damage : DamageState::NoResult;
          ++damageInView_[d == DamageState::NoResult ? 5 : static_cast<std::size_t>(d)];
        }
      }
    }
  }
  counts.buildingsVisible += visibleBuildings;
  times.cull += msSince(clock_, t0);

  // Animate.
  t0 = clock_.nowSeconds();
  animate(view.eye(), timeSeconds, counts);
  times.animate += msSince(clock_, t0);
  t0 = clock_.nowSeconds();
  enforceMemoryBudget();
  const double evictMs = msSince(clock_, t0);

  // Upload the changed rows of the building table and the whole used floor table.
  t0 = clock_.nowSeconds();
  table_.upload(device_, !animated_.empty());
  times.upload += msSince(clock_, t0) + streamingMs + evictMs;

  // Buildings available for drawing: every building of each maximal loaded subtree.
  std::uint64_t loaded = 0;
  std::vector<std::uint32_t> stack = {0};
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    if (tiles_[i]->tile.state == TileState::Loaded) {
      loaded += tileset_->nodes[i].subtreeBuildings;
      continue;
    }
    for (std::uint32_t c : tileset_->nodes[i].children) stack.push_back(c);
  }
  counts.buildingsLoaded += static_cast<std::uint32_t>(loaded);

  bool responsesReady = true;
  for (std::uint32_t i : selection_.draw) {
    if (tiles_[i]->summaryLoad.state == TileState::Loading) responsesReady = false;
  }
  for (const auto& t : tiles_) {
    if (t->historyLoad.state == TileState::Loading) responsesReady = false;
  }
  settled_ = selection_.complete() && decodeQueue_.empty() && responsesReady;
}

void CityScene::animate(const glm::vec3& eye, double timeSeconds, FrameCounts& counts) {
  const float radius = options_.animationRadiusM;
  // The tiles within the radius keep (or fetch) their histories this frame. What they animate is
  // chosen again only when something it depends on changed: the eye, the radius, the cap, a
  // tile's residency or visible set. A still camera while playing costs only the sampling below.
  std::uint64_t signature = 1469598103934665603ull;  // FNV-1a over the inputs of the choice
  auto mix = [&signature](std::uint64_t v) {
    signature ^= v;
    signature *= 1099511628211ull;
  };
  auto bitsOf = [](float v) {
    std::uint32_t b = 0;
    std::memcpy(&b, &v, sizeof b);
    return static_cast<std::uint64_t>(b);
  };
  mix(bitsOf(eye.x));
  mix(bitsOf(eye.y));
  mix(bitsOf(eye.z));
  mix(bitsOf(radius));
  mix(options_.maxAnimatedBuildings);
  mix(residencyGeneration_);
  mix(viewSignature_);  // the visible sets (culling) of every drawn tile
  std::vector<std::uint32_t>& inRadius = animationTiles_;
  inRadius.clear();
  if (radius > 0.0f) {
    for (std::uint32_t i : selection_.draw) {
      TileRuntime& t = *tiles_[i];
      const TileNode& n = tileset_->nodes[i];
      if (!t.loaded || n.coarse || !n.response || n.response->historyFile.empty()) continue;
      const float tileDistance =
          std::max(0.0f, std::hypot(std::max({n.bounds.minX - eye.x, 0.0f, eye.x - n.bounds.maxX}),
                                    std::max({n.bounds.minY - eye.y, 0.0f, eye.y - n.bounds.maxY}),
                                    std::max(eye.z - n.maxHeightM, 0.0f)));
      if (static_cast<double>(tileDistance) > static_cast<double>(radius)) continue;
      requestHistory(i);
      t.historyUsed = frame_;
      if (t.historyLoad.state != TileState::Loaded) continue;
      inRadius.push_back(i);
      mix(i);
    }
  }
  if (signature != animationSignature_ || animated_.empty() != inRadius.empty() ||
      samplers_.size() != animated_.size()) {
    animationSignature_ = signature;
    chooseAnimated(eye, inRadius);
  }

  // Every animated building's floors at this time, straight into its rows of the floor table,
  // in two passes. What the sampling needs was packed in animation order when the buildings were
  // chosen (read as one stream); only the coordinates around t are scattered over the heap. The
  // first pass turns them into modal coordinates. Each building keeps a window of the four
  // samples it interpolates: from one frame to the next t moves by a fraction of a sample, so
  // most frames reuse the window and the rest fetch one new sample (a cache miss the short loop
  // lets the processor overlap with others; WebAssembly has no prefetch). The second pass turns
  // modal coordinates into floor displacements from the packed shapes.
  const std::size_t count = animated_.size();
  modal_.resize(count * 2 * kMaxHistoryModes);
  for (std::size_t j = 0; j < count; ++j) {
    windowedModalCoordinates(samplers_[j].stream, timeSeconds, windows_[j], modal_.data() + j * 2 * kMaxHistoryModes);
  }
  for (std::size_t j = 0; j < count; ++j) {
    const Animated& a = *animated_[j];
    const AnimatedSampler& sampler = samplers_[j];
    FloorGpuRecord* rows = table_.floors(a.floorBase, a.rows).data();
    const std::size_t floors = std::min<std::size_t>(sampler.floors, a.rows - 1);
    rows[0].dxMeters = rows[0].dyMeters = 0.0f;
    if (sampler.stream.sampleCount == 0 || floors == 0) {
      for (std::size_t k = 1; k < a.rows; ++k) rows[k].dxMeters = rows[k].dyMeters = 0.0f;
    } else {
      // The packed arena holds scales x, shapes x, scales y, shapes y.
      const std::size_t mx = sampler.stream.modesX, my = sampler.stream.modesY;
      const float* shapesX = samplerArena_.data() + sampler.arenaOffset + mx;
      const float* shapesY = shapesX + std::size_t{sampler.floors} * mx + my;
      const float* cx = modal_.data() + j * 2 * kMaxHistoryModes;
      const float* cy = cx + kMaxHistoryModes;
      floorDisplacements(shapesX, cx, mx, shapesY, cy, my, floors, rows + 1);
    }
    if (!a.peaksWritten) {
      // The peak drifts do not change with time: written once, when the summary is there.
      const TileRuntime& t = *tiles_[a.ref.node];
      if (t.summary) {
        if (a.ref.index < t.summary->buildings.size()) {
          const BuildingResponse& summary = t.summary->buildings[a.ref.index];
          for (std::uint32_t k = 0; k < a.rows; ++k) {
            rows[k].peakDriftAbove = k < summary.storeys ? t.summary->storeyPeakDrift[summary.firstStorey + k] : 0.0f;
          }
        }
        animated_[j]->peaksWritten = true;
      }
    }
  }
  counts.buildingsAnimated += static_cast<std::uint32_t>(animated_.size());
  counts.modelsAnimated += modelsAnimated_;
}

void CityScene::chooseAnimated(const glm::vec3& eye, const std::vector<std::uint32_t>& tiles) {
  const float radius = options_.animationRadiusM;
  struct Candidate {
    float distance2;
    std::uint32_t node, index, position;
  };
  std::vector<Candidate> candidates;
  const double r2 = static_cast<double>(radius) * radius;
  for (std::uint32_t i : tiles) {
    const TileRuntime& t = *tiles_[i];
    const LoadedTile& tile = *t.loaded;
    for (const IndexRange& range : t.visible) {
      for (std::uint32_t p = range.begin; p < range.end; ++p) {
        const std::uint32_t b = tile.tree.order()[p];
        const BuildingAttributes& a = tile.data.buildings[b].attributes;
        // Distance from the eye to the building's axis at mid-height.
        const double cx = a.centroidX + tile.data.originX - static_cast<double>(eye.x);
        const double cy = a.centroidY + tile.data.originY - static_cast<double>(eye.y);
        const double cz = 0.5 * static_cast<double>(a.heightM + a.minHeightM) - static_cast<double>(eye.z);
        const double d2 = cx * cx + cy * cy + cz * cz;
        if (d2 <= r2 && t.history->buildings[b].floors == a.storeys) {
          candidates.push_back({static_cast<float>(d2), i, b, p});
        }
      }
    }
  }
  if (candidates.size() > options_.maxAnimatedBuildings) {
    std::nth_element(candidates.begin(),
                     candidates.begin() + static_cast<std::ptrdiff_t>(options_.maxAnimatedBuildings), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.distance2 < b.distance2; });
    candidates.resize(options_.maxAnimatedBuildings);
  }

  // Keep the floor rows of buildings that stay animated; release the rest; allocate the new.
  // (Each tile maps its buildings to their entries in animated_: no hashing.)
  ++choice_;
  for (const Candidate& c : candidates) {
    TileRuntime& t = *tiles_[c.node];
    const LoadedTile& tile = *t.loaded;
    if (t.animatedIndex.size() != tile.data.buildings.size()) {
      t.animatedIndex.assign(tile.data.buildings.size(), kNotAnimated);
    }
    if (const std::uint32_t k = t.animatedIndex[c.index]; k != kNotAnimated) {
      animated_[k]->choice = choice_;
      continue;
    }
    const std::uint32_t rows = tile.data.buildings[c.index].attributes.storeys + 1u;
    const auto base = table_.reserveFloors(rows);
    if (!base) break;
    auto a = std::make_unique<Animated>();
    a->ref = {c.node, c.index};
    a->slot = tile.slotBase + c.position;
    a->floorBase = *base;
    a->rows = rows;
    a->choice = choice_;
    table_.edit(a->slot, 1)[0].floorBase = static_cast<float>(*base);
    t.animatedIndex[c.index] = static_cast<std::uint32_t>(animated_.size());
    animated_.push_back(std::move(a));
  }
  bool released = false;
  for (auto& a : animated_) {
    if (a->choice == choice_) continue;
    TileRuntime& t = *tiles_[a->ref.node];
    if (t.loaded) {
      table_.edit(a->slot, 1)[0].floorBase = -1.0f;
    }
    if (a->ref.index < t.animatedIndex.size()) t.animatedIndex[a->ref.index] = kNotAnimated;
    table_.releaseFloors(a->floorBase, a->rows);
    a.reset();
    released = true;
  }
  if (released) {
    animated_.erase(std::remove(animated_.begin(), animated_.end(), nullptr), animated_.end());
    reindexAnimated();
  }
  // Their histories, in the same order, for the sampling loop (valid until the next choice: any
  // change of residency changes the signature, and the choice is made again before sampling).
  samplers_.resize(animated_.size());
  windows_.resize(animated_.size());
  samplerArena_.clear();
  modelsAnimated_ = 0;
  for (std::size_t j = 0; j < animated_.size(); ++j) {
    if (tiles_[animated_[j]->ref.node]->loaded->meshOf(animated_[j]->ref.index) != nullptr) ++modelsAnimated_;
    const BuildingHistory& h = tiles_[animated_[j]->ref.node]->history->buildings[animated_[j]->ref.index];
    AnimatedSampler& sampler = samplers_[j];
    sampler.stream.x = h.x.coordinates.data();
    sampler.stream.y = h.y.coordinates.data();
    sampler.stream.startSeconds = h.startSeconds;
    sampler.stream.sampleRateHz = h.sampleRateHz;
    sampler.stream.sampleCount = h.sampleCount;
    sampler.stream.modesX = h.x.modes;
    sampler.stream.modesY = h.y.modes;
    sampler.floors = h.floors;
    sampler.arenaOffset = static_cast<std::uint32_t>(samplerArena_.size());
    windows_[j] = SampleWindow{};  // nothing in its window yet
    for (const HistoryDirection* d : {&h.x, &h.y}) {
      samplerArena_.insert(samplerArena_.end(), d->scales.begin(), d->scales.end());
      samplerArena_.insert(samplerArena_.end(), d->shapes.begin(), d->shapes.end());
    }
  }
  // The arena is complete: its scales can be pointed at.
  for (AnimatedSampler& sampler : samplers_) {
    sampler.stream.scalesX = samplerArena_.data() + sampler.arenaOffset;
    sampler.stream.scalesY =
        sampler.stream.scalesX + sampler.stream.modesX + std::size_t{sampler.floors} * sampler.stream.modesX;
  }
}

// ---------------------------------------------------------------------------------------------
// Selection, filters, picking, search.

void CityScene::applyFlags(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded) return;
  const LoadedTile& tile = *t.loaded;
  const bool filtering = filters_.active();
  for (std::uint32_t b = 0; b < tile.data.buildings.size(); ++b) {
    BuildingGpuRecord& row = table_.row(tile.slotBase + tile.positionOf[b]);
    const BuildingAttributes& a = tile.data.buildings[b].attributes;
    const BuildingResponse* r = t.summary && b < t.summary->buildings.size() ? &t.summary->buildings[b] : nullptr;
    BuildingTable::setFlag(row, kFlagSelected, !selected_.empty() && a.id == selected_);
    BuildingTable::setFlag(row, kFlagDimmed, filtering && !filters_.passes(a, r));
    BuildingTable::setFlag(row, kFlagHidden, hiddenByLod(a.lod));
  }
  table_.changed(tile.slotBase, tile.buildingCount());
}

void CityScene::applyFlagsEverywhere() {
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    if (tiles_[i]->loaded) applyFlags(i);
  }
}

bool CityScene::hiddenByLod(std::uint8_t lod) const {
  // A LOD2 building with models switched off is drawn as its LOD1 extrusion, like the LOD1 ones.
  return lod == 2 && showLod2_ ? false : !showLod1_;
}

void CityScene::setLodVisibility(bool lod1, bool lod2) {
  if (lod1 == showLod1_ && lod2 == showLod2_) return;
  showLod1_ = lod1;
  showLod2_ = lod2;
  applyFlagsEverywhere();
}

void CityScene::setFilters(const BuildingFilters& filters) {
  if (filters == filters_) return;
  filters_ = filters;
  applyFlagsEverywhere();
}

std::optional<BuildingRef> CityScene::find(std::string_view id) const {
  std::optional<BuildingRef> coarse;
  const std::string key(id);
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    const TileRuntime& t = *tiles_[i];
    if (!t.loaded) continue;
    const auto it = t.loaded->idIndex.find(key);
    if (it == t.loaded->idIndex.end()) continue;
    if (!t.loaded->data.coarse) return BuildingRef{i, it->second};
    // Of the coarse copies, the deepest (the most detailed) wins.
    if (!coarse || tileset_->nodes[i].level > tileset_->nodes[coarse->node].level) coarse = BuildingRef{i, it->second};
  }
  return coarse;
}

std::optional<BuildingInfo> CityScene::info(BuildingRef ref) const {
  if (ref.node >= tiles_.size() || !tiles_[ref.node]->loaded) return std::nullopt;
  const TileRuntime& t = *tiles_[ref.node];
  const CityTile& d = t.loaded->data;
  if (ref.index >= d.buildings.size()) return std::nullopt;
  BuildingInfo info;
  info.attributes = d.buildings[ref.index].attributes;
  info.attributes.centroidX += d.originX;
  info.attributes.centroidY += d.originY;
  info.detailed = !d.coarse;
  info.tile = tileset_->nodes[ref.node].key();
  if (const TileMesh* m = t.loaded->meshOf(ref.index)) {
    info.modelSource = meshSourceName(m->source);
    info.modelTriangles = static_cast<std::uint32_t>((d.coarse ? m->farTriangles.size() : m->triangles.size()) / 3);
  }
  // Its results: from this tile's summary, or, while that is on its way (a leaf just loaded for
  // the selection), from another loaded copy's (the coarse tiles above carry the same results).
  const TileRuntime* source = &t;
  std::uint32_t index = ref.index;
  if (!t.summary && tileset_->nodes[ref.node].response) {
    const std::string& id = d.buildings[ref.index].attributes.id;
    for (const auto& other : tiles_) {
      if (!other->loaded || !other->summary) continue;
      const auto it = other->loaded->idIndex.find(id);
      if (it == other->loaded->idIndex.end()) continue;
      source = other.get();
      index = it->second;
      break;
    }
  }
  if (source->summary && index < source->summary->buildings.size()) {
    info.hasResponse = true;
    info.response = source->summary->buildings[index];
    const auto first =
        source->summary->storeyPeakDrift.begin() + static_cast<std::ptrdiff_t>(info.response.firstStorey);
    info.storeyPeakDrift.assign(first, first + static_cast<std::ptrdiff_t>(info.response.storeys));
  }
  return info;
}

bool CityScene::select(const std::string& id) {
  if (id == selected_) return true;
  const auto ref = id.empty() || !tileset_ ? std::nullopt : find(id);
  const SearchEntry* entry = id.empty() || ref ? nullptr : index_.entry(id);
  if (!id.empty() && !ref && entry == nullptr) return false;
  selected_ = id;
  series_.reset();
  seriesFor_.clear();
  detailWanted_.clear();
  applyFlagsEverywhere();
  if (id.empty() || !tileset_) return true;
  if (entry != nullptr) {
    // In no loaded tile (a large city's coarse tiles hold only its largest buildings): its leaf,
    // from the index.
    detailWanted_.push_back(entry->leaf);
  } else if (tiles_[ref->node]->loaded->data.coarse) {
    // Its leaf (full attributes and history): the leaves whose bounds hold its centroid.
    const auto info = this->info(*ref);
    for (std::uint32_t i = 0; i < tileset_->nodes.size(); ++i) {
      const TileNode& n = tileset_->nodes[i];
      if (n.children.empty() && n.bounds.contains(static_cast<float>(info->attributes.centroidX),
                                                  static_cast<float>(info->attributes.centroidY))) {
        detailWanted_.push_back(i);
      }
    }
  }
  return true;
}

std::optional<BuildingSeries> CityScene::selectionSeries(std::size_t samples) {
  if (selected_.empty() || samples < 2) return std::nullopt;
  if (series_ && seriesFor_ == selected_ && series_->roofDisplacementM.size() == samples) return series_;
  const auto ref = find(selected_);
  if (!ref) return std::nullopt;
  TileRuntime& t = *tiles_[ref->node];
  if (t.loaded->data.coarse) return std::nullopt;  // the leaf is on its way
  requestHistory(ref->node);                       // when not loaded or loading (and any backoff has passed)
  t.historyUsed = frame_;
  if (t.historyLoad.state != TileState::Loaded || ref->index >= t.history->buildings.size()) return std::nullopt;
  const BuildingHistory& h = t.history->buildings[ref->index];
  const BuildingAttributes& a = t.loaded->data.buildings[ref->index].attributes;
  if (h.floors == 0) return std::nullopt;
  BuildingSeries s;
  s.durationSeconds = duration();
  std::vector<float> x(h.floors + 1u), y(h.floors + 1u);
  const float storeyHeight = std::max(a.storeyHeightM(), 0.1f);
  for (std::size_t i = 0; i < samples; ++i) {
    const double time = s.durationSeconds * static_cast<double>(i) / static_cast<double>(samples - 1);
    sampleHistory(h, time, x, y);
    s.roofDisplacementM.push_back(std::hypot(x[h.floors], y[h.floors]));
    float drift = 0.0f;
    for (std::size_t k = 0; k < h.floors; ++k) {
      drift = std::max(drift, std::hypot(x[k + 1] - x[k], y[k + 1] - y[k]) / storeyHeight);
    }
    s.maxDriftRatio.push_back(drift);
  }
  series_ = std::move(s);
  seriesFor_ = selected_;
  return series_;
}

std::optional<BuildingRef> CityScene::pick(const glm::vec3& origin, const glm::vec3& direction) const {
  float best = INFINITY;
  std::optional<BuildingRef> hit;
  std::vector<std::pair<float, std::uint32_t>> candidates;
  const float o[3] = {origin.x, origin.y, origin.z};
  const float dir[3] = {direction.x, direction.y, direction.z};
  for (std::uint32_t node : selection_.draw) {
    const TileRuntime& t = *tiles_[node];
    if (!t.loaded) continue;
    const LoadedTile& tile = *t.loaded;
    candidates.clear();
    tile.tree.raycast(origin, direction, best == INFINITY ? 1.0e7f : best, candidates);
    for (const auto& [entry, position] : candidates) {
      if (entry > best) break;  // boxes come nearest first: nothing further can be nearer
      const std::uint32_t b = tile.tree.order()[position];
      const TileBuilding& tb = tile.data.buildings[b];
      if (hiddenByLod(tb.attributes.lod)) continue;  // hidden: not pickable
      if (const TileMesh* m = showLod2_ ? tile.meshOf(b) : nullptr) {
        // A LOD2 model is picked on its own triangles (the far mesh in coarse tiles).
        const glm::vec3 offset(tile.origin.x, tile.origin.y, tb.attributes.minHeightM);
        const auto tHit = tile.data.coarse
                              ? rayTriangles<std::uint16_t>(o, dir, m->farPositions, m->farTriangles, offset)
                              : rayTriangles<std::uint32_t>(o, dir, m->positions, m->triangles, offset);
        if (tHit && *tHit < best) {
          best = *tHit;
          hit = BuildingRef{node, b};
        }
        continue;
      }
      for (std::uint32_t p = tb.firstPart; p < tb.firstPart + tb.partCount; ++p) {
        const TilePart& part = tile.data.parts[p];
        PrismView prism;
        prism.xy = &tile.data.vertices[part.firstVertex].x;
        prism.ringCounts = &tile.data.ringVertexCounts[part.firstRing];
        prism.ringCount = part.ringCount;
        prism.offsetX = tile.origin.x;
        prism.offsetY = tile.origin.y;
        prism.minZ = part.minHeightM;
        prism.maxZ = part.heightM;
        if (const auto tHit = rayPrism(o, dir, prism); tHit && *tHit < best) {
          best = *tHit;
          hit = BuildingRef{node, b};
        }
      }
    }
  }
  return hit;
}

// The city index's side (CityIndex): search and lists load the index on first use.

const SearchEntry* CityScene::indexEntry(std::string_view id) const {
  return index_.entry(id);
}

std::vector<BuildingListEntry> CityScene::search(std::string_view query, std::size_t limit) {
  index_.request();
  return index_.search(query, limit);
}

std::vector<BuildingListEntry> CityScene::filteredList(std::size_t limit, std::size_t* total) {
  index_.request();
  return index_.filteredList(filters_, limit, total);
}

bool CityScene::searchIndexSettled() const {
  return tileset_ ? index_.settled() : manifestFailed_;
}

}  // namespace qv
