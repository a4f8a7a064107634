#include "ResponseFinish.h"

#include <time.h>

#include <algorithm>
#include <numeric>

#include "qv/seismic/ConsequencesFile.h"

namespace qv::prep::detail {
namespace {

double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

void RunLosses::append(RunLosses&& other) {
  losses.insert(losses.end(), other.losses.begin(), other.losses.end());
  district.insert(district.end(), other.district.begin(), other.district.end());
  key.insert(key.end(), other.key.begin(), other.key.end());
  classes.insert(classes.end(), other.classes.begin(), other.classes.end());
}

Status finishResponse(ResponseWriter& writer, FinishInputs in, ResponseRunReport& report) {
  const double totalsStart = cpuSeconds();
  // The mean history rate, summed leaf by leaf in the tileset's order: the same bits however the
  // leaves were spread over threads or machines.
  double rateSum = 0.0;
  std::uint64_t rateCount = 0;
  for (const LeafRate& r : in.leafRates) {
    rateSum += r.sum;
    rateCount += r.count;
  }
  ResponseInfo info = std::move(in.info);
  info.sampleRateHz = rateCount > 0 ? rateSum / static_cast<double>(rateCount) : 0.0;
  // The consequences' totals: the city, and each district, over the buildings in the city's order
  // (leaf by leaf), whichever thread or machine analysed them: the Monte Carlo intervals are the
  // same from run to run.
  RunLosses& l = in.losses;
  const bool withDistricts = in.districts != nullptr && l.district.size() == l.losses.size();
  std::vector<std::size_t> order(l.losses.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&l](std::size_t a, std::size_t b) { return l.key[a] < l.key[b]; });
  std::vector<seismic::BuildingLoss> losses;
  losses.reserve(order.size());
  std::vector<LossClass> classes;
  classes.reserve(order.size());
  std::vector<int> districts;
  for (const std::size_t i : order) {
    losses.push_back(l.losses[i]);
    classes.push_back(l.classes[i]);
    if (withDistricts) districts.push_back(l.district[i]);
  }
  l = RunLosses{};
  seismic::ConsequenceTotals totals;
  totals.timeOfDay = info.timeOfDay;
  totals.population = in.population;
  totals.city = seismic::totalLosses(losses);
  totals.city.byTime = seismic::casualtiesByTimeOfDay(losses);
  addClassTotals(losses, classes, totals);
  if (in.districts != nullptr) {
    for (std::size_t d = 0; d < in.districts->names.size(); ++d) {
      std::vector<seismic::BuildingLoss> inside;
      for (std::size_t i = 0; i < districts.size(); ++i) {
        if (districts[i] == static_cast<int>(d)) inside.push_back(losses[i]);
      }
      seismic::LossTotals t = seismic::totalLosses(inside);
      t.byTime = seismic::casualtiesByTimeOfDay(inside);
      totals.districts.push_back({in.districts->names[d], std::move(t), in.districts->outline(d)});
    }
    // The buildings in no district, as a row of their own where the file names one (the city's own
    // districts do, so that their rows add up to the city).
    std::vector<seismic::BuildingLoss> outside;
    for (std::size_t i = 0; i < districts.size(); ++i) {
      if (districts[i] < 0) outside.push_back(losses[i]);
    }
    if (!in.districts->outsideName.empty() && !outside.empty()) {
      seismic::LossTotals t = seismic::totalLosses(outside);
      t.byTime = seismic::casualtiesByTimeOfDay(outside);
      totals.districts.push_back({in.districts->outsideName, std::move(t), {}});
    }
    totals.districtsSource = in.districts->source.empty()
                                 ? std::string("a districts file given to the response (--districts)")
                                 : in.districts->source;
    totals.districtsInferred = in.districts->inferred;
  }
  report.losses = totals.city;
  report.timeOfDay = info.timeOfDay;
  report.lossSeconds += cpuSeconds() - totalsStart;
  auto consequences = writer.writeFile("consequences.json", seismic::consequencesToJson(totals));
  if (!consequences.ok()) return Error{consequences.error()};
  info.consequences = *consequences;
  auto written = writer.commit(info);
  if (!written.ok()) return Error{written.error()};
  for (int k = 0; k < 6; ++k) report.damage[k] = written->damage[k];
  report.noResultReasons = written->noResultReasons;
  report.approximateBuildings = written->approximate;
  report.summaryBytes = written->summaryBytes;
  report.historyBytes = written->historyBytes;
  report.uncompressedBytes = written->uncompressedBytes;
  report.driftSeriesBytes = written->driftSeriesBytes;
  report.driftSeriesBuildings = written->driftSeriesBuildings;
  report.folder = written->folder;
  report.meanSampleRateHz = info.sampleRateHz;
  return {};
}

}  // namespace qv::prep::detail
