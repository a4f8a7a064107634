#include "qv/scene/Viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "qv/core/JsonWriter.h"
#include "qv/scene/FlyToPose.h"

namespace qv {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

struct Viewer::TestContent {
  std::vector<TestPrism> prisms;
  std::vector<MeshHandle> meshes;
  std::vector<FloorGpuRecord> floors;
  std::vector<std::uint32_t> floorBase;  // per prism
};

Viewer::Viewer(RenderDevice& device) : device_(device), controller_(camera_) {}

Viewer::~Viewer() {
  if (test_) {
    for (MeshHandle m : test_->meshes) device_.destroyMesh(m);
  }
}

void Viewer::showTestScene() {
  test_ = std::make_unique<TestContent>();
  test_->prisms = makeTestPrisms();
  std::vector<BuildingGpuRecord> records;
  std::uint32_t floorBase = 0;
  for (const TestPrism& p : test_->prisms) {
    test_->meshes.push_back(device_.createMesh(p.mesh));
    BuildingGpuRecord r;
    r.storeyHeightMeters = p.storeyHeight;
    r.storeys = static_cast<float>(p.storeys);
    r.floorBase = static_cast<float>(floorBase);
    r.peakValue = p.swayRatio;
    r.damageState = static_cast<float>(std::min(4, static_cast<int>(p.swayRatio * 200.0f)));
    records.push_back(r);
    test_->floorBase.push_back(floorBase);
    floorBase += static_cast<std::uint32_t>(p.storeys + 1);
  }
  device_.writeBuildings(0, records);
  duration_ = 20.0;
  time_ = 0.0;
  loop_ = true;  // the test prisms sway on and on
  // A three-quarter view from the south-west that shows every prism.
  camera_ = CameraState{0.0, -5.0, 420.0, 30.0, 35.0, 45.0};
  controller_.setHome(camera_);
}

void Viewer::setViewport(int widthPixels, int heightPixels, double widthCss, double heightCss) {
  widthPixels_ = std::max(1, widthPixels);
  heightPixels_ = std::max(1, heightPixels);
  widthCss_ = std::max(1.0, widthCss);
  heightCss_ = std::max(1.0, heightCss);
  controller_.setViewport(widthCss, heightCss);
  controller_.setLensShift(lensShift());
}

void Viewer::openCity(const std::string& manifestUrl, Fetcher& fetcher, const CitySceneOptions& options) {
  fetcher_ = &fetcher;
  scenarios_.reset();  // another city folder: its catalogue comes with its manifest
  switch_ = ScenarioSwitch{switch_.serial, 0, ScenarioSwitch::State::None, {}};
  pendingSelection_.clear();
  previousManifestUrl_.clear();
  keepEndAfterSwitch_ = false;
  framingKept_ = false;
  createCity(manifestUrl, options);
  dataSource_ = dataOriginProblem(options.origin).empty() ? dataOriginDescription(options.origin) : std::string();
}

void Viewer::createCity(const std::string& url, const CitySceneOptions& options) {
  manifestUrl_ = url;
  // The city shown gives back its meshes and table rows before the next one takes their place.
  city_.reset();
  city_ = std::make_unique<CityScene>(device_, *fetcher_, url, options,
                                      [this](const LoadError& e) { addError(e.message, e.key, true); });
  city_->setResolvedSink([this](const std::string& key) { withdrawErrors(key); });
  cityFramed_ = false;
  settled_ = false;
  shownDistrict_.clear();
}

void Viewer::switchCity(const std::string& url) {
  // What the person set up stays: the camera, the time (Viewer members), the filters, the levels
  // of detail shown, the detail settings and the selection (applied once the new city knows it).
  const CitySceneOptions options = city_->options();
  const BuildingFilters filters = city_->filters();
  const bool lod1 = city_->showLod1();
  const bool lod2 = city_->showLod2();
  if (!city_->selected().empty()) pendingSelection_ = city_->selected();
  keepEndAfterSwitch_ = ended();
  // The old city's messages (its files' failures) go with it; the catalogue's and the link's stay.
  for (std::size_t i = errors_.size(); i-- > 0;) {
    if (!errorOfCity_[i]) continue;
    errors_.erase(errors_.begin() + static_cast<std::ptrdiff_t>(i));
    errorKeys_.erase(errorKeys_.begin() + static_cast<std::ptrdiff_t>(i));
    errorOfCity_.erase(errorOfCity_.begin() + static_cast<std::ptrdiff_t>(i));
  }
  createCity(url, options);
  city_->setFilters(filters);
  city_->setLodVisibility(lod1, lod2);
  cameraSetByUser_ = true;  // the first frame of the new manifest keeps the camera
  framingKept_ = true;      // and the view's place beside the panel
  openingTimeSet_ = true;   // and the time
  if (scenarios_) scenarios_->setOpen(url, nullptr);
}

std::uint64_t Viewer::selectScenario(std::uint32_t index, std::string* problem) {
  const auto refuse = [problem](std::string why) -> std::uint64_t {
    if (problem != nullptr) *problem = std::move(why);
    return 0;
  };
  if (!scenarios_ || scenarios_->state() == CityScenarios::CatalogueState::Loading) {
    return refuse("the city's scenario list has not loaded yet");
  }
  if (!scenarios_->available()) return refuse("this city has no scenario list (scenarios.json beside its manifest)");
  const ScenarioStatus* s = scenarios_->find(index);
  if (s == nullptr) return refuse("the city's scenario list has no scenario " + std::to_string(index));
  switch_ = ScenarioSwitch{switch_.serial + 1, index, ScenarioSwitch::State::Checking, {}};
  if (s->entry.manifest == urlFileName(manifestUrl_)) {
    switch_.state = ScenarioSwitch::State::Loading;  // shown already: only wait for it to load
  } else if (s->state != ScenarioState::Ready) {
    scenarios_->check(index);  // written since it was looked at, perhaps
  }
  // The city is replaced in the next frame (advanceScenarios), never in the middle of one: the
  // panel calling this holds the current city.
  return switch_.serial;
}

void Viewer::advanceScenarios() {
  if (!city_) return;
  // A selection kept over a switch: once the new city knows the building (a loaded tile or its
  // index); given up when it never will.
  if (!pendingSelection_.empty() && city_->manifestLoaded()) {
    if (!city_->selected().empty() || city_->select(pendingSelection_) || (settled_ && city_->searchIndexSettled())) {
      pendingSelection_.clear();  // selected meanwhile (the person chose another), applied, or unknown
    }
  }
  const auto fail = [this](std::string problem) {
    switch_.state = ScenarioSwitch::State::Failed;
    switch_.problem = std::move(problem);
  };
  const ScenarioStatus* s = scenarios_ ? scenarios_->find(switch_.index) : nullptr;
  if (switch_.state == ScenarioSwitch::State::Checking) {
    if (s == nullptr) {
      fail("scenario " + std::to_string(switch_.index) + " is no longer listed");
    } else if (s->state == ScenarioState::Ready) {
      const std::string url = scenarios_->manifestUrl(s->entry);
      withdrawErrors(url);
      previousManifestUrl_ = manifestUrl_;
      switchCity(url);
      switch_.state = ScenarioSwitch::State::Loading;
    } else if (s->state == ScenarioState::NotReady || s->state == ScenarioState::Broken) {
      fail("Scenario " + std::to_string(s->entry.index) + " \"" + s->entry.name + "\" cannot be shown" +
           (s->state == ScenarioState::NotReady ? " yet" : "") + ": " + s->problem + ".");
      reportError(switch_.problem, scenarios_->manifestUrl(s->entry));
    }
  } else if (switch_.state == ScenarioSwitch::State::Loading) {
    const Tileset* tileset = city_->tileset();
    if (city_->manifestFailed()) {
      // Checked a moment ago, gone or broken since: said so, and the scenario shown before comes back.
      std::string why = "its manifest could not be loaded";
      for (std::size_t i = errors_.size(); i-- > 0;) {
        if (errorOfCity_[i]) {
          why = errors_[i];
          break;
        }
      }
      const std::string name = s != nullptr ? " \"" + s->entry.name + "\"" : std::string();
      fail("Scenario " + std::to_string(switch_.index) + name + " could not be opened: " + why);
      reportError(switch_.problem, manifestUrl_);
      if (!previousManifestUrl_.empty() && previousManifestUrl_ != manifestUrl_) switchCity(previousManifestUrl_);
    } else if (tileset != nullptr && cityFramed_ && settled_) {
      // Its totals too: consequences() reports the scenario shown, not nothing.
      const bool totals = !tileset->response || !tileset->response->consequences || city_->consequences() != nullptr ||
                          city_->consequencesFailed();
      if (totals) switch_.state = ScenarioSwitch::State::Loaded;
    }
  }
  // The other scenarios' manifests, one at a time, once the view has what it needs.
  if (scenarios_ && settled_ && switch_.state != ScenarioSwitch::State::Loading) scenarios_->checkNext();
}

void Viewer::startBench(double seconds) {
  benchSeconds_ = std::clamp(seconds, 1.0, 3600.0);
  loop_ = true;  // a flight longer than the record keeps measuring a moving city
  bench_.reset();
  benchResult_.clear();
}

bool Viewer::setCamera(const CameraState& camera) {
  cameraSetByUser_ = true;
  flight_.reset();
  CameraState next = camera;
  const bool valid = sanitizeCamera(next, camera_);
  camera_ = next;
  return valid;
}

void Viewer::play() {
  if (ended()) {
    // Again from the opening moment: a second before the shaking arrives.
    const std::optional<double> arrival = city_ ? city_->firstShakingSeconds() : std::nullopt;
    time_ = arrival ? std::clamp(*arrival - 1.0, 0.0, duration_) : 0.0;
  }
  playing_ = true;
}

ColorMode Viewer::shownColorMode() const {
  if (colorMode_ != ColorMode::CurrentDrift || !damageAfterShaking_ || !ended() || !city_) return colorMode_;
  const Tileset* tileset = city_->tileset();
  const bool probabilities = tileset != nullptr && tileset->response && tileset->response->consequences;
  return probabilities ? ColorMode::ModerateOrWorse : colorMode_;
}

bool Viewer::setTime(double seconds) {
  if (!std::isfinite(seconds)) return false;
  time_ = std::clamp(seconds, 0.0, duration_);
  timeChosen_ = true;
  return true;
}

void Viewer::setFramingInsetCss(double left, double widestLeft) {
  widestInsetCss_ = std::isfinite(widestLeft) ? widestLeft : -1.0;
  const double inset = std::isfinite(left) ? std::max(left, 0.0) : 0.0;
  // The panel's width follows its content (the consequences arriving, a section opened): once the
  // city is framed the view keeps its place unless the inset changes by more than
  // kFramingInsetStepCss (another layout), so the city does not slide sideways under the user.
  if ((cityFramed_ || framingKept_) && std::abs(inset - framingInsetCss_) <= kFramingInsetStepCss) return;
  framingInsetCss_ = inset;
  controller_.setLensShift(lensShift());
}

float Viewer::lensShift() const {
  // The centre of the part right of the panels: inset / width in normalized device units.
  const double inset = std::min(framingInsetCss_, widthCss_ * 0.6);
  return widthCss_ > 0.0 && inset > 0.0 ? static_cast<float>(inset / widthCss_) : 0.0f;
}

void Viewer::withdrawErrors(const std::string& key) {
  if (key.empty()) return;
  for (std::size_t i = errors_.size(); i-- > 0;) {
    if (errorKeys_[i] != key) continue;
    errors_.erase(errors_.begin() + static_cast<std::ptrdiff_t>(i));
    errorKeys_.erase(errorKeys_.begin() + static_cast<std::ptrdiff_t>(i));
    errorOfCity_.erase(errorOfCity_.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

void Viewer::reportError(std::string message, std::string key) {
  addError(std::move(message), std::move(key), false);
}

void Viewer::addError(std::string message, std::string key, bool ofCity) {
  // Keep the list bounded: a broken server must not grow memory without end.
  if (errors_.size() >= 200) {
    errors_.erase(errors_.begin());
    errorKeys_.erase(errorKeys_.begin());
    errorOfCity_.erase(errorOfCity_.begin());
  }
  errors_.push_back(std::move(message));
  errorKeys_.push_back(std::move(key));
  errorOfCity_.push_back(ofCity);
}

void Viewer::frameCityOnce() {
  if (!city_ || !city_->manifestLoaded() || cityFramed_) return;
  // The first frame with the manifest: the duration, and a camera that frames the whole city.
  cityFramed_ = true;
  duration_ = city_->duration();
  // Another scenario's record may be shorter: the time stays within it, and at its end when the
  // last one had ended (the city then shows its damage, as before the switch).
  time_ = keepEndAfterSwitch_ ? duration_ : std::min(time_, duration_);
  keepEndAfterSwitch_ = false;
  CameraState overview = city_->overviewCamera(camera_.fovDeg);
  // The panels cover the left of the canvas: the lens shift (lensShift) puts the city's centre in
  // the middle of the rest; seen from a little farther, it still fits there, also beside the
  // widest panel the layout allows (the same first view whenever the panel's content arrives).
  const double widest = widestInsetCss_ >= 0.0 ? std::min(widestInsetCss_, widthCss_ * 0.6) : -1.0;
  const double shift = widest >= 0.0 && widthCss_ > 0.0 ? widest / widthCss_ : static_cast<double>(lensShift());
  overview.distance *= 1.0 + 0.5 * shift;
  controller_.setHome(overview);
  if (!cameraSetByUser_) camera_ = overview;
  if (const Tileset* tileset = city_->tileset()) geo_ = GeoFrame(tileset->originLon, tileset->originLat);
  // The city folder's scenarios, once its manifest is there (the catalogue is kept while switching
  // between them).
  if (!scenarios_ && fetcher_ != nullptr) {
    scenarios_ = std::make_unique<CityScenarios>(
        *fetcher_, manifestUrl_,
        [this](const std::string& message, const std::string& key) { reportError(message, key); },
        city_->options().requestTimeoutMs);
  }
  if (scenarios_) scenarios_->setOpen(manifestUrl_, city_->tileset());
}

void Viewer::advanceBench(double dtSeconds) {
  if (benchSeconds_ <= 0.0 || !benchResult_.empty()) return;
  // The flight starts on the first frame after the initial view has loaded.
  if (!bench_ && settled_) {
    bench_ = std::make_unique<BenchRun>(benchSeconds_, city_ ? city_->tileset() : nullptr, camera_.fovDeg);
    benchElapsed_ = 0.0;
    playing_ = true;
  } else if (bench_) {
    benchElapsed_ += std::max(0.0, dtSeconds);
  }
  if (bench_) camera_ = bench_->cameraAt(benchElapsed_);
}

void Viewer::advanceFlight(double dtSeconds) {
  if (!flight_) return;
  // Ease in and out; any gesture ends the flight.
  if (controller_.dragging()) {
    flight_.reset();
    return;
  }
  flight_->elapsed += std::max(0.0, dtSeconds);
  const double f = std::clamp(flight_->elapsed / flight_->duration, 0.0, 1.0);
  const double s = f * f * (3.0 - 2.0 * f);
  const CameraState& a = flight_->from;
  const CameraState& b = flight_->to;
  camera_.x = a.x + (b.x - a.x) * s;
  camera_.y = a.y + (b.y - a.y) * s;
  // Distance interpolates geometrically (zooming feels even).
  camera_.distance = a.distance * std::pow(b.distance / a.distance, s);
  // Heading the short way round, pitch linearly (Fly to may choose another side and height).
  const double turn = std::remainder(b.headingDeg - a.headingDeg, 360.0);
  camera_.headingDeg = std::fmod(a.headingDeg + turn * s + 360.0, 360.0);
  camera_.pitchDeg = a.pitchDeg + (b.pitchDeg - a.pitchDeg) * s;
  if (f >= 1.0) flight_.reset();
}

void Viewer::frameTestScene(const CameraView& view, FrameTimesMs& times, FrameCounts& counts,
                            std::vector<DrawItem>& items, FrameUniforms& uniforms) {
  auto t0 = Clock::now();
  std::vector<std::size_t> visible;
  for (std::size_t i = 0; i < test_->prisms.size(); ++i) {
    if (view.frustum().intersects(test_->prisms[i].bounds)) visible.push_back(i);
  }
  counts.buildingsLoaded = static_cast<std::uint32_t>(test_->prisms.size());
  counts.buildingsVisible = static_cast<std::uint32_t>(visible.size());
  times.cull = msSince(t0);
  // The test scene animates every visible prism: no LOD work.
  counts.buildingsAnimated = counts.buildingsVisible;
  t0 = Clock::now();
  test_->floors.clear();
  for (const TestPrism& p : test_->prisms) testPrismFloors(p, time_, test_->floors);
  times.animate = msSince(t0);
  t0 = Clock::now();
  device_.writeFloors(0, test_->floors);
  times.upload = msSince(t0);
  uniforms.ground = Rect{-400.0f, -400.0f, 400.0f, 400.0f};
  for (std::size_t i : visible) items.push_back(DrawItem{test_->meshes[i], glm::vec3(0.0f), {}});
}

void Viewer::frame(double dtSeconds) {
  const auto frameStart = Clock::now();
  FrameTimesMs times;
  FrameCounts counts;

  frameCityOnce();
  advanceBench(dtSeconds);
  advanceFlight(dtSeconds);
  controller_.update(dtSeconds);
  sanitizeCamera(camera_, controller_.home());
  if (playing_ && duration_ > 0.0 && std::isfinite(dtSeconds)) {
    time_ += std::max(0.0, dtSeconds) * speed_;
    if (time_ >= duration_) {
      if (loop_) {
        time_ = std::fmod(time_, duration_);
      } else {
        time_ = duration_;  // the end: the shaking is over, the city shows its damage
        playing_ = false;
      }
    }
  }

  const CameraView view(camera_, widthPixels_, heightPixels_, lensShift());
  std::vector<DrawItem> items;
  FrameUniforms uniforms;

  if (test_) frameTestScene(view, times, counts, items, uniforms);
  if (city_) {
    // The first view plays from the moment the shaking arrives (a second before it), unless a
    // link or the user chose the time.
    if (!openingTimeSet_ && !timeChosen_) {
      if (const std::optional<double> arrival = city_->firstShakingSeconds()) {
        time_ = std::clamp(*arrival - 1.0, 0.0, duration_);
        openingTimeSet_ = true;
      }
    }
    city_->setSwayAmplitude(amplitude_);
    city_->update(view, time_, times, counts, items);
    // Drawn in the current-drift colours, the buildings with a drift series follow their history
    // too (coloured by their drift at this time), not only those moved floor by floor.
    if (shownColorMode() == ColorMode::CurrentDrift) counts.buildingsAnimated += counts.buildingsSeriesOnly;
    uniforms.showModels = city_->showLod2();
    markers_.clear();
    city_->mapMarkers(widthCss_ > 0.0 ? static_cast<float>(widthPixels_ / widthCss_) : 1.0f, markers_);
    uniforms.markers = markers_;
    uniforms.groundItems = city_->groundItems();
    if (const Tileset* t = city_->tileset()) {
      // Ground under the whole city with a margin.
      const float margin = std::max(t->bounds.width(), t->bounds.height()) * 0.5f + 2000.0f;
      uniforms.ground =
          Rect{t->bounds.minX - margin, t->bounds.minY - margin, t->bounds.maxX + margin, t->bounds.maxY + margin};
    }
  }

  // Render.
  const auto t0 = Clock::now();
  uniforms.viewProjection = view.viewProjection();
  uniforms.eye = view.eye();
  uniforms.colorMode = shownColorMode();
  uniforms.amplitude = amplitude_;
  uniforms.timeSeconds = static_cast<float>(time_);
  uniforms.viewportWidth = widthPixels_;
  uniforms.viewportHeight = heightPixels_;
  device_.render(uniforms, items);
  times.render = msSince(t0);

  const DeviceFrameStats device = device_.lastFrameStats();
  counts.drawCalls = device.drawCalls;
  counts.triangles = device.triangles;
  counts.uploadBytes = device.uploadBytes;
  times.total = msSince(frameStart);
  stats_.record(dtSeconds, times, counts);
  if (bench_ && benchResult_.empty()) {
    if (benchElapsed_ > 0.0) bench_->record(dtSeconds, times, counts);
    if (benchElapsed_ >= bench_->seconds()) benchResult_ = bench_->resultJson();
  }
  settled_ = city_ ? (city_->manifestFailed() || (cityFramed_ && city_->settled())) : true;
  advanceScenarios();
}

void Viewer::setMeasuredHeapBytes(std::uint64_t bytes) {
  if (city_) city_->setMeasuredHeapBytes(bytes);
}

std::string Viewer::statsJson(const MemoryInfo& memory) const {
  const StatsSummary s = stats_.summary();
  JsonWriter w;
  w.beginObject();
  w.field("fps", s.fps);
  w.key("frameMs").beginObject();
  w.field("cull", s.frameMs.cull).field("lod", s.frameMs.lod).field("animate", s.frameMs.animate);
  w.field("upload", s.frameMs.upload).field("render", s.frameMs.render).field("total", s.frameMs.total);
  w.endObject();
  w.field("drawCalls", s.drawCalls);
  w.field("triangles", s.triangles);
  w.key("buildings").beginObject();
  w.field("loaded", s.latest.buildingsLoaded).field("visible", s.latest.buildingsVisible);
  w.field("animated", s.latest.buildingsAnimated);
  w.endObject();
  const TileCounts tiles = city_ ? city_->tileCounts() : TileCounts{};
  w.key("tiles").beginObject();
  w.field("loaded", tiles.loaded).field("pending", tiles.pending).field("failed", tiles.failed);
  w.field("drawn", tiles.drawn).field("drawLimited", tiles.drawLimited).field("memoryLimited", tiles.memoryLimited);
  w.endObject();
  w.field("heapBytes", memory.heapBytes);
  w.field("heapReservedBytes", memory.heapReservedBytes);
  // What the scene counts against its budget, by part (the heap also holds what it does not
  // count: the panels, the animation's tables, the allocator's own overhead).
  const MemoryUse use = city_ ? city_->memoryUse() : MemoryUse{};
  w.key("memory").beginObject();
  w.field("budgetBytes", city_ ? city_->memoryBudgetBytes() : 0);
  w.field("countedBytes", use.total()).field("indexBytes", use.index).field("tilesBytes", use.tilesCpu);
  w.field("meshBytes", use.tilesGpu).field("historyBytes", use.histories).field("groundBytes", use.ground);
  w.field("tableSlackBytes", use.tableSlack).field("otherHeapBytes", use.otherHeap);
  w.endObject();
  w.field("uploadBytes", s.uploadBytes);
  w.field("timeSeconds", time_);
  w.endObject();
  return w.take();
}

std::optional<BuildingInfo> Viewer::pick(double cssX, double cssY) const {
  if (!city_) return std::nullopt;
  const CameraView view(camera_, widthPixels_, heightPixels_, lensShift());
  glm::vec3 origin, direction;
  view.ray(cssX * widthPixels_ / widthCss_, cssY * heightPixels_ / heightCss_, origin, direction);
  const auto ref = city_->pick(origin, direction);
  if (!ref) return std::nullopt;
  // The building hit, described from its most detailed loaded copy (as building(id) does): a far
  // view picks on a coarse tile's simplified copy, which lacks names and addresses.
  const auto picked = city_->info(*ref);
  if (!picked) return std::nullopt;
  return building(picked->attributes.id);
}

std::optional<BuildingInfo> Viewer::building(const std::string& id) const {
  if (!city_) return std::nullopt;
  const auto ref = city_->find(id);
  if (!ref) return std::nullopt;
  return city_->info(*ref);
}

bool Viewer::select(const std::string& id) {
  return city_ && city_->select(id);
}

const std::string& Viewer::selection() const {
  static const std::string kNone;
  return city_ ? city_->selected() : kNone;
}

void Viewer::flyTo(double x, double y, double distance) {
  CameraState to = camera_;
  to.x = x;
  to.y = y;
  to.distance = distance;
  sanitizeCamera(to, camera_);
  flight_ = Flight{camera_, to, 0.0, 1.2};
  cameraSetByUser_ = true;
}

namespace {

const seismic::ConsequenceTotals::District* findDistrict(const CityScene* city, const std::string& name) {
  const seismic::ConsequenceTotals* file = city != nullptr ? city->consequences() : nullptr;
  if (file == nullptr || name.empty()) return nullptr;
  for (const seismic::ConsequenceTotals::District& d : file->districts) {
    if (d.name == name && !d.outline.empty()) return &d;
  }
  return nullptr;
}

}  // namespace

const std::vector<std::vector<glm::dvec2>>& Viewer::shownDistrictOutline() const {
  // Projected once per district shown (an outline may hold up to 20,000 points), again only when
  // the consequences it came from were loaded anew.
  const seismic::ConsequenceTotals::District* d = geo_.valid() ? findDistrict(city_.get(), shownDistrict_) : nullptr;
  if (d == outlineSource_) return outline_;
  outlineSource_ = d;
  outline_.clear();
  if (d == nullptr) return outline_;
  for (const auto& ring : d->outline) {
    std::vector<glm::dvec2>& out = outline_.emplace_back();
    out.reserve(ring.size());
    for (const auto& p : ring) out.push_back(geo_.forwardUnchecked(LonLat{p[0], p[1]}));
  }
  return outline_;
}

bool Viewer::showDistrict(const std::string& name) {
  if (name.empty()) {
    shownDistrict_.clear();
    return true;
  }
  const seismic::ConsequenceTotals::District* d = findDistrict(city_.get(), name);
  if (d == nullptr || !geo_.valid()) return false;
  shownDistrict_ = name;
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  for (const std::vector<glm::dvec2>& ring : shownDistrictOutline()) {
    for (const glm::dvec2& p : ring) {
      minX = std::min(minX, p.x);
      minY = std::min(minY, p.y);
      maxX = std::max(maxX, p.x);
      maxY = std::max(maxY, p.y);
    }
  }
  if (!(minX <= maxX && minY <= maxY)) return false;
  // The outline's larger side across about two thirds of the view (the lens shift keeps the panel's
  // side clear), seen from the current heading and pitch.
  const double extent = std::max({maxX - minX, maxY - minY, 50.0});
  const double halfFov = 0.5 * camera_.fovDeg * 3.14159265358979 / 180.0;
  flyTo(0.5 * (minX + maxX), 0.5 * (minY + maxY), 0.75 * extent / std::tan(halfFov));
  return true;
}

std::optional<ViewArea> Viewer::viewArea() const {
  if (city_ == nullptr || !city_->viewBox() || !geo_.valid()) return std::nullopt;
  const std::array<double, 4>& box = *city_->viewBox();
  const auto southWest = geo_.reverse({box[0], box[1]});
  const auto northEast = geo_.reverse({box[2], box[3]});
  if (!southWest || !northEast) return std::nullopt;
  // Transverse Mercator bends meridians: the box's other corners may reach a little further.
  const auto northWest = geo_.reverse({box[0], box[3]});
  const auto southEast = geo_.reverse({box[2], box[1]});
  ViewArea a;
  a.west = std::min(southWest->lon, northWest ? northWest->lon : southWest->lon);
  a.east = std::max(northEast->lon, southEast ? southEast->lon : northEast->lon);
  a.south = std::min(southWest->lat, southEast ? southEast->lat : southWest->lat);
  a.north = std::max(northEast->lat, northWest ? northWest->lat : northEast->lat);
  return a;
}

bool Viewer::flyToSelection() {
  const auto info = building(selection());
  FlyToTarget target;
  if (info) {
    target.x = info->attributes.centroidX;
    target.y = info->attributes.centroidY;
    target.baseZ = info->attributes.minHeightM;
    target.topZ = info->attributes.heightM;
    target.footprintAreaM2 = info->attributes.footprintAreaM2;
  } else {
    // Not loaded yet (a large city's far view holds only its largest buildings): the index knows where.
    const SearchEntry* e = city_ ? city_->indexEntry(selection()) : nullptr;
    if (e == nullptr) return false;
    target.x = e->x;
    target.y = e->y;
    target.topZ = e->heightM;
  }
  // From the side where no loaded building stands between the eye and the building (FlyToPose.h).
  const double reach = flyToDistance(target.topZ, target.footprintAreaM2);
  const std::vector<Box> occluders =
      city_ ? city_->buildingBoxesNear(target.x, target.y, reach, selection()) : std::vector<Box>{};
  flyToPose(chooseFlyToPose(camera_, target, occluders).camera);
  return true;
}

void Viewer::flyToPose(const CameraState& pose) {
  CameraState to = pose;
  sanitizeCamera(to, camera_);
  flight_ = Flight{camera_, to, 0.0, 1.2};
  cameraSetByUser_ = true;
}

std::optional<glm::dvec2> Viewer::groundAt(double cssX, double cssY) const {
  const CameraView view(camera_, widthPixels_, heightPixels_, lensShift());
  return view.groundPoint(cssX * widthPixels_ / widthCss_, cssY * heightPixels_ / heightCss_);
}

double Viewer::metresPerCssPixel() const {
  const CameraView view(camera_, widthPixels_, heightPixels_, lensShift());
  return static_cast<double>(widthPixels_) / widthCss_ /
         static_cast<double>(view.pixelsPerMeterAt(static_cast<float>(camera_.distance)));
}

void Viewer::map2d(Map2dFrame& out) const {
  out.clear();
  if (!city_) return;
  const CameraView view(camera_, widthPixels_, heightPixels_, lensShift());
  city_->map2d(view, widthPixels_ > 0 ? widthCss_ / widthPixels_ : 1.0, shownColorMode(), time(), out);
}

glm::mat4 Viewer::viewProjection() const {
  return CameraView(camera_, widthPixels_, heightPixels_, lensShift()).viewProjection();
}

std::optional<glm::dvec2> Viewer::worldToScreen(double x, double y, double z) const {
  const CameraView view(camera_, widthPixels_, heightPixels_, lensShift());
  const auto p = view.project(glm::vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
  if (!p) return std::nullopt;
  return glm::dvec2(static_cast<double>(p->x) * widthCss_ / widthPixels_,
                    static_cast<double>(p->y) * heightCss_ / heightPixels_);
}

std::string Viewer::cameraJson() const {
  JsonWriter w;
  w.beginObject();
  w.field("x", camera_.x).field("y", camera_.y).field("distance", camera_.distance);
  w.field("headingDeg", camera_.headingDeg).field("pitchDeg", camera_.pitchDeg).field("fovDeg", camera_.fovDeg);
  w.endObject();
  return w.take();
}

}  // namespace qv
