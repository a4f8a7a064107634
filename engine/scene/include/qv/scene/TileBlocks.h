// TileBlocks: the far form of a coarse tile, its buildings merged into blocks on a square grid, so
// that far away the triangles drawn follow the screen, not the building count.
//
// A level's grid has square cells of side cellM (metres), aligned to the city frame's origin, so
// the cells of one level are disjoint and the cells of level k + 1 are 2 × 2 cells of level k. A
// block is what of the tile's buildings lies in one cell: the bounding rectangle of its parts'
// outer rings clipped to the cell, from the lowest part's base to the highest part's top among
// those reaching into the cell. A building belongs to every block its footprint reaches into.
// Every point of a block is thus within a cell diagonal of a wall of its tallest member, and every
// member is covered: the block's geometric error is at most √2 × cellM. Blocks are drawn as boxes
// (four walls and a roof, 10 triangles); what colour they show is the worst of their members'
// (aggregateBlockRows).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/geometry/BuildingMesh.h"
#include "qv/scene/RenderDevice.h"
#include "qv/scene/TileMeshBuilder.h"
#include "qv/spatial/BoxTree.h"

namespace qv {

/// Side (metres) of the cells of block level 0; level k has cells of kBlockCellM × 2^k.
inline constexpr float kBlockCellM = 8.0f;
/// Levels 0 .. kBlockLevels - 1 (the coarsest cell is 8 m × 2^15 = 262 km).
inline constexpr int kBlockLevels = 16;

[[nodiscard]] inline float blockCellM(int level) {
  return kBlockCellM * static_cast<float>(1u << static_cast<unsigned>(level));
}

/// A far-view tile chooses its form region by region: each square region of this level's grid
/// (512 m) is drawn building by building or as the blocks of one level, after its own distance
/// from the eye, so the far side of a large tile gets coarser blocks than its near side. Cells of
/// every block level up to a grid's region level nest in exactly one of its regions, so regions
/// never overlap.
inline constexpr int kBlockRegionLevel = 6;
/// Blocks are at most a region wide, so a tile much wider than its regions draws at least one
/// block per region however far away it is: the root of a 59 km × 37 km synth-city of 2,000,000
/// buildings, 8,400 regions of 512 m, drew 79,000 triangles from afar where the preset's
/// screen-sized blocks need a fifth of that. A tile wider than this many regions of 512 m also
/// gets a far grid (regionLevelFor: at most this many regions across), which CityScene uses while
/// the whole tile is far enough for blocks coarser than 512 m; nearer, the 512 m grid follows the
/// distance more closely.
inline constexpr float kMaxRegionsAcross = 32.0f;

/// The region level of the far grid of a far-view tile whose buildings span `widthM` × `heightM`:
/// the finest level from kBlockRegionLevel on with at most kMaxRegionsAcross regions along the
/// longer side (kBlockRegionLevel: no far grid needed).
[[nodiscard]] int regionLevelFor(float widthM, float heightM);

/// The regions of a far-view tile: those its buildings' boxes reach into, in Morton order of the
/// grid, and its buildings in region order (each building in the region of its box's centre).
struct TileRegions {
  int level = kBlockRegionLevel;  ///< regions are the cells of this block level (regionLevelFor)
  std::vector<Box> boxes;         ///< each region's square, from the tile's lowest base to its highest top
  /// Positions (the tile's BoxTree order) region by region: region r's buildings are
  /// appendOrder[positionStart[r] .. positionStart[r + 1]). Their mesh is built in this order.
  std::vector<std::uint32_t> appendOrder;
  std::vector<std::uint32_t> positionStart;
  std::vector<std::uint32_t> regionOfPosition;  ///< the region each position's building is drawn in
  std::vector<std::uint64_t> codes;             ///< each region's Morton code on the grid, ascending (regionOf)
  /// The region holding city-frame point (x, y), or UINT32_MAX when the tile has none there.
  [[nodiscard]] std::uint32_t regionOf(float x, float y) const;
};

/// The regions of `tile` on the grid of block level `level` (kBlockRegionLevel .. kBlockLevels - 1).
TileRegions buildTileRegions(const TileContent& tile, int level = kBlockRegionLevel);

/// One level's blocks, region by region (region r's blocks are [regionStart[r], regionStart[r + 1])),
/// in Morton order within a region. The tree is built over `boxes` in this order: its order()
/// maps its positions to block indices.
struct TileBlockLevel {
  float cellM = 0.0f;
  std::vector<Box> boxes;         ///< city frame
  std::vector<glm::ivec2> cells;  ///< each block's cell: (x, y) × cellM is its lower-left corner
  std::vector<std::uint32_t> regionStart;
  BoxTree tree;
  /// Members of block p: positions (in the tile's BoxTree order) members[memberStart[p] ..
  /// memberStart[p + 1]); memberStart has boxes.size() + 1 entries.
  std::vector<std::uint32_t> memberStart;
  std::vector<std::uint32_t> members;
};

/// The blocks of `tile` on cells of side `cellM` (> 0, at most the region side, blockCellM(regions.level)), ordered by
/// the tile's `regions`. Buildings without parts are left out.
TileBlockLevel buildBlockLevel(const TileContent& tile, float cellM, const TileRegions& regions);

/// The boxes of `level` as one mesh (tile-local positions: the city frame less tile.origin),
/// block p in slot slotBase + p, no floor rings: a roof and the walls that can show (a wall on the
/// cell's edge is left out where the neighbouring block covers that edge and is at least as tall:
/// it lies inside the city's volume). `runs`, when given, receives where each block's triangles
/// are (as buildTileMesh does for buildings).
MeshData buildBlockMesh(const TileBlockLevel& level, const glm::vec3& origin, std::uint32_t slotBase,
                        TileIndexRuns* runs = nullptr);

/// Block rows from the tile's building rows (`buildingRows[p]` is the row of position p): the
/// worst of the members (of those a filter keeps, when it keeps any): highest damage state (a result beats pending,
/// pending beats none), highest peak drift, highest loss code (packLossCode: tag first, then expected state); selected
/// when any member is, dimmed and hidden only when every member is; storeys and storey height of the tallest member,
/// base at the block's base; never animated. `out.size()` == level.boxes.size().
void aggregateBlockRows(const TileBlockLevel& level, std::span<const BuildingGpuRecord> buildingRows,
                        std::span<BuildingGpuRecord> out);

/// Estimated heap bytes of a level (for the memory budget).
std::uint64_t blockLevelCpuBytes(const TileBlockLevel& level);

}  // namespace qv
