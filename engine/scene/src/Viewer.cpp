#include "qv/scene/Viewer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "qv/core/JsonWriter.h"

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
}

bool Viewer::setCamera(const CameraState& camera) {
  CameraState next = camera;
  const bool valid = sanitizeCamera(next, camera_);
  camera_ = next;
  return valid;
}

bool Viewer::setTime(double seconds) {
  if (!std::isfinite(seconds)) return false;
  time_ = std::clamp(seconds, 0.0, duration_);
  return true;
}

void Viewer::reportError(std::string message) {
  // Keep the list bounded: a broken server must not grow memory without end.
  if (errors_.size() >= 200) errors_.erase(errors_.begin());
  errors_.push_back(std::move(message));
}

void Viewer::frame(double dtSeconds) {
  const auto frameStart = Clock::now();
  FrameTimesMs times;
  FrameCounts counts;

  controller_.update(dtSeconds);
  sanitizeCamera(camera_, controller_.home());
  if (playing_ && duration_ > 0.0 && std::isfinite(dtSeconds)) {
    time_ = std::fmod(time_ + std::max(0.0, dtSeconds) * speed_, duration_);
  }

  const CameraView view(camera_, widthPixels_, heightPixels_);
  std::vector<DrawItem> items;

  // Cull.
  auto t0 = Clock::now();
  std::vector<std::size_t> visible;
  if (test_) {
    for (std::size_t i = 0; i < test_->prisms.size(); ++i) {
      if (view.frustum().intersects(test_->prisms[i].bounds)) visible.push_back(i);
    }
    counts.buildingsLoaded = static_cast<std::uint32_t>(test_->prisms.size());
  }
  counts.buildingsVisible = static_cast<std::uint32_t>(visible.size());
  times.cull = msSince(t0);

  // LOD: the test scene animates every visible prism.
  t0 = Clock::now();
  counts.buildingsAnimated = counts.buildingsVisible;
  times.lod = msSince(t0);

  // Animate.
  t0 = Clock::now();
  if (test_) {
    test_->floors.clear();
    for (const TestPrism& p : test_->prisms) testPrismFloors(p, time_, test_->floors);
  }
  times.animate = msSince(t0);

  // Upload.
  t0 = Clock::now();
  if (test_) device_.writeFloors(0, test_->floors);
  times.upload = msSince(t0);

  // Render.
  t0 = Clock::now();
  FrameUniforms uniforms;
  uniforms.viewProjection = view.viewProjection();
  uniforms.eye = view.eye();
  uniforms.colorMode = colorMode_;
  uniforms.amplitude = amplitude_;
  uniforms.viewportWidth = widthPixels_;
  uniforms.viewportHeight = heightPixels_;
  if (test_) {
    uniforms.ground = Rect{-400.0f, -400.0f, 400.0f, 400.0f};
    for (std::size_t i : visible) items.push_back(DrawItem{test_->meshes[i], glm::vec3(0.0f)});
  }
  device_.render(uniforms, items);
  times.render = msSince(t0);

  const DeviceFrameStats device = device_.lastFrameStats();
  counts.drawCalls = device.drawCalls;
  counts.triangles = device.triangles;
  counts.uploadBytes = device.uploadBytes;
  times.total = msSince(frameStart);
  stats_.record(dtSeconds, times, counts);
  settled_ = true;
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
  w.key("tiles").beginObject();
  w.field("loaded", 0).field("pending", 0).field("failed", 0);
  w.endObject();
  w.field("heapBytes", memory.heapBytes);
  w.field("heapReservedBytes", memory.heapReservedBytes);
  w.field("uploadBytes", s.uploadBytes);
  w.field("timeSeconds", time_);
  w.endObject();
  return w.take();
}

std::optional<glm::dvec2> Viewer::worldToScreen(double x, double y, double z) const {
  const CameraView view(camera_, widthPixels_, heightPixels_);
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
