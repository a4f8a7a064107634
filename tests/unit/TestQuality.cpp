#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "qv/quality/FrameGovernor.h"
#include "qv/quality/QualityPreset.h"
#include "qv/quality/SoftwareRenderer.h"

using qv::FrameGovernor;
using qv::GovernorReason;

TEST_CASE("isSoftwareRenderer recognises the CPU rasterizers browsers report", "[quality][renderer]") {
  // Strings as Chromium, Edge and Firefox report them (UNMASKED_RENDERER_WEBGL).
  const std::string software = GENERATE(
      std::string("ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero) (0x0000C0DE)), SwiftShader driver)"),
      std::string("Google SwiftShader"),
      std::string("ANGLE (Microsoft, Microsoft Basic Render Driver Direct3D11 vs_5_0 ps_5_0, D3D11)"),
      std::string("llvmpipe (LLVM 15.0.6, 256 bits)"), std::string("llvmpipe, or similar"), std::string("softpipe"),
      std::string("Mesa OffScreen Software Renderer"), std::string("WARP"),
      std::string("ANGLE (Microsoft, WARP Direct3D11, D3D11)"));
  CAPTURE(software);
  CHECK(qv::isSoftwareRenderer(software));
}

TEST_CASE("isSoftwareRenderer leaves GPUs, masked and empty names at full quality", "[quality][renderer]") {
  const std::string gpu =
      GENERATE(std::string("ANGLE (Intel, Intel(R) UHD Graphics 620 Direct3D11 vs_5_0 ps_5_0, D3D11)"),
               std::string("ANGLE (NVIDIA, NVIDIA GeForce RTX 3060 Direct3D11 vs_5_0 ps_5_0, D3D11)"),
               std::string("Mesa Intel(R) Xe Graphics (TGL GT2)"), std::string("Apple M1"),
               std::string("AMD Radeon Pro 5500M OpenGL Engine"), std::string("WebKit WebGL"), std::string(""),
               // "warp" inside another word is not Microsoft's WARP.
               std::string("Warpspeed GPU 9000 by Vendor"));
  CAPTURE(gpu);
  CHECK_FALSE(qv::isSoftwareRenderer(gpu));
}

namespace {

// Feeds `seconds` of frames of `frameMs` each; returns the step after each frame.
std::vector<int> feed(FrameGovernor& g, double frameMs, double seconds) {
  std::vector<int> steps;
  const int n = static_cast<int>(std::lround(seconds * 1000.0 / frameMs));
  for (int i = 0; i < n; ++i) steps.push_back(g.addFrame(frameMs));
  return steps;
}

}  // namespace

TEST_CASE("FrameGovernor holds the step while frames are fast enough", "[quality][governor]") {
  FrameGovernor g;
  for (int s : feed(g, 16.7, 30.0)) REQUIRE(s == 0);
  for (int s : feed(g, 45.0, 30.0)) REQUIRE(s == 0);  // 22 FPS: under the 50 ms limit
  CHECK(g.reason() == GovernorReason::Steady);
}

TEST_CASE("FrameGovernor steps down once per window of slow frames, down to its floor", "[quality][governor]") {
  FrameGovernor g;  // 2 s window, 50 ms limit, 3 steps
  // 100 ms frames (10 FPS): the first change once 2 s of them are in, not before.
  std::vector<int> steps = feed(g, 100.0, 1.9);
  CHECK(steps.back() == 0);
  steps = feed(g, 100.0, 0.1);
  CHECK(steps.back() == 1);
  CHECK(g.reason() == GovernorReason::TooSlow);
  CHECK(g.lastChangeMedianMs() == Approx(100.0));
  // Each step is judged on its own frames: the next change needs another full window.
  steps = feed(g, 100.0, 1.9);
  CHECK(steps.back() == 1);
  feed(g, 100.0, 0.1);
  CHECK(g.step() == 2);
  feed(g, 100.0, 20.0);
  CHECK(g.step() == g.options().maxStep);
}

TEST_CASE("FrameGovernor judges the median: one long stall does not lower detail", "[quality][governor]") {
  FrameGovernor g;
  feed(g, 16.7, 1.0);
  g.addFrame(1500.0);  // a tile decoded in one frame, a tab switch
  for (int s : feed(g, 16.7, 5.0)) REQUIRE(s == 0);
}

TEST_CASE("FrameGovernor raises detail only with clear headroom, and not straight after a step down",
          "[quality][governor]") {
  FrameGovernor g;
  feed(g, 80.0, 2.0);
  REQUIRE(g.step() == 1);
  // 30 ms frames: faster than the limit but not by enough (hysteresis): stays.
  for (int s : feed(g, 30.0, 20.0)) REQUIRE(s == 1);
  g.reset();
  feed(g, 80.0, 2.0);
  REQUIRE(g.step() == 1);
  // 10 ms frames right after the step down: held for the raise hold time (10 s), then up.
  std::vector<int> steps = feed(g, 10.0, 9.0);
  CHECK(steps.back() == 1);
  feed(g, 10.0, 2.0);
  CHECK(g.step() == 0);
  CHECK(g.reason() == GovernorReason::Headroom);
}

TEST_CASE("FrameGovernor: a sequence of frame times in, the steps out", "[quality][governor]") {
  qv::FrameGovernorOptions o;
  o.windowSeconds = 1.0;
  o.raiseHoldSeconds = 0.0;
  o.maxStep = 2;
  FrameGovernor g(o);
  // Slow (down to the floor), then fast (back up), with a 1 s window: 200 ms frames fill a window
  // in 5 frames, 10 ms frames in 100. The two slow frames after the last step down still count
  // (400 ms), so the first step up comes after 60 fast frames, the next after a fresh window.
  std::vector<int> seen;
  for (int i = 0; i < 12; ++i) seen.push_back(g.addFrame(200.0));
  CHECK(seen == std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1, 1, 2, 2, 2});
  seen.clear();
  for (int i = 0; i < 200; ++i) seen.push_back(g.addFrame(10.0));
  CHECK(seen[58] == 2);
  CHECK(seen[59] == 1);
  CHECK(seen[158] == 1);
  CHECK(seen[159] == 0);
  // Bad input is ignored.
  CHECK(g.addFrame(-5.0) == 0);
  CHECK(g.addFrame(std::nan("")) == 0);
}

TEST_CASE("detailScaleForStep makes each step coarser and cheaper", "[quality][governor]") {
  const qv::DetailScale s0 = qv::detailScaleForStep(0);
  CHECK(s0.screenSpaceError == 1.0f);
  CHECK(s0.drawTiles == 1.0f);
  CHECK(qv::detailScaleForStep(-1).screenSpaceError == 1.0f);
  for (int step = 1; step <= 3; ++step) {
    const qv::DetailScale a = qv::detailScaleForStep(step - 1);
    const qv::DetailScale b = qv::detailScaleForStep(step);
    CHECK(b.screenSpaceError > a.screenSpaceError);
    CHECK(b.drawTiles < a.drawTiles);
    CHECK(b.animationRadius < a.animationRadius);
    CHECK(b.animatedBuildings < a.animatedBuildings);
  }
}

TEST_CASE("Quality presets: each lighter preset draws and animates less, and the governor's steps lower them further",
          "[quality][presets]") {
  using qv::QualityPreset;
  const qv::QualitySettings high = qv::qualitySettings(QualityPreset::High);
  const qv::QualitySettings balanced = qv::qualitySettings(QualityPreset::Balanced);
  const qv::QualitySettings low = qv::qualitySettings(QualityPreset::Low);
  for (const auto& [heavier, lighter] : {std::pair{high, balanced}, std::pair{balanced, low}}) {
    CHECK(lighter.maxScreenSpaceError > heavier.maxScreenSpaceError);
    CHECK(lighter.blockPixels > heavier.blockPixels);
    CHECK(lighter.maxDrawTiles < heavier.maxDrawTiles);
    CHECK(lighter.animationRadiusM < heavier.animationRadiusM);
    CHECK(lighter.maxAnimatedBuildings < heavier.maxAnimatedBuildings);
  }
  // Step 0 is the preset itself; a step scales it as detailScaleForStep says; never under 8 tiles.
  CHECK(qv::qualitySettings(QualityPreset::Low, 0) == low);
  const qv::DetailScale s2 = qv::detailScaleForStep(2);
  const qv::QualitySettings low2 = qv::qualitySettings(QualityPreset::Low, 2);
  CHECK(low2.maxScreenSpaceError == Approx(low.maxScreenSpaceError * s2.screenSpaceError));
  CHECK(low2.animationRadiusM == Approx(low.animationRadiusM * s2.animationRadius));
  CHECK(low2.maxDrawTiles < low.maxDrawTiles);
  CHECK(qv::qualitySettings(QualityPreset::Low, 100).maxDrawTiles == 8u);
  CHECK(std::string(qv::qualityName(QualityPreset::Low)) == "Low (weak devices)");
}
