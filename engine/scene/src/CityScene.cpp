#include "qv/scene/CityScene.h"

#include "CitySceneState.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "qv/core/Crc32.h"
#include "qv/scene/BuildingTable.h"
#include "qv/scene/Report.h"
#include "qv/scene/TileMeshBuilder.h"
#include "qv/spatial/BoxTree.h"

namespace qv {
namespace {

double msSince(const SceneClock& clock, double startSeconds) {
  return (clock.nowSeconds() - startSeconds) * 1000.0;
}

// The loader's options from the scene's (which the viewer may change between frames).
FileLoaderOptions loaderOptions(const CitySceneOptions& options) {
  return {options.maxRequestsInFlight, options.requestTimeoutMs, options.slowestBytesPerSecond};
}

}  // namespace

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
    if (t && t->loaded) destroyMeshes(*t->loaded);
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
  wasLoaded_ = std::make_unique<bool[]>(tileset_->nodes.size());
  if (tileset_->ground && !tileset_->ground->nodes.empty()) {
    ground_ = std::make_unique<GroundScene>(device_, loader_, manifestUrl_, *tileset_->ground);
  }
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
  if (ground_) c.pending += ground_->pending();  // the map's cells the view wants
  // Tiles the view wants but has not requested yet (the request limit) are pending as well.
  for (std::uint32_t i : selection_.wanted) {
    if (tiles_[i]->tile.state == TileState::Unloaded) ++c.pending;
  }
  c.drawn = static_cast<std::uint32_t>(selection_.draw.size());
  c.drawLimited = selection_.budgetLimited;
  c.memoryLimited = selection_.memoryLimited;
  return c;
}

FileSpec CityScene::tileSpec(std::uint32_t node) const {
  const TileNode& n = tileset_->nodes[node];
  return FileSpec{FileKind::Tile, resolveUrl(manifestUrl_, n.file), n.bytes, n.crc32, n.key()};
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
  // Far-view tiles are drawn region by region: their buildings' mesh in region order.
  if (tile->data.coarse) {
    tile->regions = buildTileRegions(*tile);
    if (const Box& all = tile->tree.bounds(); !all.empty()) {
      if (const int level = regionLevelFor(all.maxX - all.minX, all.maxY - all.minY); level > kBlockRegionLevel)
        tile->farRegions = std::make_unique<TileRegions>(buildTileRegions(*tile, level));
    }
  }
  const MeshData mesh = buildTileMesh(*tile, tile->slotBase, &tile->runs, tile->regions.appendOrder);
  tile->mesh = device_.createMesh(mesh);
  tile->gpuBytes = meshGpuBytes(mesh);
  tile->cpuBytes = tileCpuBytes(*tile) + tile->runs.firstIndex.size() * 3 * sizeof(std::uint32_t);
  if (tile->farRegions) {
    const TileRegions& r = *tile->farRegions;
    tile->cpuBytes +=
        r.boxes.size() * sizeof(Box) + r.codes.size() * sizeof(std::uint64_t) +
        (r.appendOrder.size() + r.positionStart.size() + r.regionOfPosition.size()) * sizeof(std::uint32_t);
  }
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
  noteMeasuredHeap();
  double t0 = clock_.nowSeconds();
  decodeArrived(frameStart);
  const double streamingMs = msSince(clock_, t0);

  t0 = clock_.nowSeconds();
  selectAndRequest(view);
  // The map after the buildings' tiles: they come first in the limit of requests in flight.
  // The map's detail follows the buildings' (the quality presets and the governor coarsen both).
  if (ground_) {
    ground_->mutableOptions().maxScreenSpaceError = options_.maxScreenSpaceError;
    ground_->update(view);
  }
  times.lod += msSince(clock_, t0);

  t0 = clock_.nowSeconds();
  counts.buildingsVisible += cull(view, items);
  countDamageInView();
  times.cull += msSince(clock_, t0);

  t0 = clock_.nowSeconds();
  animate(view, timeSeconds, counts);
  times.animate += msSince(clock_, t0);
  t0 = clock_.nowSeconds();
  enforceMemoryBudget();
  table_.trim();
  const double evictMs = msSince(clock_, t0);

  // Upload the changed rows of the building table and the whole used floor table.
  t0 = clock_.nowSeconds();
  table_.upload(device_, !animated_.empty());
  times.upload += msSince(clock_, t0) + streamingMs + evictMs;

  counts.buildingsLoaded += static_cast<std::uint32_t>(loadedBuildings());
  settled_ = selection_.complete() && decodeQueue_.empty() && responsesReady() && (!ground_ || ground_->settled());
}

void CityScene::decodeArrived(double frameStart) {
  // Decode and mesh what arrived, within the time budget (at least one tile per frame), before
  // choosing tiles: a tile decoded now lets its children be requested in this same frame. When
  // frames are slow anyway (a software renderer drawing a million triangles), the budget grows
  // with the frame interval, so loading is not held back by drawing.
  const double t0 = clock_.nowSeconds();
  const double intervalMs = lastUpdate_ ? (frameStart - *lastUpdate_) * 1000.0 : 0.0;
  lastUpdate_ = frameStart;
  const double budgetMs = std::max(options_.workBudgetMs, std::min(0.5 * intervalMs, 200.0));
  while (!decodeQueue_.empty()) {
    const std::uint32_t node = decodeQueue_.front();
    decodeQueue_.erase(decodeQueue_.begin());
    finishTile(node);
    if (msSince(clock_, t0) > budgetMs) break;
  }
}

void CityScene::selectAndRequest(const CameraView& view) {
  // LOD: which tiles to draw and to load.
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
  // The GPU tables' unused room and the heap the parts do not count (where it is measured) are
  // not the tiles' either.
  const MemoryUse use = memoryUse();
  const std::uint64_t notTiles = use.index + histories + use.tableSlack + use.otherHeap;
  selectorOptions.memoryBudgetBytes = std::max<std::uint64_t>({1, budget / 8, budget - std::min(budget, notTiles)});
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
  // and addresses for search, the inspection window and exports), with the response summary in
  // its order, within three quarters of the budget: the tiles keep a quarter, enough for the
  // root of a 2,000,000-building region and the leaves around the camera.
  index_.setMemoryAllowance(budget - budget / 4);
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
  // A failed tile the view no longer uses (nor the selection) is forgotten, its message withdrawn:
  // what is not shown has not failed; it is asked for again when wanted.
  // The same for a failed history that neither the animation nor the inspection asked for in the
  // last frame (e.g. its tile's sways turned out too small to show once its summary came).
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    TileRuntime& t = *tiles_[i];
    if (t.tile.state == TileState::Failed && t.lastUsed != frame_) loader_.forget(t.tile, tileSpec(i));
    if (t.historyLoad.state == TileState::Failed && t.historyUsed + 1 < frame_) {
      loader_.forget(t.historyLoad, historySpec(i));
    }
  }
}

std::uint32_t CityScene::cull(const CameraView& view, std::vector<DrawItem>& items) {
  // A tile's visible runs closer than this many indices (about 170 triangles) are drawn as one,
  // and a tile is drawn in at most this many runs.
  constexpr std::uint32_t kMergeGapIndices = 512;
  constexpr std::uint32_t kMaxSpansPerTile = 16;
  // Buildings smaller on screen than about a pixel are not drawn (nor counted as visible).
  const SizeCull size{view.eye(), options_.minBuildingPixels / std::max(view.pixelsPerMeterAt(1.0f), 1e-6f)};
  const Frustum& frustum = view.frustum();
  // Tile boxes first, then the buildings of partly visible tiles.
  std::uint32_t visibleBuildings = 0;
  seriesInView_ = 0;
  // Leaves' plain-prism meshes are made within a time budget (at least one a frame); until then a
  // leaf is drawn with its storeys.
  const double prismStart = clock_.nowSeconds();
  bool mayBuildPrisms = true;
  for (std::uint32_t i : selection_.draw) {
    TileRuntime& t = *tiles_[i];
    t.inView.clear();
    t.visible.clear();
    t.spans.clear();
    t.regionForm.clear();
    t.farGrid = false;
    for (auto& spans : t.blockSpans) spans.clear();
    if (!t.loaded) continue;
    const auto n = static_cast<std::uint32_t>(t.loaded->positionOf.size());
    if (frustum.classify(nodeBox(tileset_->nodes[i])) == Containment::Outside) continue;
    // What is in view is counted (the panel's totals in view), what shows on screen is drawn.
    t.loaded->tree.query(frustum, t.inView);
    const std::vector<std::uint32_t>& withSeries = t.loaded->seriesBefore;
    for (const IndexRange& r : t.inView) {
      visibleBuildings += r.end - r.begin;
      if (r.end < withSeries.size()) seriesInView_ += withSeries[r.end] - withSeries[r.begin];
    }
    if (t.loaded->data.coarse) {
      cullRegions(i, view, items);
      continue;
    }
    if (size.minAngle > 0.0f)
      t.loaded->tree.query(frustum, t.visible, size);
    else
      t.visible = t.inView;
    // A leaf none of whose buildings moves: walls as plain prisms (the same picture).
    bool prisms = false;
    if (options_.stillPrisms && t.animatedCount == 0) {
      const bool built = static_cast<bool>(t.loaded->prismMesh);
      prisms = preparePrisms(i, mayBuildPrisms);
      if (prisms && !built) mayBuildPrisms = msSince(clock_, prismStart) < 0.5 * options_.workBudgetMs;
    }
    const MeshHandle mesh = prisms ? t.loaded->prismMesh : t.loaded->mesh;
    // Only the visible buildings' triangles are drawn (in few runs): the triangles a frame draws
    // follow the view, not the tile. A tile seen whole is drawn whole.
    if (t.visible.size() == 1 && t.visible[0].begin == 0 && t.visible[0].end == n) {
      items.push_back(DrawItem{mesh, t.loaded->origin, {}});
      continue;
    }
    visibleIndexSpans(prisms ? t.loaded->prismRuns : t.loaded->runs, t.visible, kMergeGapIndices, kMaxSpansPerTile,
                      t.spans);
    if (t.spans.empty()) continue;
    items.push_back(DrawItem{mesh, t.loaded->origin, t.spans});
  }
  return visibleBuildings;
}

bool CityScene::preparePrisms(std::uint32_t node, bool mayBuild) {
  LoadedTile& tile = *tiles_[node]->loaded;
  if (tile.prismMesh) return true;
  if (tile.prismsTried || !mayBuild || tile.data.coarse) return false;
  tile.prismsTried = true;
  TileIndexRuns runs;
  const MeshData mesh = buildTileMesh(tile, tile.slotBase, &runs, {}, TileWalls::Prisms);
  // Worth a second mesh only where it saves a quarter of the triangles or more (a tile of
  // one-storey buildings has no rings to drop).
  const std::uint64_t storeyIndices = tile.runs.firstIndex.empty() ? 0 : tile.runs.firstIndex.back();
  if (mesh.indices.size() * 4 > storeyIndices * 3) return false;
  tile.prismMesh = device_.createMesh(mesh);
  if (!tile.prismMesh) return false;
  tile.prismRuns = std::move(runs);
  tile.gpuBytes += meshGpuBytes(mesh);
  tile.cpuBytes += tile.prismRuns.firstIndex.size() * 3 * sizeof(std::uint32_t);
  return true;
}

const BuildingLoss* CityScene::indexLoss(std::uint32_t node, std::uint32_t building) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded || index_.summary() == nullptr) return nullptr;
  LoadedTile& tile = *t.loaded;
  if (tile.indexPosition.empty()) {
    tile.indexPosition.assign(tile.buildingCount(), LoadedTile::kNoIndexPosition);
    for (std::uint32_t b = 0; b < tile.buildingCount(); ++b) {
      if (const auto at = index_.position(tile.data.buildings[b].attributes.id)) tile.indexPosition[b] = *at;
    }
  }
  if (building >= tile.indexPosition.size() || tile.indexPosition[building] == LoadedTile::kNoIndexPosition) {
    return nullptr;
  }
  return index_.lossAt(tile.indexPosition[building]);
}

void CityScene::countDamageInView() {
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
    mix(t.inView.size());
    for (const IndexRange& r : t.inView) mix((static_cast<std::uint64_t>(r.begin) << 32) | r.end);
  }
  mix(residencyGeneration_);
  mix(index_.summary() != nullptr ? 1 : 0);  // the view's losses come from it where tiles have none
  const bool viewChanged = viewSignature != viewSignature_;
  viewSignature_ = viewSignature;
  if (viewChanged) {
    damageInView_.fill(0);
    lossInView_.clear();
    lossInViewPending_ = false;
    viewBox_.reset();
    for (std::uint32_t i : selection_.draw) {
      const TileRuntime& t = *tiles_[i];
      if (!t.loaded) continue;
      for (const IndexRange& r : t.inView) {
        for (std::uint32_t p = r.begin; p < r.end; ++p) {
          const std::uint32_t b = t.loaded->tree.order()[p];
          if (b < t.loaded->data.buildings.size()) {
            const BuildingAttributes& a = t.loaded->data.buildings[b].attributes;
            const double x = a.centroidX + t.loaded->data.originX;
            const double y = a.centroidY + t.loaded->data.originY;
            if (!viewBox_) viewBox_ = std::array<double, 4>{x, y, x, y};
            std::array<double, 4>& box = *viewBox_;
            box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x), std::max(box[3], y)};
          }
          const DamageState d =
              t.summary && b < t.summary->buildings.size() ? t.summary->buildings[b].damage : DamageState::NoResult;
          ++damageInView_[d == DamageState::NoResult ? 5 : static_cast<std::size_t>(d)];
          if (d != DamageState::NoResult && t.summary) {
            if (b < t.summary->losses.size()) {
              lossInView_.add(t.summary->losses[b]);
            } else if (const BuildingLoss* l = indexLoss(i, b)) {
              lossInView_.add(*l);  // a tile summary without losses: the index has them
            } else if (!t.summary->odds.empty() && index_.summary() == nullptr) {
              lossInViewPending_ = true;  // it has probabilities; its losses come with the index
            }
          }
        }
      }
    }
  }
}

std::uint64_t CityScene::loadedBuildings() const {
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
  return loaded;
}

bool CityScene::responsesReady() const {
  bool ready = true;
  for (std::uint32_t i : selection_.draw) {
    if (tiles_[i]->summaryLoad.state == TileState::Loading) ready = false;
  }
  for (const auto& t : tiles_) {
    if (t->historyLoad.state == TileState::Loading) ready = false;
  }
  return ready;
}

bool CityScene::situationReportReady() const {
  if (!tileset_) return false;
  const bool consequencesSettled = !tileset_->response || !tileset_->response->consequences ||
                                   index_.consequences() != nullptr || index_.consequencesFailed();
  return index_.settled() && consequencesSettled;
}

std::optional<std::string> CityScene::situationReport() const {
  if (!situationReportReady()) return std::nullopt;
  ReportInputs inputs;
  inputs.tileset = &*tileset_;
  inputs.consequences = index_.consequences();
  inputs.buildings = index_.entries();
  inputs.summary = index_.summary();
  return situationReportHtml(inputs);
}

}  // namespace qv
