#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "qv/scene/InspectionValues.h"

using namespace qv;

TEST_CASE("Displacements are shown in units that show them", "[inspection][units]") {
  // The case: a 3-storey building's 0.020 m read "0.0 m".
  CHECK(displacementText(0.020) == "20 mm");
  CHECK(displacementText(0.0004) == "0.4 mm");
  CHECK(displacementText(0.0095) == "9.5 mm");
  CHECK(displacementText(0.00996) == "10 mm");  // rounds into whole millimetres
  CHECK(displacementText(0.123) == "123 mm");
  CHECK(displacementText(0.9996) == "1.00 m");  // would read "1000 mm"
  CHECK(displacementText(1.23) == "1.23 m");
  CHECK(displacementText(0.0) == "0 mm");
  CHECK(displacementText(-0.00001) == "0.0 mm");
  CHECK(displacementText(std::numeric_limits<double>::quiet_NaN()) == "-");
  // Feet: inches below a foot.
  CHECK(displacementText(0.020, true) == "0.79 in");
  CHECK(displacementText(0.1, true) == "3.9 in");
  CHECK(displacementText(1.23, true) == "4.04 ft");
  CHECK(std::string(displacementUnit(0.5).name) == "mm");
  CHECK(std::string(displacementUnit(2.0).name) == "m");
}

TEST_CASE("Drift ratios read as percentages that do not hide small drifts", "[inspection][units]") {
  CHECK(driftPercentText(0.0022) == "0.22 %");
  CHECK(driftPercentText(0.0145) == "1.45 %");
  CHECK(driftPercentText(0.0004) == "0.040 %");
  CHECK(driftPercentText(0.0) == "0.00 %");
  CHECK(driftPercentText(std::numeric_limits<double>::infinity()) == "-");
}

TEST_CASE("Axis ticks are round numbers inside the range", "[inspection][axes]") {
  const auto a = axisTicks(0.0, 20.0, 4);
  REQUIRE(a.size() == 5);
  CHECK(a.front() == 0.0);
  CHECK(a[1] == Approx(5.0));
  CHECK(a.back() == Approx(20.0));
  // Up to 2.3: a step of 0.5 would need 5 intervals, so 1 (at most 4 intervals).
  const auto b = axisTicks(0.0, 2.3, 4);
  REQUIRE(b.size() == 3);
  CHECK(b[1] == Approx(1.0));
  CHECK(b.back() == Approx(2.0));
  CHECK(axisTicks(0.0, 2.3, 5).size() == 5);  // 0, 0.5, ... 2
  const auto c = axisTicks(-0.31, 0.31, 8);   // a ground motion in g: symmetric, through 0
  REQUIRE(c.size() == 7);
  CHECK(c.front() == Approx(-0.3));
  CHECK(c[3] == 0.0);
  for (int maxTicks : {1, 3, 5, 8}) {
    const auto t = axisTicks(0.0, 37.3, maxTicks);
    CHECK(t.size() <= static_cast<std::size_t>(maxTicks) + 1);
    CHECK_FALSE(t.empty());
  }
  CHECK(axisTicks(1.0, 1.0, 4).empty());
  CHECK(axisTicks(0.0, std::numeric_limits<double>::infinity(), 4).empty());
  CHECK(tickLabel(2.5, 0.5) == "2.5");
  CHECK(tickLabel(10.0, 5.0) == "10");
  CHECK(tickLabel(0.25, 0.05) == "0.25");
  CHECK(tickLabel(-0.0000001, 0.1) == "0.0");
}

TEST_CASE("Storey drift bars use a fixed scale that holds the building's HAZUS thresholds", "[inspection][scale]") {
  // Complete at 4 %: the scale reaches it; complete at 1.5 %: the scale is 2.5 %.
  CHECK(storeyDriftScaleMax({0.0033, 0.0058, 0.0156, 0.04}) == Approx(0.04));
  CHECK(storeyDriftScaleMax({0.002, 0.004, 0.008, 0.015}) == Approx(0.025));
  // A complete threshold of 7 % (light wood frame) is on the scale.
  CHECK(storeyDriftScaleMax({0.004, 0.012, 0.035, 0.07}) >= 0.07);
  CHECK(storeyDriftScaleMax({0.004, 0.012, 0.035, 0.0712}) == Approx(0.075));
}

TEST_CASE("The drift read from the compressed history carries the encoder's error bound", "[inspection][history]") {
  // Two floors each within 1.9 % of a 20 mm roof displacement, over 3 m: 0.025 % drift.
  CHECK(historyDriftErrorBound(0.020, 3.0) == Approx(2.0 * 0.019 * 0.020 / 3.0));
  CHECK(historyDriftErrorBound(0.020, 0.0) == 0.0);
}
