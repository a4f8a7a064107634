#include "qv/scene/Bench.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "qv/core/JsonWriter.h"

namespace qv {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kOverviewShare = 0.35;  // of the flight, then the low pass

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  const std::size_t i = rank == 0 ? 0 : rank - 1;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v.end());
  return v[i];
}

void writeStat(JsonWriter& w, const char* name, const std::vector<double>& v) {
  w.key(name).beginObject().field("median", percentile(v, 0.5)).field("p95", percentile(v, 0.95)).endObject();
}

}  // namespace

BenchRun::BenchRun(double seconds, const Tileset* tileset, double fovDeg) : seconds_(std::max(seconds, 1.0)) {
  Rect bounds{-150.0f, -150.0f, 150.0f, 150.0f};
  double denseX = 0.0, denseY = 0.0;
  if (tileset != nullptr && !tileset->nodes.empty()) {
    bounds = tileset->bounds;
    // The densest area: the 500 m cell of a grid over the city holding the most buildings (leaves
    // counted at their centres), entered at the building-weighted centre of its leaves. (Per-leaf
    // density would pick a tiny leaf of two buildings at the city's edge.)
    constexpr double kCellM = 500.0;
    struct Cell {
      double buildings = 0.0, x = 0.0, y = 0.0;
    };
    std::map<std::pair<long, long>, Cell> cells;
    for (const TileNode& n : tileset->nodes) {
      if (!n.children.empty() || n.buildings == 0) continue;
      const double cx = n.bounds.centerX(), cy = n.bounds.centerY();
      Cell& c = cells[{std::lround(std::floor(cx / kCellM)), std::lround(std::floor(cy / kCellM))}];
      c.buildings += n.buildings;
      c.x += cx * n.buildings;
      c.y += cy * n.buildings;
    }
    double best = 0.0;
    for (const auto& [key, c] : cells) {
      if (c.buildings > best) {
        best = c.buildings;
        denseX = c.x / c.buildings;
        denseY = c.y / c.buildings;
      }
    }
  }
  const double size = std::max({static_cast<double>(bounds.width()), static_cast<double>(bounds.height()), 300.0});
  overview_.x = bounds.centerX();
  overview_.y = bounds.centerY();
  overview_.distance = size * 0.5 / std::tan(fovDeg * kPi / 360.0) * 1.15;
  overview_.pitchDeg = 50.0;
  overview_.headingDeg = 0.0;
  overview_.fovDeg = fovDeg;
  // The low pass crosses the densest area diagonally over up to 2 km.
  const double half = std::min(1000.0, size * 0.4);
  passX0_ = denseX - half * 0.7071;
  passY0_ = denseY - half * 0.7071;
  passX1_ = denseX + half * 0.7071;
  passY1_ = denseY + half * 0.7071;
  passHeading_ = 45.0;
}

CameraState BenchRun::cameraAt(double elapsed) const {
  const double f = std::clamp(elapsed / seconds_, 0.0, 1.0);
  CameraState c = overview_;
  if (f < kOverviewShare) {
    c.headingDeg = 60.0 * f / kOverviewShare;
    return c;
  }
  const double g = (f - kOverviewShare) / (1.0 - kOverviewShare);
  c.x = passX0_ + (passX1_ - passX0_) * g;
  c.y = passY0_ + (passY1_ - passY0_) * g;
  c.distance = 450.0;
  c.pitchDeg = 28.0;
  c.headingDeg = passHeading_;
  return c;
}

void BenchRun::record(double interval, const FrameTimesMs& t, const FrameCounts& c) {
  if (interval > 0.0) interval_.push_back(interval);
  cull_.push_back(t.cull);
  lod_.push_back(t.lod);
  animate_.push_back(t.animate);
  upload_.push_back(t.upload);
  render_.push_back(t.render);
  total_.push_back(t.total);
  drawCalls_.push_back(c.drawCalls);
  triangles_.push_back(static_cast<double>(c.triangles));
}

std::string BenchRun::resultJson() const {
  std::vector<double> fps;
  fps.reserve(interval_.size());
  for (double i : interval_) fps.push_back(1.0 / i);
  JsonWriter w;
  w.beginObject();
  w.field("seconds", seconds_).field("frames", static_cast<std::uint64_t>(total_.size()));
  writeStat(w, "fps", fps);
  w.key("frameMs").beginObject();
  writeStat(w, "cull", cull_);
  writeStat(w, "lod", lod_);
  writeStat(w, "animate", animate_);
  writeStat(w, "upload", upload_);
  writeStat(w, "render", render_);
  writeStat(w, "total", total_);
  w.endObject();
  writeStat(w, "drawCalls", drawCalls_);
  writeStat(w, "triangles", triangles_);
  w.endObject();
  return w.take();
}

}  // namespace qv
