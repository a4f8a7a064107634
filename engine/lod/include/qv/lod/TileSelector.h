// Graphics LOD over the tile hierarchy: which tiles to draw this frame and which to load next.
//
// REPLACE refinement (as in 3D Tiles) with a draw budget: starting from the root, the node with
// the largest screen-space error is replaced by its visible children while its error exceeds
// the threshold (or it lies within the animation radius of the eye, where full detail is needed) and the
// budget allows. A node is only replaced once all its visible children are loaded (or failed), so
// the drawn set never has holes or overlaps while tiles stream in: coarse tiles first, then
// refining where the camera needs detail.
//
// With a memory budget, refinement also stops where the tiles drawn and wanted would not fit
// (nodeBytes: each node's resident size, measured once it has been loaded, estimated before), so a
// city larger than the budget is drawn coarser far away instead of exceeding it; the most important
// nodes (the detail radius, then the largest errors) get the budget first. A tile that was replaced
// by its children is not needed any more: under memory pressure the scene may evict it, and the
// selector then passes through it to its children (wanting the missing ones) instead of loading it
// again.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "qv/format/Tileset.h"
#include "qv/geometry/OrbitCamera.h"

namespace qv {

enum class TileState : std::uint8_t { Unloaded = 0, Loading, Loaded, Failed };

struct TileSelectorOptions {
  float maxScreenSpaceError = 12.0f;  ///< device pixels
  std::uint32_t maxDrawTiles = 240;   ///< the draw-call budget for city tiles
  /// Tiles closer to the eye than this (metres) are refined to leaves: the buildings animated
  /// there need full detail. 0 disables.
  float detailRadiusM = 0.0f;
  /// Bytes each node holds once loaded (indexed like Tileset::nodes), and the budget the drawn and
  /// wanted nodes must fit in. Empty or 0: no memory limit.
  std::span<const std::uint64_t> nodeBytes;
  std::uint64_t memoryBudgetBytes = 0;
  /// Per node, whether it has been loaded before (and evicted): such a node that the view wants
  /// refined is passed through to its children, missing ones wanted, instead of being loaded
  /// again only to stand in for them. Empty: every unloaded node is loaded first (coarse first).
  std::span<const bool> wasLoaded;
};

struct TileSelection {
  std::vector<std::uint32_t> draw;    ///< loaded nodes to draw, no two overlapping
  std::vector<std::uint32_t> wanted;  ///< nodes to load, most important first
  std::vector<std::uint32_t> used;    ///< every node the selection passed through, and arrived children
                                      ///< waiting for their siblings (kept from eviction: LRU)
  bool budgetLimited = false;         ///< refinement stopped at the draw budget
  /// Loaded nodes replaced by their children this frame (in `used`): under memory pressure the
  /// scene may evict them; the selector then passes through them to their loaded children.
  std::vector<std::uint32_t> replaced;
  bool memoryLimited = false;  ///< refinement stopped at the memory budget
  std::uint64_t bytes = 0;     ///< nodeBytes of the drawn and wanted nodes
  /// Nothing is waiting: every tile the view needs is loaded or failed.
  [[nodiscard]] bool complete() const { return wanted.empty(); }
};

/// Screen-space error of a node for a view, in device pixels.
float screenSpaceError(const TileNode& node, const CameraView& view);

/// Distance from a point to the nearest point of a box (0 inside), metres.
float distanceToBox(const glm::vec3& p, const Box& b);
/// 3D box of a node: its footprint bounds from the ground to its tallest building.
Box nodeBox(const TileNode& node);

void selectTiles(const Tileset& tileset, std::span<const TileState> states, const CameraView& view,
                 const TileSelectorOptions& options, TileSelection& out);

}  // namespace qv
