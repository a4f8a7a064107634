#include <catch2/catch.hpp>

#include <map>

#include "qv/scene/BuildingTable.h"
#include "qv/scene/NullRenderDevice.h"

using namespace qv;

namespace {

// A device that records which rows it was sent.
class RowRecorder final : public RenderDevice {
 public:
  NullRenderDevice null;
  MeshHandle createMesh(const MeshData& mesh) override { return null.createMesh(mesh); }
  void destroyMesh(MeshHandle mesh) override { null.destroyMesh(mesh); }
  std::size_t meshTriangles(MeshHandle mesh) const override { return null.meshTriangles(mesh); }
  void render(const FrameUniforms& u, std::span<const DrawItem> items) override { null.render(u, items); }
  DeviceFrameStats lastFrameStats() const override { return null.lastFrameStats(); }
  std::size_t gpuBytes() const override { return null.gpuBytes(); }

  std::vector<std::pair<std::uint32_t, std::size_t>> buildingWrites;  // first, count
  std::map<std::uint32_t, BuildingGpuRecord> buildings;
  std::size_t floorRowsSent = 0;
  void writeBuildings(std::uint32_t first, std::span<const BuildingGpuRecord> rows) override {
    buildingWrites.push_back({first, rows.size()});
    for (std::size_t i = 0; i < rows.size(); ++i) buildings[first + static_cast<std::uint32_t>(i)] = rows[i];
  }
  void writeFloors(std::uint32_t first, std::span<const FloorGpuRecord> rows) override {
    CHECK(first == 0);
    floorRowsSent = rows.size();
  }
  void writeSeries(std::uint32_t first, std::span<const std::uint8_t> codes) override {
    seriesFirst = first;
    seriesSent = codes.size();
  }
  std::uint32_t seriesFirst = 0;
  std::size_t seriesSent = 0;
};

}  // namespace

TEST_CASE("Only the changed building rows are sent, once", "[scene][table]") {
  BuildingTable table(1000, 1000);
  RowRecorder device;
  const auto a = table.reserveBuildings(10);
  const auto b = table.reserveBuildings(5);
  REQUIRE(a);
  REQUIRE(b);
  CHECK(*b >= *a + 10);  // ranges do not overlap
  for (BuildingGpuRecord& row : table.edit(*a, 10)) row.storeys = 3.0f;
  table.upload(device, false);
  REQUIRE(device.buildingWrites.size() == 1);
  CHECK(device.buildingWrites[0] == std::pair<std::uint32_t, std::size_t>{*a, 10});
  CHECK(device.buildings.at(*a + 9).storeys == 3.0f);

  table.upload(device, false);  // nothing changed: nothing sent
  CHECK(device.buildingWrites.size() == 1);

  // Two edits far apart go as one span from the first to the last.
  table.edit(*a + 2, 1)[0].damageState = 4.0f;
  table.row(*b + 4).peakValue = 0.5f;
  table.changed(*b + 4, 1);
  table.upload(device, false);
  REQUIRE(device.buildingWrites.size() == 2);
  CHECK(device.buildingWrites[1] == std::pair<std::uint32_t, std::size_t>{*a + 2, *b + 4 - (*a + 2) + 1});
  CHECK(device.buildings.at(*a + 2).damageState == 4.0f);
  CHECK(device.buildings.at(*b + 4).peakValue == 0.5f);
  CHECK(device.floorRowsSent == 0);
}

TEST_CASE("Flags are set and cleared bit by bit", "[scene][table]") {
  BuildingGpuRecord row;
  BuildingTable::setFlag(row, kFlagSelected, true);
  BuildingTable::setFlag(row, kFlagHidden, true);
  CHECK(static_cast<unsigned>(row.flags) == (kFlagSelected | kFlagHidden));
  BuildingTable::setFlag(row, kFlagSelected, false);
  BuildingTable::setFlag(row, kFlagDimmed, false);
  CHECK(static_cast<unsigned>(row.flags) == kFlagHidden);
}

TEST_CASE("Rows are reused after release, a full table says so, floors are sent up to the highest in use",
          "[scene][table]") {
  BuildingTable table(16, 40);
  const auto a = table.reserveBuildings(16);
  REQUIRE(a);
  CHECK_FALSE(table.reserveBuildings(1));  // full
  table.releaseBuildings(*a, 16);
  CHECK(table.reserveBuildings(0));  // a tile without buildings still takes a row

  const auto f1 = table.reserveFloors(6);
  const auto f2 = table.reserveFloors(30);
  REQUIRE(f1);
  REQUIRE(f2);
  CHECK_FALSE(table.reserveFloors(10));
  table.floors(*f2, 30)[29].dxMeters = 0.25f;
  RowRecorder device;
  table.upload(device, true);
  CHECK(device.floorRowsSent == 36);
  table.releaseFloors(*f1, 6);
  CHECK(table.reserveFloors(6) == f1);
}

TEST_CASE("The table gives back the rows of evicted tiles once they are many, and keeps what is in use",
          "[scene][table]") {
  BuildingTable table(1u << 21, 1u << 22);
  // A large coarse tile and a leaf above it; the coarse tile is evicted after a flight.
  const auto coarse = table.reserveBuildings(200000);
  const auto leaf = table.reserveBuildings(3000);
  REQUIRE(coarse);
  REQUIRE(leaf);
  table.edit(*leaf, 3000)[2999].storeys = 7.0f;
  const std::uint64_t full = table.heapBytes();
  CHECK(full >= 203000u * sizeof(BuildingGpuRecord));
  CHECK(full <= 203000u * sizeof(BuildingGpuRecord) * 9 / 8 + 1);  // an eighth of room, not twice
  CHECK(table.inUseBytes() == 203000u * sizeof(BuildingGpuRecord));
  // The rows are below the leaf's: nothing can be given back (the leaf keeps its rows).
  table.releaseBuildings(*coarse, 200000);
  CHECK_FALSE(table.trim());
  CHECK(table.heapBytes() == full);
  // Once the leaf goes too, the room is given back and the table still grows when needed.
  const auto small = table.reserveBuildings(100);
  REQUIRE(small == coarse);
  table.releaseBuildings(*leaf, 3000);
  CHECK(table.trim());
  CHECK(table.heapBytes() == 100u * sizeof(BuildingGpuRecord));
  CHECK_FALSE(table.trim());  // nothing more to give
  const auto again = table.reserveBuildings(5000);
  REQUIRE(again == 100u);
  table.edit(*again, 5000)[4999].storeys = 3.0f;
  RowRecorder device;
  table.upload(device, false);
  REQUIRE(device.buildings.count(*again + 4999) == 1);
  CHECK(device.buildings[*again + 4999].storeys == 3.0f);
  // A change marked on rows that were given back is not sent.
  table.changed(10000, 50);
  device.buildingWrites.clear();
  table.upload(device, false);
  CHECK(device.buildingWrites.empty());
}

TEST_CASE("Floors are sent up to the highest in use now, not the highest ever", "[scene][table]") {
  BuildingTable table(16, 1u << 20);
  const auto low = table.reserveFloors(10);
  const auto high = table.reserveFloors(200000);
  REQUIRE(low);
  REQUIRE(high);
  RowRecorder device;
  table.upload(device, true);
  CHECK(device.floorRowsSent == 200010);
  table.releaseFloors(*high, 200000);
  table.upload(device, true);
  CHECK(device.floorRowsSent == 10);
  CHECK(table.trim());
  CHECK(table.heapBytes() < 20000u);
}
