// CityScene's animation: which buildings move floor by floor (those whose sway shows on screen,
// within the radius, most visible first, up to the cap) and their floors' displacements every
// frame, sampled from their response histories.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "CitySceneState.h"
#include "qv/anim/FloorDisplacements.h"
#include "qv/anim/HistorySampling.h"

namespace qv {

void CityScene::reindexAnimated() {
  for (const auto& t : tiles_) t->animatedCount = 0;
  for (std::size_t k = 0; k < animated_.size(); ++k) {
    TileRuntime& t = *tiles_[animated_[k]->ref.node];
    ++t.animatedCount;
    if (animated_[k]->ref.index < t.animatedIndex.size()) {
      t.animatedIndex[animated_[k]->ref.index] = static_cast<std::uint32_t>(k);
    }
  }
}

void CityScene::animate(const CameraView& view, double timeSeconds, FrameCounts& counts) {
  const std::uint64_t signature = findAnimationTiles(view);
  if (signature != animationSignature_ || animated_.empty() != animationTiles_.empty() ||
      samplers_.size() != animated_.size()) {
    animationSignature_ = signature;
    chooseAnimated(view, animationTiles_);
  }
  sampleFloors(timeSeconds);
  counts.buildingsAnimated += static_cast<std::uint32_t>(animated_.size());
  // In view with a drift series and not moved floor by floor (Viewer::frame counts them as
  // following their history in the current-drift colours).
  std::uint32_t movingWithSeries = 0;
  for (const auto& a : animated_) movingWithSeries += table_.row(a->slot).seriesBase >= 0.0f ? 1u : 0u;
  counts.buildingsSeriesOnly += seriesInView_ - std::min(seriesInView_, movingWithSeries);
  counts.modelsAnimated += modelsAnimated_;
}

std::uint64_t CityScene::findAnimationTiles(const CameraView& view) {
  const glm::vec3 eye = view.eye();
  const float radius = options_.animationRadiusM;
  // The tiles within the radius where a building's sway can show keep (or fetch) their histories
  // this frame. What they animate is chosen again only when something it depends on changed: the
  // eye, the radius, the cap, the amplitude, a tile's residency or visible set. A still camera
  // while playing costs only the sampling below.
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
  mix(bitsOf(swayAmplitude_));
  mix(bitsOf(options_.swayPixels));
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
      // No building of the tile sways a pixel from here (known once its summary is there).
      if (t.maxRoofM >= 0.0f &&
          t.maxRoofM * swayAmplitude_ * view.pixelsPerMeterAt(std::max(tileDistance, 1.0f)) < options_.swayPixels) {
        continue;
      }
      requestHistory(i);
      t.historyUsed = frame_;
      if (t.historyLoad.state != TileState::Loaded) continue;
      inRadius.push_back(i);
      mix(i);
      mix(bitsOf(t.maxRoofM));  // its summary's arrival changes whose sway shows
    }
  }
  return signature;
}

void CityScene::sampleFloors(double timeSeconds) {
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
}

void CityScene::chooseAnimated(const CameraView& view, const std::vector<std::uint32_t>& tiles) {
  keepAnimated(animationCandidates(view, tiles));
  packSamplers();
}

std::vector<CityScene::AnimationCandidate> CityScene::animationCandidates(
    const CameraView& view, const std::vector<std::uint32_t>& tiles) const {
  using Candidate = AnimationCandidate;
  const glm::vec3 eye = view.eye();
  const float radius = options_.animationRadiusM;
  std::vector<Candidate> candidates;
  const double r2 = static_cast<double>(radius) * radius;
  for (std::uint32_t i : tiles) {
    const TileRuntime& t = *tiles_[i];
    const LoadedTile& tile = *t.loaded;
    const bool summary = t.summary && t.summary->buildings.size() == tile.data.buildings.size();
    for (const IndexRange& range : t.visible) {
      for (std::uint32_t p = range.begin; p < range.end; ++p) {
        const std::uint32_t b = tile.tree.order()[p];
        const BuildingAttributes& a = tile.data.buildings[b].attributes;
        // Distance from the eye to the building's axis at mid-height.
        const double cx = a.centroidX + tile.data.originX - static_cast<double>(eye.x);
        const double cy = a.centroidY + tile.data.originY - static_cast<double>(eye.y);
        const double cz = 0.5 * static_cast<double>(a.heightM + a.minHeightM) - static_cast<double>(eye.z);
        const double d2 = cx * cx + cy * cy + cz * cz;
        if (d2 > r2 || t.history->buildings[b].floors != a.storeys) continue;
        // Its sway on screen: the peak roof displacement, exaggerated, at its distance (without
        // a summary yet, as if it showed: the nearest then come first).
        const auto d = static_cast<float>(std::sqrt(d2));
        const float roof = summary ? t.summary->buildings[b].peakRoofDisplacementM : 1.0f;
        const float pixels = roof * swayAmplitude_ * view.pixelsPerMeterAt(std::max(d, 1.0f));
        if (pixels >= options_.swayPixels) candidates.push_back({pixels, i, b, p});
      }
    }
  }
  if (candidates.size() > options_.maxAnimatedBuildings) {
    std::nth_element(candidates.begin(),
                     candidates.begin() + static_cast<std::ptrdiff_t>(options_.maxAnimatedBuildings), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.swayPixels > b.swayPixels; });
    candidates.resize(options_.maxAnimatedBuildings);
  }
  return candidates;
}

void CityScene::keepAnimated(const std::vector<AnimationCandidate>& candidates) {
  using Candidate = AnimationCandidate;
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
  if (released) animated_.erase(std::remove(animated_.begin(), animated_.end(), nullptr), animated_.end());
  reindexAnimated();  // also each tile's count, which decides its walls (CityScene::cull)
}

void CityScene::packSamplers() {
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

}  // namespace qv
