// Per-frame measurements made inside the engine, and their medians over recent frames: what
// `quakeview.stats()` and the Performance panel report.
#pragma once

#include <cstdint>

#include "qv/core/RollingStats.h"

namespace qv {

/// Milliseconds spent in each phase of one frame (CPU time on the frame loop's thread).
struct FrameTimesMs {
  double cull = 0.0;
  double lod = 0.0;
  double animate = 0.0;
  double upload = 0.0;
  double render = 0.0;
  double total = 0.0;
};

struct FrameCounts {
  std::uint32_t drawCalls = 0;
  std::uint64_t triangles = 0;
  std::uint64_t uploadBytes = 0;
  std::uint32_t buildingsLoaded = 0;
  std::uint32_t buildingsVisible = 0;
  /// Buildings whose drawing follows their history this frame: moved floor by floor, and (in the
  /// current-drift colours, Viewer::frame adds them) those coloured by their drift series.
  std::uint32_t buildingsAnimated = 0;
  std::uint32_t modelsAnimated = 0;  ///< of the moving ones LOD2 models (skinned to their floor bones)
  /// Buildings in view with a drift series that are not moved floor by floor (CityScene::update).
  std::uint32_t buildingsSeriesOnly = 0;
};

/// Medians (and 95th percentiles) over the last N frames.
struct StatsSummary {
  double fps = 0.0;
  FrameTimesMs frameMs;
  FrameTimesMs frameMsP95;
  double drawCalls = 0.0;
  double triangles = 0.0;
  double uploadBytes = 0.0;
  FrameCounts latest;
};

class FrameStats {
 public:
  explicit FrameStats(std::size_t window = 120);
  /// intervalSeconds: wall time since the previous frame began (for FPS).
  void record(double intervalSeconds, const FrameTimesMs& times, const FrameCounts& counts);
  [[nodiscard]] StatsSummary summary() const;
  [[nodiscard]] std::uint64_t frames() const { return frames_; }
  void clear();

 private:
  RollingStats interval_, cull_, lod_, animate_, upload_, render_, total_, drawCalls_, triangles_, upload_bytes_;
  FrameCounts latest_;
  std::uint64_t frames_ = 0;
};

}  // namespace qv
