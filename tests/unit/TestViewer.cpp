#include <catch2/catch.hpp>

#include <limits>

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
