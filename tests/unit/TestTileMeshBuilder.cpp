#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <set>

#include <glm/geometric.hpp>

#include "MiniCity.h"
#include "qv/scene/TileMeshBuilder.h"

using namespace qv;
using test::MiniCity;

namespace {

// Node `node` of the city, decoded and indexed.
TileContent tileOf(const MiniCity& city, std::uint32_t node) {
  const std::string url = "city/" + city.tileset.nodes[node].file;
  Result<CityTile> decoded = decodeCityTile(city.files.at(url), url);
  REQUIRE(decoded.ok());
  return indexTile(std::move(decoded).value());
}

struct SlotGeometry {
  int plain = 0, model = 0, fallback = 0;
  float topZ = -1e9f;
  glm::vec2 sum{0.0f};
};

// Per slot: vertex counts by kind, the highest vertex and the sum of plain vertices' positions.
std::map<std::uint32_t, SlotGeometry> bySlot(const MeshData& mesh) {
  std::map<std::uint32_t, SlotGeometry> out;
  for (const BuildingVertex& v : mesh.vertices) {
    SlotGeometry& g = out[v.slot];
    if ((v.kind & kKindModel) != 0) {
      ++g.model;
      g.topZ = std::max(g.topZ, v.z);
    } else if ((v.kind & kKindFallback) != 0) {
      ++g.fallback;
    } else {
      ++g.plain;
      g.sum += glm::vec2(v.x, v.y);
    }
  }
  return out;
}

}  // namespace

TEST_CASE("A tile's index finds every building and its row", "[scene][tilemesh]") {
  const MiniCity city;
  for (std::uint32_t node = 0; node < city.tileset.nodes.size(); ++node) {
    CAPTURE(node);
    const TileContent tile = tileOf(city, node);
    REQUIRE(tile.buildingCount() == city.tileset.nodes[node].buildings);
    REQUIRE(tile.positionOf.size() == tile.buildingCount());
    for (std::uint32_t b = 0; b < tile.buildingCount(); ++b) {
      CHECK(tile.idIndex.at(tile.data.buildings[b].attributes.id) == b);
      CHECK(tile.tree.order()[tile.positionOf[b]] == b);
      CHECK(tile.meshOf(b) == nullptr);  // no LOD2 in this city
    }
  }
}

TEST_CASE("A tile's mesh draws each building at its place, in its own row, with floor rings in leaves",
          "[scene][tilemesh]") {
  const MiniCity city;
  const TileContent root = tileOf(city, 0);
  const std::uint32_t slotBase = 1000;
  const auto coarse = bySlot(buildTileMesh(root, slotBase));
  REQUIRE(coarse.size() == root.buildingCount());
  for (std::uint32_t b = 0; b < root.buildingCount(); ++b) {
    const BuildingAttributes& a = root.data.buildings[b].attributes;
    const SlotGeometry& g = coarse.at(slotBase + root.positionOf[b]);
    const glm::vec2 centre = g.sum / static_cast<float>(g.plain) + glm::vec2(root.origin);
    CHECK(centre.x == Approx(a.centroidX + root.data.originX).margin(0.5));
    CHECK(centre.y == Approx(a.centroidY + root.data.originY).margin(0.5));
  }
  // The same building in a leaf has a vertex ring at each floor level (the floors bend apart).
  const TileContent leaf = tileOf(city, 1);
  const auto detailed = bySlot(buildTileMesh(leaf, 0));
  const std::string& id = leaf.data.buildings[0].attributes.id;
  const int leafVertices = detailed.at(leaf.positionOf[0]).plain;
  const int coarseVertices = coarse.at(slotBase + root.positionOf[root.idIndex.at(id)]).plain;
  CHECK(leafVertices > coarseVertices);
  // The rings sit at the building's floor levels: its base, every storey of 3.5 m, its roof.
  std::set<float> heights;
  for (const BuildingVertex& v : buildTileMesh(leaf, 0).vertices) {
    if (v.slot == leaf.positionOf[0]) heights.insert(v.z);
  }
  std::set<float> levels;
  for (int k = 0; k <= MiniCity::kStoreys; ++k) levels.insert(static_cast<float>(k) * MiniCity::kStoreyHeight);
  CHECK(heights == levels);

  // As plain prisms (a still leaf): the same buildings in the same rows and places, walls from base
  // to roof without rings, and far fewer triangles.
  TileIndexRuns storeyRuns, prismRuns;
  const MeshData storeys = buildTileMesh(leaf, 0, &storeyRuns);
  const MeshData prisms = buildTileMesh(leaf, 0, &prismRuns, {}, TileWalls::Prisms);
  const auto plain = bySlot(prisms);
  REQUIRE(plain.size() == detailed.size());
  for (const auto& [slot, g] : plain) {
    const SlotGeometry& withRings = detailed.at(slot);
    CHECK(g.plain < withRings.plain);
    const glm::vec2 a = g.sum / static_cast<float>(g.plain);
    const glm::vec2 b = withRings.sum / static_cast<float>(withRings.plain);
    CHECK(a.x == Approx(b.x).margin(0.01));
    CHECK(a.y == Approx(b.y).margin(0.01));
  }
  std::set<float> prismHeights;
  for (const BuildingVertex& v : prisms.vertices) {
    if (v.slot == leaf.positionOf[0]) prismHeights.insert(v.z);
  }
  CHECK(prismHeights == std::set<float>{0.0f, MiniCity::kStoreys * MiniCity::kStoreyHeight});
  CHECK(prisms.triangleCount() * 2 < storeys.triangleCount());
  // Its runs cover each position's triangles as the storeys' runs do theirs.
  REQUIRE(prismRuns.firstIndex.size() == storeyRuns.firstIndex.size());
  CHECK(prismRuns.firstIndex.back() == prisms.indices.size());
  for (std::size_t p = 0; p + 1 < prismRuns.firstIndex.size(); ++p) {
    CHECK(prismRuns.firstIndex[p] < prismRuns.firstIndex[p + 1]);
    for (std::uint32_t k = prismRuns.firstIndex[p]; k < prismRuns.firstIndex[p + 1]; ++k)
      CHECK(prisms.vertices[prisms.indices[k]].slot == p);
  }
}

TEST_CASE("A LOD2 model is meshed with its LOD1 fallback in the same row", "[scene][tilemesh][lod2]") {
  const MiniCity city(true, true);
  const TileContent tile = tileOf(city, 1);
  const auto it = tile.idIndex.find(MiniCity::kLod2Id);
  REQUIRE(it != tile.idIndex.end());
  REQUIRE(tile.meshOf(it->second) != nullptr);
  const MeshData mesh = buildTileMesh(tile, 0);
  const auto slots = bySlot(mesh);
  const SlotGeometry& g = slots.at(tile.positionOf[it->second]);
  CHECK(g.model > 0);
  CHECK(g.fallback > 0);
  CHECK(g.plain == 0);
  CHECK(g.topZ == Approx(MiniCity::kSpireTopM).margin(0.01));
  CHECK(mesh.modelTriangles > 0);
  CHECK(mesh.fallbackTriangles > 0);
  // Every other building is plain.
  for (const auto& [slot, other] : slots) {
    if (slot != tile.positionOf[it->second]) CHECK(other.model + other.fallback == 0);
  }
}

TEST_CASE("Far away (coarse tiles) a LOD2 model is its extruded parts: vertical walls and flat roofs only",
          "[scene][tilemesh][lod2]") {
  const MiniCity city(true, true);
  const TileContent tile = tileOf(city, 0);
  REQUIRE(tile.data.coarse);
  const auto it = tile.idIndex.find(MiniCity::kLod2Id);
  REQUIRE(it != tile.idIndex.end());
  REQUIRE(tile.meshOf(it->second) != nullptr);
  CHECK(tile.drawnModelOf(it->second) == nullptr);
  const MeshData mesh = buildTileMesh(tile, 0);
  const std::uint32_t slot = tile.positionOf[it->second];
  const auto slots = bySlot(mesh);
  const SlotGeometry& g = slots.at(slot);
  CHECK(g.model + g.fallback == 0);
  CHECK(g.plain > 0);
  CHECK(mesh.modelTriangles == 0);
  // Every triangle of it is a wall (its normal horizontal) or a roof or floor (its corners level).
  int triangles = 0;
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const BuildingVertex& a = mesh.vertices[mesh.indices[i]];
    const BuildingVertex& b = mesh.vertices[mesh.indices[i + 1]];
    const BuildingVertex& c = mesh.vertices[mesh.indices[i + 2]];
    if (a.slot != slot) continue;
    ++triangles;
    const glm::vec3 n =
        glm::cross(glm::vec3(b.x - a.x, b.y - a.y, b.z - a.z), glm::vec3(c.x - a.x, c.y - a.y, c.z - a.z));
    const bool level = a.z == b.z && b.z == c.z;
    const bool vertical = std::abs(n.z) <= 1e-4f * glm::length(n);
    CHECK((level || vertical));
  }
  CHECK(triangles > 0);
}

TEST_CASE("A tile's first rows carry its storeys and say whether results are on their way", "[scene][tilemesh]") {
  const MiniCity withResponse;
  const TileContent tile = tileOf(withResponse, 1);
  std::vector<BuildingGpuRecord> rows(tile.buildingCount());
  for (bool pending : {true, false}) {
    initialBuildingRows(tile, pending, rows);
    for (const BuildingGpuRecord& row : rows) {
      CHECK(row.storeys == static_cast<float>(MiniCity::kStoreys));
      CHECK(row.storeyHeightMeters == Approx(MiniCity::kStoreyHeight));
      CHECK(row.damageState == (pending ? kDamagePending : -1.0f));
      CHECK(row.floorBase == -1.0f);
      CHECK(row.flags == 0.0f);
    }
  }
}

TEST_CASE("A tile's index runs find each building's triangles and draw visible ranges in few runs",
          "[scene][tilemesh][spans]") {
  const MiniCity city;
  const TileContent leaf = tileOf(city, 1);
  TileIndexRuns runs;
  const MeshData mesh = buildTileMesh(leaf, 0, &runs);
  const std::uint32_t n = leaf.buildingCount();
  REQUIRE(runs.firstIndex.size() == n + 1);
  CHECK(runs.firstIndex.back() == mesh.indices.size());
  // Every triangle between position p's first index and the next belongs to p's row.
  for (std::uint32_t p = 0; p < n; ++p) {
    REQUIRE(runs.firstIndex[p] < runs.firstIndex[p + 1]);
    for (std::uint32_t i = runs.firstIndex[p]; i < runs.firstIndex[p + 1]; ++i) {
      REQUIRE(mesh.vertices[mesh.indices[i]].slot == p);
    }
  }
  const std::uint32_t perBuilding = runs.firstIndex[1] - runs.firstIndex[0];
  std::vector<IndexSpan> spans;

  // Two ranges far apart stay two runs; their triangles are exactly those of their buildings.
  const std::vector<IndexRange> two{{0, 2, false}, {n - 2, n, false}};
  visibleIndexSpans(runs, two, 0, 16, spans);
  REQUIRE(spans.size() == 2);
  CHECK(spans[0].firstIndex == runs.firstIndex[0]);
  CHECK(spans[0].indexCount == runs.firstIndex[2] - runs.firstIndex[0]);
  CHECK(spans[1].firstIndex == runs.firstIndex[n - 2]);
  CHECK(spans[1].firstIndex + spans[1].indexCount == mesh.indices.size());

  // A gap of one building is bridged when the allowed gap covers it, not otherwise.
  const std::vector<IndexRange> gapOfOne{{0, 1, false}, {2, 3, false}};
  visibleIndexSpans(runs, gapOfOne, perBuilding, 16, spans);
  CHECK(spans.size() == 1);
  visibleIndexSpans(runs, gapOfOne, perBuilding - 1, 16, spans);
  CHECK(spans.size() == 2);

  // Every other building visible: at most the cap of runs, covering every visible building.
  std::vector<IndexRange> alternate;
  for (std::uint32_t p = 0; p < n; p += 2) alternate.push_back({p, p + 1, false});
  REQUIRE(alternate.size() > 4);
  visibleIndexSpans(runs, alternate, 0, 4, spans);
  CHECK(spans.size() == 4);
  for (const IndexRange& r : alternate) {
    bool covered = false;
    for (const IndexSpan& s : spans) {
      covered = covered ||
                (s.firstIndex <= runs.firstIndex[r.begin] && runs.firstIndex[r.end] <= s.firstIndex + s.indexCount);
    }
    CHECK(covered);
  }
  // Nothing visible: no run.
  visibleIndexSpans(runs, std::vector<IndexRange>{}, 0, 4, spans);
  CHECK(spans.empty());
}
