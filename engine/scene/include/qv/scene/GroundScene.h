// GroundScene: the map under the city (streets, water, parks and their names) streamed from the
// city's ground pyramid (Tileset::ground, qv/format/GroundTile.h) and drawn under the buildings.
//
// Each frame it walks the pyramid from its one top cell: a cell in view whose screen-space error
// exceeds the limit is replaced by its children once every child in view has loaded (until then
// the cell itself is drawn and the children are requested), so the triangles drawn follow the
// screen, not the size of the city, and no part of the map is ever drawn twice. Ground tiles are
// small: they are decoded and uploaded as they arrive. Cells not drawn for a while are evicted,
// least recently used first, beyond the memory budget.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/format/GroundTile.h"
#include "qv/format/Tileset.h"
#include "qv/geometry/OrbitCamera.h"
#include "qv/scene/FileLoader.h"
#include "qv/scene/RenderDevice.h"

namespace qv {

struct GroundSceneOptions {
  /// Device pixels of error before a cell is refined (its geometric error, or its side / 48 when
  /// larger: inner cells leave out the streets and small parks).
  float maxScreenSpaceError = 12.0f;
  std::uint32_t maxDrawCells = 160;               ///< cells drawn at most (refinement stops there)
  std::uint64_t memoryBudgetBytes = 48ull << 20;  ///< decoded labels + GPU meshes
};

/// A name on a drawn cell, in the city frame.
struct MapLabel {
  GroundLabelKind kind = GroundLabelKind::Street;
  std::uint8_t rank = 128;
  glm::dvec2 position{0.0};           ///< metres, city frame
  float angleRad = 0.0f;              ///< GroundLabel::angleRad
  float lengthM = 0.0f;               ///< GroundLabel::lengthM
  const std::string* text = nullptr;  ///< valid until the next update()
  float z = 0.0f;                     ///< metres above the ground (a building's roof for its name)
  bool facility = false;              ///< a highlighted building's name, not the map's
  float liftPx = 0.0f;                ///< drawn this many pixels above its point (clear of a marker)
};

class GroundScene {
 public:
  /// Ground tiles are resolved relative to `manifestUrl` and fetched through `loader` (the city's,
  /// so that they share its limit of requests in flight and its error reporting).
  GroundScene(RenderDevice& device, FileLoader& loader, std::string manifestUrl, const GroundLayer& layer,
              GroundSceneOptions options = {});
  ~GroundScene();
  GroundScene(const GroundScene&) = delete;
  GroundScene& operator=(const GroundScene&) = delete;

  /// Chooses the cells to draw from `view`, requests missing ones (while the loader has room),
  /// evicts beyond the budget, and fills items() and labels().
  void update(const CameraView& view);

  GroundSceneOptions& mutableOptions() { return options_; }

  [[nodiscard]] std::span<const GroundDrawItem> items() const { return items_; }
  /// The labels of the drawn cells, most important (lowest rank) first.
  [[nodiscard]] const std::vector<MapLabel>& labels() const { return labels_; }
  /// Every cell the view wants has loaded or failed.
  [[nodiscard]] bool settled() const { return pending_ == 0; }
  /// Cells the last frame wanted that have neither loaded nor failed yet.
  [[nodiscard]] std::uint32_t pending() const { return pending_; }
  [[nodiscard]] std::uint32_t cellsDrawn() const { return static_cast<std::uint32_t>(items_.size()); }
  [[nodiscard]] std::uint32_t cellsLoaded() const;
  [[nodiscard]] std::uint32_t cellsFailed() const;
  [[nodiscard]] std::uint64_t memoryBytes() const;
  [[nodiscard]] std::uint64_t trianglesDrawn() const { return trianglesDrawn_; }

 private:
  struct Cell;
  void visit(std::uint32_t index, const CameraView& view, std::vector<std::uint32_t>& drawn);
  void request(Cell& cell);
  void evict(Cell& cell);
  [[nodiscard]] bool usable(const Cell& cell) const;  // loaded, or failed (nothing to draw)

  RenderDevice& device_;
  FileLoader& loader_;
  std::string manifestUrl_;
  GroundLayer layer_;
  GroundSceneOptions options_;
  std::vector<std::unique_ptr<Cell>> cells_;  // stable addresses: loads in flight point into them
  std::uint32_t root_ = UINT32_MAX;
  std::uint64_t frame_ = 0;
  std::vector<GroundDrawItem> items_;
  std::vector<MapLabel> labels_;
  std::uint64_t trianglesDrawn_ = 0;
  std::uint32_t pending_ = 1;  // nothing is settled before the first update
};

/// The ground mesh of a decoded tile: its vertices with their run's class, its triangles in order.
void groundMesh(const GroundTile& tile, std::vector<GroundVertex>& vertices, std::vector<std::uint32_t>& indices);

}  // namespace qv
