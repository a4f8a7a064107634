// bench_default_suite: the built-in default suite (docs/seismic.md, "The default suite") against
// the target spectrum of the shared NYC ShakeMap at 16 sites 2 km apart: its records are scaled at
// a building's first-mode period T1 to the target, as `response` scales them; the table gives, per
// T1, how far the suite's mean spectrum (geometric mean over the records' components) departs from
// the target between 0.2 T1 and 2 T1. The records are not matched to the spectrum.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "qv/prep/ResponseRun.h"
#include "qv/prep/ShakeMap.h"
#include "qv/seismic/ResponseSpectrum.h"
#include "qv/seismic/SyntheticMotion.h"

using namespace qv;

int main() {
  auto grid = prep::readShakeMapGrid(std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/shakemap/nyc-m5.8-scenario-grid.xml");
  if (!grid.ok()) {
    std::fprintf(stderr, "%s\n", grid.error().c_str());
    return 1;
  }
  std::vector<seismic::ResponseSpectrum> spectra;
  for (const std::uint64_t seed : prep::kDefaultSuiteSeeds) {
    seismic::SyntheticMotionParameters p;
    p.seed = seed;
    p.peakGroundAccelerationG = 0.35;
    auto pair = seismic::generateSyntheticPair(p);
    if (!pair.ok()) return 1;
    for (const seismic::GroundMotion* m : {&pair->first, &pair->second}) {
      auto s = seismic::ResponseSpectrum::compute(*m, 0.01, 20.0);
      if (!s.ok()) return 1;
      spectra.push_back(std::move(s).value());
    }
  }
  std::printf("bench_default_suite: %zu records (%zu components), NYC M5.8 ShakeMap, 16 sites\n\n",
              std::size(prep::kDefaultSuiteSeeds), spectra.size());
  std::printf("%6s %22s %22s %22s\n", "T1 s", "mean/target at 0.2 T1", "mean/target at 2 T1", "worst |error| %");
  for (const double t1 : {0.2, 0.5, 1.0, 2.0, 4.0}) {
    double worst = 0.0, low = 0.0, high = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const auto at = prep::sampleShakeMap(*grid, -74.02 + 0.02 * i, 40.70 + 0.02 * j);
        if (!at) return 1;
        const seismic::SpectralOrdinates site{at->pgaG, at->psa03G, at->psa10G, at->psa30G};
        const double target1 = seismic::shakeMapTargetSaG(site, t1);
        for (int k = 0; k <= 20; ++k) {
          const double t = 0.2 * t1 * std::pow(10.0, static_cast<double>(k) / 20.0);
          double logSum = 0.0;
          for (const seismic::ResponseSpectrum& s : spectra) logSum += std::log(target1 / s.saG(t1) * s.saG(t));
          const double ratio =
              std::exp(logSum / static_cast<double>(spectra.size())) / seismic::shakeMapTargetSaG(site, t);
          worst = std::max(worst, std::abs(ratio - 1.0));
          if (k == 0 && i == 0 && j == 0) low = ratio;
          if (k == 20 && i == 0 && j == 0) high = ratio;
        }
      }
    }
    std::printf("%6.1f %22.2f %22.2f %22.0f\n", t1, low, high, 100.0 * worst);
  }
  std::printf(
      "\nratios at the first site (-74.02, 40.70); worst over the 16 sites and 21 periods from 0.2 T1 to\n"
      "2 T1; at T1 itself the mean is the target (each record is scaled there).\n");
  return 0;
}
