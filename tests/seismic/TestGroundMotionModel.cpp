#include <catch2/catch.hpp>

#include "qv/seismic/GroundMotionModel.h"

using namespace qv::seismic;

TEST_CASE("BSSA14 median PGA matches published verification values", "[seismic][gmpe]") {
  // OpenQuake Engine hazardlib verification table for BSSA14, unspecified mechanism
  // (openquake/hazardlib/tests/gsim/data/BSSA2014/BSSA_2014_NOSOF_MEAN.csv), PGA in g.
  struct Case {
    double magnitude, rjbKm, vs30, pgaG;
  };
  const Case cases[] = {
      {3.0, 0.0, 760.0, 0.00686845}, {6.0, 20.0, 760.0, 0.0953544}, {7.0, 0.0, 760.0, 0.442594},
      {7.0, 20.0, 760.0, 0.144087},  {7.0, 50.0, 760.0, 0.0630401}, {7.0, 100.0, 760.0, 0.026798},
      {7.0, 20.0, 400.0, 0.192966},  {7.0, 20.0, 200.0, 0.214568},  {6.0, 50.0, 400.0, 0.0500482},
  };
  for (const Case& c : cases) {
    CAPTURE(c.magnitude, c.rjbKm, c.vs30);
    CHECK(bssa14MedianPgaG(c.magnitude, c.rjbKm, c.vs30) == Approx(c.pgaG).epsilon(2e-3));
  }
}

TEST_CASE("BSSA14 PGA decreases with distance and increases with magnitude", "[seismic][gmpe]") {
  for (const double m : {4.0, 5.5, 6.5, 7.5}) {
    double previous = 1e9;
    for (const double r : {0.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 400.0}) {
      const double pga = bssa14MedianPgaG(m, r, 760.0);
      CHECK(pga < previous);
      previous = pga;
    }
  }
  for (const double r : {0.0, 10.0, 50.0}) {
    double previous = 0.0;
    for (const double m : {3.0, 4.0, 5.0, 6.0, 7.0, 8.0}) {
      const double pga = bssa14MedianPgaG(m, r, 760.0);
      CHECK(pga > previous);
      previous = pga;
    }
  }
  // Reverse faults shake harder than normal ones (e3 > e2).
  CHECK(bssa14MedianPgaG(6.5, 10.0, 760.0, FaultMechanism::Reverse) >
        bssa14MedianPgaG(6.5, 10.0, 760.0, FaultMechanism::Normal));
}

TEST_CASE("Site shaking: scale to the predicted PGA and S-wave delay", "[seismic][gmpe]") {
  Scenario s;
  s.magnitude = 7.0;
  s.depthKm = 15.0;
  s.siteFactor = 1.5;
  const auto near = shakingAtSite(s, 20.0, 0.6);
  REQUIRE(near.ok());
  CHECK(near->pgaG == Approx(1.5 * 0.144087).epsilon(2e-3));
  CHECK(near->scale == Approx(near->pgaG / 0.6));
  CHECK(near->delaySeconds == Approx(25.0 / 3.5));  // hypocentral distance sqrt(20² + 15²) = 25 km
  const auto far = shakingAtSite(s, 40.0, 0.6);
  REQUIRE(far.ok());
  CHECK(far->delaySeconds > near->delaySeconds);
  CHECK(far->scale < near->scale);

  const auto badMagnitude = shakingAtSite(Scenario{0, 0, 10, 9.5}, 10.0, 0.5);
  REQUIRE_FALSE(badMagnitude.ok());
  CHECK(badMagnitude.error() == "scenario: magnitude 9.5 is outside [3, 8.5] (BSSA14)");
  CHECK_FALSE(shakingAtSite(s, -1.0, 0.5).ok());
  CHECK_FALSE(shakingAtSite(s, 10.0, 0.0).ok());
}

TEST_CASE("The S-wave delay is hypocentral distance over the wave speed, the same for every caller",
          "[seismic][gmpe]") {
  CHECK(shearWaveDelayS(30.0, 40.0, 5.0) == Approx(10.0));  // a 3-4-5 triangle: 50 km at 5 km/s
  CHECK(shearWaveDelayS(0.0, 0.0, 3.5) == 0.0);
  CHECK(shearWaveDelayS(7.0, 0.0, 3.5) == Approx(2.0));
  // shakingAtSite's delay is this function's (quakeview-prep uses both and must not disagree).
  Scenario s;
  s.magnitude = 6.0;
  s.depthKm = 12.0;
  s.shearWaveSpeedKmPerS = 3.2;
  for (const double km : {0.0, 3.7, 41.3, 250.0}) {
    const auto site = shakingAtSite(s, km, 0.3);
    REQUIRE(site.ok());
    CHECK(site->delaySeconds == shearWaveDelayS(km, 12.0, 3.2));
  }
}
