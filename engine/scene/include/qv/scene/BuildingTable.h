// BuildingTable: the CPU side of the two GPU tables the shaders read, and what has changed since
// the last upload.
//
// The building table has one BuildingGpuRecord per loaded building (its storeys, results and
// flags), in ranges a tile reserves when it loads (one row per building, in the tile's BoxTree
// order) and releases when it is evicted. The floor table has one FloorGpuRecord per floor level of
// each animated building (its displacement this frame), in ranges reserved while it animates.
// The series table holds the drift series (one byte a window) of the buildings and blocks of the
// loaded tiles whose summaries carry them, in ranges reserved with the summary and released with
// the tile. Edits mark building rows and series samples changed; upload() sends the changed span of
// the building and series tables and the used part of the floor table.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "qv/scene/RenderDevice.h"

namespace qv {

class RangeAllocator;

class BuildingTable {
 public:
  /// Capacities of the two index spaces (the device grows its textures on demand).
  static constexpr std::uint32_t kMaxBuildingRows = 1u << 21;
  static constexpr std::uint32_t kMaxFloorRows = 1u << 22;
  /// 2048 x 2048 RGBA8 texels (the size every WebGL2 device has), four samples each: 16 MB; the
  /// scene asks its device (RenderDevice::maxSeriesSamples) for what it can hold.
  static constexpr std::uint32_t kMaxSeriesSamples = 1u << 24;

  BuildingTable(std::uint32_t maxBuildingRows = kMaxBuildingRows, std::uint32_t maxFloorRows = kMaxFloorRows,
                std::uint32_t maxSeriesSamples = kMaxSeriesSamples);
  ~BuildingTable();
  BuildingTable(const BuildingTable&) = delete;
  BuildingTable& operator=(const BuildingTable&) = delete;

  /// Reserves `count` consecutive building rows (at least one is reserved, for a tile without
  /// buildings); the first, or nullopt when the table is full. Their contents are unspecified
  /// until written.
  std::optional<std::uint32_t> reserveBuildings(std::uint32_t count);
  void releaseBuildings(std::uint32_t first, std::uint32_t count);
  /// A building row for editing; `changed` (or edit()) marks it for the next upload.
  [[nodiscard]] BuildingGpuRecord& row(std::uint32_t slot) { return buildings_[slot]; }
  [[nodiscard]] const BuildingGpuRecord& row(std::uint32_t slot) const { return buildings_[slot]; }
  /// Rows [first, first + count), marked changed.
  std::span<BuildingGpuRecord> edit(std::uint32_t first, std::uint32_t count);
  void changed(std::uint32_t first, std::uint32_t count);
  /// Sets or clears BuildingFlag bits of a row (not marked changed).
  static void setFlag(BuildingGpuRecord& row, BuildingFlag flag, bool on);

  /// Reserves `count` consecutive floor rows; the first, or nullopt when full.
  std::optional<std::uint32_t> reserveFloors(std::uint32_t count);
  void releaseFloors(std::uint32_t first, std::uint32_t count);
  /// Floor rows [first, first + count) of reserved rows (written every frame by the animation).
  std::span<FloorGpuRecord> floors(std::uint32_t first, std::uint32_t count);
  [[nodiscard]] std::span<const FloorGpuRecord> floors(std::uint32_t first, std::uint32_t count) const;

  /// Reserves `count` (> 0) consecutive series samples; the first, or nullopt when full.
  std::optional<std::uint32_t> reserveSeries(std::uint32_t count);
  void releaseSeries(std::uint32_t first, std::uint32_t count);
  /// Series samples [first, first + count) of reserved ones, marked changed.
  std::span<std::uint8_t> editSeries(std::uint32_t first, std::uint32_t count);
  /// Every series sample (reserved or not: read only where a row points).
  [[nodiscard]] std::span<const std::uint8_t> series() const { return seriesCodes_; }
  /// Series samples reserved now.
  [[nodiscard]] std::uint64_t seriesInUse() const;

  /// Gives back the CPU side's room beyond the highest row (and sample) in use, when it is large
  /// (a quarter or more of what is in use): the rows of tiles evicted after a flight. Whether it
  /// did. The device's textures keep their size.
  bool trim();
  /// Bytes the CPU side holds: every row and sample the tables have room for, in use or not.
  [[nodiscard]] std::uint64_t heapBytes() const;
  /// Bytes of the rows and samples reserved now (what the tiles and animated buildings use).
  [[nodiscard]] std::uint64_t inUseBytes() const;

  /// Sends the changed building rows and series samples (each one span from the first to the last
  /// changed) and, when `floorsInUse`, every floor row up to the highest reserved to `device`; then
  /// nothing is changed.
  void upload(RenderDevice& device, bool floorsInUse);
  /// The changed span [first, end) waiting for upload; first >= end when none.
  [[nodiscard]] std::pair<std::uint32_t, std::uint32_t> changedRange() const { return {changedFirst_, changedEnd_}; }

 private:
  std::vector<BuildingGpuRecord> buildings_;
  std::vector<FloorGpuRecord> floorRows_;
  std::vector<std::uint8_t> seriesCodes_;
  std::unique_ptr<RangeAllocator> buildingSlots_;
  std::unique_ptr<RangeAllocator> floorSlots_;
  std::unique_ptr<RangeAllocator> seriesSlots_;
  std::uint32_t changedFirst_ = UINT32_MAX, changedEnd_ = 0;
  std::uint32_t seriesChangedFirst_ = UINT32_MAX, seriesChangedEnd_ = 0;
  std::uint64_t seriesInUse_ = 0;
};

}  // namespace qv
