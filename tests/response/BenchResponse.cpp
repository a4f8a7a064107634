// bench_response: the whole `quakeview-prep response` step (solve, encode, write) on an existing
// city, with a record in X and Y, printed as one table row: the figures of issue 4's performance
// goals. Make the city first, e.g.
//   quakeview-prep synth-city --buildings 100000 --seed 1 --out /tmp/c100k
//   bench_response --city /tmp/c100k [--motion FILE] [--threads N]
// The run writes a new response folder into the city (and removes the previous one), as the
// command does.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "qv/prep/ResponseRun.h"

namespace {

double processCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

}  // namespace

int main(int argc, char** argv) {
  std::string city;
  std::string motion = QUAKEVIEW_SHARED_DATA_DIR "/ground-motions/TAK000.AT2";
  unsigned threads = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--city") == 0) {
      city = argv[i + 1];
    } else if (std::strcmp(argv[i], "--motion") == 0) {
      motion = argv[i + 1];
    } else if (std::strcmp(argv[i], "--threads") == 0) {
      threads = static_cast<unsigned>(std::strtoul(argv[i + 1], nullptr, 10));
    }
  }
  if (city.empty()) {
    std::fprintf(stderr, "usage: bench_response --city DIR [--motion FILE] [--threads N]\n");
    return 2;
  }
  qv::prep::ResponseRunOptions options;
  options.motions = {motion};
  options.motionY = motion;
  options.threads = threads;
  const double cpuStart = processCpuSeconds();
  const auto wallStart = std::chrono::steady_clock::now();
  const auto report = qv::prep::runCityResponse(city, options);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  const double cpu = processCpuSeconds() - cpuStart;
  if (!report.ok()) {
    std::fprintf(stderr, "bench_response: %s\n", report.error().c_str());
    return 1;
  }
  const qv::prep::ResponseRunReport& r = *report;
  const double bytes = static_cast<double>(r.summaryBytes + r.historyBytes);
  const double perBuilding = r.buildings > 0 ? bytes / static_cast<double>(r.buildings) : 0.0;
  std::printf("bench_response: %s, %s in X and Y, %zu frames at %.3g s\n\n", city.c_str(), r.motion.c_str(), r.frames,
              r.timeStepS);
  std::printf("%9s %14s %9s %9s %8s %8s %10s %11s %11s %9s %9s %9s\n", "buildings", "storey-steps/s", "solve s",
              "encode s", "cpu s", "wall s", "MB written", "summary MB", "B/building", "worst %", "p99 %", "RSS MiB");
  std::printf("%9llu %13.1fM %9.1f %9.1f %8.1f %8.1f %10.1f %11.1f %11.0f %9.2f %9.2f %9.0f\n",
              static_cast<unsigned long long>(r.buildings), static_cast<double>(r.storeySteps) / wall / 1e6,
              r.solveSeconds, r.encodeSeconds, cpu, wall, bytes / 1e6, static_cast<double>(r.summaryBytes) / 1e6,
              perBuilding, 100.0 * r.worstRelativeError, 100.0 * r.p99RelativeError, peakRssMiB());
  std::printf(
      "\nstorey-steps/s = storeys x output frames x directions / wall time; solve s and encode s: CPU seconds\n"
      "over all threads (solve excludes the encoder); cpu s: the whole process; wall s includes reading the\n"
      "tiles, encoding and writing every response tile and the manifest; MB = 10^6 bytes (summaries and\n"
      "histories); worst and p99: reconstructed floor displacement against the full-rate solution, as a\n"
      "percentage of each building's peak roof displacement; RSS: peak resident set of the process.\n");
  return 0;
}
