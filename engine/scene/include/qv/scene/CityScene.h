// CityScene: a prepared city streamed over HTTP and drawn with per-tile merged meshes.
//
// Each frame it selects tiles by screen-space error within a draw budget (engine::lod), requests
// what is missing (a bounded number in flight, most important first, retried with backoff on
// transient failures), decodes and meshes arrived tiles under a time budget, evicts the least
// recently used tiles beyond a memory budget, culls buildings against the frustum with each
// tile's BoxTree, and animates the buildings within the animation radius from their response
// histories, writing every floor's displacement into the GPU floor table.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "qv/anim/HistorySampling.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/Tileset.h"
#include "qv/geometry/Bounds.h"
#include "qv/geometry/OrbitCamera.h"
#include "qv/lod/TileSelector.h"
#include "qv/scene/BuildingInfo.h"
#include "qv/scene/BuildingTable.h"
#include "qv/scene/CityIndex.h"
#include "qv/scene/Fetcher.h"
#include "qv/scene/FileLoader.h"
#include "qv/scene/FrameStats.h"
#include "qv/scene/GroundScene.h"
#include "qv/scene/Map2d.h"
#include "qv/scene/RenderDevice.h"
#include "qv/scene/SceneClock.h"
#include "qv/scene/ViewConsequences.h"

namespace qv {

struct CitySceneOptions {
  float maxScreenSpaceError = 12.0f;  ///< device pixels before a coarse tile is refined
  std::uint32_t maxDrawTiles = 240;   ///< draw-call budget for city tiles
  /// Buildings whose box diagonal spans fewer device pixels than this are not drawn (0: all are).
  float minBuildingPixels = 1.0f;
  /// Far-view tiles are drawn, region by region, as merged blocks (qv/scene/TileBlocks.h) on the
  /// grid whose cells span about this many device pixels (0.71 to 1.41 times) where the region is
  /// nearest the eye, or building by building where cells that small would merge next to nothing
  /// (0: always building by building): far away the triangles follow the screen, not the city.
  float blockPixels = 4.0f;
  /// Leaves none of whose buildings is animated are drawn with plain-prism walls (TileWalls) in
  /// place of a vertex ring per floor: the same picture with a fraction of the triangles.
  bool stillPrisms = true;
  /// Tile, summary and history requests issued and not yet answered (the browser queues them
  /// over its own connections; more than its six lets a tile arrive while others are queued).
  std::uint32_t maxRequestsInFlight = 16;
  /// A request's time limit: this, plus the file's size (from the manifest) at
  /// `slowestBytesPerSecond`, doubled for each failure of the same file so far (at most 8x, and
  /// never beyond 30 minutes). A 100 KiB tile gets 20.4 s; the 64 MiB search index of a
  /// million-building city 4.6 minutes, which it needs where frames are slow (the browser reads a
  /// download on the page's thread, between frames).
  std::uint32_t requestTimeoutMs = 20000;
  std::uint32_t slowestBytesPerSecond = 256u << 10;
  /// Sway floor by floor: the buildings whose sway shows, i.e. whose peak roof displacement times
  /// the amplitude exaggeration (setSwayAmplitude) reaches `swayPixels` on screen, within
  /// `animationRadiusM` of the eye (the full-detail distance, which bounds the work), at most
  /// `maxAnimatedBuildings`, those whose sway shows most first. Every other building with a
  /// response still follows it in colour (its drift series). 0 m animates nothing.
  float animationRadiusM = 1000.0f;
  std::uint32_t maxAnimatedBuildings = 20000;
  float swayPixels = 1.0f;
  /// What the scene may hold: decoded tiles, GPU meshes, histories, the city index, the GPU tables'
  /// unused room and, where the heap is measured (setMeasuredHeapBytes), the rest of the heap
  /// beyond the engine's own memory (MemoryUse::otherHeap).
  std::uint64_t memoryBudgetBytes = 512ull << 20;
  double workBudgetMs = 12.0;  ///< decoding and meshing per frame
  /// The deployment's data origin policy: a city from an origin it does not allow is refused
  /// before any request (qv::dataOriginProblem).
  DataOriginPolicy origin;
  /// The time retries, the decode budget and frame timings are measured in; nullptr: steadyClock().
  /// Not owned; must outlive the scene.
  SceneClock* clock = nullptr;
};

/// What the scene holds against its memory budget (bytes), by part: what `memoryBytes()` sums.
struct MemoryUse {
  std::uint64_t index = 0;       ///< city index: search index and the city-wide response summary
  std::uint64_t tilesCpu = 0;    ///< decoded tiles, their drift series and response summaries, arrived files
  std::uint64_t tilesGpu = 0;    ///< the tiles' meshes on the device (outside the WASM heap in a browser)
  std::uint64_t histories = 0;   ///< decoded response histories of the animated leaves
  std::uint64_t ground = 0;      ///< the map under the city
  std::uint64_t tableSlack = 0;  ///< the GPU tables' CPU copy: room no tile or building uses now
  /// The rest of the measured heap (setMeasuredHeapBytes) beyond what it held when the scene first
  /// measured it (the engine's own memory, which comes on top of the budget): the allocator's
  /// overhead, what the parts above do not count; 0 where the heap is not measured.
  std::uint64_t otherHeap = 0;
  [[nodiscard]] std::uint64_t total() const {
    return index + tilesCpu + tilesGpu + histories + ground + tableSlack + otherHeap;
  }
};

struct TileCounts {
  std::uint32_t loaded = 0;
  std::uint32_t pending = 0;  ///< wanted by the view and not loaded yet (tiles and response tiers)
  std::uint32_t failed = 0;
  std::uint32_t drawn = 0;     ///< tiles drawn in the last frame
  bool drawLimited = false;    ///< the last selection stopped refining at the draw-call budget
  bool memoryLimited = false;  ///< the last selection stopped refining at the memory budget
};

/// Time series of one building for plots: `samples` values evenly spaced over [0, duration].
struct BuildingSeries {
  std::vector<float> roofDisplacementM;  ///< |(x, y)| of the roof
  std::vector<float> maxDriftRatio;      ///< largest inter-storey drift ratio over the storeys
  double durationSeconds = 0.0;
};

/// A building of the scene: the tile (manifest node index) and its index in that tile's file.
struct BuildingRef {
  std::uint32_t node = 0;
  std::uint32_t index = 0;
  friend bool operator==(BuildingRef, BuildingRef) = default;
};

class CityScene {
 public:
  /// Receives every error: files that failed (keyed by their URL) and problems of the city as a
  /// whole (an empty key: they stand).
  using ErrorSink = std::function<void(const LoadError&)>;

  /// Starts loading `manifestUrl` (tileset.json); tiles are resolved relative to it.
  CityScene(RenderDevice& device, Fetcher& fetcher, std::string manifestUrl, CitySceneOptions options,
            ErrorSink onError);
  /// Called with the key of an earlier error once what failed has recovered (a tile that loads
  /// after failing), so the viewer can withdraw it.
  void setResolvedSink(FileLoader::ResolvedSink sink) { loader_.setResolvedSink(std::move(sink)); }
  ~CityScene();
  CityScene(const CityScene&) = delete;
  CityScene& operator=(const CityScene&) = delete;

  /// One frame: streaming, culling, LOD, animation; appends what to draw to `items`.
  void update(const CameraView& view, double timeSeconds, FrameTimesMs& times, FrameCounts& counts,
              std::vector<DrawItem>& items);

  [[nodiscard]] bool manifestLoaded() const { return tileset_.has_value(); }
  [[nodiscard]] bool manifestFailed() const { return manifestFailed_; }
  [[nodiscard]] const Tileset* tileset() const { return tileset_ ? &*tileset_ : nullptr; }
  /// Everything the current view needs has loaded or failed (and no work is queued).
  [[nodiscard]] bool settled() const { return settled_; }
  /// Whether some loaded tile's buildings carry drift series (the response has them): every
  /// building drawn then follows its response in the current-drift colours.
  [[nodiscard]] bool hasDriftSeries() const;
  /// When the shaking first reaches the city, as far as the drift series loaded so far say (the
  /// earliest window in which a building's drift reaches a tenth of its tile's largest); nullopt
  /// before any series.
  [[nodiscard]] std::optional<double> firstShakingSeconds() const { return firstShaking_; }
  [[nodiscard]] TileCounts tileCounts() const;
  /// Length of the response histories in seconds (0 without a response).
  [[nodiscard]] double duration() const;
  /// A camera that frames the whole city.
  [[nodiscard]] CameraState overviewCamera(double fovDeg = 45.0) const;
  /// Bytes held: decoded tiles and histories (CPU) and meshes (GPU).
  [[nodiscard]] std::uint64_t memoryBytes() const { return memoryUse().total(); }
  /// The same by part.
  [[nodiscard]] MemoryUse memoryUse() const;
  /// The live heap as the platform measures it (a browser: the WASM allocator's bytes in use),
  /// after the last frame; 0: not measured. The scene then counts what its parts leave out of it
  /// (MemoryUse::otherHeap, the least over the last frames: not a passing peak) against its budget,
  /// so that the heap stays within the budget, plus the engine's own memory, however well the parts
  /// are estimated.
  void setMeasuredHeapBytes(std::uint64_t bytes) { measuredHeap_ = bytes; }
  [[nodiscard]] std::uint64_t memoryBudgetBytes() const { return options_.memoryBudgetBytes; }
  /// The last frame's choice of tiles (drawn, wanted, limits).
  [[nodiscard]] const TileSelection& tileSelection() const { return selection_; }

  // Picking, lookup and inspection.
  /// The first building a ray (city frame, any direction length) meets among the drawn tiles.
  [[nodiscard]] std::optional<BuildingRef> pick(const glm::vec3& origin, const glm::vec3& direction) const;
  /// The boxes (city frame) of every loaded building, other than `exceptId`, whose footprint box
  /// comes within `radiusM` of (x, y): the occluders Fly to steers around (qv/scene/FlyToPose.h).
  /// A building loaded in a coarse tile and its leaf gives a box from each.
  [[nodiscard]] std::vector<Box> buildingBoxesNear(double x, double y, double radiusM, std::string_view exceptId) const;
  /// The best loaded copy of a building: its leaf when loaded, else a coarse tile holding it.
  [[nodiscard]] std::optional<BuildingRef> find(std::string_view id) const;
  [[nodiscard]] std::optional<BuildingInfo> info(BuildingRef ref) const;
  /// Highlights the building with this id wherever it is loaded ("" clears) and loads its leaf
  /// (full attributes, history) if needed, found through the search index when no loaded tile
  /// holds it. False (nothing changes) for an id neither a loaded tile nor the index knows.
  bool select(const std::string& id);
  /// The building's entry in the search index (nullptr while the index is not loaded or without it).
  [[nodiscard]] const SearchEntry* indexEntry(std::string_view id) const;
  [[nodiscard]] const std::string& selected() const { return selected_; }
  /// The selected building's motion over the whole record, once its history is loaded.
  [[nodiscard]] std::optional<BuildingSeries> selectionSeries(std::size_t samples);

  // Filters, search and lists: city-wide, from the search index (and the response's summary in
  // its order), which loads once the first view has; until then they are empty.
  void setFilters(const BuildingFilters& filters);
  [[nodiscard]] const BuildingFilters& filters() const { return filters_; }
  /// Which kinds of building are drawn (and pickable): LOD1 extrusions, LOD2 detailed models.
  /// With LOD2 off, LOD2 buildings are drawn (and picked) as their LOD1 extrusions, shown or
  /// hidden with the LOD1 buildings.
  void setLodVisibility(bool lod1, bool lod2);
  /// The exaggeration the displacements are drawn with (Viewer::amplitude): which sways show
  /// (CitySceneOptions::swayPixels). Non-finite or non-positive values count as 1.
  void setSwayAmplitude(float amplitude) {
    swayAmplitude_ = std::isfinite(amplitude) && amplitude > 0.0f ? amplitude : 1.0f;
  }
  [[nodiscard]] bool showLod1() const { return showLod1_; }
  [[nodiscard]] bool showLod2() const { return showLod2_; }
  /// Buildings whose id, name or address contain every word of `query` (the search index is
  /// requested on first use; until it arrives nothing matches). At most `limit`, index order.
  [[nodiscard]] std::vector<BuildingListEntry> search(std::string_view query, std::size_t limit);
  /// Buildings passing the filters, most damaged first (then by peak drift), at most `limit`;
  /// `total` receives how many pass in all.
  [[nodiscard]] std::vector<BuildingListEntry> filteredList(std::size_t limit, std::size_t* total = nullptr);
  /// The buildings marked on the map: with a facility filter on (critical facilities or facility
  /// categories) those it keeps, at most kMaxMarkedBuildings, most likely damaged first; else
  /// none. Made again only when the filters or the city index change.
  const std::vector<BuildingListEntry>& markedBuildings();
  static constexpr std::size_t kMaxMarkedBuildings = 2000;
  /// Appends the markers of markedBuildings() and of the selected building (MapMarker: discs of
  /// 7 and 10 CSS pixels at their roofs, coloured by P(damage >= moderate) on the drift ramp, or by
  /// the damage state without probabilities) to `out`; `pixelRatio`: framebuffer pixels per CSS
  /// pixel.
  void mapMarkers(float pixelRatio, std::vector<MapMarker>& out);
  /// The selected building's list row (for its marker and label), nullopt without a selection or
  /// before the city index has it.
  [[nodiscard]] const std::optional<BuildingListEntry>& selectedListEntry();
  /// How many buildings of each use the city has, most first (CityIndex::useCounts).
  [[nodiscard]] std::vector<std::pair<std::string, std::size_t>> useCounts() const { return index_.useCounts(); }
  [[nodiscard]] bool searchIndexLoaded() const { return index_.loaded(); }
  /// Why the search index or the city-wide response is not loaded for memory ("" when both fit
  /// the budget; CityIndex::memoryNotice).
  [[nodiscard]] const std::string& cityIndexNotice() const { return index_.memoryNotice(); }
  /// The search index (and the response summary in its order) has loaded, failed or been left out
  /// for memory, or the city has none.
  [[nodiscard]] bool searchIndexSettled() const;
  /// Damage states (none .. complete, no result) of the buildings in view, from the last frame.
  [[nodiscard]] const std::array<std::uint64_t, 6>& damageInView() const { return damageInView_; }
  /// The consequences of the buildings in view (expected values and a normal-approximation 90 %
  /// interval, qv/scene/ViewConsequences.h); zeros without HAZUS results.
  [[nodiscard]] seismic::LossTotals consequencesInView() const { return lossInView_.totals(); }
  /// False while a building in view has a result whose losses are still on their way (tile
  /// summaries without LOSS take them from the city index's summary, which loads after the index):
  /// consequencesInView() then leaves it out, and callers say the view's totals are loading.
  [[nodiscard]] bool consequencesInViewComplete() const { return !lossInViewPending_; }
  /// The box (city frame, metres: min x, min y, max x, max y) around the footprint centres of the
  /// buildings damageInView counts, from the last frame; nullopt when none is in view.
  [[nodiscard]] const std::optional<std::array<double, 4>>& viewBox() const { return viewBox_; }
  /// The city's and districts' totals (the response's consequences.json) once loaded; nullptr before,
  /// after a failure (consequencesFailed) and for responses without them.
  [[nodiscard]] const seismic::ConsequenceTotals* consequences() const { return index_.consequences(); }
  [[nodiscard]] bool consequencesFailed() const { return index_.consequencesFailed(); }
  /// The 2D map's shapes (qv/scene/Map2d.h) of the buildings the last frame culled in view (its
  /// `view`, whose pixels are `cssPerPixel` CSS pixels), coloured in `mode` at scene time `t`.
  void map2d(const CameraView& view, double cssPerPixel, ColorMode mode, double t, Map2dFrame& out) const;
  /// The situation report (qv/scene/Report.h) from the city's files, as `quakeview-prep report`
  /// makes it; nullopt while the search index, its response summary or the consequence totals are
  /// still on their way (a file that failed is left out, and the report says what is missing).
  [[nodiscard]] std::optional<std::string> situationReport() const;
  /// Whether situationReport() has its files (cheap: for a button's state).
  [[nodiscard]] bool situationReportReady() const;
  /// The record suite's spread over the city (CityIndex::medianDriftBeta).
  [[nodiscard]] std::optional<float> suiteDriftSpread() const { return index_.medianDriftBeta(); }

  /// The map under the city (streets, water, parks, names): nullptr when the city has no ground
  /// layer or its input had no such features (Tileset::ground says which).
  [[nodiscard]] const GroundScene* ground() const { return ground_.get(); }
  /// The last frame's ground meshes to draw (FrameUniforms::groundItems).
  [[nodiscard]] std::span<const GroundDrawItem> groundItems() const {
    return ground_ ? ground_->items() : std::span<const GroundDrawItem>{};
  }

  [[nodiscard]] const CitySceneOptions& options() const { return options_; }
  CitySceneOptions& mutableOptions() { return options_; }

 private:
  struct LoadedTile;
  struct TileRuntime;
  struct BlockLevelRuntime;
  struct Animated;

  void onManifest(FetchResponse response);
  void reportCityError(std::string message);
  [[nodiscard]] FileSpec tileSpec(std::uint32_t node) const;
  [[nodiscard]] FileSpec summarySpec(std::uint32_t node) const;
  [[nodiscard]] FileSpec historySpec(std::uint32_t node) const;
  void request(std::uint32_t node);     // the tile (when due) and its summary
  void finishTile(std::uint32_t node);  // decode + mesh (time-budgeted)
  void evict(std::uint32_t node);
  /// Gives back a loaded tile's meshes (its buildings', its plain prisms', its block levels').
  void destroyMeshes(LoadedTile& tile);
  /// After animated_ changed order: each tile's building -> entry map.
  void reindexAnimated();
  void markNoResult(std::uint32_t node);  // its summary failed: hatch its buildings
  void requestSummary(std::uint32_t node);
  void requestHistory(std::uint32_t node);
  void applySummary(std::uint32_t node);
  /// The losses of building `building` of tile `node` from the city index's summary (for tile
  /// summaries without LOSS), nullptr until the index has them.
  const BuildingLoss* indexLoss(std::uint32_t node, std::uint32_t building);
  /// Its buildings' drift series into the series table and their rows (once per loaded tile).
  void applySeries(std::uint32_t node);
  /// The blocks' drift series of one block level from its members' rows (after their rows).
  void refreshBlockSeries(BlockLevelRuntime& blocks, std::span<const BuildingGpuRecord> buildingRows);
  /// Gives back the series samples of a loaded tile and its block levels.
  void releaseSeries(LoadedTile& tile);
  void enforceMemoryBudget();           // evicts what this frame did not use, least recently used first
  void applyFlags(std::uint32_t node);  // selection and filter bits of one tile's rows
  void applyFlagsEverywhere();
  void refreshBlockRows(std::uint32_t node);  // block rows from the tile's building rows
  /// The block level a far-view tile's part in `box` is drawn at from `view` (made now if
  /// needed), or -1: building by building.
  int blockLevelFor(std::uint32_t node, const Box& box, const CameraView& view, int maxLevel);
  void cullRegions(std::uint32_t node, const CameraView& view, std::vector<DrawItem>& items);
  /// Whether the leaf's plain-prism mesh is there to draw (made now when `mayBuild` and worth it).
  bool preparePrisms(std::uint32_t node, bool mayBuild);
  /// The building a ray picks in a tile drawn as `blocks` (nearer than `best`, which it lowers).
  std::optional<std::uint32_t> pickInBlocks(const TileRuntime& t, int level, const glm::vec3& origin,
                                            const glm::vec3& direction, float& best) const;
  // The steps of a frame (update), in order.
  void decodeArrived(double frameStart);                                     // decode and mesh within the work budget
  void selectAndRequest(const CameraView& view);                             // choose tiles; request, retry
  std::uint32_t cull(const CameraView& view, std::vector<DrawItem>& items);  // visible buildings
  void countDamageInView();                                                  // when the visible sets changed
  [[nodiscard]] std::uint64_t loadedBuildings() const;
  [[nodiscard]] bool responsesReady() const;  // no summary of a drawn tile, no history on its way
  void animate(const CameraView& view, double timeSeconds, FrameCounts& counts);
  /// Chooses the animated buildings (nearest first, up to the cap) among the visible buildings of
  /// `tiles` (within the radius, histories loaded), keeping the floor rows of those that stay.
  void chooseAnimated(const CameraView& view, const std::vector<std::uint32_t>& tiles);
  /// The drawn leaves within the radius whose histories are loaded (requesting the others) into
  /// animationTiles_; returns the signature of what the choice of animated buildings depends on.
  std::uint64_t findAnimationTiles(const CameraView& view);
  struct AnimationCandidate {
    float swayPixels;  // peak roof displacement × amplitude on screen at its distance
    std::uint32_t node, index, position;
  };
  /// Visible buildings of `tiles` within the radius whose sway reaches options_.swayPixels, those
  /// whose sway shows most first, up to the cap.
  [[nodiscard]] std::vector<AnimationCandidate> animationCandidates(const CameraView& view,
                                                                    const std::vector<std::uint32_t>& tiles) const;
  /// Makes `candidates` the animated buildings: keeps the floor rows of those that stay.
  void keepAnimated(const std::vector<AnimationCandidate>& candidates);
  /// What the sampling loop reads, packed in animation order.
  void packSamplers();
  /// Every animated building's floor rows at this time.
  void sampleFloors(double timeSeconds);

  RenderDevice& device_;
  Fetcher& fetcher_;
  std::string manifestUrl_;
  CitySceneOptions options_;
  float swayAmplitude_ = 1.0f;
  ErrorSink onError_;
  Fetcher::RequestId manifestRequest_ = 0;
  std::optional<Tileset> tileset_;
  bool manifestFailed_ = false;
  bool settled_ = false;
  std::vector<std::unique_ptr<TileRuntime>> tiles_;
  std::vector<TileState> states_;  // the tiles' states as the selector reads them (copied each frame)
  std::vector<std::uint32_t> decodeQueue_;
  std::uint64_t frame_ = 0;
  SceneClock& clock_;
  FileLoader loader_;                    // every file after the manifest, and the in-flight limit
  CityIndex index_;                      // the search index and the response summary in its order
  std::unique_ptr<GroundScene> ground_;  // after loader_: its loads are cancelled first
  std::optional<double> lastUpdate_;     // the previous frame's start, seconds
  TileSelection selection_;
  /// Per node, the bytes it holds once loaded (tile data, mesh, summary): measured when it last
  /// loaded, else estimated from its file size at the ratio measured so far for its kind (coarse
  /// or leaf). The selector keeps the tiles drawn and wanted within the budget with these.
  std::vector<std::uint64_t> nodeBytes_;
  std::unique_ptr<bool[]> wasLoaded_;         // per node: loaded at some time (a span needs contiguous bools)
  std::uint64_t residentOfFile_[2] = {0, 0};  // [leaf, coarse]: resident bytes of the tiles loaded so far
  std::uint64_t fileOfResident_[2] = {0, 0};  // their file bytes
  void updateNodeBytes();
  std::uint64_t measuredHeap_ = 0;
  std::array<std::uint64_t, 16> otherHeapRecent_{};  // otherHeap measured in the last frames
  std::uint64_t otherHeapSamples_ = 0;
  std::optional<std::uint64_t> heapBaseline_;                       // the heap not counted when first measured
  std::uint64_t otherHeap_ = 0;                                     // their least
  void noteMeasuredHeap();                                          // at the start of a frame
  [[nodiscard]] std::uint64_t tileBytes(std::uint32_t node) const;  // a loaded tile's resident bytes

  // GPU tables and their CPU mirrors.
  BuildingTable table_{BuildingTable::kMaxBuildingRows, BuildingTable::kMaxFloorRows, device_.maxSeriesSamples()};
  std::vector<std::unique_ptr<Animated>> animated_;
  /// What sampling one animated building needs, packed when the buildings are chosen (the
  /// pointers stay valid until the next choice: any change of residency triggers one first).
  struct AnimatedSampler {
    HistoryStream stream;           // its scales point into samplerArena_
    std::uint32_t arenaOffset = 0;  // scales x, shapes x, scales y, shapes y in samplerArena_
    std::uint16_t floors = 0;
  };
  std::vector<SampleWindow> windows_;      // of animated_, same order
  std::vector<AnimatedSampler> samplers_;  // of animated_, same order
  std::vector<float> samplerArena_;
  std::vector<BuildingListEntry> marked_;  // markedBuildings(), for markedFilters_ and markedIndexBytes_
  BuildingFilters markedFilters_;
  std::uint64_t markedIndexBytes_ = UINT64_MAX;
  std::string markedSelection_;  // the selection's list entry, for its marker
  std::optional<BuildingListEntry> markedSelectionEntry_;
  std::uint64_t markedSelectionIndexBytes_ = UINT64_MAX;
  std::optional<double> firstShaking_;         // firstShakingSeconds()
  std::uint32_t seriesInView_ = 0;             // buildings in view with a drift series (cull)
  std::uint32_t modelsAnimated_ = 0;           // of animated_, LOD2 models drawn skinned
  std::vector<float> modal_;                   // per animated building: 8 x then 8 y modal coordinates this frame
  std::vector<std::uint32_t> animationTiles_;  // this frame's tiles within the radius, histories loaded
  std::uint64_t animationSignature_ = 0;       // inputs of the last choice of animated buildings
  std::uint64_t choice_ = 0;                   // counts the choices
  std::uint64_t residencyGeneration_ = 0;      // bumped when a tile or a history arrives or leaves

  std::string selected_;
  std::vector<std::uint32_t> detailWanted_;  // leaves to load for the selection
  BuildingFilters filters_;
  bool showLod1_ = true;
  bool showLod2_ = true;
  [[nodiscard]] bool hiddenByLod(std::uint8_t lod) const;
  std::array<std::uint64_t, 6> damageInView_{};
  std::optional<std::array<double, 4>> viewBox_;
  ConsequenceSums lossInView_;
  bool lossInViewPending_ = false;   // a building in view awaits its losses from the index
  std::uint64_t viewSignature_ = 0;  // visible sets and summaries behind damageInView_
  std::string seriesFor_;
  std::optional<BuildingSeries> series_;
};

}  // namespace qv
