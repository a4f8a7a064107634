// Occupants of a real city against its census: the shared Manhattan extract, read, tiled and
// counted building by building as `quakeview-prep response` counts them (seismic::buildingOccupants
// on exposureFromAttributes with the floor area over the tiles' parts).
#include <catch2/catch.hpp>

#include <set>

#include "IngestTestData.h"
#include "qv/format/CityTile.h"
#include "qv/prep/Files.h"
#include "qv/prep/Tiler.h"
#include "qv/seismic/Loss.h"

namespace qv::prep {
namespace {

// The area of the shared PBF (lon -74.031..-73.963, lat 40.695..40.759, without the band
// 40.7300..40.7361 that holds no buildings): residents (2020) and daytime population. docs/losses.md
// ("Occupants", "The census figures of the shared Manhattan area") derives both from published figures.
constexpr double kResidents = 512000;
constexpr double kDaytimePopulation = 1750000;

}  // namespace

TEST_CASE("The shared Manhattan area holds about its census residents at night and its daytime population by day",
          "[ingest][occupants][real-data]") {
  CityModel city = test::manhattanSouth().model.value();  // a copy: the tiler takes its model
  const test::TempDir dir;
  TilerOptions options;
  options.showProgress = false;
  const Result<TilerReport> report = writeCityTiles(city, dir.path("city"), options);
  REQUIRE(report.ok());

  std::array<double, 3> total{};
  double floorArea = 0;
  std::set<std::string> seen;
  std::size_t overCapacity = 0, fromParts = 0;
  for (const TileNode& node : report->tileset.nodes) {
    if (node.coarse) continue;
    const auto bytes = readFile(dir.path("city") + "/" + node.file);
    REQUIRE(bytes.ok());
    const Result<CityTile> tile = decodeCityTile(*bytes, node.file);
    REQUIRE(tile.ok());
    for (const TileBuilding& b : tile->buildings) {
      REQUIRE(seen.insert(b.attributes.id).second);
      const double partsArea = buildingFloorAreaM2(*tile, b);
      if (partsArea > 0) ++fromParts;
      const seismic::Exposure e = seismic::exposureFromAttributes(b.attributes, b.attributes.storeys, partsArea);
      const seismic::BuildingOccupants o = seismic::buildingOccupants(e);
      for (std::size_t t = 0; t < 3; ++t) {
        total[t] += o.at[t];
        if (o.at[t] > o.capacity * (1 + 1e-9)) ++overCapacity;
      }
      floorArea += e.floorAreaM2;
      if (b.attributes.id == "w34633854") {  // the Empire State Building: its tiers, not its base x 102
        INFO("Empire State Building floor area " << e.floorAreaM2 << " m2, " << o.at[1] << " by day");
        CHECK(e.floorAreaM2 < 0.6 * b.attributes.footprintAreaM2 * b.attributes.storeys);
        CHECK(o.at[1] > 5000);
        CHECK(o.at[1] < 30000);
        CHECK(o.at[0] < o.at[1] / 20);  // an office building is nearly empty at night
      }
    }
  }
  INFO("night " << total[0] << ", day " << total[1] << ", commute " << total[2] << ", floor area " << floorArea);
  CHECK(seen.size() > 17000);
  CHECK(fromParts == seen.size());
  CHECK(overCapacity == 0);
  CHECK(total[0] == Approx(kResidents).epsilon(0.25));
  CHECK(total[1] == Approx(kDaytimePopulation).epsilon(0.25));
  CHECK(total[2] > total[0]);  // commute lies between night and day here
  CHECK(total[2] < total[1]);
}

}  // namespace qv::prep
