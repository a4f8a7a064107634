// CityScene's memory: what each tile holds (measured once loaded, estimated before), and eviction
// beyond the memory budget (histories outside the animation radius first, then the least recently
// used tiles, then the coarse tiles the view replaced).
#include <algorithm>

#include "CitySceneState.h"

namespace qv {

void CityScene::noteMeasuredHeap() {
  if (measuredHeap_ == 0) return;
  // What the parts count of the heap (not the meshes, which the device holds), against what it is.
  MemoryUse use = memoryUse();
  use.otherHeap = 0;
  const std::uint64_t counted = use.total() - use.tilesGpu;
  const std::uint64_t uncounted = measuredHeap_ - std::min(measuredHeap_, counted);
  // The engine's own memory (its code's data, the panels, fonts: what the heap held before this
  // city had anything) comes on top of the budget; what grew since, uncounted, is the city's.
  if (!heapBaseline_) heapBaseline_ = uncounted;
  otherHeapRecent_[otherHeapSamples_ % otherHeapRecent_.size()] = uncounted - std::min(uncounted, *heapBaseline_);
  ++otherHeapSamples_;
  const auto n = static_cast<std::ptrdiff_t>(std::min<std::uint64_t>(otherHeapSamples_, otherHeapRecent_.size()));
  otherHeap_ = *std::min_element(otherHeapRecent_.begin(), otherHeapRecent_.begin() + n);
}

std::uint64_t CityScene::tileBytes(std::uint32_t node) const {
  const TileRuntime& t = *tiles_[node];
  std::uint64_t total = t.bytes.size() + t.historyBytes;
  if (t.loaded) {
    total += t.loaded->cpuBytes + t.loaded->gpuBytes;
    // Drift series: the table's copy and the device's.
    std::uint64_t series = t.loaded->seriesCount + t.loaded->seriesBefore.size() * sizeof(std::uint32_t) / 2;
    for (const auto& blocks : t.loaded->blocks) series += blocks ? blocks->seriesCount : 0;
    total += 2 * series;
  }
  if (t.summary) {
    total += t.summary->buildings.size() * sizeof(BuildingResponse) +
             t.summary->storeyPeakDrift.size() * sizeof(float) + t.summary->driftSeries.codes.size() +
             t.summary->driftSeries.spans.size() * sizeof(DriftSpan);
  }
  return total;
}

MemoryUse CityScene::memoryUse() const {
  MemoryUse use;
  use.index = index_.bytes();
  use.ground = ground_ ? ground_->memoryBytes() : 0;
  const std::uint64_t tableHeap = table_.heapBytes(), tableInUse = table_.inUseBytes();
  use.tableSlack = tableHeap - std::min(tableHeap, tableInUse);
  use.otherHeap = otherHeap_;
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    const TileRuntime& t = *tiles_[i];
    const std::uint64_t gpu = t.loaded ? t.loaded->gpuBytes : 0;
    use.histories += t.historyBytes;
    use.tilesGpu += gpu;
    use.tilesCpu += tileBytes(i) - t.historyBytes - gpu;
  }
  return use;
}

void CityScene::updateNodeBytes() {
  // Resident bytes per file byte, as measured on the tiles loaded so far; before any, what the
  // synthetic and OSM cities measure natively per byte of the tile itself (coarse tiles about 9,
  // leaves about 17: a leaf's mesh has a ring of vertices per floor), times what the stored
  // files are compressed by (docs/formats.md: about 3 for the synthetic city, 1.8 for Manhattan
  // with its LOD2 models; the larger, so that the first tiles requested stay within the budget).
  constexpr double kDefaultRatio[2] = {17.0 * 3.0, 9.0 * 3.0};
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
      tiles_[i]->bytesMeasured = true;
      wasLoaded_[i] = true;
    } else if (!tiles_[i]->bytesMeasured) {
      const TileNode& n = tileset_->nodes[i];
      nodeBytes_[i] = static_cast<std::uint64_t>(static_cast<double>(n.bytes) * ratio[n.children.empty() ? 0 : 1]);
    }
  }
}

void CityScene::destroyMeshes(LoadedTile& tile) {
  if (tile.mesh) device_.destroyMesh(tile.mesh);
  if (tile.prismMesh) device_.destroyMesh(tile.prismMesh);
  for (const auto& blocks : tile.blocks) {
    if (blocks) device_.destroyMesh(blocks->mesh);
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
    destroyMeshes(*t.loaded);
    releaseSeries(*t.loaded);
    for (const auto& blocks : t.loaded->blocks) {
      if (blocks) table_.releaseBuildings(blocks->slotBase, static_cast<std::uint32_t>(blocks->level.boxes.size()));
    }
    table_.releaseBuildings(t.loaded->slotBase, t.loaded->buildingCount());
    t.loaded.reset();
  }
  t.summary.reset();
  t.maxRoofM = -1.0f;
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

}  // namespace qv
