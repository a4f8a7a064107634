#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>

#include "qv/lod/TileSelector.h"

using namespace qv;

namespace {

// A two-level quadtree over 2 km × 2 km: a coarse root (error 20 m) and four leaves.
Tileset twoLevels() {
  Tileset t;
  TileNode root;
  root.bounds = Rect{-1000, -1000, 1000, 1000};
  root.maxHeightM = 100.0f;
  root.coarse = true;
  root.geometricErrorM = 20.0f;
  root.file = "r";
  t.nodes.push_back(root);
  for (std::uint32_t q = 0; q < 4; ++q) {
    TileNode leaf;
    leaf.level = 1;
    leaf.x = q % 2;
    leaf.y = q / 2;
    const float x0 = leaf.x == 0 ? -1000.0f : 0.0f, y0 = leaf.y == 0 ? -1000.0f : 0.0f;
    leaf.bounds = Rect{x0, y0, x0 + 1000.0f, y0 + 1000.0f};
    leaf.maxHeightM = 100.0f;
    leaf.file = "l";
    t.nodes.push_back(leaf);
    t.nodes[0].children.push_back(q + 1);
  }
  return t;
}

bool contains(const std::vector<std::uint32_t>& v, std::uint32_t x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

TEST_CASE("Far away the coarse root is drawn alone", "[lod]") {
  const Tileset t = twoLevels();
  const std::vector<TileState> states(5, TileState::Loaded);
  const CameraView view(CameraState{0, 0, 40000, 0, 60, 45}, 1280, 720);
  CHECK(screenSpaceError(t.nodes[0], view) < 12.0f);
  TileSelection s;
  selectTiles(t, states, view, {}, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});
  CHECK(s.complete());
}

TEST_CASE("Close up the root is replaced by its visible children once they are loaded", "[lod]") {
  const Tileset t = twoLevels();
  const CameraView view(CameraState{-500, -500, 800, 0, 45, 45}, 1280, 720);
  CHECK(screenSpaceError(t.nodes[0], view) > 12.0f);

  std::vector<TileState> states(5, TileState::Unloaded);
  TileSelection s;
  selectTiles(t, states, view, {}, s);
  CHECK(s.draw.empty());                             // nothing loaded yet
  CHECK(s.wanted == std::vector<std::uint32_t>{0});  // the coarse root first
  states[0] = TileState::Loaded;
  selectTiles(t, states, view, {}, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});  // the root stands in while leaves load
  CHECK(contains(s.wanted, 1));
  CHECK_FALSE(s.complete());
  for (std::uint32_t i : s.wanted) states[i] = TileState::Loaded;
  selectTiles(t, states, view, {}, s);
  CHECK_FALSE(contains(s.draw, 0));
  CHECK(contains(s.draw, 1));
  CHECK(s.complete());
  // Every drawn leaf is visible.
  for (std::uint32_t i : s.draw) CHECK(view.frustum().intersects(nodeBox(t.nodes[i])));
}

TEST_CASE("A failed child is skipped, not waited for", "[lod]") {
  const Tileset t = twoLevels();
  const CameraView view(CameraState{0, 0, 1500, 0, 80, 45}, 1280, 720);
  std::vector<TileState> states = {TileState::Loaded, TileState::Loaded, TileState::Failed, TileState::Loaded,
                                   TileState::Loaded};
  TileSelection s;
  selectTiles(t, states, view, {}, s);
  CHECK(s.complete());
  CHECK_FALSE(contains(s.draw, 0));
  CHECK_FALSE(contains(s.draw, 2));
  CHECK(contains(s.draw, 1));
}

TEST_CASE("The draw budget caps refinement", "[lod]") {
  const Tileset t = twoLevels();
  const CameraView view(CameraState{0, 0, 1500, 0, 80, 45}, 1280, 720);
  const std::vector<TileState> states(5, TileState::Loaded);
  TileSelectorOptions options;
  options.maxDrawTiles = 2;
  TileSelection s;
  selectTiles(t, states, view, options, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});
  CHECK(s.budgetLimited);
  // The children it could not draw are loaded: they stay in use (not evicted as least recently
  // used), or a scene at the budget would fetch and drop them again every frame.
  for (std::uint32_t c = 1; c <= 4; ++c) CHECK(contains(s.used, c));
}

TEST_CASE("Tiles within the detail radius of the eye refine even when their error is small", "[lod]") {
  Tileset t = twoLevels();
  t.nodes[0].geometricErrorM = 0.01f;  // coarse enough for any view by error alone
  const CameraView view(CameraState{500, 500, 300, 0, 60, 45}, 1280, 720);
  const std::vector<TileState> states(5, TileState::Loaded);
  TileSelectorOptions options;
  TileSelection s;
  selectTiles(t, states, view, options, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});
  options.detailRadiusM = 400.0f;
  selectTiles(t, states, view, options, s);
  CHECK(contains(s.draw, 4));  // the north-east leaf under the eye
  CHECK_FALSE(contains(s.draw, 0));
  // From far away the same radius reaches nothing.
  const CameraView far(CameraState{500, 500, 30000, 0, 60, 45}, 1280, 720);
  selectTiles(t, states, far, options, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});
}

TEST_CASE("The memory budget caps refinement: coarser tiles are drawn instead", "[lod][memory]") {
  const Tileset t = twoLevels();
  const CameraView view(CameraState{0, 0, 1500, 0, 80, 45}, 1280, 720);
  const std::vector<TileState> states(5, TileState::Loaded);
  const std::vector<std::uint64_t> bytes = {100, 40, 40, 40, 40};
  TileSelectorOptions options;
  options.nodeBytes = bytes;
  options.memoryBudgetBytes = 150;  // the root (100) or its four children (160): only the root fits
  TileSelection s;
  selectTiles(t, states, view, options, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});
  CHECK(s.memoryLimited);
  CHECK(s.bytes == 100);
  CHECK(s.replaced.empty());
  // The children are not kept from eviction: nothing the view draws needs them.
  for (std::uint32_t c = 1; c <= 4; ++c) CHECK_FALSE(contains(s.used, c));
  options.memoryBudgetBytes = 160;
  selectTiles(t, states, view, options, s);
  CHECK(s.draw.size() == 4);
  CHECK_FALSE(s.memoryLimited);
  CHECK(s.bytes == 160);
  CHECK(s.replaced == std::vector<std::uint32_t>{0});  // the scene may evict it under pressure
}

TEST_CASE("Children are not wanted when they would not fit beside the tile they replace", "[lod][memory]") {
  const Tileset t = twoLevels();
  const CameraView view(CameraState{0, 0, 1500, 0, 80, 45}, 1280, 720);
  std::vector<TileState> states = {TileState::Loaded, TileState::Unloaded, TileState::Unloaded, TileState::Unloaded,
                                   TileState::Unloaded};
  const std::vector<std::uint64_t> bytes = {100, 40, 40, 40, 40};
  TileSelectorOptions options;
  options.nodeBytes = bytes;
  options.memoryBudgetBytes = 200;  // the root stays drawn while they load: 100 + 160 > 200
  TileSelection s;
  selectTiles(t, states, view, options, s);
  CHECK(s.draw == std::vector<std::uint32_t>{0});
  CHECK(s.wanted.empty());
  CHECK(s.memoryLimited);
  CHECK(s.complete());
  options.memoryBudgetBytes = 260;
  selectTiles(t, states, view, options, s);
  CHECK(s.wanted.size() == 4);
  CHECK(s.bytes == 260);
}

TEST_CASE("An evicted coarse tile is passed through to its children, not loaded again", "[lod][memory]") {
  const Tileset t = twoLevels();
  const CameraView view(CameraState{0, 0, 1500, 0, 80, 45}, 1280, 720);
  std::vector<TileState> states = {TileState::Unloaded, TileState::Loaded, TileState::Loaded, TileState::Unloaded,
                                   TileState::Loaded};
  const std::unique_ptr<bool[]> wasLoaded(new bool[5]{true, false, false, false, false});
  TileSelectorOptions options;
  options.wasLoaded = std::span<const bool>(wasLoaded.get(), 5);
  TileSelection s;
  selectTiles(t, states, view, options, s);
  // The view wants the children: the loaded ones are drawn, the missing one is wanted, the root is not.
  CHECK(s.draw.size() == 3);
  CHECK_FALSE(contains(s.draw, 3));
  CHECK(s.wanted == std::vector<std::uint32_t>{3});
  // Never loaded, the same root is loaded first (coarse first), its loaded children standing in.
  options.wasLoaded = {};
  selectTiles(t, states, view, options, s);
  CHECK(s.wanted == std::vector<std::uint32_t>{0});
  CHECK(s.draw.size() == 3);
  // From far away the evicted root is the right tile again: wanted, its children drawn meanwhile.
  options.wasLoaded = std::span<const bool>(wasLoaded.get(), 5);
  const CameraView far(CameraState{0, 0, 40000, 0, 60, 45}, 1280, 720);
  selectTiles(t, states, far, options, s);
  CHECK(s.wanted == std::vector<std::uint32_t>{0});
  CHECK(s.draw.size() == 3);
}
