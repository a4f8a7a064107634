// Graphics LOD over the tile hierarchy: which tiles to draw this frame and which to load next.
//
// REPLACE refinement (as in 3D Tiles) with a draw budget: starting from the root, the node with
// the largest screen-space error is replaced by its visible children while its error exceeds
// the threshold (or it lies within the animation radius of the eye, where full detail is needed) and the
// budget allows. A node is only replaced once all its visible children are loaded (or failed), so
// the drawn set never has holes or overlaps while tiles stream in: coarse tiles first, then
// refining where the camera needs detail.
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
};

struct TileSelection {
  std::vector<std::uint32_t> draw;    ///< loaded nodes to draw, no two overlapping
  std::vector<std::uint32_t> wanted;  ///< nodes to load, most important first
  std::vector<std::uint32_t> used;    ///< every node the selection passed through, and arrived children
                                      ///< waiting for their siblings (kept from eviction: LRU)
  bool budgetLimited = false;         ///< refinement stopped at the draw budget
  /// Nothing is waiting: every tile the view needs is loaded or failed.
  [[nodiscard]] bool complete() const { return wanted.empty(); }
};

/// Screen-space error of a node for a view, in device pixels.
float screenSpaceError(const TileNode& node, const CameraView& view);

/// 3D box of a node: its footprint bounds from the ground to its tallest building.
Box nodeBox(const TileNode& node);

void selectTiles(const Tileset& tileset, std::span<const TileState> states, const CameraView& view,
                 const TileSelectorOptions& options, TileSelection& out);

}  // namespace qv
