// CityScene's far view: a far-view tile drawn region by region, building by building or as merged
// blocks (qv/scene/TileBlocks.h), the blocks' levels made when first needed and their rows kept
// the worst of their members'.
#include <algorithm>
#include <cmath>

#include "CitySceneState.h"

namespace qv {

void CityScene::cullRegions(std::uint32_t node, const CameraView& view, std::vector<DrawItem>& items) {
  // Region by region (TileBlocks.h): building by building, or the blocks of the level its
  // distance allows; neighbours in the same form are one run of one mesh.
  TileRuntime& t = *tiles_[node];
  LoadedTile& tile = *t.loaded;
  const Frustum& frustum = view.frustum();
  // The far grid while the whole tile is far enough for blocks coarser than the 512 m regions (its
  // nearest point asks for them, so every region does); else the 512 m grid.
  t.farGrid =
      tile.farRegions && blockLevelFor(node, tile.tree.bounds(), view, tile.farRegions->level) > kBlockRegionLevel;
  auto extend = [](std::vector<IndexSpan>& spans, std::uint32_t first, std::uint32_t end) {
    if (end <= first) return;
    if (!spans.empty() && spans.back().firstIndex + spans.back().indexCount == first) {
      spans.back().indexCount += end - first;
    } else {
      spans.push_back(IndexSpan{first, end - first, 0, 0});
    }
  };
  auto form = [&](const TileRegions& regions) {
    t.regionForm.assign(regions.boxes.size(), kRegionHidden);
    t.spans.clear();
    for (auto& spans : t.blockSpans) spans.clear();
    for (std::uint32_t r = 0; r < regions.boxes.size(); ++r) {
      const Box& box = regions.boxes[r];
      if (frustum.classify(box) == Containment::Outside) continue;
      const int level = blockLevelFor(node, box, view, regions.level);
      // On the far grid only blocks of its own levels can be drawn (the buildings' mesh and the
      // finer levels follow the 512 m regions): else the 512 m grid after all.
      if (t.farGrid && level <= kBlockRegionLevel) return false;
      t.regionForm[r] = static_cast<std::int8_t>(level);
      if (level < 0) {
        extend(t.spans, tile.runs.firstIndex[regions.positionStart[r]],
               tile.runs.firstIndex[regions.positionStart[r + 1]]);
      } else {
        const BlockLevelRuntime& blocks = *tile.blocks[level];
        extend(t.blockSpans[level], blocks.runs.firstIndex[blocks.level.regionStart[r]],
               blocks.runs.firstIndex[blocks.level.regionStart[r + 1]]);
      }
    }
    return true;
  };
  if (!form(t.farGrid ? *tile.farRegions : tile.regions)) {
    t.farGrid = false;
    form(tile.regions);
  }
  if (!t.spans.empty()) items.push_back(DrawItem{tile.mesh, tile.origin, t.spans});
  for (int level = 0; level < kBlockLevels; ++level) {
    if (!t.blockSpans[level].empty())
      items.push_back(DrawItem{tile.blocks[level]->mesh, tile.origin, t.blockSpans[level]});
  }
}

int CityScene::blockLevelFor(std::uint32_t node, const Box& box, const CameraView& view, int maxLevel) {
  LoadedTile& tile = *tiles_[node]->loaded;
  if (!tile.data.coarse || options_.blockPixels <= 0.0f || tile.buildingCount() == 0) return -1;
  // Cells of about blockPixels where the box is nearest the eye.
  const glm::vec3 eye = view.eye();
  const float dx = std::max({box.minX - eye.x, 0.0f, eye.x - box.maxX});
  const float dy = std::max({box.minY - eye.y, 0.0f, eye.y - box.maxY});
  const float dz = std::max({box.minZ - eye.z, 0.0f, eye.z - box.maxZ});
  const float distance = std::sqrt(dx * dx + dy * dy + dz * dz);
  const float cellM = options_.blockPixels * distance / std::max(view.pixelsPerMeterAt(1.0f), 1e-6f);
  if (!(cellM >= kBlockCellM * 0.75f)) return -1;
  // The level whose cells are nearest that size (between 0.71 and 1.41 times it).
  const int level = std::min(static_cast<int>(std::lround(std::log2(cellM / kBlockCellM))), maxLevel);
  if (level < tile.minBlockLevel) return -1;
  if (tile.blocks[level]) return level;
  // Cells smaller than the buildings' mean spacing merge next to nothing: not worth making.
  const Rect bounds = tile.tree.bounds().rect();
  const float spacing = std::sqrt(std::max(bounds.maxX - bounds.minX, 1.0f) *
                                  std::max(bounds.maxY - bounds.minY, 1.0f) / static_cast<float>(tile.buildingCount()));
  if (blockCellM(level) < spacing) {
    tile.minBlockLevel = level + 1;
    return -1;
  }
  auto blocks = std::make_unique<BlockLevelRuntime>();
  // Levels above the 512 m regions are only drawn on the far grid: made on its regions.
  blocks->level = buildBlockLevel(tile, blockCellM(level), level > kBlockRegionLevel ? *tile.farRegions : tile.regions);
  const auto count = static_cast<std::uint32_t>(blocks->level.boxes.size());
  // Worth it only where the blocks' boxes take well under the buildings' triangles.
  const std::uint64_t buildingTriangles = tile.runs.firstIndex.empty() ? 0 : tile.runs.firstIndex.back() / 3;
  if (count == 0 || static_cast<std::uint64_t>(count) * 10 * 2 > buildingTriangles) {
    tile.minBlockLevel = level + 1;
    return -1;
  }
  const auto slotBase = table_.reserveBuildings(count);
  if (!slotBase) return -1;  // the building table is full: drawn building by building
  blocks->slotBase = *slotBase;
  const MeshData mesh = buildBlockMesh(blocks->level, tile.origin, blocks->slotBase, &blocks->runs);
  blocks->mesh = device_.createMesh(mesh);
  if (!blocks->mesh) {
    table_.releaseBuildings(blocks->slotBase, count);
    return -1;
  }
  tile.gpuBytes += meshGpuBytes(mesh);
  tile.cpuBytes += blockLevelCpuBytes(blocks->level) + blocks->runs.firstIndex.size() * 3 * sizeof(std::uint32_t);
  tile.blocks[level] = std::move(blocks);
  refreshBlockRows(node);
  return level;
}

void CityScene::refreshBlockRows(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded) return;
  const LoadedTile& tile = *t.loaded;
  const std::span<const BuildingGpuRecord> rows(&table_.row(tile.slotBase), tile.buildingCount());
  for (const auto& blocks : tile.blocks) {
    if (!blocks) continue;
    const auto count = static_cast<std::uint32_t>(blocks->level.boxes.size());
    aggregateBlockRows(blocks->level, rows, table_.edit(blocks->slotBase, count));
    if (tile.seriesCount > 0) refreshBlockSeries(*blocks, rows);
  }
}

}  // namespace qv
