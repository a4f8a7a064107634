#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "qv/core/SplitMix64.h"
#include "qv/quality/PanelCache.h"

using qv::PanelRefresh;
using qv::PixelRect;

namespace {

/// How many of the rectangles cover each pixel of a width x height grid.
std::vector<int> coverage(const std::vector<PixelRect>& rects, int width, int height) {
  std::vector<int> count(static_cast<std::size_t>(width * height), 0);
  for (const PixelRect& r : rects) {
    for (int y = r.y0; y < r.y1; ++y) {
      for (int x = r.x0; x < r.x1; ++x) {
        if (x >= 0 && y >= 0 && x < width && y < height) ++count[static_cast<std::size_t>(y * width + x)];
      }
    }
  }
  return count;
}

}  // namespace

TEST_CASE("disjointCover covers the windows' union once per pixel, within the screen", "[quality][panels]") {
  constexpr int kWidth = 64, kHeight = 48;
  qv::SplitMix64 random{GENERATE(std::uint64_t{1}, 2, 3, 4, 5, 6, 7, 8)};
  std::vector<PixelRect> windows;
  const int n = 1 + static_cast<int>(random.next() % 6);
  for (int i = 0; i < n; ++i) {
    const int x = static_cast<int>(random.next() % 80) - 8, y = static_cast<int>(random.next() % 60) - 6;
    windows.push_back({x, y, x + static_cast<int>(random.next() % 40), y + static_cast<int>(random.next() % 30)});
  }
  const std::vector<PixelRect> cover = qv::disjointCover(windows, kWidth, kHeight);
  const std::vector<int> want = coverage(windows, kWidth, kHeight);
  const std::vector<int> got = coverage(cover, kWidth, kHeight);
  for (std::size_t i = 0; i < want.size(); ++i) {
    INFO("pixel " << i % kWidth << "," << i / kWidth);
    REQUIRE(got[i] == (want[i] > 0 ? 1 : 0));
  }
  for (const PixelRect& r : cover) {
    CHECK_FALSE(r.empty());
    CHECK(r.x0 >= 0);
    CHECK(r.y0 >= 0);
    CHECK(r.x1 <= kWidth);
    CHECK(r.y1 <= kHeight);
  }
}

TEST_CASE("disjointCover: an inspection window over the panel adds only its part outside it", "[quality][panels]") {
  const std::vector<PixelRect> windows{{0, 0, 400, 700}, {300, 100, 700, 400}, {-5, 690, 2000, 800}};
  const std::vector<PixelRect> cover = qv::disjointCover(windows, 1280, 720);
  long long area = 0;
  for (const PixelRect& r : cover) area += r.area();
  CHECK(area == 400LL * 700 + 300LL * 300 + 1280LL * 30 - 400LL * 10);
  CHECK(cover.front() == PixelRect{0, 0, 400, 700});
  CHECK(qv::disjointCover(std::vector<PixelRect>{}, 100, 100).empty());
  CHECK(qv::disjointCover(std::vector<PixelRect>{{10, 10, 10, 50}, {200, 0, 300, 10}}, 100, 100).empty());
}

TEST_CASE("PanelRefresh redraws a change at once when the user acts, else at most every passiveSeconds",
          "[quality][panels]") {
  PanelRefresh refresh({.passiveSeconds = 0.25, .inputSeconds = 0.2, .inputFrames = 1});
  const std::vector<PixelRect> panel{{0, 0, 400, 700}};
  double t = 0.0;
  // The first frame is drawn; the same picture again is not.
  CHECK(refresh.redraw(1, panel, false, t));
  CHECK_FALSE(refresh.redraw(1, panel, false, t += 0.05));
  // A passive change (the time line moved) waits for the interval; the picture then shown is the
  // newest content, and an unchanged frame after it draws nothing.
  CHECK_FALSE(refresh.redraw(2, panel, false, t += 0.05));
  CHECK_FALSE(refresh.redraw(3, panel, false, t += 0.05));
  CHECK(refresh.staleFrames() == 2);
  CHECK(refresh.redraw(4, panel, false, t = 0.26));
  CHECK_FALSE(refresh.redraw(4, panel, false, t += 0.05));
  // A click is drawn at once, and so is the widget's answer in the frames just after it.
  CHECK(refresh.redraw(5, panel, true, t += 0.05));
  CHECK(refresh.redraw(6, panel, false, t += 0.05));
  CHECK(refresh.redraw(7, panel, false, t += 0.05));
  CHECK_FALSE(refresh.redraw(8, panel, false, t += 0.2));  // input long ago, last redraw 0.2 s ago
  // A window that opens, moves or closes is drawn at once, even without input.
  const std::vector<PixelRect> withInspection{{0, 0, 400, 700}, {800, 50, 1200, 500}};
  CHECK(refresh.redraw(8, withInspection, false, t += 0.01));
  CHECK(refresh.redraw(8, panel, false, t += 0.01));
  // A lost texture is redrawn whatever it shows.
  refresh.invalidate();
  CHECK(refresh.redraw(8, panel, false, t += 0.01));
  CHECK(refresh.redraws() == 8);
}

TEST_CASE("PanelRefresh: on a slow device the frames just after a click are drawn at once too", "[quality][panels]") {
  PanelRefresh refresh({.passiveSeconds = 0.25, .inputSeconds = 0.2, .inputFrames = 3});
  const std::vector<PixelRect> panel{{0, 0, 400, 700}};
  CHECK(refresh.redraw(1, panel, false, 0.0));
  CHECK(refresh.redraw(2, panel, true, 0.1));   // 0.4 s frames: the widget answers frames later
  CHECK(refresh.redraw(3, panel, false, 0.3));  // the last redraw was only 0.2 s ago
  CHECK(refresh.redraw(4, panel, false, 0.45));
  CHECK(refresh.redraw(5, panel, false, 0.6));
  CHECK_FALSE(refresh.redraw(6, panel, false, 0.65));  // three frames on, passive again
}

TEST_CASE("PanelRefresh with no passive interval redraws every change", "[quality][panels]") {
  PanelRefresh refresh({.passiveSeconds = 0.0, .inputSeconds = 0.0, .inputFrames = 0});
  const std::vector<PixelRect> panel{{0, 0, 400, 700}};
  for (std::uint64_t key = 1; key < 10; ++key)
    CHECK(refresh.redraw(key, panel, false, 0.001 * static_cast<double>(key)));
  CHECK_FALSE(refresh.redraw(9, panel, false, 1.0));
  CHECK(refresh.staleFrames() == 0);
}
