#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "qv/scene/PixelRatio.h"

using namespace qv;

namespace {

// Runs `frames` frames of `seconds` each on a canvas `cssWidth` wide; returns the last ratio.
double run(PixelRatioGovernor& g, double deviceRatio, double cssWidth, double seconds, int frames) {
  double ratio = 0.0;
  for (int i = 0; i < frames; ++i) ratio = g.update(deviceRatio, cssWidth, seconds);
  return ratio;
}

}  // namespace

TEST_CASE("The pixel ratio is the device's up to 2, and up to 1.5 on a phone-wide canvas", "[scene][pixelratio]") {
  PixelRatioGovernor g;
  CHECK(g.update(1.0, 1280.0, 0.0) == 1.0);
  CHECK(g.update(1.25, 1280.0, 0.016) == 1.25);
  CHECK(g.update(3.0, 1280.0, 0.016) == 2.0);
  CHECK(g.update(3.0, 390.0, 0.016) == 1.5);   // a phone: 390 x 844 CSS px at 3 becomes 585 x 1266
  CHECK(g.update(2.0, 768.0, 0.016) == 2.0);   // a tablet is not narrow
  CHECK(g.update(0.8, 390.0, 0.016) == 0.8);   // a zoomed-out page is never drawn above its ratio
  CHECK(g.update(0.0, 1280.0, 0.016) == 1.0);  // a browser reporting nonsense
  CHECK(g.update(std::nan(""), 1280.0, 0.016) == 1.0);
  CHECK(std::isinf(g.slowCap()));
}

TEST_CASE("Slow frames step the ratio down to 1, fast ones never do", "[scene][pixelratio]") {
  PixelRatioGovernor fast;
  CHECK(run(fast, 3.0, 1280.0, 0.016, 1000) == 2.0);

  PixelRatioGovernor slow;
  slow.update(3.0, 1280.0, 0.0);
  CHECK(run(slow, 3.0, 1280.0, 0.2, PixelRatioGovernor::kWindowFrames) == 1.75);
  CHECK(run(slow, 3.0, 1280.0, 0.2, PixelRatioGovernor::kWindowFrames) == 1.5);
  CHECK(run(slow, 3.0, 1280.0, 0.2, 20 * PixelRatioGovernor::kWindowFrames) == 1.0);
  // Once lowered it stays: fast frames later do not resize the canvas back.
  CHECK(run(slow, 3.0, 1280.0, 0.01, 1000) == 1.0);

  // A few slow frames among fast ones (a tile upload) leave the median fast.
  PixelRatioGovernor hiccup;
  double ratio = 0.0;
  for (int i = 0; i < 300; ++i) ratio = hiccup.update(2.0, 1280.0, i % 5 == 0 ? 0.3 : 0.016);
  CHECK(ratio == 2.0);

  // A device at 1 has nothing to give up.
  PixelRatioGovernor plain;
  CHECK(run(plain, 1.0, 1280.0, 0.5, 200) == 1.0);
  CHECK(std::isinf(plain.slowCap()));
}

TEST_CASE("A phone with slow frames steps down from its own cap", "[scene][pixelratio]") {
  PixelRatioGovernor g;
  g.update(3.0, 390.0, 0.0);
  CHECK(run(g, 3.0, 390.0, 0.1, PixelRatioGovernor::kWindowFrames) == 1.25);
  CHECK(g.slowCap() == 1.25);
}
