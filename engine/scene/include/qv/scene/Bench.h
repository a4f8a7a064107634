// The benchmark mode (`?bench=SECONDS`): flies a fixed camera path — an overview of the whole city
// turning slowly, then a low pass through its densest area — while the animation plays, and
// reports per-frame figures measured inside the engine as {median, p95}.
#pragma once

#include <string>
#include <vector>

#include "qv/format/Tileset.h"
#include "qv/geometry/OrbitCamera.h"
#include "qv/scene/FrameStats.h"

namespace qv {

class BenchRun {
 public:
  /// `seconds` of flight over `tileset` (null: around the origin, as for the test scene).
  BenchRun(double seconds, const Tileset* tileset, double fovDeg);

  /// The camera for `elapsedSeconds` since the flight began.
  [[nodiscard]] CameraState cameraAt(double elapsedSeconds) const;
  void record(double frameIntervalSeconds, const FrameTimesMs& times, const FrameCounts& counts);
  [[nodiscard]] double seconds() const { return seconds_; }
  [[nodiscard]] std::size_t frames() const { return total_.size(); }
  /// {seconds, frames, fps, frameMs: {cull, lod, animate, upload, render, total}, drawCalls,
  /// triangles}, each value but seconds and frames as {median, p95}.
  [[nodiscard]] std::string resultJson() const;

 private:
  double seconds_;
  CameraState overview_;
  double passX0_ = 0, passY0_ = 0, passX1_ = 0, passY1_ = 0, passHeading_ = 0;
  std::vector<double> interval_, cull_, lod_, animate_, upload_, render_, total_, drawCalls_, triangles_;
};

}  // namespace qv
