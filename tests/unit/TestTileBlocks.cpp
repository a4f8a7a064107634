#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <set>

#include "qv/scene/TileBlocks.h"

using namespace qv;

namespace {

// A coarse tile of axis-aligned rectangular buildings (tile-local metres, origin at `origin`).
struct TileBuilder {
  CityTile tile;
  explicit TileBuilder(double originX = 1000.0, double originY = -500.0) {
    tile.coarse = true;
    tile.originX = originX;
    tile.originY = originY;
    tile.extent = 10000.0f;
  }
  // One part from (x0, y0) to (x1, y1), from base to top; a new building unless `sameBuilding`.
  void rect(float x0, float y0, float x1, float y1, float top, float base = 0.0f, bool sameBuilding = false) {
    TilePart part;
    part.firstVertex = static_cast<std::uint32_t>(tile.vertices.size());
    part.vertexCount = 4;
    part.firstRing = static_cast<std::uint32_t>(tile.ringVertexCounts.size());
    part.ringCount = 1;
    part.firstTriangle = static_cast<std::uint32_t>(tile.roofTriangles.size() / 3);
    part.triangleCount = 2;
    part.minHeightM = base;
    part.heightM = top;
    for (const glm::vec2 v : {glm::vec2(x0, y0), glm::vec2(x1, y0), glm::vec2(x1, y1), glm::vec2(x0, y1)})
      tile.vertices.push_back(v);
    tile.ringVertexCounts.push_back(4);
    for (int i : {0, 1, 2, 0, 2, 3}) tile.roofTriangles.push_back(static_cast<std::uint16_t>(i));
    tile.parts.push_back(part);
    if (sameBuilding) {
      ++tile.buildings.back().partCount;
      return;
    }
    TileBuilding b;
    b.attributes.id = "b" + std::to_string(tile.buildings.size());
    b.attributes.heightM = top;
    b.attributes.storeys = static_cast<std::uint16_t>(std::max(1.0f, std::round(top / 3.0f)));
    b.attributes.centroidX = 0.5f * (x0 + x1);
    b.attributes.centroidY = 0.5f * (y0 + y1);
    b.firstPart = static_cast<std::uint32_t>(tile.parts.size() - 1);
    b.partCount = 1;
    tile.buildings.push_back(b);
  }
  TileContent build() { return indexTile(tile); }
};

// A grid of n × n buildings of 12 m × 12 m, 20 m apart, of heights 6 .. 6 + (i + j) m.
TileContent gridTile(int n) {
  TileBuilder t;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const float x = 3.0f + 20.0f * static_cast<float>(i), y = 5.0f + 20.0f * static_cast<float>(j);
      t.rect(x, y, x + 12.0f, y + 12.0f, 6.0f + static_cast<float>(i + j));
    }
  }
  return t.build();
}

bool inside(const Box& b, float x, float y, float z) {
  constexpr float e = 1e-3f;
  return x >= b.minX - e && x <= b.maxX + e && y >= b.minY - e && y <= b.maxY + e && z >= b.minZ - e && z <= b.maxZ + e;
}

}  // namespace

TEST_CASE("Blocks cover every building, lie in one grid cell each and never overlap", "[scene][blocks]") {
  const TileContent tile = gridTile(12);
  for (const float cell : {32.0f, 64.0f, 128.0f}) {
    CAPTURE(cell);
    const TileBlockLevel level = buildBlockLevel(tile, cell, buildTileRegions(tile));
    REQUIRE(!level.boxes.empty());
    REQUIRE(level.memberStart.size() == level.boxes.size() + 1);
    // Each block within one cell of the city-aligned grid.
    for (const Box& b : level.boxes) {
      const float cx = std::floor((b.minX + 1e-3f) / cell), cy = std::floor((b.minY + 1e-3f) / cell);
      CHECK(b.maxX <= (cx + 1.0f) * cell + 1e-3f);
      CHECK(b.maxY <= (cy + 1.0f) * cell + 1e-3f);
    }
    // No two blocks share floor area.
    for (std::size_t a = 0; a < level.boxes.size(); ++a) {
      for (std::size_t c = a + 1; c < level.boxes.size(); ++c) {
        const Box& p = level.boxes[a];
        const Box& q = level.boxes[c];
        const float ox = std::min(p.maxX, q.maxX) - std::max(p.minX, q.minX);
        const float oy = std::min(p.maxY, q.maxY) - std::max(p.minY, q.minY);
        CHECK_FALSE((ox > 1e-3f && oy > 1e-3f));
      }
    }
    // Every corner of every building, at its roof, is inside a block it is a member of.
    for (std::uint32_t b = 0; b < tile.buildingCount(); ++b) {
      const TilePart& part = tile.data.parts[tile.data.buildings[b].firstPart];
      for (std::uint32_t v = part.firstVertex; v < part.firstVertex + 4; ++v) {
        const float x = tile.data.vertices[v].x + tile.origin.x, y = tile.data.vertices[v].y + tile.origin.y;
        bool covered = false;
        for (std::size_t k = 0; k < level.boxes.size() && !covered; ++k) {
          if (!inside(level.boxes[k], x, y, part.heightM)) continue;
          for (std::uint32_t m = level.memberStart[k]; m < level.memberStart[k + 1]; ++m)
            covered = covered || tile.tree.order()[level.members[m]] == b;
        }
        CHECK(covered);
      }
    }
  }
  // Coarser cells, fewer blocks; 240 m of city on 128 m cells: at most 3 × 3.
  CHECK(buildBlockLevel(tile, 128.0f, buildTileRegions(tile)).boxes.size() <= 9);
  CHECK(buildBlockLevel(tile, 64.0f, buildTileRegions(tile)).boxes.size() <
        buildBlockLevel(tile, 32.0f, buildTileRegions(tile)).boxes.size());
}

TEST_CASE("A block rises to its tallest member within its cell, and a long building belongs to every cell it crosses",
          "[scene][blocks]") {
  TileBuilder t(0.0, 0.0);
  t.rect(1.0f, 1.0f, 20.0f, 20.0f, 10.0f);                                  // low, cell (0, 0)
  t.rect(40.0f, 1.0f, 60.0f, 20.0f, 30.0f);                                 // tower base, cell (1, 0)
  t.rect(45.0f, 5.0f, 55.0f, 15.0f, 120.0f, 30.0f, /*sameBuilding=*/true);  // its spire part
  t.rect(1.0f, 40.0f, 126.0f, 50.0f, 8.0f);                                 // a long shed across (0..3, 1)
  const TileContent tile = t.build();
  const TileBlockLevel level = buildBlockLevel(tile, 32.0f, buildTileRegions(tile));
  std::map<std::pair<int, int>, std::size_t> byCell;
  for (std::size_t k = 0; k < level.boxes.size(); ++k) {
    const Box& b = level.boxes[k];
    byCell[{static_cast<int>(std::floor(b.minX / 32.0f)), static_cast<int>(std::floor(b.minY / 32.0f))}] = k;
  }
  REQUIRE(byCell.size() == level.boxes.size());
  REQUIRE(byCell.count({0, 0}) == 1);
  CHECK(level.boxes[byCell.at({0, 0})].maxZ == Approx(10.0f));
  // The tower's parts reach into cell (1, 0) only: one block at the spire's top, from the ground.
  REQUIRE(byCell.count({1, 0}) == 1);
  CHECK(level.boxes[byCell.at({1, 0})].maxZ == Approx(120.0f));
  CHECK(level.boxes[byCell.at({1, 0})].minZ == Approx(0.0f));
  // The shed: in all four cells of row 1, each block clipped to its cell.
  for (int cx = 0; cx < 4; ++cx) {
    CAPTURE(cx);
    REQUIRE(byCell.count({cx, 1}) == 1);
    const std::size_t k = byCell.at({cx, 1});
    CHECK(level.boxes[k].maxX - level.boxes[k].minX <= 32.0f + 1e-3f);
    CHECK(level.memberStart[k + 1] - level.memberStart[k] == 1);
  }
  CHECK(level.boxes.size() == 6);
}

TEST_CASE("A block's mesh is a box per block in its own row, its colour its worst member's", "[scene][blocks]") {
  const TileContent tile = gridTile(8);
  const TileBlockLevel level = buildBlockLevel(tile, 64.0f, buildTileRegions(tile));
  const std::uint32_t slotBase = 500;
  TileIndexRuns runs;
  const MeshData mesh = buildBlockMesh(level, tile.origin, slotBase, &runs);
  CHECK(mesh.triangleCount() <= level.boxes.size() * 10);  // at most four walls and a roof
  REQUIRE(runs.firstIndex.size() == level.boxes.size() + 1);
  for (const BuildingVertex& v : mesh.vertices) {
    REQUIRE(v.slot >= slotBase);
    REQUIRE(v.slot < slotBase + level.boxes.size());
    CHECK(inside(level.boxes[v.slot - slotBase], v.x + tile.origin.x, v.y + tile.origin.y, v.z));
  }
  for (std::size_t p = 0; p < level.boxes.size(); ++p) {
    const std::uint32_t indices = runs.firstIndex[p + 1] - runs.firstIndex[p];
    CHECK(indices >= 6);  // its roof
    CHECK(indices <= 30);
  }

  // Rows: building at position p has damage p % 5 (or pending / none for some), peak p / 1000.
  std::vector<BuildingGpuRecord> rows(tile.buildingCount());
  for (std::uint32_t p = 0; p < rows.size(); ++p) {
    rows[p].damageState = static_cast<float>(p % 5);
    rows[p].peakValue = static_cast<float>(p) / 1000.0f;
    rows[p].flags = static_cast<float>(kFlagDimmed | (p == 7 ? kFlagSelected : 0u));
    rows[p].lossCode = static_cast<float>(p);
  }
  std::vector<BuildingGpuRecord> out(level.boxes.size());
  aggregateBlockRows(level, rows, out);
  bool sawSelected = false;
  for (std::size_t k = 0; k < out.size(); ++k) {
    float damage = -1.0f, peak = 0.0f, loss = -1.0f;
    bool selected = false;
    for (std::uint32_t m = level.memberStart[k]; m < level.memberStart[k + 1]; ++m) {
      const std::uint32_t p = level.members[m];
      damage = std::max(damage, rows[p].damageState);
      peak = std::max(peak, rows[p].peakValue);
      loss = std::max(loss, rows[p].lossCode);
      selected = selected || p == 7;
    }
    CHECK(out[k].damageState == damage);
    CHECK(out[k].peakValue == peak);
    CHECK(out[k].lossCode == loss);
    CHECK(out[k].floorBase == -1.0f);  // never animated
    const auto flags = static_cast<unsigned>(out[k].flags);
    CHECK(((flags & kFlagSelected) != 0) == selected);
    CHECK((flags & kFlagDimmed) != 0);  // every member dimmed
    sawSelected = sawSelected || selected;
  }
  CHECK(sawSelected);
  // One member passing the filter un-dims its block; a result beats pending, pending beats none.
  const std::uint32_t first = level.members[level.memberStart[0]];
  rows[first].flags = 0.0f;
  for (std::uint32_t m = level.memberStart[0]; m < level.memberStart[1]; ++m)
    rows[level.members[m]].damageState = kDamageNoResult;
  rows[first].damageState = kDamagePending;
  REQUIRE(level.memberStart[1] - level.memberStart[0] > 1);
  rows[level.members[level.memberStart[1] - 1]].damageState = 4.0f;  // dimmed: left out of the colour
  aggregateBlockRows(level, rows, out);
  CHECK((static_cast<unsigned>(out[0].flags) & kFlagDimmed) == 0);
  CHECK(out[0].damageState == kDamagePending);  // the kept member's, not the dimmed ones' results
  CHECK(out[0].peakValue == rows[first].peakValue);
  for (std::uint32_t m = level.memberStart[0]; m < level.memberStart[1]; ++m) rows[level.members[m]].flags = 0.0f;
  rows[level.members[level.memberStart[1] - 1]].damageState = 1.0f;
  aggregateBlockRows(level, rows, out);
  CHECK(out[0].damageState == 1.0f);
}

TEST_CASE("A block's wall inside its neighbour is left out, one that shows is kept", "[scene][blocks]") {
  TileBuilder t(0.0, 0.0);
  t.rect(0.0f, 0.0f, 64.0f, 64.0f, 10.0f);    // fills cell (0, 0)
  t.rect(64.0f, 0.0f, 128.0f, 64.0f, 20.0f);  // fills cell (1, 0), taller
  const TileContent tile = t.build();
  const TileBlockLevel level = buildBlockLevel(tile, 64.0f, buildTileRegions(tile));
  REQUIRE(level.boxes.size() == 2);
  TileIndexRuns runs;
  const MeshData mesh = buildBlockMesh(level, tile.origin, 0, &runs);
  for (std::uint32_t p = 0; p < 2; ++p) {
    const std::uint32_t triangles = (runs.firstIndex[p + 1] - runs.firstIndex[p]) / 3;
    // The low block's wall facing the tall one is inside it; the tall one's shows above the low roof.
    CHECK(triangles == (level.boxes[p].maxZ < 15.0f ? 8u : 10u));
  }
  CHECK(mesh.triangleCount() == 18);
}

TEST_CASE("A far-view tile's regions: every building in one, blocks of each level region by region",
          "[scene][blocks]") {
  // 3 km of city across the 512 m region grid (and across the origin, negative cells included).
  TileBuilder t(-1500.0, -700.0);
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 14; ++j) {
      const float x = 100.0f * static_cast<float>(i) + 10.0f, y = 100.0f * static_cast<float>(j) + 10.0f;
      t.rect(x, y, x + 30.0f, y + 20.0f, 10.0f + static_cast<float>(j));
    }
  }
  const TileContent tile = t.build();
  const TileRegions regions = buildTileRegions(tile);
  REQUIRE(regions.boxes.size() >= 12);  // 6 x 3 regions at least
  REQUIRE(regions.positionStart.size() == regions.boxes.size() + 1);
  REQUIRE(regions.positionStart.back() == tile.buildingCount());
  std::set<std::uint32_t> seen(regions.appendOrder.begin(), regions.appendOrder.end());
  CHECK(seen.size() == tile.buildingCount());  // a permutation of the positions
  for (std::uint32_t r = 0; r < regions.boxes.size(); ++r) {
    const Box& box = regions.boxes[r];
    CHECK(regions.level == kBlockRegionLevel);  // 3 km: six regions across
    CHECK(box.maxX - box.minX == Approx(blockCellM(regions.level)));
    CHECK(box.maxX - box.minX == Approx(512.0f));
    for (std::uint32_t k = regions.positionStart[r]; k < regions.positionStart[r + 1]; ++k) {
      const std::uint32_t p = regions.appendOrder[k];
      CHECK(regions.regionOfPosition[p] == r);
      const Box b = buildingBox(tile, tile.tree.order()[p]);
      const float cx = 0.5f * (b.minX + b.maxX), cy = 0.5f * (b.minY + b.maxY);
      CHECK(inside(box, cx, cy, box.minZ));
      CHECK(regions.regionOf(cx, cy) == r);
    }
  }
  for (const float cell : {64.0f, 256.0f, 512.0f}) {
    CAPTURE(cell);
    const TileBlockLevel level = buildBlockLevel(tile, cell, regions);
    REQUIRE(level.regionStart.size() == regions.boxes.size() + 1);
    REQUIRE(level.regionStart.back() == level.boxes.size());
    for (std::uint32_t r = 0; r < regions.boxes.size(); ++r) {
      for (std::uint32_t k = level.regionStart[r]; k < level.regionStart[r + 1]; ++k) {
        const Box& b = level.boxes[k];
        CHECK(inside(regions.boxes[r], b.minX, b.minY, regions.boxes[r].minZ));
        CHECK(inside(regions.boxes[r], b.maxX, b.maxY, regions.boxes[r].minZ));
      }
    }
  }
}

TEST_CASE("A tile wider than 32 regions of 512 m gets a far grid, on which its far view draws screen-sized blocks",
          "[scene][blocks]") {
  // The finest level from 512 m on with at most 32 regions along the longer side.
  CHECK(regionLevelFor(0.0f, 0.0f) == kBlockRegionLevel);
  CHECK(regionLevelFor(16384.0f, 100.0f) == kBlockRegionLevel);  // 32 regions of 512 m exactly
  CHECK(regionLevelFor(16385.0f, 100.0f) == kBlockRegionLevel + 1);
  CHECK(regionLevelFor(100.0f, 59000.0f) == kBlockRegionLevel + 2);  // a 59 km region: 2,048 m regions
  CHECK(regionLevelFor(1e9f, 1e9f) == kBlockLevels - 1);
  CHECK(regionLevelFor(NAN, 0.0f) == kBlockLevels - 1);

  // 40 km × 20 km of buildings, one a kilometre.
  TileBuilder t(-20000.0, -10000.0);
  t.tile.extent = 50000.0f;
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 20; ++j) {
      const float x = 1000.0f * static_cast<float>(i) + 100.0f, y = 1000.0f * static_cast<float>(j) + 100.0f;
      t.rect(x, y, x + 60.0f, y + 40.0f, 10.0f + static_cast<float>(i % 7));
    }
  }
  const TileContent tile = t.build();
  CHECK(buildTileRegions(tile).level == kBlockRegionLevel);  // the 512 m grid: 79 regions across
  const Box& all = tile.tree.bounds();
  const TileRegions regions = buildTileRegions(tile, regionLevelFor(all.maxX - all.minX, all.maxY - all.minY));
  REQUIRE(regions.level == kBlockRegionLevel + 2);  // the far grid, 2,048 m: 20 across
  REQUIRE(regions.boxes.size() <= 21u * 11u);
  REQUIRE(regions.positionStart.back() == tile.buildingCount());
  for (std::uint32_t r = 0; r < regions.boxes.size(); ++r) {
    const Box& box = regions.boxes[r];
    CHECK(box.maxX - box.minX == Approx(2048.0f));
    for (std::uint32_t k = regions.positionStart[r]; k < regions.positionStart[r + 1]; ++k) {
      const Box b = buildingBox(tile, tile.tree.order()[regions.appendOrder[k]]);
      CHECK(regions.regionOf(0.5f * (b.minX + b.maxX), 0.5f * (b.minY + b.maxY)) == r);
    }
  }
  // Blocks as wide as a region: one a region at most, each inside its region, every building a member.
  const TileBlockLevel level = buildBlockLevel(tile, blockCellM(regions.level), regions);
  REQUIRE(level.regionStart.back() == level.boxes.size());
  CHECK(level.boxes.size() <= regions.boxes.size());
  std::set<std::uint32_t> members(level.members.begin(), level.members.end());
  CHECK(members.size() == tile.buildingCount());
  for (std::uint32_t r = 0; r < regions.boxes.size(); ++r) {
    for (std::uint32_t k = level.regionStart[r]; k < level.regionStart[r + 1]; ++k) {
      CHECK(inside(regions.boxes[r], level.boxes[k].minX, level.boxes[k].minY, regions.boxes[r].minZ));
      CHECK(inside(regions.boxes[r], level.boxes[k].maxX, level.boxes[k].maxY, regions.boxes[r].minZ));
    }
  }
}
