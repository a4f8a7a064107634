#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>
#include <set>

#include "MiniCity.h"
#include "qv/anim/SeriesSampling.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/scene/Viewer.h"

using namespace qv;
using test::FakeFetcher;
using test::MiniCity;

namespace {

// A device that keeps what it is sent, so tests can look at the GPU tables.
class RecordingDevice final : public RenderDevice {
 public:
  std::map<std::uint32_t, BuildingGpuRecord> buildings;  // slot -> row
  std::vector<FloorGpuRecord> floors;
  std::vector<std::uint8_t> series;
  std::vector<MapMarker> markers;                                           // the last frame's
  std::map<std::uint32_t, std::map<std::uint32_t, glm::vec2>> slotCentres;  // mesh -> slot -> local centre
  // mesh -> slot -> vertex counts: plain, LOD2 model, LOD1 fallback of a model
  std::map<std::uint32_t, std::map<std::uint32_t, std::array<int, 3>>> slotVertices;
  bool showModels = true;  // the last frame's FrameUniforms::showModels
  std::vector<DrawItem> lastItems;
  std::map<std::uint32_t, std::vector<std::uint32_t>> triangleSlots;  // mesh -> slot of each triangle
  NullRenderDevice counter;

  MeshHandle createMesh(const MeshData& mesh) override {
    const MeshHandle h = counter.createMesh(mesh);
    // Per slot: the centre of what is drawn with LOD2 models shown, and the vertex counts of its
    // plain, model (kKindModel) and fallback (kKindFallback) geometry, which the shader chooses between.
    std::map<std::uint32_t, std::pair<glm::vec2, int>> acc;
    for (const BuildingVertex& v : mesh.vertices) {
      auto& counts = slotVertices[h.id][v.slot];
      if ((v.kind & kKindFallback) != 0) {
        ++counts[2];
        continue;
      }
      ++counts[(v.kind & kKindModel) != 0 ? 1 : 0];
      auto& a = acc[v.slot];
      a.first += glm::vec2(v.x, v.y);
      a.second += 1;
    }
    for (const auto& [slot, a] : acc) slotCentres[h.id][slot] = a.first / static_cast<float>(a.second);
    auto& slots = triangleSlots[h.id];
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) slots.push_back(mesh.vertices[mesh.indices[i]].slot);
    return h;
  }
  void destroyMesh(MeshHandle m) override {
    counter.destroyMesh(m);
    slotCentres.erase(m.id);
    triangleSlots.erase(m.id);
  }
  /// Whether the item draws any triangle of `slot` (its spans, or the whole mesh).
  bool draws(const DrawItem& item, std::uint32_t slot) const {
    if (item.spans.empty()) return true;
    const auto& slots = triangleSlots.at(item.mesh.id);
    for (const IndexSpan& span : item.spans) {
      for (std::uint32_t t = span.firstIndex / 3; t < (span.firstIndex + span.indexCount) / 3; ++t) {
        if (slots[t] == slot) return true;
      }
    }
    return false;
  }
  std::size_t meshTriangles(MeshHandle m) const override { return counter.meshTriangles(m); }
  void writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> r) override {
    counter.writeBuildings(first, r);
    for (std::size_t i = 0; i < r.size(); ++i) buildings[first + static_cast<std::uint32_t>(i)] = r[i];
  }
  void writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> r) override {
    counter.writeFloors(first, r);
    if (floors.size() < first + r.size()) floors.resize(first + r.size());
    std::copy(r.begin(), r.end(), floors.begin() + static_cast<std::ptrdiff_t>(first));
  }
  void writeSeries(std::uint32_t first, std::span<const std::uint8_t> c) override {
    counter.writeSeries(first, c);
    if (series.size() < first + c.size()) series.resize(first + c.size());
    std::copy(c.begin(), c.end(), series.begin() + static_cast<std::ptrdiff_t>(first));
  }
  void render(const FrameUniforms& u, std::span<const DrawItem> items) override {
    counter.render(u, items);
    lastItems.assign(items.begin(), items.end());
    showModels = u.showModels;
    markers.assign(u.markers.begin(), u.markers.end());
  }
  DeviceFrameStats lastFrameStats() const override { return counter.lastFrameStats(); }
  std::size_t gpuBytes() const override { return counter.gpuBytes(); }

  /// Vertices drawn for the building whose centre is at `world` (within 0.5 m), 0 when none.
  int verticesAt(glm::vec2 world) const {
    for (const DrawItem& item : lastItems) {
      const auto it = slotCentres.find(item.mesh.id);
      if (it == slotCentres.end()) continue;
      for (const auto& [slot, c] : it->second) {
        const glm::vec2 d = c + glm::vec2(item.origin.x, item.origin.y) - world;
        if (d.x * d.x + d.y * d.y < 0.25f && draws(item, slot)) {
          const auto& counts = slotVertices.at(item.mesh.id).at(slot);
          return counts[0] + (showModels ? counts[1] : counts[2]);
        }
      }
    }
    return 0;
  }

  /// World centre of every drawn slot.
  std::map<std::uint32_t, glm::vec2> drawnSlots() const {
    std::map<std::uint32_t, glm::vec2> out;
    for (const DrawItem& item : lastItems) {
      const auto it = slotCentres.find(item.mesh.id);
      if (it == slotCentres.end()) continue;
      for (const auto& [slot, c] : it->second) {
        if (draws(item, slot)) out[slot] = c + glm::vec2(item.origin.x, item.origin.y);
      }
    }
    return out;
  }
};

void runFrames(Viewer& viewer, int frames, double dt = 1.0 / 60.0) {
  for (int i = 0; i < frames; ++i) viewer.frame(dt);
}

// Runs frames 50 ms apart on the scene's fake clock (retries wait on it) until `done` or
// `limitSeconds` of that clock pass.
template <typename Done>
void runFramesUntil(Viewer& viewer, FakeClock& clock, double limitSeconds, Done done) {
  const double start = clock.nowSeconds();
  while (!done() && clock.nowSeconds() - start < limitSeconds) {
    viewer.frame(1.0 / 60.0);
    clock.advance(0.05);
  }
}

// A MiniCity served by a fake fetcher, and a viewer with a recording device to open it in.
struct SceneRig {
  MiniCity city;
  FakeFetcher fetcher;
  RecordingDevice device;
  FakeClock clock;  // the scene's time: only runFramesUntil moves it
  Viewer viewer{device};
  explicit SceneRig(MiniCity c = MiniCity()) : city(std::move(c)) { city.serve(fetcher); }
  /// Opens the city in a 1280 x 720 viewport, animating within `animationRadiusM` of the eye
  /// (every building there: swayPixels 0, unless `options` says otherwise).
  void open(float animationRadiusM, CitySceneOptions options = {}, bool everySway = true) {
    options.animationRadiusM = animationRadiusM;
    if (everySway) options.swayPixels = 0.0f;
    options.clock = &clock;
    viewer.openCity("city/tileset.json", fetcher, options);
    viewer.setViewport(1280, 720, 1280.0, 720.0);
  }
};

// Opens the city animating within 1 km (every sway when `everySway`, else those reaching a pixel),
// paused, settled, looking at its centre from 500 m.
Viewer& openPausedAtCentre(SceneRig& rig, bool everySway) {
  rig.open(1000.0f, CitySceneOptions{}, everySway);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 500.0, 0.0, 60.0, 45.0});
  viewer.pause();
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  return viewer;
}

// The grid cell (i, j) whose building has its centre at `world`.
std::pair<int, int> cellOf(glm::vec2 world) {
  const int i = static_cast<int>(std::lround(world.x / 40.0 - 0.5 + MiniCity::kSide / 2));
  const int j = static_cast<int>(std::lround(world.y / 40.0 - 0.5 + MiniCity::kSide / 2));
  return {i, j};
}

}  // namespace

TEST_CASE("A streamed city loads coarse tiles first and refines where the camera needs detail", "[scene][city]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  // Far away: the coarse root suffices.
  viewer.setCamera(CameraState{0.0, 0.0, 6000.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 5);
  REQUIRE(viewer.city()->manifestLoaded());
  CHECK(viewer.settled());
  CHECK(rig.fetcher.count("city/tiles/0-0-0.qvt") == 1);
  CHECK(rig.fetcher.count("city/tiles/1-0-0.qvt") == 0);
  CHECK(rig.device.lastItems.size() == 1);
  CHECK(viewer.stats().latest.buildingsLoaded == 64);
  CHECK(viewer.stats().latest.buildingsVisible == 64);
  const auto tiles = viewer.city()->tileCounts();
  CHECK(tiles.loaded == 1);

  // Close to the south-west quadrant: its leaf replaces the root there; the rest stays coarse
  // until its leaves arrive, and the drawn set never overlaps.
  viewer.setCamera(CameraState{-80.0, -80.0, 150.0, 0.0, 45.0, 45.0});
  viewer.frame(1.0 / 60.0);
  CHECK_FALSE(viewer.settled());
  runFrames(viewer, 10);
  CHECK(viewer.settled());
  CHECK(rig.fetcher.count("city/tiles/1-0-0.qvt") == 1);
  CHECK(viewer.city()->tileCounts().loaded >= 2);
  // Every building drawn at most once.
  const auto drawn = rig.device.drawnSlots();
  std::set<std::pair<int, int>> cells;
  for (const auto& [slot, centre] : drawn) {
    CHECK(cells.insert(cellOf(centre)).second);
  }
  // The summary tier colours the buildings: damage states from the response.
  int withDamage = 0;
  for (const auto& [slot, row] : rig.device.buildings) withDamage += row.damageState >= 0.0f ? 1 : 0;
  CHECK(withDamage > 0);
}

TEST_CASE("Only the visible buildings' triangles are drawn: a narrow view draws a part of its tiles",
          "[scene][city][spans]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  // Close to the south-west corner, looking north-east over a few buildings with a narrow lens.
  viewer.setCamera(CameraState{-140.0, -140.0, 60.0, 45.0, 20.0, 25.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  const auto& latest = viewer.stats().latest;
  const auto drawn = rig.device.drawnSlots();
  std::uint64_t wholeTiles = 0;
  for (const DrawItem& item : rig.device.lastItems) wholeTiles += rig.device.meshTriangles(item.mesh);
  REQUIRE(latest.buildingsVisible > 0);
  CHECK(latest.buildingsVisible < latest.buildingsLoaded);
  // Every visible building is drawn; a few neighbours may come along in a merged run, not the tile.
  CHECK(drawn.size() >= latest.buildingsVisible);
  CHECK(drawn.size() < latest.buildingsLoaded);
  CHECK(latest.triangles < wholeTiles);
  CHECK(latest.triangles > 0);
  // From far away the whole city is in view: whole tiles, every building.
  viewer.setCamera(CameraState{0.0, 0.0, 6000.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 20);
  CHECK(rig.device.drawnSlots().size() == viewer.stats().latest.buildingsVisible);
  CHECK(viewer.stats().latest.buildingsVisible == 64);
}

TEST_CASE("Far away a far-view tile is drawn as blocks: a box per cell, its worst member's colour, picking a building",
          "[scene][city][blocks]") {
  SceneRig rig;
  CitySceneOptions options;
  options.blockPixels = 60.0f;  // cells up to 60 px: blocks already 6 km away from this small city
  rig.open(0.0f, options);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 6000.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  const auto& latest = viewer.stats().latest;
  CHECK(latest.buildingsVisible == 64);  // every building still counts as in view
  // 320 m of city on 256 m cells aligned to the origin: 2 x 2 blocks, 10 triangles each.
  const auto drawn = rig.device.drawnSlots();
  REQUIRE(drawn.size() == 4);
  CHECK(latest.triangles == 40 + 2);  // and the ground's two
  // Each quadrant holds damage states 0 .. 4: each block shows the worst, complete damage.
  for (const auto& [slot, centre] : drawn) {
    CAPTURE(slot);
    REQUIRE(rig.device.buildings.count(slot) == 1);
    CHECK(rig.device.buildings.at(slot).damageState == 4.0f);
    CHECK(rig.device.buildings.at(slot).floorBase == -1.0f);
  }
  // A click on a building's roof answers with that building, not a block.
  const double x = MiniCity::centreX(2), y = MiniCity::centreY(5);
  const auto screen = viewer.worldToScreen(x, y, MiniCity::kStoreys * MiniCity::kStoreyHeight * 0.99);
  REQUIRE(screen.has_value());
  const auto picked = viewer.pick(screen->x, screen->y);
  REQUIRE(picked.has_value());
  CHECK(picked->attributes.id == MiniCity::idOf(2, 5));
  // Its far-view copy has no name; the city index gives it while its leaf is on its way.
  CHECK_FALSE(picked->detailed);
  CHECK(picked->attributes.name == "Building 2-5");
  // Selecting it marks its block, and a filter that only it passes keeps its block undimmed.
  viewer.city()->select(MiniCity::idOf(2, 5));
  runFrames(viewer, 2);
  int selectedBlocks = 0;
  for (const auto& [slot, centre] : rig.device.drawnSlots())
    selectedBlocks += (static_cast<unsigned>(rig.device.buildings.at(slot).flags) & kFlagSelected) != 0 ? 1 : 0;
  CHECK(selectedBlocks == 1);
  // Close by, building by building again.
  viewer.city()->select("");
  viewer.setCamera(CameraState{0.0, 0.0, 600.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 20);
  CHECK(rig.device.drawnSlots().size() == viewer.stats().latest.buildingsVisible);
}

TEST_CASE("The buildings whose sway shows on screen move floor by floor, most visible first", "[scene][city][anim]") {
  SceneRig rig;
  Viewer& viewer = openPausedAtCentre(rig, false);  // the default: a sway of a pixel
  REQUIRE(viewer.stats().latest.buildingsVisible == 64);
  // True scale: the test city's sways (5 to 15 cm) are under a pixel from 500 m: none is moved.
  CHECK(viewer.stats().latest.buildingsAnimated == 0);

  // The sway of each drawn building on screen, exaggerated by `amplitude`, and whether it moves.
  auto sways = [&](float amplitude) {
    const CameraView view(viewer.camera(), 1280, 720);
    std::vector<std::pair<float, bool>> out;
    for (const auto& [slot, centre] : rig.device.drawnSlots()) {
      const auto [i, j] = cellOf(centre);
      const glm::vec3 axis(static_cast<float>(MiniCity::centreX(i)), static_cast<float>(MiniCity::centreY(j)),
                           0.5f * MiniCity::kStoreys * MiniCity::kStoreyHeight);
      const float pixels = static_cast<float>(MiniCity::amplitude(i, j)) * amplitude *
                           view.pixelsPerMeterAt(glm::length(axis - view.eye()));
      out.emplace_back(pixels, rig.device.buildings.at(slot).floorBase >= 0.0f);
    }
    return out;
  };
  // Exaggerated 50 times every sway shows (4 to 13 pixels): all 64 move.
  viewer.setAmplitude(50.0f);
  runFrames(viewer, 20);
  CHECK(viewer.stats().latest.buildingsAnimated == 64);
  // Exaggerated 8 times, only the larger sways reach a pixel: exactly those move.
  viewer.setAmplitude(8.0f);
  runFrames(viewer, 20);
  int moving = 0;
  for (const auto& [pixels, moves] : sways(8.0f)) {
    INFO("sway " << pixels << " px");
    if (std::abs(pixels - 1.0f) > 0.02f) CHECK(moves == (pixels >= 1.0f));
    moving += moves ? 1 : 0;
  }
  CHECK(moving > 0);
  CHECK(moving < 64);
  CHECK(static_cast<int>(viewer.stats().latest.buildingsAnimated) == moving);
  // With a cap, the most visible sways are the ones kept.
  viewer.setAmplitude(50.0f);
  viewer.city()->mutableOptions().maxAnimatedBuildings = 10;
  runFrames(viewer, 20);
  float slowestMoving = 1e9f, fastestStill = 0.0f;
  moving = 0;
  for (const auto& [pixels, moves] : sways(50.0f)) {
    if (moves) {
      slowestMoving = std::min(slowestMoving, pixels);
      ++moving;
    } else {
      fastestStill = std::max(fastestStill, pixels);
    }
  }
  CHECK(moving == 10);
  CHECK(slowestMoving >= fastestStill * 0.999f);
}

TEST_CASE("Each animated building moves by its own history", "[scene][city][anim]") {
  SceneRig rig;
  Viewer& viewer = openPausedAtCentre(rig, true);
  CHECK(viewer.stats().latest.buildingsAnimated == 64);
  CHECK(viewer.duration() == 10.0);

  // Forward jumps, a jump back, small steps (the animator reuses the samples it already has) and
  // the end of the history (where the samples clamp).
  for (double t : {0.37, 2.5, 7.91, 1.2, 1.21, 1.23, 1.26, 9.99}) {
    REQUIRE(viewer.setTime(t));
    viewer.frame(1.0 / 60.0);
    std::set<long> distinct;
    int checked = 0;
    for (const auto& [slot, centre] : rig.device.drawnSlots()) {
      const BuildingGpuRecord& row = rig.device.buildings.at(slot);
      REQUIRE(row.floorBase >= 0.0f);
      const auto [i, j] = cellOf(centre);
      const auto base = static_cast<std::size_t>(row.floorBase);
      const double expectedRoof = MiniCity::roofX(i, j, t);
      // Linear interpolation of 50 Hz samples and 16-bit quantization: well within 2 %.
      CHECK(rig.device.floors[base + MiniCity::kStoreys].dxMeters ==
            Approx(expectedRoof).margin(0.02 * MiniCity::amplitude(i, j)));
      CHECK(rig.device.floors[base].dxMeters == 0.0f);  // the ground does not move relative to itself
      CHECK(rig.device.floors[base + 2].dxMeters ==
            Approx(expectedRoof * 2.0 / 5.0).margin(0.02 * MiniCity::amplitude(i, j)));
      CHECK(rig.device.floors[base + 1].peakDriftAbove > 0.0f);
      distinct.insert(std::lround(rig.device.floors[base + MiniCity::kStoreys].dxMeters * 1e5));
      ++checked;
    }
    CHECK(checked == 64);
    CHECK(distinct.size() > 50);  // buildings do not move in lockstep
  }

  // Paused: the displacements stay as they are from frame to frame.
  const auto before = rig.device.floors;
  runFrames(viewer, 3);
  CHECK(rig.device.floors.size() == before.size());
  for (std::size_t k = 0; k < before.size(); ++k) CHECK(rig.device.floors[k].dxMeters == before[k].dxMeters);

  // Outside the radius nothing animates, and rows are released.
  auto drawnSlotSet = [&rig] {
    std::set<std::uint32_t> slots;
    for (const auto& [slot, centre] : rig.device.drawnSlots()) slots.insert(slot);
    return slots;
  };
  const auto animatedSlots = drawnSlotSet();
  const std::uint64_t animatedTriangles = viewer.stats().latest.triangles;
  CitySceneOptions& live = viewer.city()->mutableOptions();
  live.animationRadiusM = 0.0f;
  viewer.frame(1.0 / 60.0);
  CHECK(viewer.stats().latest.buildingsAnimated == 0);
  for (const auto& [slot, centre] : rig.device.drawnSlots()) CHECK(rig.device.buildings.at(slot).floorBase == -1.0f);
  // Still, the same buildings are drawn with plain walls (no ring per floor): far fewer triangles.
  viewer.frame(1.0 / 60.0);
  CHECK(drawnSlotSet() == animatedSlots);
  CHECK(viewer.stats().latest.triangles * 2 < animatedTriangles);
  // Moving again, with their storeys.
  live.animationRadiusM = 1000.0f;
  runFrames(viewer, 3);
  CHECK(viewer.stats().latest.buildingsAnimated == 64);
  CHECK(drawnSlotSet() == animatedSlots);
  CHECK(viewer.stats().latest.triangles == animatedTriangles);
  // Unless told to keep the storeys (CitySceneOptions::stillPrisms).
  live.animationRadiusM = 0.0f;
  live.stillPrisms = false;
  runFrames(viewer, 2);
  CHECK(viewer.stats().latest.triangles == animatedTriangles);
}

TEST_CASE("A corrupt tile and a missing tile are reported while the rest renders", "[scene][city][errors]") {
  SceneRig rig;
  rig.fetcher.files["city/tiles/1-1-0.qvt"][100] ^= 0xFF;  // corrupt
  rig.fetcher.files.erase("city/tiles/1-0-1.qvt");         // missing
  rig.open(1000.0f);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 500.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 20);
  CHECK(viewer.settled());
  const auto& errors = viewer.errors();
  REQUIRE(errors.size() >= 2);
  bool corrupt = false, missing = false;
  for (const std::string& e : errors) {
    if (e.find("Tile 1/1/0 failed") != std::string::npos && e.find("truncated, corrupt or stale") != std::string::npos)
      corrupt = true;
    if (e.find("Tile 1/0/1 failed") != std::string::npos && e.find("HTTP 404") != std::string::npos) missing = true;
  }
  CHECK(corrupt);
  CHECK(missing);
  CHECK(viewer.city()->tileCounts().failed == 2);
  // The two good leaves are drawn (32 buildings) and the failed quadrants leave holes, no overlap.
  CHECK(rig.device.drawnSlots().size() == 32);
  // Errors are reported once, not every frame, even while retries happen.
  const std::size_t count = errors.size();
  runFrames(viewer, 30);
  CHECK(viewer.errors().size() == count);

  // Looking away (far off, the leaves no longer used), the failures are forgotten and their
  // messages withdrawn; looking back, they are asked for again and reported again.
  viewer.setCamera(CameraState{20000.0, 20000.0, 300.0, 0.0, 60.0, 45.0});
  runFramesUntil(viewer, rig.clock, 5.0, [&] { return viewer.city()->tileCounts().failed == 0; });
  CHECK(viewer.city()->tileCounts().failed == 0);
  for (const std::string& e : viewer.errors()) CHECK(e.find("Tile 1/") == std::string::npos);
  viewer.setCamera(CameraState{0.0, 0.0, 500.0, 0.0, 60.0, 45.0});
  runFramesUntil(viewer, rig.clock, 60.0, [&] { return viewer.city()->tileCounts().failed == 2; });
  CHECK(viewer.city()->tileCounts().failed == 2);
}

TEST_CASE("A failed history no one asks for any more is forgotten, its message withdrawn", "[scene][city][errors]") {
  SceneRig rig;
  rig.fetcher.files.erase("city/response/1-0-0.qvh");  // missing
  CitySceneOptions options;
  rig.open(1000.0f, options, false);  // sways of a pixel, as in the viewer
  Viewer& viewer = rig.viewer;
  viewer.setAmplitude(50.0f);  // every building's sway shows from 500 m
  viewer.setCamera(CameraState{0.0, 0.0, 500.0, 0.0, 60.0, 45.0});
  auto historyError = [&viewer] {
    for (const std::string& e : viewer.errors()) {
      if (e.find("1-0-0.qvh") != std::string::npos) return true;
    }
    return false;
  };
  runFramesUntil(viewer, rig.clock, 5.0, historyError);
  REQUIRE(historyError());
  // True scale: no sway shows from here, nothing needs the history: its failure is withdrawn.
  viewer.setAmplitude(1.0f);
  runFramesUntil(viewer, rig.clock, 5.0, [&] { return !historyError(); });
  CHECK_FALSE(historyError());
  // Wanted again, it is asked for again and its failure reported again.
  viewer.setAmplitude(50.0f);
  runFramesUntil(viewer, rig.clock, 60.0, historyError);
  CHECK(historyError());
}

TEST_CASE("Tiles are evicted beyond the memory budget and reloaded when needed", "[scene][city][memory]") {
  SceneRig rig;
  rig.open(100.0f);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{-80.0, -80.0, 120.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 15);
  INFO("tiles loaded " << viewer.city()->tileCounts().loaded << " pending " << viewer.city()->tileCounts().pending
                       << " failed " << viewer.city()->tileCounts().failed << " requests "
                       << rig.fetcher.requested.size());
  REQUIRE(viewer.settled());
  CHECK(rig.fetcher.count("city/tiles/1-0-0.qvt") == 1);
  // A budget that holds what this view needs, and not much more.
  const std::uint64_t budget = viewer.city()->memoryBytes() + 1024;
  viewer.city()->mutableOptions().memoryBudgetBytes = budget;
  // Fly to the opposite corner: the first leaf is no longer used and is evicted.
  viewer.setCamera(CameraState{80.0, 80.0, 120.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 15);
  CHECK(viewer.settled());
  CHECK(viewer.city()->memoryBytes() <= budget);
  // Back again: it is requested a second time.
  viewer.setCamera(CameraState{-80.0, -80.0, 120.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 15);
  CHECK(rig.fetcher.count("city/tiles/1-0-0.qvt") == 2);
  CHECK(viewer.stats().latest.buildingsVisible > 0);
  CHECK(viewer.city()->memoryBytes() <= budget);
}

TEST_CASE(
    "The city-wide files get three quarters of the memory budget, and what does not fit is left out with a notice",
    "[scene][city][memory]") {
  SceneRig rig;
  CitySceneOptions options;
  options.memoryBudgetBytes = 4096;  // three quarters of it are under the table of the index of 64 buildings
  rig.open(0.0f, options);
  Viewer& viewer = rig.viewer;
  for (int i = 0; i < 40 && !viewer.city()->searchIndexSettled(); ++i) runFrames(viewer, 1);
  REQUIRE(viewer.city()->searchIndexSettled());
  CHECK_FALSE(viewer.city()->searchIndexLoaded());
  CHECK(rig.fetcher.count("city/search.qvi") == 0);
  CHECK(viewer.city()->cityIndexNotice().find("search index of 64 buildings") != std::string::npos);
  // A budget that holds it: fetched, and the notice gone.
  viewer.city()->mutableOptions().memoryBudgetBytes = 512ull << 20;
  runFramesUntil(viewer, rig.clock, 10.0, [&] { return viewer.city()->searchIndexLoaded(); });
  CHECK(viewer.city()->searchIndexLoaded());
  CHECK(viewer.city()->cityIndexNotice().empty());
}

namespace {
// Close over the whole city: the four leaves replace the root; the view must settle.
void viewCloseOverTheCity(Viewer& viewer) {
  viewer.setCamera(CameraState{0.0, 0.0, 150.0, 0.0, 89.0, 60.0});
  for (int i = 0; i < 60 && !viewer.settled(); ++i) runFrames(viewer, 1);
  REQUIRE(viewer.settled());
}
}  // namespace

TEST_CASE("A view larger than the memory budget is drawn coarser, within the budget, without reloading",
          "[scene][city][memory]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  viewCloseOverTheCity(viewer);
  const std::uint32_t fullDraws = viewer.stats().latest.drawCalls;
  REQUIRE(fullDraws >= 4);
  const std::size_t visible = viewer.stats().latest.buildingsVisible;
  // A budget below what the leaves take: only the root fits.
  const std::uint64_t full = viewer.city()->memoryBytes();
  viewer.city()->mutableOptions().memoryBudgetBytes = full * 2 / 3;
  runFrames(viewer, 10);
  CHECK(viewer.settled());
  CHECK(viewer.city()->tileSelection().memoryLimited);
  CHECK(viewer.city()->tileSelection().draw == std::vector<std::uint32_t>{0});
  CHECK(viewer.city()->memoryBytes() <= full * 2 / 3);
  CHECK(viewer.stats().latest.buildingsVisible == visible);  // the root draws every building, coarser
  // Steady: nothing is fetched again frame after frame.
  const std::size_t requests = rig.fetcher.requested.size();
  runFrames(viewer, 30);
  CHECK(rig.fetcher.requested.size() == requests);
  // With the budget back, the leaves return.
  viewer.city()->mutableOptions().memoryBudgetBytes = full * 2;
  for (int i = 0; i < 60 && viewer.city()->tileSelection().draw.size() < 4; ++i) runFrames(viewer, 1);
  CHECK(viewer.city()->tileSelection().draw.size() == 4);
}

TEST_CASE("Heap the scene's parts do not count, once measured, comes out of the tiles' share of the budget",
          "[scene][city][memory]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  viewCloseOverTheCity(viewer);
  REQUIRE(viewer.city()->tileSelection().draw.size() == 4);
  const std::uint64_t full = viewer.city()->memoryBytes();
  viewer.city()->mutableOptions().memoryBudgetBytes = full * 2;
  CHECK(viewer.city()->memoryUse().otherHeap == 0);  // not measured: not counted
  // A heap that holds, besides what the parts count, 1.4 times what the view needs (a browser's
  // allocator overhead, the panels): it is counted, and only the root fits beside it.
  const auto countedHeap = [&] {
    MemoryUse use = viewer.city()->memoryUse();
    return use.total() - use.tilesGpu - use.otherHeap;
  };
  const auto framesWithRestOfHeap = [&](std::uint64_t rest, int frames) {
    for (int i = 0; i < frames; ++i) {
      viewer.setMeasuredHeapBytes(countedHeap() + rest);
      runFrames(viewer, 1);
    }
  };
  // The engine's own memory, as first measured, comes on top of the budget.
  const std::uint64_t engine = full / 8;
  framesWithRestOfHeap(engine, 1);
  CHECK(viewer.city()->memoryUse().otherHeap == 0);
  CHECK(viewer.city()->tileSelection().draw.size() == 4);
  // (What the scene counts can change a little between the test's measure and the frame's.)
  const auto near = [&](std::uint64_t bytes, std::uint64_t expected) {
    return bytes + full / 10 >= expected && bytes <= expected + full / 10;
  };
  const std::uint64_t rest = full * 7 / 5;
  framesWithRestOfHeap(engine + rest, 20);
  CHECK(near(viewer.city()->memoryUse().otherHeap, rest));
  CHECK(viewer.city()->tileSelection().memoryLimited);
  CHECK(viewer.city()->tileSelection().draw == std::vector<std::uint32_t>{0});
  const MemoryUse use = viewer.city()->memoryUse();
  CHECK(use.tilesCpu + use.tilesGpu <= full * 2 - rest);  // the leaves evicted
  // A passing peak of the heap (one frame) is not taken for the rest of it.
  framesWithRestOfHeap(engine, 1);
  framesWithRestOfHeap(engine + full * 4, 1);
  CHECK(near(viewer.city()->memoryUse().otherHeap, 0));
  // Once the heap holds less beside the parts, the leaves return.
  for (int i = 0; i < 60 && viewer.city()->tileSelection().draw.size() < 4; ++i) framesWithRestOfHeap(engine, 1);
  CHECK(viewer.city()->tileSelection().draw.size() == 4);
}

TEST_CASE("A manifest that cannot be loaded is an error, not a hang", "[scene][city][errors]") {
  FakeFetcher fetcher;
  fetcher.files["bad/tileset.json"] = {'{', 'x'};
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.openCity("missing/tileset.json", fetcher);
  runFrames(viewer, 3);
  CHECK(viewer.settled());
  REQUIRE(viewer.errors().size() == 1);
  CHECK(viewer.errors()[0].find("missing/tileset.json: HTTP 404") != std::string::npos);
  Viewer other(device);
  other.openCity("bad/tileset.json", fetcher);
  runFrames(other, 3);
  CHECK(other.settled());
  REQUIRE(other.errors().size() == 1);
  CHECK(other.errors()[0].find("not valid JSON") != std::string::npos);
}

TEST_CASE("Picking finds the building under the cursor, hidden kinds and filters show in the GPU flags",
          "[scene][city][pick]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 600.0, 0.0, 70.0, 45.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  std::size_t total = 0;
  const auto list = viewer.city()->filteredList(1000, &total);
  REQUIRE(total == 64);
  const BuildingListEntry& target = list.front();
  const auto info = viewer.building(target.id);
  REQUIRE(info.has_value());
  // A point inside its roof, as the user sees it.
  const auto screen = viewer.worldToScreen(target.x, target.y, info->attributes.heightM * 0.99);
  REQUIRE(screen.has_value());
  const auto picked = viewer.pick(screen->x, screen->y);
  REQUIRE(picked.has_value());
  CHECK(picked->attributes.id == target.id);
  // The sky picks nothing.
  CHECK_FALSE(viewer.pick(640.0, 2.0).has_value());

  // LOD1 hidden: the building is neither drawn (hidden flag) nor pickable.
  viewer.city()->setLodVisibility(false, true);
  runFrames(viewer, 2);
  CHECK_FALSE(viewer.pick(screen->x, screen->y).has_value());
  for (const auto& [slot, row] : rig.device.buildings) CHECK((static_cast<unsigned>(row.flags) & kFlagHidden) != 0);
  viewer.city()->setLodVisibility(true, true);
  runFrames(viewer, 2);
  CHECK(viewer.pick(screen->x, screen->y).has_value());

  // A damage filter dims exactly the buildings below it.
  BuildingFilters filters;
  filters.minDamage = static_cast<int>(list.front().damage);
  viewer.city()->setFilters(filters);
  runFrames(viewer, 2);
  int dimmed = 0;
  int kept = 0;
  for (const auto& [slot, row] : rig.device.buildings) {
    const bool isDimmed = (static_cast<unsigned>(row.flags) & kFlagDimmed) != 0;
    CHECK(isDimmed == (row.damageState < static_cast<float>(filters.minDamage)));
    (isDimmed ? dimmed : kept) += 1;
  }
  CHECK(kept > 0);
  std::size_t passing = 0;
  (void)viewer.city()->filteredList(1000, &passing);
  CHECK(passing > 0);
  CHECK(passing < 64 + 1);
}

TEST_CASE("A building's results show while its full-detail tile's results are still on their way",
          "[scene][city][select]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  // Far away: only the coarse root and its results.
  viewer.setCamera(CameraState{0.0, 0.0, 6000.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 5);
  REQUIRE(viewer.settled());
  const auto coarse = viewer.building("s1");
  REQUIRE(coarse.has_value());
  REQUIRE_FALSE(coarse->detailed);
  REQUIRE(coarse->hasResponse);

  // Selecting it brings in its leaf; the leaf's results are held back by a slow server.
  for (int q = 0; q < 4; ++q) {
    rig.fetcher.held.insert("city/response/1-" + std::to_string(q % 2) + "-" + std::to_string(q / 2) + ".qvs");
  }
  REQUIRE(viewer.select("s1"));
  for (int i = 0; i < 50 && !viewer.building("s1")->detailed; ++i) runFrames(viewer, 1);
  const auto detailed = viewer.building("s1");
  REQUIRE(detailed->detailed);
  // Described from the leaf (full detail), with the results the root already has: not "no result".
  CHECK(detailed->hasResponse);
  CHECK(detailed->response.damage == coarse->response.damage);
  CHECK(detailed->storeyPeakDrift == coarse->storeyPeakDrift);
  rig.fetcher.held.clear();
  runFrames(viewer, 5);
  CHECK(viewer.building("s1")->hasResponse);
}

TEST_CASE("A LOD2 model is drawn, picked on its own triangles and hidden with the LOD2 switch", "[scene][city][lod2]") {
  SceneRig rig(MiniCity(true, true));
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  const double x = MiniCity::centreX(0), y = MiniCity::centreY(0);
  // Close to the model, from the side: the leaf (skinned mesh) is drawn.
  viewer.setCamera(CameraState{x, y, 150.0, 30.0, 20.0, 45.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  const auto info = viewer.building(MiniCity::kLod2Id);
  REQUIRE(info.has_value());
  CHECK(info->attributes.lod == 2);
  CHECK(info->modelSource == "cityjson");
  CHECK(info->modelTriangles == 6);
  CHECK(buildingInfoJson(*info).find("\"modelSource\":\"cityjson\"") != std::string::npos);

  // Its spire, 30 m up where the footprint's prism (17.5 m) has long ended, picks it ...
  const auto spire = viewer.worldToScreen(x, y, 30.0);
  REQUIRE(spire.has_value());
  const auto picked = viewer.pick(spire->x, spire->y);
  REQUIRE(picked.has_value());
  CHECK(picked->attributes.id == MiniCity::kLod2Id);
  // ... and so does its wall low down; a point beside the spire at 30 m (inside the prism's
  // outline, outside the pyramid) does not pick it.
  const auto wall = viewer.worldToScreen(x, y - 9.0, 2.0);
  REQUIRE(wall.has_value());
  const auto pickedWall = viewer.pick(wall->x, wall->y);
  REQUIRE(pickedWall.has_value());
  CHECK(pickedWall->attributes.id == MiniCity::kLod2Id);
  const auto beside = viewer.worldToScreen(x + 9.0, y + 9.0, 30.0);
  REQUIRE(beside.has_value());
  const auto pickedBeside = viewer.pick(beside->x, beside->y);
  CHECK((!pickedBeside.has_value() || pickedBeside->attributes.id != MiniCity::kLod2Id));

  // The drawn mesh holds the model's six triangles for its slot (flat-shaded: 18 vertices), not
  // an extruded prism.
  CHECK(rig.device.verticesAt(glm::vec2(x, y)) == 18);
  // Its neighbour, a LOD1 building, is an extruded prism with a ring per floor.
  CHECK(rig.device.verticesAt(glm::vec2(MiniCity::centreX(1), y)) > 18);

  // LOD2 switched off: the building is its LOD1 extrusion again (a prism with a ring per floor,
  // drawn and picked), so the spire is gone but the walls are still there.
  viewer.city()->setLodVisibility(true, false);
  runFrames(viewer, 2);
  const auto noSpire = viewer.pick(spire->x, spire->y);
  CHECK((!noSpire.has_value() || noSpire->attributes.id != MiniCity::kLod2Id));
  const auto prismWall = viewer.pick(wall->x, wall->y);
  REQUIRE(prismWall.has_value());
  CHECK(prismWall->attributes.id == MiniCity::kLod2Id);
  CHECK(rig.device.verticesAt(glm::vec2(x, y)) > 18);
  // LOD1 off as well: now it is hidden like every other building.
  viewer.city()->setLodVisibility(false, false);
  runFrames(viewer, 2);
  const auto none = viewer.pick(wall->x, wall->y);
  CHECK((!none.has_value() || none->attributes.id != MiniCity::kLod2Id));
  // LOD1 off, LOD2 on: only the model is drawn and picked.
  viewer.city()->setLodVisibility(false, true);
  runFrames(viewer, 2);
  const auto onlyModel = viewer.pick(spire->x, spire->y);
  REQUIRE(onlyModel.has_value());
  CHECK(onlyModel->attributes.id == MiniCity::kLod2Id);
  CHECK(rig.device.verticesAt(glm::vec2(x, y)) == 18);
}

TEST_CASE("Hostile city addresses are refused before any request, with a message", "[scene][city][errors]") {
  CHECK(dataUrlProblem("/city/tileset.json").empty());
  CHECK(dataUrlProblem("city/tileset.json").empty());
  CHECK(dataUrlProblem("tiles/a:b/tileset.json").empty());
  CHECK(dataUrlProblem("https://example.org/city/tileset.json").empty());
  CHECK(dataUrlProblem("HTTP://example.org/tileset.json").empty());
  CHECK(isAbsoluteHttpUrl("https://example.org/t.json"));
  CHECK_FALSE(isAbsoluteHttpUrl("/t.json"));
  const std::vector<std::string> hostile = {
      "javascript:alert(1)", "file:///etc/passwd",  "data:application/json,{}", "JaVaScRiPt:x", "",
      "city\ntileset.json",  std::string(5000, 'a')};
  for (const std::string& bad : hostile) {
    CAPTURE(bad.substr(0, 40));
    CHECK_FALSE(dataUrlProblem(bad).empty());
  }

  FakeFetcher fetcher;
  RecordingDevice device;
  Viewer viewer(device);
  viewer.openCity("javascript:alert(1)", fetcher, CitySceneOptions{});
  runFrames(viewer, 3);
  CHECK(fetcher.requested.empty());
  CHECK(viewer.settled());
  REQUIRE(viewer.errors().size() == 1);
  CHECK(viewer.errors()[0].find("only http:// and https://") != std::string::npos);
  CHECK(viewer.errors()[0].find("javascript:") != std::string::npos);
}

TEST_CASE("A root that holds only some buildings: lists, search and selection come from the city index",
          "[scene][city][index]") {
  SceneRig rig(MiniCity(true, false, 16));  // the root draws 16 of the 64 buildings
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  // Far away: only the root is drawn.
  viewer.setCamera(CameraState{0.0, 0.0, 200000.0, 0.0, 70.0, 45.0});
  std::size_t total = 0;
  CHECK(viewer.city()->filteredList(1000, &total).empty());  // the index is not there yet
  for (int i = 0; i < 40 && !viewer.city()->searchIndexSettled(); ++i) runFrames(viewer, 1);
  REQUIRE(viewer.city()->searchIndexLoaded());
  REQUIRE(viewer.city()->tileCounts().loaded == 1);
  CHECK(viewer.city()->tileCounts().pending == 0);

  // The whole city is listed, with the response's damage, worst first.
  const auto list = viewer.city()->filteredList(1000, &total);
  CHECK(total == 64);
  REQUIRE(list.size() == 64);
  CHECK(list.front().damage == DamageState::Complete);
  const std::string farId = MiniCity::idOf(7, 7);  // in the last leaf, not in the root
  const auto it = std::find_if(list.begin(), list.end(), [&](const BuildingListEntry& e) { return e.id == farId; });
  REQUIRE(it != list.end());
  CHECK(it->damage == MiniCity::responseOf(7, 7).damage);
  CHECK(it->x == Approx(MiniCity::centreX(7)));
  CHECK(it->y == Approx(MiniCity::centreY(7)));
  CHECK_FALSE(viewer.building(farId).has_value());  // no loaded tile holds it

  // Filters apply to every building, not only those drawn.
  BuildingFilters filters;
  filters.minDamage = static_cast<int>(DamageState::Extensive);
  viewer.city()->setFilters(filters);
  (void)viewer.city()->filteredList(1000, &total);
  std::size_t expected = 0;
  for (int i = 0; i < MiniCity::kSide; ++i) {
    for (int j = 0; j < MiniCity::kSide; ++j) expected += (i + j) % 5 >= 3 ? 1u : 0u;
  }
  CHECK(total == expected);
  viewer.city()->setFilters(BuildingFilters{});

  // Search by name finds it; selecting it loads its leaf, wherever the camera is.
  const auto hits = viewer.city()->search("Building 7-7", 10);
  REQUIRE(hits.size() == 1);
  CHECK(hits[0].id == farId);
  REQUIRE(viewer.select(farId));
  CHECK(viewer.selection() == farId);
  CHECK(viewer.flyToSelection());
  for (int i = 0; i < 40 && !viewer.building(farId); ++i) runFrames(viewer, 1);
  const auto info = viewer.building(farId);
  REQUIRE(info.has_value());
  CHECK(info->detailed);
  CHECK(info->hasResponse);
  CHECK(info->attributes.centroidX == Approx(MiniCity::centreX(7)));
  // An id the city does not have is refused and changes nothing.
  CHECK_FALSE(viewer.select("s999"));
  CHECK(viewer.selection() == farId);
}

TEST_CASE("A search index and city-wide response that fail are retried with backoff and recover",
          "[scene][city][index][errors]") {
  SceneRig rig(MiniCity(true, false, 16));
  rig.fetcher.statusOverride["city/search.qvi"] = 503;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 200000.0, 0.0, 70.0, 45.0});
  for (int i = 0; i < 40 && !viewer.city()->searchIndexSettled(); ++i) runFrames(viewer, 1);
  // The failure is shown and the city-wide list is empty, but the view keeps working.
  REQUIRE(viewer.city()->searchIndexSettled());
  CHECK_FALSE(viewer.city()->searchIndexLoaded());
  REQUIRE(viewer.errors().size() == 1);
  CHECK(viewer.errors()[0].find("Search index city/search.qvi failed: HTTP 503") != std::string::npos);
  const std::size_t firstTries = rig.fetcher.count("city/search.qvi");
  CHECK(firstTries == 1);
  // Its time limit grows with its size (a city-wide file may be large) and with each failure.
  const CitySceneOptions defaults;
  const double indexBytes = static_cast<double>(rig.fetcher.files.at("city/search.qvi").size());
  const double firstLimitMs = defaults.requestTimeoutMs + indexBytes * 1000.0 / defaults.slowestBytesPerSecond;
  CHECK(rig.fetcher.lastTimeoutMs.at("city/search.qvi") == static_cast<std::uint32_t>(firstLimitMs));

  // The server still fails: retried after a backoff (one second after the first failure), reported
  // once. Not before the second has passed, however many frames run.
  runFrames(viewer, 30);
  rig.clock.advance(0.9);
  runFrames(viewer, 30);
  CHECK(rig.fetcher.count("city/search.qvi") == firstTries);
  runFramesUntil(viewer, rig.clock, 5.0, [&] { return rig.fetcher.count("city/search.qvi") > firstTries; });
  CHECK(rig.fetcher.count("city/search.qvi") > firstTries);
  CHECK(rig.fetcher.lastTimeoutMs.at("city/search.qvi") == static_cast<std::uint32_t>(2 * firstLimitMs));
  CHECK(viewer.errors().size() == 1);

  // The server recovers but the response summary in the index's order fails now.
  rig.fetcher.statusOverride.erase("city/search.qvi");
  rig.fetcher.statusOverride["city/response/index.qvs"] = 500;
  runFramesUntil(viewer, rig.clock, 10.0, [&] { return viewer.city()->searchIndexLoaded(); });
  REQUIRE(viewer.city()->searchIndexLoaded());
  runFramesUntil(viewer, rig.clock, 10.0, [&] {
    return viewer.errors().size() == 1 && viewer.errors()[0].find("index.qvs") != std::string::npos;
  });
  std::size_t total = 0;
  auto list = viewer.city()->filteredList(1000, &total);
  CHECK(total == 64);
  REQUIRE(viewer.errors().size() == 1);  // the index's error is withdrawn, the summary's is shown
  CHECK(viewer.errors()[0].find("Response summary city/response/index.qvs failed: HTTP 500") != std::string::npos);

  // Once the summary comes back too, the list carries the damage and no error remains.
  rig.fetcher.statusOverride.clear();
  runFramesUntil(viewer, rig.clock, 10.0, [&] { return viewer.errors().empty(); });
  CHECK(viewer.errors().empty());
  list = viewer.city()->filteredList(1000, &total);
  REQUIRE(list.size() == 64);
  CHECK(list.front().damage == DamageState::Complete);
}

TEST_CASE("A city on an origin the site does not allow is refused before any request, with how to allow it",
          "[scene][city][trust]") {
  DataOriginPolicy policy;
  policy.pageOrigin = "https://quake.city.gov";
  policy.allowedOrigins = {"https://data.city.gov"};

  policy.urlOrigin = "https://quake.city.gov";
  CHECK(dataOriginProblem(policy).empty());
  CHECK(dataOriginDescription(policy) == "this site (https://quake.city.gov)");
  policy.urlOrigin = "https://data.city.gov";
  CHECK(dataOriginProblem(policy).empty());
  CHECK(dataOriginDescription(policy) == "https://data.city.gov (allowed by this site's config.json)");
  // Another port, another scheme or a look-alike host is another origin.
  for (const char* other : {"https://data.city.gov:8443", "http://data.city.gov", "https://data.city.gov.evil.example",
                            "https://evil.example", "null", ""}) {
    policy.urlOrigin = other;
    INFO(other);
    CHECK_FALSE(dataOriginProblem(policy).empty());
  }
  policy.urlOrigin = "https://evil.example";
  const std::string message = dataOriginProblem(policy);
  CHECK(message.find("a city from https://evil.example, which this site does not allow") != std::string::npos);
  CHECK(message.find("config.json") != std::string::npos);
  CHECK(message.find("{\"dataOrigins\": [\"https://evil.example\"]}") != std::string::npos);
  // Without a page origin (tools, tests) there is no policy.
  CHECK(dataOriginProblem(DataOriginPolicy{}).empty());

  // The scene asks for nothing, settles, and the viewer shows the message.
  SceneRig rig;
  CitySceneOptions options;
  options.origin = policy;
  rig.open(0.0f, options);
  runFrames(rig.viewer, 5);
  CHECK(rig.fetcher.requested.empty());
  CHECK(rig.viewer.settled());
  REQUIRE(rig.viewer.errors().size() == 1);
  CHECK(rig.viewer.errors()[0] == message);
  CHECK(rig.viewer.dataSource().empty());

  // Allowed: it loads, and the viewer says where it came from.
  SceneRig allowed;
  options.origin.urlOrigin = "https://data.city.gov";
  allowed.open(0.0f, options);
  runFrames(allowed.viewer, 5);
  CHECK(allowed.viewer.city()->manifestLoaded());
  CHECK(allowed.viewer.errors().empty());
  CHECK(allowed.viewer.dataSource() == "https://data.city.gov (allowed by this site's config.json)");
}

TEST_CASE("building(id) says why a building has no result and when a result is approximate", "[scene][info]") {
  BuildingInfo info;
  info.attributes.id = "w3";
  info.hasResponse = true;
  info.response.noResultReason = NoResultReason::BaseAboveGround;
  const std::string none = buildingInfoJson(info);
  CHECK(none.find("\"damageState\":\"no_result\"") != std::string::npos);
  CHECK(none.find("\"noResultReason\":\"base_above_ground\"") != std::string::npos);
  CHECK(none.find("\"approximate\":false") != std::string::npos);

  info.response.source = ResponseSource::Model;
  info.response.damage = DamageState::Slight;
  info.response.noResultReason = NoResultReason::None;
  info.response.approximate = true;
  info.response.unconvergedSteps = 12;
  info.response.worstResidualRatio = 0.25f;
  const std::string approximate = buildingInfoJson(info);
  CHECK(approximate.find("\"noResultReason\":null") != std::string::npos);
  CHECK(approximate.find("\"approximate\":true") != std::string::npos);
  CHECK(approximate.find("\"unconvergedSteps\":12") != std::string::npos);
  CHECK(approximate.find("\"worstResidualRatio\":0.25") != std::string::npos);
}

TEST_CASE("Fly to shows a low-rise building surrounded by towers: no other building hides its centre",
          "[scene][city][flyto]") {
  // Building (3, 3), 17.5 m, with 120 m towers south, west and east of it (20 m gaps between them).
  const std::map<std::pair<int, int>, float> towers{{{2, 2}, 120.0f}, {{3, 2}, 120.0f}, {{4, 2}, 120.0f},
                                                    {{2, 3}, 120.0f}, {{4, 3}, 120.0f}, {{2, 4}, 120.0f}};
  SceneRig rig(MiniCity(true, false, MiniCity::kSide * MiniCity::kSide, towers));
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  // The user looks north over the city, so flying straight in would look across the southern towers.
  viewer.setCamera(CameraState{0.0, -300.0, 900.0, 0.0, 45.0, 45.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());

  // The first building a ray from the eye to the building's centre meets (the scene's own picking).
  auto firstHit = [&](const std::string& id) -> std::string {
    const auto info = viewer.building(id);
    REQUIRE(info.has_value());
    const CameraView view(viewer.camera(), 1280, 720);
    const glm::vec3 centre(static_cast<float>(info->attributes.centroidX),
                           static_cast<float>(info->attributes.centroidY), info->attributes.heightM * 0.5f);
    const glm::vec3 eye = view.eye();
    const auto ref = viewer.city()->pick(eye, glm::normalize(centre - eye));
    if (!ref) return "(nothing)";
    const auto hit = viewer.city()->info(*ref);
    return hit ? hit->attributes.id : "(unknown)";
  };
  auto flyAndSettle = [&](const std::string& id) {
    REQUIRE(viewer.select(id));
    REQUIRE(viewer.flyToSelection());
    runFrames(viewer, 120);  // the 1.2 s flight
    for (int i = 0; i < 40 && !viewer.settled(); ++i) runFrames(viewer, 1);
  };

  const std::string low = MiniCity::idOf(3, 3);
  // What the old Fly to did (keep heading and pitch, frame from 150 m): a tower is in the way.
  viewer.setCamera(CameraState{MiniCity::centreX(3), MiniCity::centreY(3), 150.0, 0.0, 45.0, 45.0});
  runFrames(viewer, 20);
  CHECK(firstHit(low) == MiniCity::idOf(3, 2));

  viewer.setCamera(CameraState{0.0, -300.0, 900.0, 0.0, 45.0, 45.0});
  runFrames(viewer, 20);
  flyAndSettle(low);
  CHECK(viewer.camera().x == Approx(MiniCity::centreX(3)));
  CHECK(viewer.camera().y == Approx(MiniCity::centreY(3)));
  CHECK(firstHit(low) == low);
  // From another side or height than the user's (through a gap between the towers, or the open north).
  CHECK((viewer.camera().headingDeg != Approx(0.0).margin(1.0) || viewer.camera().pitchDeg != Approx(45.0)));

  // A tower with nothing tall in front keeps the user's heading and pitch.
  viewer.setCamera(CameraState{0.0, -300.0, 900.0, 0.0, 45.0, 45.0});
  runFrames(viewer, 20);
  const std::string tower = MiniCity::idOf(3, 2);
  flyAndSettle(tower);
  CHECK(viewer.camera().headingDeg == Approx(0.0).margin(1e-6));
  CHECK(viewer.camera().pitchDeg == Approx(45.0));
  CHECK(viewer.camera().distance == Approx(300.0));  // 2.5 x 120 m
  CHECK(firstHit(tower) == tower);
}

TEST_CASE("Every drawn building and block follows its drift series, with no history loaded", "[scene][city][series]") {
  SceneRig rig(MiniCity(true, false, MiniCity::kSide * MiniCity::kSide, {}, true));
  CitySceneOptions options;
  options.blockPixels = 60.0f;  // blocks 6 km away, as in the far-view test
  rig.open(0.0f, options);      // nothing moves floor by floor: only the series
  Viewer& viewer = rig.viewer;
  viewer.pause();
  viewer.setCamera(CameraState{0.0, 0.0, 600.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  // Every building in view follows its history in the current-drift colours.
  CHECK(viewer.stats().latest.buildingsVisible == 64);
  CHECK(viewer.stats().latest.buildingsAnimated == 64);
  const auto drawn = rig.device.drawnSlots();
  REQUIRE(drawn.size() == 64);
  auto refOf = [](const BuildingGpuRecord& row) {
    return SeriesRef{static_cast<std::int64_t>(row.seriesBase), row.seriesStart,
                     static_cast<std::uint32_t>(row.seriesCount), row.seriesRateHz};
  };
  for (const auto& [slot, centre] : drawn) {
    const BuildingGpuRecord& row = rig.device.buildings.at(slot);
    REQUIRE(row.floorBase == -1.0f);
    REQUIRE(row.seriesBase >= 0.0f);
    CHECK(row.seriesRateHz == kDriftSeriesRateHz);
    CHECK(row.seriesCount == 41.0f);  // 10 s at 4 windows a second, and the last sample's window
    // Its largest drift over the record is its peak storey drift (every storey of a MiniCity
    // building drifts the roof's fifth over 3.5 m), within the series' quantization.
    const auto [i, j] = cellOf(centre);
    float peak = 0.0f;
    for (double t = 0.0; t < 10.0; t += 0.05)
      peak = std::max(peak, seriesDriftAt(rig.device.series, refOf(row), kSeriesFullScale, t));
    CHECK(peak == Approx(MiniCity::amplitude(i, j) / 5.0 / MiniCity::kStoreyHeight).epsilon(0.03));
  }
  // Buildings shake differently: their drifts at one moment differ.
  std::set<long> distinct;
  for (const auto& [slot, centre] : drawn)
    distinct.insert(std::lround(
        1e6 * seriesDriftAt(rig.device.series, refOf(rig.device.buildings.at(slot)), kSeriesFullScale, 3.3)));
  CHECK(distinct.size() > 20);
  // In the peak-drift colours the series are not drawn: nothing follows its history.
  viewer.setColorMode(ColorMode::PeakDrift);
  runFrames(viewer, 2);
  CHECK(viewer.stats().latest.buildingsAnimated == 0);
  viewer.setColorMode(ColorMode::CurrentDrift);

  // Far away, as blocks: each block's drift at a window's centre is the largest of its members'.
  viewer.setCamera(CameraState{0.0, 0.0, 6000.0, 0.0, 60.0, 45.0});
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  CHECK(viewer.stats().latest.buildingsAnimated == 64);
  const auto blocks = rig.device.drawnSlots();
  REQUIRE(blocks.size() == 4);
  for (const auto& [slot, centre] : blocks) {
    const BuildingGpuRecord& block = rig.device.buildings.at(slot);
    REQUIRE(block.seriesBase >= 0.0f);
    // The block's quadrant of the grid: its members' rows are the root tile's (the coarse copies).
    for (const double t : {1.125, 4.625, 8.375}) {
      float worst = 0.0f;
      for (int i = 0; i < MiniCity::kSide; ++i) {
        for (int j = 0; j < MiniCity::kSide; ++j) {
          if ((MiniCity::centreX(i) < 0.0) != (centre.x < 0.0f) || (MiniCity::centreY(j) < 0.0) != (centre.y < 0.0f))
            continue;
          worst = std::max(worst, static_cast<float>(std::abs(MiniCity::roofX(i, j, t))));
        }
      }
      // At a window's centre (1.125 s, ...) the block shows that window's largest member drift: at
      // least the instantaneous drift there (less the 50 Hz samples' distance from that moment).
      const double largest =
          MiniCity::amplitude(MiniCity::kSide - 1, MiniCity::kSide - 1) / 5.0 / MiniCity::kStoreyHeight;
      CHECK(seriesDriftAt(rig.device.series, refOf(block), kSeriesFullScale, t) >=
            worst / 5.0f / MiniCity::kStoreyHeight - 0.12 * largest);
      CHECK(seriesDriftAt(rig.device.series, refOf(block), kSeriesFullScale, t) <= 1.03 * largest);
    }
  }
}

TEST_CASE("Critical facilities kept by a filter and the selection are marked on the map at a fixed size",
          "[scene][city][markers]") {
  SceneRig rig;
  // Plant hospitals in the served index: column i = 0 (8 buildings).
  auto& bytes = rig.fetcher.files.at("city/search.qvi");
  auto entries = decodeSearchIndex(bytes, "planted");
  REQUIRE(entries.ok());
  for (SearchEntry& e : *entries) {
    for (int j = 0; j < MiniCity::kSide; ++j) {
      if (e.id == MiniCity::idOf(0, j)) {
        e.use = "hospital";
        e.facility = FacilityCategory::Essential;
        e.facilityKind = "hospital";
      }
    }
  }
  bytes = encodeSearchIndex(*entries);
  rig.city.tileset.search->bytes = bytes.size();
  rig.city.tileset.search->crc32 = crc32(bytes);
  const std::string json = tilesetToJson(rig.city.tileset);
  rig.fetcher.files["city/tileset.json"] = std::vector<std::uint8_t>(json.begin(), json.end());
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 2000.0, 0.0, 60.0, 45.0});
  runFramesUntil(viewer, rig.clock, 10.0, [&] { return viewer.settled() && viewer.city()->searchIndexLoaded(); });
  REQUIRE(viewer.city()->searchIndexLoaded());
  runFrames(viewer, 2);
  CHECK(rig.device.markers.empty());  // no facility filter: no markers
  const std::uint64_t trianglesBefore = viewer.stats().latest.triangles;

  BuildingFilters critical;
  critical.criticalOnly = true;
  viewer.city()->setFilters(critical);
  runFrames(viewer, 2);
  REQUIRE(rig.device.markers.size() == MiniCity::kSide);
  for (const MapMarker& m : rig.device.markers) {
    CHECK(m.radiusPixels == 7.0f);  // CSS and framebuffer pixels are one here
    CHECK_FALSE(m.selected);
    CHECK(m.position.x == Approx(MiniCity::centreX(0)));
    CHECK(m.position.z == Approx(MiniCity::kStoreys * MiniCity::kStoreyHeight));  // on its roof
    // Coloured by its damage state on the ramp (this city's results have no probabilities).
    CHECK(m.color != glm::vec3(1.0f));
  }
  // Two triangles a marker, in one draw call.
  CHECK(viewer.stats().latest.triangles == trianglesBefore + 2 * MiniCity::kSide);

  // The selection gets its own, larger marker with a white ring.
  viewer.city()->select(MiniCity::idOf(5, 5));
  runFrames(viewer, 2);
  REQUIRE(rig.device.markers.size() == MiniCity::kSide + 1);
  const MapMarker& selected = rig.device.markers.back();
  CHECK(selected.selected);
  CHECK(selected.radiusPixels == 10.0f);
  CHECK(selected.position.x == Approx(MiniCity::centreX(5)));
  CHECK(selected.position.y == Approx(MiniCity::centreY(5)));
  // Filters off, selection cleared: none.
  viewer.city()->setFilters(BuildingFilters{});
  viewer.city()->select("");
  runFrames(viewer, 2);
  CHECK(rig.device.markers.empty());
}

TEST_CASE("The first view plays from the shaking's arrival and frames the city beside the panel",
          "[scene][city][opening]") {
  // The city's shaking arrives 5 s into the record: every tile summary's series start later.
  SceneRig rig(MiniCity(true, false, MiniCity::kSide * MiniCity::kSide, {}, true));
  for (TileNode& n : rig.city.tileset.nodes) {
    auto& bytes = rig.fetcher.files.at("city/" + n.response->summaryFile);
    auto summary = decodeResponseSummary(bytes, n.response->summaryFile);
    REQUIRE(summary.ok());
    REQUIRE_FALSE(summary->driftSeries.empty());
    for (DriftSpan& span : summary->driftSeries.spans) span.startSeconds += 5.0f;
    bytes = encodeResponseSummary(*summary);
    n.response->summaryBytes = bytes.size();
    n.response->summaryCrc32 = crc32(bytes);
  }
  const std::string json = tilesetToJson(rig.city.tileset);
  rig.fetcher.files["city/tileset.json"] = std::vector<std::uint8_t>(json.begin(), json.end());

  SECTION("untouched, it opens a second before the shaking, beside a 400 px panel") {
    rig.viewer.setFramingInsetCss(400.0);
    rig.open(0.0f);
    runFrames(rig.viewer, 20);
    REQUIRE(rig.viewer.city()->firstShakingSeconds().has_value());
    CHECK(*rig.viewer.city()->firstShakingSeconds() == Approx(5.0).margin(0.3));
    // Playing since: 20 frames of 1/60 s after it was set.
    CHECK(rig.viewer.time() == Approx(4.0).margin(0.5));
    // The city's centre is in the middle of the canvas right of the panel.
    const auto centre = rig.viewer.worldToScreen(0.0, 0.0, 0.0);
    REQUIRE(centre.has_value());
    CHECK(centre->x == Approx((400.0 + 1280.0) / 2.0).margin(40.0));
    // The whole city is in view.
    for (const double corner : {-160.0, 160.0}) {
      const auto p = rig.viewer.worldToScreen(corner, corner, 0.0);
      REQUIRE(p.has_value());
      CHECK(p->x > 400.0);
      CHECK(p->x < 1280.0);
    }
    // The panel growing with its content (numbers arriving) does not move the city under the
    // user; another layout does.
    const float shift = rig.viewer.lensShift();
    rig.viewer.setFramingInsetCss(400.0 + Viewer::kFramingInsetStepCss * 0.8);
    runFrames(rig.viewer, 2);
    CHECK(rig.viewer.lensShift() == shift);
    const auto still = rig.viewer.worldToScreen(0.0, 0.0, 0.0);
    REQUIRE(still.has_value());
    CHECK(still->x == Approx(centre->x).margin(0.5));
    rig.viewer.setFramingInsetCss(0.0);
    runFrames(rig.viewer, 2);
    CHECK(rig.viewer.lensShift() == 0.0f);
  }
  SECTION("a time chosen before (a link) is kept") {
    rig.open(0.0f);
    rig.viewer.pause();
    for (int i = 0; i < 10 && rig.viewer.duration() == 0.0; ++i) runFrames(rig.viewer, 1);  // the record's duration
    REQUIRE(rig.viewer.duration() > 1.0);
    REQUIRE(rig.viewer.setTime(0.5));
    runFrames(rig.viewer, 20);
    REQUIRE(rig.viewer.city()->firstShakingSeconds().has_value());
    CHECK(rig.viewer.time() == Approx(0.5));
  }
}

TEST_CASE("Tile summaries without losses: colours, the probability filter, the view's totals and the inspection",
          "[scene][city][losses]") {
  // As quakeview-prep writes a city with an index: tiles carry the drawing probabilities (DPRB),
  // the index's summary the full losses and sites.
  SceneRig rig(MiniCity(true, false, MiniCity::kSide * MiniCity::kSide, {}, false, true));
  rig.open(1000.0f);
  Viewer& viewer = rig.viewer;
  viewer.setCamera(CameraState{0.0, 0.0, 2500.0, 0.0, 85.0, 45.0});  // from above: the whole city in view
  viewer.pause();
  runFrames(viewer, 30);
  REQUIRE(viewer.settled());
  CityScene& city = *viewer.city();

  // Every drawn building's colour code carries its P(DS >= moderate) from the tile's DPRB.
  int coded = 0;
  for (const auto& [slot, row] : rig.device.buildings) {
    if (row.damageState < 0.0f) continue;
    REQUIRE(row.lossCode >= 0.0f);
    ++coded;
  }
  CHECK(coded >= MiniCity::kSide * MiniCity::kSide);

  // The view's totals add the index's losses of the buildings in view: all of them here.
  const seismic::LossTotals inView = city.consequencesInView();
  CHECK(inView.buildings == MiniCity::kSide * MiniCity::kSide);
  double repair = 0.0;
  for (int i = 0; i < MiniCity::kSide; ++i) {
    for (int j = 0; j < MiniCity::kSide; ++j) repair += MiniCity::lossOf(i, j).repairCostUsd;
  }
  CHECK(inView.repairCostUsd.expected == Approx(repair));

  // The inspection shows the building's losses and site shaking from the index.
  const auto ref = city.find(MiniCity::idOf(3, 5));
  REQUIRE(ref.has_value());
  const auto info = city.info(*ref);
  REQUIRE(info.has_value());
  REQUIRE(info->loss.has_value());
  CHECK(info->loss->repairCostUsd == MiniCity::lossOf(3, 5).repairCostUsd);
  CHECK(info->loss->structuralAtLeast(2) == Approx(MiniCity::lossOf(3, 5).structuralAtLeast(2)));
  REQUIRE(info->site.has_value());
  CHECK(info->site->pgaG == MiniCity::siteOf(3, 5).pgaG);

  // The probability filter dims by the tiles' probabilities: P(DS >= moderate) >= 22 %.
  BuildingFilters filters;
  filters.probabilityState = 2;
  filters.minProbabilityPercent = 22;
  city.setFilters(filters);
  runFrames(viewer, 2);
  int dimmed = 0, kept = 0;
  for (const auto& [slot, row] : rig.device.buildings) {
    if (row.lossCode < 0.0f) continue;
    const float moderate = static_cast<float>(static_cast<int>(row.lossCode) % kLossCodeExpectedFactor) / 255.0f;
    const bool isDimmed = (static_cast<unsigned>(row.flags) & kFlagDimmed) != 0;
    if (moderate < 0.21f) CHECK(isDimmed);
    if (moderate > 0.23f) CHECK_FALSE(isDimmed);
    (isDimmed ? dimmed : kept) += 1;
  }
  CHECK(dimmed > 0);
  CHECK(kept > 0);
}

TEST_CASE("The 2D map holds each building in view once, from above, in the colour the 3D view gives it",
          "[scene][city][map2d]") {
  SceneRig rig;
  rig.open(0.0f);
  Viewer& viewer = rig.viewer;
  viewer.setColorMode(ColorMode::DamageState);
  viewer.setCamera(CameraState{0.0, 0.0, 700.0, 0.0, 90.0, 45.0});
  viewer.pause();
  runFrames(viewer, 20);
  REQUIRE(viewer.settled());
  Map2dFrame map;
  viewer.map2d(map);
  // The 8 x 8 buildings 40 m apart, one footprint ring each (a part each), inside the viewport.
  CHECK(map.shapes == 64);
  std::set<std::uint32_t> colours;
  std::size_t rings = 0;
  for (std::size_t i = 0; i + 1 < map.data.size();) {
    colours.insert(static_cast<std::uint32_t>(map.data[i]));
    const auto n = static_cast<std::size_t>(map.data[i + 1]);
    i += 2;
    REQUIRE((n == 1 || n >= 3));
    rings += n >= 3 ? 1u : 0u;
    for (std::size_t k = 0; k < n; ++k) {
      CHECK((map.data[i + 2 * k] >= 0.0f && map.data[i + 2 * k] <= 1280.0f));
      CHECK((map.data[i + 2 * k + 1] >= 0.0f && map.data[i + 2 * k + 1] <= 720.0f));
    }
    i += 2 * n;
  }
  CHECK(rings == 64);
  // Damage colours only: the palette's stops (or the no-result colour).
  std::set<std::uint32_t> palette{packRgb(kNoResultColor)};
  for (const Rgb& c : kDamagePalette) palette.insert(packRgb(c));
  for (const std::uint32_t c : colours) CHECK(palette.count(c) == 1);
  CHECK(colours.size() >= 2);
  // North up: a building east of another is drawn to its right.
  const auto east = viewer.worldToScreen(100.0, 0.0, 0.0);
  const auto west = viewer.worldToScreen(-100.0, 0.0, 0.0);
  REQUIRE((east && west));
  CHECK(east->x > west->x);

  // Far away each building is one dot.
  viewer.setCamera(CameraState{0.0, 0.0, 60000.0, 0.0, 90.0, 45.0});
  runFrames(viewer, 5);
  viewer.map2d(map);
  CHECK(map.shapes == 64);
  CHECK(map.points == 64);

  // A filter dims the buildings it leaves out: their colour fades towards the dimmed grey.
  viewer.setCamera(CameraState{0.0, 0.0, 700.0, 0.0, 90.0, 45.0});
  BuildingFilters only;
  only.minDamage = 4;
  viewer.city()->setFilters(only);
  runFrames(viewer, 5);
  viewer.map2d(map);
  std::size_t dimmed = 0;
  for (std::size_t i = 0; i + 1 < map.data.size();) {
    const auto c = static_cast<std::uint32_t>(map.data[i]);
    dimmed += palette.count(c) == 0 ? 1u : 0u;
    i += 2 + 2 * static_cast<std::size_t>(map.data[i + 1]);
  }
  CHECK(dimmed > 32);
}

TEST_CASE("A building's 2D colour is the shader's: modes, missing results, dimming and selection", "[scene][map2d]") {
  BuildingGpuRecord row;
  row.damageState = 2.0f;
  row.peakValue = 0.005f;
  row.lossCode = packLossCode(0.75f, 2.0f, 2);
  CHECK(packRgb(buildingRowColor(row, ColorMode::DamageState, 0, {}, {})) == packRgb(kDamagePalette[2]));
  CHECK(packRgb(buildingRowColor(row, ColorMode::PeakDrift, 0, {}, {})) == packRgb(kDamagePalette[2]));  // 0.5 % drift
  CHECK(packRgb(buildingRowColor(row, ColorMode::InspectionTag, 0, {}, {})) == packRgb(kTagPalette[2]));
  CHECK(packRgb(buildingRowColor(row, ColorMode::ModerateOrWorse, 0, {}, {})) == packRgb(kDamagePalette[3]));
  // Not animated and without a series, "drift now" shows the peak in greys, never a damage colour.
  CHECK(packRgb(buildingRowColor(row, ColorMode::CurrentDrift, 0, {}, {})) == packRgb(notAnimatedGrey(0.5f)));
  BuildingGpuRecord none = row;
  none.damageState = kDamageNoResult;
  CHECK(packRgb(buildingRowColor(none, ColorMode::DamageState, 0, {}, {})) == packRgb(kNoResultColor));
  BuildingGpuRecord noLoss = row;
  noLoss.lossCode = -1.0f;
  CHECK(packRgb(buildingRowColor(noLoss, ColorMode::ModerateOrWorse, 0, {}, {})) == packRgb(kNoResultColor));
  BuildingGpuRecord dim = row;
  dim.flags = static_cast<float>(kFlagDimmed);
  const Rgb d = buildingRowColor(dim, ColorMode::DamageState, 0, {}, {});
  CHECK(std::abs(d.r - (kDamagePalette[2].r + (kDimmedColor.r - kDamagePalette[2].r) * 0.85f)) < 1e-5f);
  BuildingGpuRecord selected = row;
  selected.flags = static_cast<float>(kFlagSelected);
  CHECK(packRgb(buildingRowColor(selected, ColorMode::DamageState, 0, {}, {})) !=
        packRgb(buildingRowColor(row, ColorMode::DamageState, 0, {}, {})));
  // Animated floor by floor: its largest storey drift now (1 % between the first two floors).
  std::vector<FloorGpuRecord> floors(3);
  floors[1].dxMeters = 0.03f;  // 3 m storeys: 1 % drift
  floors[2].dxMeters = 0.03f;
  BuildingGpuRecord moving = row;
  moving.floorBase = 0.0f;
  moving.storeys = 2.0f;
  CHECK(packRgb(buildingRowColor(moving, ColorMode::CurrentDrift, 0, {}, floors)) == packRgb(kDamagePalette[3]));
}
