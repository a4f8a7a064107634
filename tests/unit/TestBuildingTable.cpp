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
