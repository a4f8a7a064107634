#include "qv/scene/BuildingTable.h"

#include <algorithm>

#include "qv/core/RangeAllocator.h"

namespace qv {

BuildingTable::BuildingTable(std::uint32_t maxBuildingRows, std::uint32_t maxFloorRows, std::uint32_t maxSeriesSamples)
    : buildingSlots_(std::make_unique<RangeAllocator>(maxBuildingRows)),
      floorSlots_(std::make_unique<RangeAllocator>(maxFloorRows)),
      seriesSlots_(std::make_unique<RangeAllocator>(maxSeriesSamples)) {}

BuildingTable::~BuildingTable() = default;

namespace {

// Grows `rows` to `size`, leaving an eighth more room (not twice as much, as a vector's own growth
// may: these tables reach tens of megabytes).
template <typename T>
void growTo(std::vector<T>& rows, std::size_t size, const T& fill = T{}) {
  if (rows.size() >= size) return;
  if (rows.capacity() < size) rows.reserve(size + size / 8);
  rows.resize(size, fill);
}

// Gives back the room beyond `end` (rows no range uses) once it is more than a quarter of `end`
// and at least `minRows`: after a flight, the rows of evicted tiles.
template <typename T>
bool trimTo(std::vector<T>& rows, std::size_t end, std::size_t minRows) {
  if (rows.capacity() <= end + std::max(end / 4, minRows)) return false;
  std::vector<T> kept(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(std::min(end, rows.size())));
  rows.swap(kept);
  return true;
}

}  // namespace

std::optional<std::uint32_t> BuildingTable::reserveBuildings(std::uint32_t count) {
  const auto first = buildingSlots_->allocate(std::max(count, 1u));
  if (first) growTo(buildings_, buildingSlots_->end());
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
  if (first) growTo(floorRows_, floorSlots_->end());
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
  growTo<std::uint8_t>(seriesCodes_, seriesSlots_->end(), 0);
  seriesInUse_ += count;
  return first;
}

void BuildingTable::releaseSeries(std::uint32_t first, std::uint32_t count) {
  if (count == 0) return;
  seriesSlots_->release(first, count);
  seriesInUse_ -= std::min<std::uint64_t>(seriesInUse_, count);
}

bool BuildingTable::trim() {
  bool trimmed = trimTo(buildings_, buildingSlots_->end(), 16384);
  trimmed = trimTo(floorRows_, floorSlots_->end(), 65536) || trimmed;
  trimmed = trimTo(seriesCodes_, seriesSlots_->end(), 1u << 20) || trimmed;
  return trimmed;
}

std::uint64_t BuildingTable::heapBytes() const {
  return buildings_.capacity() * sizeof(BuildingGpuRecord) + floorRows_.capacity() * sizeof(FloorGpuRecord) +
         seriesCodes_.capacity();
}

std::uint64_t BuildingTable::inUseBytes() const {
  return std::uint64_t{buildingSlots_->used()} * sizeof(BuildingGpuRecord) +
         std::uint64_t{floorSlots_->used()} * sizeof(FloorGpuRecord) + seriesInUse_;
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
  }
  if (seriesChangedFirst_ < seriesChangedEnd_) {
    device.writeSeries(seriesChangedFirst_,
                       std::span(seriesCodes_).subspan(seriesChangedFirst_, seriesChangedEnd_ - seriesChangedFirst_));
  }
  seriesChangedFirst_ = UINT32_MAX;
  seriesChangedEnd_ = 0;
  if (changedFirst_ < changedEnd_) {
    changedEnd_ = std::min<std::uint32_t>(changedEnd_, static_cast<std::uint32_t>(buildings_.size()));
  }
  if (changedFirst_ < changedEnd_) {
    device.writeBuildings(changedFirst_, std::span(buildings_).subspan(changedFirst_, changedEnd_ - changedFirst_));
  }
  changedFirst_ = UINT32_MAX;
  changedEnd_ = 0;
  if (floorsInUse) {
    device.writeFloors(0, std::span(floorRows_).first(std::min<std::size_t>(floorRows_.size(), floorSlots_->end())));
  }
}

}  // namespace qv
