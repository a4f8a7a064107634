#include "qv/scene/BuildingTable.h"

#include <algorithm>

#include "qv/core/RangeAllocator.h"

namespace qv {

BuildingTable::BuildingTable(std::uint32_t maxBuildingRows, std::uint32_t maxFloorRows, std::uint32_t maxSeriesSamples)
    : buildingSlots_(std::make_unique<RangeAllocator>(maxBuildingRows)),
      floorSlots_(std::make_unique<RangeAllocator>(maxFloorRows)),
      seriesSlots_(std::make_unique<RangeAllocator>(maxSeriesSamples)) {}

BuildingTable::~BuildingTable() = default;

std::optional<std::uint32_t> BuildingTable::reserveBuildings(std::uint32_t count) {
  const auto first = buildingSlots_->allocate(std::max(count, 1u));
  if (first && buildings_.size() < buildingSlots_->highWater()) buildings_.resize(buildingSlots_->highWater());
  return first;
}

void BuildingTable::releaseBuildings(std::uint32_t first, std::uint32_t count) {
  buildingSlots_->release(first, std::max(count, 1u));
}

std::span<BuildingGpuRecord> BuildingTable::edit(std::uint32_t first, std::uint32_t count) {
  changed(first, count);
  return std::span(buildings_).subspan(first, count);
}

void BuildingTable::changed(std::uint32_t first, std::uint32_t count) {
  changedFirst_ = std::min(changedFirst_, first);
  changedEnd_ = std::max(changedEnd_, first + count);
}

void BuildingTable::setFlag(BuildingGpuRecord& row, BuildingFlag flag, bool on) {
  auto flags = static_cast<unsigned>(row.flags);
  flags = on ? (flags | flag) : (flags & ~static_cast<unsigned>(flag));
  row.flags = static_cast<float>(flags);
}

std::optional<std::uint32_t> BuildingTable::reserveFloors(std::uint32_t count) {
  const auto first = floorSlots_->allocate(count);
  if (first && floorRows_.size() < floorSlots_->highWater()) floorRows_.resize(floorSlots_->highWater());
  return first;
}

void BuildingTable::releaseFloors(std::uint32_t first, std::uint32_t count) {
  floorSlots_->release(first, count);
}

std::span<FloorGpuRecord> BuildingTable::floors(std::uint32_t first, std::uint32_t count) {
  return std::span(floorRows_).subspan(first, count);
}

std::span<const FloorGpuRecord> BuildingTable::floors(std::uint32_t first, std::uint32_t count) const {
  return std::span<const FloorGpuRecord>(floorRows_).subspan(first, count);
}

std::optional<std::uint32_t> BuildingTable::reserveSeries(std::uint32_t count) {
  if (count == 0) return std::nullopt;
  const auto first = seriesSlots_->allocate(count);
  if (!first) return std::nullopt;
  if (seriesCodes_.size() < seriesSlots_->highWater()) seriesCodes_.resize(seriesSlots_->highWater(), 0);
  seriesInUse_ += count;
  return first;
}

void BuildingTable::releaseSeries(std::uint32_t first, std::uint32_t count) {
  if (count == 0) return;
  seriesSlots_->release(first, count);
  seriesInUse_ -= std::min<std::uint64_t>(seriesInUse_, count);
}

std::span<std::uint8_t> BuildingTable::editSeries(std::uint32_t first, std::uint32_t count) {
  seriesChangedFirst_ = std::min(seriesChangedFirst_, first);
  seriesChangedEnd_ = std::max(seriesChangedEnd_, first + count);
  return std::span(seriesCodes_).subspan(first, count);
}

std::uint64_t BuildingTable::seriesInUse() const {
  return seriesInUse_;
}

void BuildingTable::upload(RenderDevice& device, bool floorsInUse) {
  if (seriesChangedFirst_ < seriesChangedEnd_) {
    seriesChangedEnd_ = std::min<std::uint32_t>(seriesChangedEnd_, static_cast<std::uint32_t>(seriesCodes_.size()));
    device.writeSeries(seriesChangedFirst_,
                       std::span(seriesCodes_).subspan(seriesChangedFirst_, seriesChangedEnd_ - seriesChangedFirst_));
  }
  seriesChangedFirst_ = UINT32_MAX;
  seriesChangedEnd_ = 0;
  if (changedFirst_ < changedEnd_) {
    changedEnd_ = std::min<std::uint32_t>(changedEnd_, static_cast<std::uint32_t>(buildings_.size()));
    device.writeBuildings(changedFirst_, std::span(buildings_).subspan(changedFirst_, changedEnd_ - changedFirst_));
  }
  changedFirst_ = UINT32_MAX;
  changedEnd_ = 0;
  if (floorsInUse) {
    device.writeFloors(0,
                       std::span(floorRows_).first(std::min<std::size_t>(floorRows_.size(), floorSlots_->highWater())));
  }
}

}  // namespace qv
