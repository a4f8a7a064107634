// TileMeshBuilder: a decoded city tile made ready to draw, without a device. `indexTile` builds
// what the scene looks buildings up by (the BoxTree in Morton order, id -> building, building ->
// position, building -> LOD2 model); `buildTileMesh` merges every building into one mesh whose
// vertices name their building's row of the GPU building table; `initialBuildingRows` gives those
// rows. Positions (the BoxTree's order) decide the rows: building b is row slotBase +
// positionOf[b], so a tile's visible ranges of positions are ranges of rows.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "qv/format/CityTile.h"
#include "qv/geometry/BuildingMesh.h"
#include "qv/scene/RenderDevice.h"
#include "qv/spatial/BoxTree.h"

namespace qv {

/// A decoded tile and its lookups. Coordinates of `data` are relative to `origin` (the city frame
/// in metres, z = 0); the tree's boxes are in the city frame.
struct TileContent {
  CityTile data;
  std::unordered_map<std::string, std::uint32_t> idIndex;  ///< building id -> index in the file
  BoxTree tree;
  std::vector<std::uint32_t> positionOf;  ///< building index -> position in tree.order()
  std::vector<std::int32_t> meshIndex;    ///< building index -> index in data.meshes, or -1 (LOD1)
  glm::vec3 origin{0.0f};

  /// The building's LOD2 model, or nullptr (LOD1 only, or out of range).
  [[nodiscard]] const TileMesh* meshOf(std::uint32_t building) const {
    return building < meshIndex.size() && meshIndex[building] >= 0
               ? &data.meshes[static_cast<std::size_t>(meshIndex[building])]
               : nullptr;
  }
  /// The LOD2 model the tile draws for the building: in leaves its model, in coarse tiles none.
  /// Far away a building is its LOD1 extrusion, the prisms of its parts: vertical walls and flat
  /// roofs at their heights, never a simplified mesh's slanted facets across storeys.
  [[nodiscard]] const TileMesh* drawnModelOf(std::uint32_t building) const {
    return data.coarse ? nullptr : meshOf(building);
  }
  [[nodiscard]] std::uint32_t buildingCount() const { return static_cast<std::uint32_t>(data.buildings.size()); }
};

/// Takes `tile` and builds its lookups. A building's box holds its prisms and the LOD2 model the
/// tile draws (drawnModelOf).
TileContent indexTile(CityTile tile);

/// The building's box in the city frame: its prisms and the LOD2 model the tile draws
/// (drawnModelOf). `building` indexes tile.data.buildings and must be in range.
Box buildingBox(const TileContent& tile, std::uint32_t building);

/// Where each position's triangles lie in a tile mesh's index buffer (buildTileMesh), so that the
/// scene draws only the visible ranges of positions. Every array has positions + 1 entries: entry p
/// is the count before position p (prefix sums), the last one the mesh's total.
struct TileIndexRuns {
  std::vector<std::uint32_t> firstIndex;
  std::vector<std::uint32_t> modelTriangles;     ///< LOD2 model triangles (kKindModel) before p
  std::vector<std::uint32_t> fallbackTriangles;  ///< their LOD1 fallbacks' (kKindFallback) before p
};

/// How a leaf's LOD1 walls are built: with a vertex ring at every floor level inside each part, so
/// that the floors bend with their displacements and each storey takes its own colour (needed only
/// while a building is animated), or as plain prisms, one quad per wall (a still building looks
/// the same; a 10-storey building takes about a tenth of the wall triangles).
enum class TileWalls : std::uint8_t { Storeys, Prisms };

/// The merged mesh of every building in position order: a LOD2 model in leaves (kKindModel)
/// followed by its LOD1 extrusion (kKindFallback), or the extrusion alone. Leaves' walls as `walls`
/// says; coarse tiles always plain prisms. Vertex slots are slotBase + position. `runs`, when
/// given, receives where each position's triangles are. `appendOrder`, when not empty, lists the
/// positions in the order their buildings are appended (a permutation); `runs` then describes its
/// entries, not positions.
MeshData buildTileMesh(const TileContent& tile, std::uint32_t slotBase, TileIndexRuns* runs = nullptr,
                       std::span<const std::uint32_t> appendOrder = {}, TileWalls walls = TileWalls::Storeys);

/// The index spans that draw the visible ranges of positions `visible` (sorted, disjoint, as
/// BoxTree::query gives them): one span per range, neighbours merged when the indices between
/// them number at most `mergeGapIndices` (drawing a few hidden triangles costs less than a draw
/// call), then the smallest gaps merged until at most `maxSpans` remain (>= 1). Replaces `out`.
void visibleIndexSpans(const TileIndexRuns& runs, std::span<const IndexRange> visible, std::uint32_t mergeGapIndices,
                       std::uint32_t maxSpans, std::vector<IndexSpan>& out);

/// The building table rows of the tile in position order (`rows.size()` == buildingCount()):
/// storey height (at least 0.5 m), storeys and base height; damage kDamagePending when the tile
/// has results on their way (`resultsPending`), else -1 (no result); flags clear; not animated.
void initialBuildingRows(const TileContent& tile, bool resultsPending, std::span<BuildingGpuRecord> rows);

/// Heap bytes the tile's data and lookups hold (an estimate used for the memory budget).
std::uint64_t tileCpuBytes(const TileContent& tile);

/// GPU bytes of a mesh (vertices and indices).
std::uint64_t meshGpuBytes(const MeshData& mesh);

}  // namespace qv
