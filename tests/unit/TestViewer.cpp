#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "qv/scene/Bench.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/scene/Viewer.h"

using namespace qv;

TEST_CASE("The test scene draws every prism in one call each, plus the ground", "[scene][viewer]") {
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  viewer.setViewport(1280, 720, 1280.0, 720.0);
  viewer.frame(1.0 / 60.0);
  const StatsSummary s = viewer.stats();
  CHECK(s.latest.buildingsLoaded == 6);
  CHECK(s.latest.buildingsVisible == 6);
  CHECK(s.latest.drawCalls == 7);
  CHECK(s.latest.triangles > 500);
  CHECK(viewer.settled());

  // Looking away from the scene culls every prism.
  CameraState away = viewer.camera();
  away.x = 50000.0;
  viewer.setCamera(away);
  viewer.frame(1.0 / 60.0);
  CHECK(viewer.stats().latest.buildingsVisible == 0);
  CHECK(viewer.stats().latest.drawCalls == 1);
}

TEST_CASE("Time advances while playing and stands still while paused", "[scene][viewer]") {
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  viewer.frame(0.5);
  CHECK(viewer.time() == Approx(0.5));
  viewer.pause();
  viewer.frame(0.5);
  CHECK(viewer.time() == Approx(0.5));
  viewer.play();
  viewer.setSpeed(2.0);
  viewer.frame(0.25);
  CHECK(viewer.time() == Approx(1.0));
  CHECK(viewer.setTime(3.0));
  CHECK(viewer.time() == 3.0);
  CHECK_FALSE(viewer.setTime(std::numeric_limits<double>::quiet_NaN()));
  CHECK(viewer.time() == 3.0);
  viewer.setTime(1e9);
  CHECK(viewer.time() == viewer.duration());
}

TEST_CASE("stats JSON carries every documented key", "[scene][viewer]") {
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  viewer.frame(1.0 / 30.0);
  viewer.frame(1.0 / 30.0);
  const std::string json = viewer.statsJson(MemoryInfo{1234, 65536});
  for (const char* key :
       {"\"fps\":", "\"frameMs\":{\"cull\":", "\"lod\":", "\"animate\":", "\"upload\":", "\"render\":", "\"total\":",
        "\"drawCalls\":7", "\"triangles\":", "\"buildings\":{\"loaded\":6", "\"visible\":6", "\"animated\":6",
        "\"tiles\":{\"loaded\":0", "\"heapBytes\":1234", "\"heapReservedBytes\":65536",
        "\"uploadBytes\":", "\"timeSeconds\":"}) {
    INFO(key);
    CHECK(json.find(key) != std::string::npos);
  }
  CHECK(json.find("\"fps\":30") != std::string::npos);
}

TEST_CASE("setCamera refuses non-finite fields and keeps the previous values", "[scene][viewer]") {
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  const CameraState before = viewer.camera();
  CameraState bad = before;
  bad.distance = std::numeric_limits<double>::quiet_NaN();
  bad.x = 10.0;
  CHECK_FALSE(viewer.setCamera(bad));
  CHECK(viewer.camera().distance == before.distance);
  CHECK(viewer.camera().x == 10.0);
  CHECK(viewer.cameraJson().find("\"x\":10") != std::string::npos);
}

TEST_CASE("The benchmark's low pass crosses the densest area, not a tiny leaf at the edge", "[scene][bench]") {
  // A 3 km city: thin 250 m leaves of 20 buildings everywhere, a dense core of four 100 m leaves of
  // 150 buildings around (600, -400), and at the far corner a tiny leaf of two buildings
  // whose bounds are only 10 m across (the highest buildings per square metre of any leaf).
  Tileset tileset;
  tileset.bounds = Rect{-1500.0f, -1500.0f, 1500.0f, 1500.0f};
  TileNode root;
  root.bounds = tileset.bounds;
  tileset.nodes.push_back(root);
  auto addLeaf = [&tileset](float x0, float y0, float size, std::uint32_t buildings) {
    TileNode leaf;
    leaf.level = 1;
    leaf.bounds = Rect{x0, y0, x0 + size, y0 + size};
    leaf.buildings = buildings;
    tileset.nodes[0].children.push_back(static_cast<std::uint32_t>(tileset.nodes.size()));
    tileset.nodes.push_back(leaf);
  };
  for (float i = 0.0f; i < 12.0f; i += 1.0f) {
    for (float j = 0.0f; j < 12.0f; j += 1.0f) addLeaf(-1500.0f + 250.0f * i, -1500.0f + 250.0f * j, 250.0f, 20);
  }
  for (float i = 0.0f; i < 2.0f; i += 1.0f) {
    for (float j = 0.0f; j < 2.0f; j += 1.0f) addLeaf(500.0f + 100.0f * i, -500.0f + 100.0f * j, 100.0f, 150);
  }
  addLeaf(1480.0f, 1480.0f, 10.0f, 2);
  const BenchRun run(20.0, &tileset, 45.0);
  double nearestCore = 1e9, nearestCorner = 1e9;
  for (double t = 0.0; t <= 20.0; t += 0.05) {
    const CameraState c = run.cameraAt(t);
    nearestCore = std::min(nearestCore, std::hypot(c.x - 600.0, c.y + 400.0));
    nearestCorner = std::min(nearestCorner, std::hypot(c.x - 1485.0, c.y - 1485.0));
  }
  CHECK(nearestCore < 60.0);
  CHECK(nearestCorner > 400.0);
}
