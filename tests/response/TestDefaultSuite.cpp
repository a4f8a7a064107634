// The built-in default suite (qv/prep/DefaultSuite.h): spectrum-matched to each site's target, its
// mean spectrum follows the target between 0.2 T1 and 2 T1 once scaled at T1, on real ShakeMap
// sites and on a scenario's; site shapes; bad targets refused; reproducible records.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <string>

#include "qv/prep/DefaultSuite.h"
#include "qv/prep/ShakeMap.h"
#include "qv/seismic/ResponseSpectrum.h"

using namespace qv;

namespace {

// Worst |mean / target - 1| over 11 periods from 0.2 T1 to 2 T1, every component of the suite
// scaled to the target at T1 as `response` scales them (the arithmetic mean, as ASCE 7-16 §16.2.3).
double worstMeanError(const std::vector<prep::DefaultSuiteRecord>& suite, const std::function<double(double)>& target,
                      double t1) {
  double worst = 0.0;
  std::vector<double> scales;
  for (const prep::DefaultSuiteRecord& r : suite) {
    for (const seismic::GroundMotion* m : {&r.x, &r.y})
      scales.push_back(target(t1) / seismic::pseudoSpectralAccelerationG(*m, t1));
  }
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.2 * t1 * std::pow(10.0, k / 10.0);
    double sum = 0.0;
    std::size_t c = 0;
    for (const prep::DefaultSuiteRecord& r : suite) {
      for (const seismic::GroundMotion* m : {&r.x, &r.y})
        sum += scales[c++] * seismic::pseudoSpectralAccelerationG(*m, t);
    }
    worst = std::max(worst, std::abs(sum / static_cast<double>(scales.size()) / target(t) - 1.0));
  }
  return worst;
}

}  // namespace

TEST_CASE("The default suite's mean spectrum is within 10 % of each site's target from 0.2 T1 to 2 T1",
          "[response][default-suite]") {
  auto grid = prep::readShakeMapGrid(std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/shakemap/nyc-m5.8-scenario-grid.xml");
  REQUIRE(grid.ok());
  // Sites of the shared NYC M5.8 ShakeMap from the Battery to Harlem (their shapes differ: PSA10/PSA03
  // goes from 0.25 to 0.36 over Manhattan), and an M6.6 scenario at 4 and 25 km.
  struct Site {
    std::string name;
    prep::SiteShape shape;
    std::function<double(double)> target;
  };
  std::vector<Site> sites;
  for (const auto& [lon, lat] : {std::pair{-74.015, 40.705}, std::pair{-73.985, 40.750}, std::pair{-73.945, 40.805}}) {
    const auto at = prep::sampleShakeMap(*grid, lon, lat);
    REQUIRE(at.has_value());
    const seismic::SpectralOrdinates o{at->pgaG, at->psa03G, at->psa10G, at->psa30G};
    sites.push_back({"ShakeMap at " + std::to_string(lon) + ", " + std::to_string(lat), prep::shakeMapSiteShape(o),
                     [o](double t) { return seismic::shakeMapTargetSaG(o, t); }});
  }
  seismic::Scenario scenario;
  scenario.magnitude = 6.6;
  scenario.vs30MetresPerSecond = 400.0;
  for (const double km : {4.0, 25.0}) {
    sites.push_back({"M6.6 scenario at " + std::to_string(km) + " km", prep::scenarioSiteShape(km), [=](double t) {
                       return seismic::bssa14MedianPsaG(t, scenario.magnitude, km, scenario.vs30MetresPerSecond);
                     }});
  }
  for (const Site& site : sites) {
    auto suite = prep::defaultSuiteFor(site.shape, &scenario);
    REQUIRE(suite.ok());
    REQUIRE(suite->size() == std::size(prep::kDefaultSuiteSeeds));
    for (const double t1 : {0.15, 1.0, 5.0}) {
      INFO(site.name << ", T1 " << t1 << " s");
      CHECK(worstMeanError(*suite, site.target, t1) <= 0.10);
    }
  }
}

TEST_CASE("Site shapes group sites whose targets have the same shape, and the shape's target has it",
          "[response][default-suite]") {
  const seismic::SpectralOrdinates site{0.30, 0.60, 0.25, 0.08};
  const seismic::SpectralOrdinates twice{0.60, 1.20, 0.50, 0.16};
  const seismic::SpectralOrdinates softer{0.30, 0.60, 0.35, 0.12};
  CHECK(prep::shakeMapSiteShape(site) == prep::shakeMapSiteShape(twice));  // the level is the scaling's
  CHECK(prep::shakeMapSiteShape(site) != prep::shakeMapSiteShape(softer));
  CHECK(prep::scenarioSiteShape(10.0) == prep::scenarioSiteShape(10.3));
  CHECK(prep::scenarioSiteShape(10.0) != prep::scenarioSiteShape(20.0));
  CHECK(prep::scenarioSiteShape(10.0) != prep::shakeMapSiteShape(site));
  // The shape's target: PGA 0.35 g, the site's ratios within half a step (2 %) each (on the
  // target's period grid).
  const prep::TargetSpectrum target = prep::shapeTarget(prep::shakeMapSiteShape(site), nullptr);
  CHECK(target.at(0.01) == Approx(0.35));
  CHECK(target.at(0.3) / target.at(0.01) == Approx(2.0).epsilon(0.021));
  CHECK(target.at(1.0) / target.at(0.3) == Approx(0.25 / 0.60).epsilon(0.021));
  CHECK(target.at(3.0) / target.at(1.0) == Approx(0.08 / 0.25).epsilon(0.03));  // 3 s: a kink between grid points
}

TEST_CASE("Spectrum matching refuses a target it cannot match to, naming it, and repeats itself exactly",
          "[response][default-suite]") {
  seismic::SyntheticMotionParameters p;
  auto seed = seismic::generateSyntheticMotion(p);
  REQUIRE(seed.ok());
  prep::TargetSpectrum empty;
  auto none = prep::matchSyntheticMotion(*seed, p, empty);
  REQUIRE_FALSE(none.ok());
  CHECK(none.error().find("no points") != std::string::npos);
  prep::TargetSpectrum negative{{0.1, 1.0}, {0.5, -0.1}};
  auto bad = prep::matchSyntheticMotion(*seed, p, negative);
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().find("target point 1") != std::string::npos);
  prep::TargetSpectrum descending{{1.0, 0.1}, {0.5, 0.5}};
  CHECK_FALSE(prep::matchSyntheticMotion(*seed, p, descending).ok());

  const prep::TargetSpectrum flat{{0.01, 20.0}, {0.5, 0.5}};
  auto a = prep::defaultSuiteRecord(3, flat);
  auto b = prep::defaultSuiteRecord(3, flat);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a->x.accelerationMps2 == b->x.accelerationMps2);
  CHECK(a->y.accelerationMps2 == b->y.accelerationMps2);
  CHECK(a->x.accelerationMps2 != a->y.accelerationMps2);
  CHECK(a->x.name.find("spectrum-matched") != std::string::npos);
}
