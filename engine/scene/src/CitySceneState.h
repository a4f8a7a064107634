// The per-node state of a CityScene, shared by its source files (CityScene.cpp: loading, the
// frame and memory; CitySceneAnimation.cpp; CitySceneBlocks.cpp: the far view; CitySceneInspection.cpp:
// flags, picking, selection; CitySceneResponse.cpp: the response files of each tile).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "qv/scene/CityScene.h"
#include "qv/scene/TileBlocks.h"
#include "qv/scene/TileMeshBuilder.h"

namespace qv {

inline constexpr std::uint32_t kNotAnimated = UINT32_MAX;
inline constexpr std::int8_t kRegionHidden = -2;  // a region out of view this frame

// One block level of a far-view tile, made when first drawn (TileBlocks.h).
struct CityScene::BlockLevelRuntime {
  TileBlockLevel level;
  MeshHandle mesh;
  TileIndexRuns runs;          // where each block's triangles are in the mesh
  std::uint32_t slotBase = 0;  // block p's row is slotBase + p
  // The blocks' drift series (the worst member at each moment) in the series table.
  std::uint32_t seriesBase = 0, seriesCount = 0;
};

struct CityScene::LoadedTile : TileContent {
  explicit LoadedTile(TileContent content) : TileContent(std::move(content)) {}
  MeshHandle mesh;
  TileIndexRuns runs;  // where each position's triangles are in the mesh
  std::uint32_t slotBase = 0;
  // Its buildings' drift series in the series table (from the summary), and per position p how
  // many positions before it have one (seriesBefore[p]; positionOf.size() + 1 entries, or empty).
  std::uint32_t seriesBase = 0, seriesCount = 0;
  std::vector<std::uint32_t> seriesBefore;
  // Per building: its position in the city index (kNoIndexPosition when it has none), made when
  // the view's totals first need the index's losses (CityScene::indexLoss).
  std::vector<std::uint32_t> indexPosition;
  static constexpr std::uint32_t kNoIndexPosition = 0xFFFFFFFFu;
  std::uint64_t cpuBytes = 0;
  std::uint64_t gpuBytes = 0;
  // Far-view tiles: block levels made so far, by level; levels below minBlockLevel are not worth
  // it (about as many blocks as buildings): the tile is drawn building by building there.
  std::unique_ptr<BlockLevelRuntime> blocks[kBlockLevels];
  int minBlockLevel = 0;
  TileRegions regions;  // far-view tiles: their regions; runs then follow regions.appendOrder
  // Far-view tiles wider than kMaxRegionsAcross regions: coarser regions for when the whole tile
  // is far (TileBlocks.h); block levels above kBlockRegionLevel are made on them.
  std::unique_ptr<TileRegions> farRegions;
  // Leaves: the same buildings with plain-prism walls (TileWalls::Prisms), drawn while none of the
  // tile's buildings is animated; made when first wanted, not at all where it saves little.
  MeshHandle prismMesh;
  TileIndexRuns prismRuns;
  bool prismsTried = false;
  // The 2D map's per-position summary of each building (CityScene::map2d), made when first drawn:
  // its centroid in the city frame and the side of a square of its footprint's area, in the tree's
  // order so that a frame reads them in sequence.
  struct MapPoint {
    float x = 0, y = 0, side = 0;
  };
  mutable std::vector<MapPoint> mapPoints;
};

struct CityScene::TileRuntime {
  FileLoad tile;                    // the tile's file; its state is the node's
  std::vector<std::uint8_t> bytes;  // arrived, waiting to be decoded
  std::unique_ptr<LoadedTile> loaded;
  std::uint64_t lastUsed = 0;
  bool bytesMeasured = false;       // nodeBytes_ holds what it measured when it last loaded
  std::vector<IndexRange> inView;   // this frame's culling result (positions in the frustum)
  std::vector<IndexRange> visible;  // ... less those under a pixel on screen: the drawn ones
  std::vector<IndexSpan> spans;     // ... as the index runs drawn (DrawItem::spans points here)
  // Far-view tiles: each region's form this frame (kRegionHidden, -1 building by building, else
  // the block level) and the runs drawn of each block level's mesh.
  std::vector<std::int8_t> regionForm;
  bool farGrid = false;  // regionForm is of the far regions (LoadedTile::farRegions) this frame
  std::vector<IndexSpan> blockSpans[kBlockLevels];

  FileLoad summaryLoad;
  std::unique_ptr<ResponseSummaryTile> summary;
  FileLoad historyLoad;
  std::unique_ptr<ResponseHistoryTile> history;
  std::uint64_t historyBytes = 0;
  std::uint64_t historyUsed = 0;
  float maxRoofM = -1.0f;  // largest peak roof displacement of its buildings (summary), -1 not yet known
  /// Per building of the loaded tile: its index in animated_, or kNotAnimated.
  std::vector<std::uint32_t> animatedIndex;
  std::uint32_t animatedCount = 0;  // of its buildings in animated_
};

struct CityScene::Animated {
  BuildingRef ref;
  std::uint32_t slot = 0;
  std::uint32_t floorBase = 0;
  std::uint32_t rows = 0;     // storeys + 1
  std::uint64_t choice = 0;   // the last choice (chooseAnimated) that kept it
  bool peaksWritten = false;  // its peak drifts are in its floor rows
};

}  // namespace qv
