// bench_ingest: readCity on the real Manhattan files against `osmium export` of the same files (the
// reference the project's goal is stated against), side by side in one run. Medians of 5 runs
// each, release builds only. Prints a table; not a ctest.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include "qv/prep/Ingest.h"

namespace {

constexpr int kRuns = 5;
/// The paper's Python + GeoPandas reading of manhattan-midtown-buildings.osm, seconds.
constexpr double kPythonGeoPandasSeconds = 1.8;

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// CPU seconds (user + system) of this process (`who` RUSAGE_SELF) or of its waited-for children.
double cpuSeconds(int who) {
  rusage usage{};
  getrusage(who, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Row {
  std::string file;
  double readCity = 0.0;
  double readPart = 0.0;
  double buildPart = 0.0;
  double readCityCpu = 0.0;
  double osmiumExport = -1.0;
  double osmiumExportCpu = -1.0;
  std::size_t buildings = 0;
  std::uint64_t points = 0;
};

}  // namespace

int main() {
  const std::string dataDir = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/osm/";
  const bool haveOsmium = std::system("command -v osmium > /dev/null 2>&1") == 0;
  const std::string exportPath =
      (std::filesystem::temp_directory_path() / ("qv-bench-ingest-" + std::to_string(::getpid()) + ".geojson"))
          .string();
  std::vector<Row> rows;
  for (const char* name : {"manhattan-midtown-buildings.osm", "nyc-manhattan-south-buildings.osm.pbf"}) {
    Row row;
    row.file = name;
    const std::string path = dataDir + name;
    std::vector<double> total;
    std::vector<double> readPart;
    std::vector<double> buildPart;
    std::vector<double> cpu;
    for (int run = 0; run < kRuns; ++run) {
      qv::prep::IngestStats stats;
      const double cpuStart = cpuSeconds(RUSAGE_SELF);
      const auto start = std::chrono::steady_clock::now();
      const auto model = qv::prep::readCity({path}, {}, &stats);
      total.push_back(secondsSince(start));
      cpu.push_back(cpuSeconds(RUSAGE_SELF) - cpuStart);
      if (!model.ok()) {
        std::fprintf(stderr, "bench_ingest: %s\n", model.error().c_str());
        return 1;
      }
      readPart.push_back(stats.readSeconds);
      buildPart.push_back(stats.buildSeconds);
      row.buildings = model->buildings.size();
      row.points = stats.points;
    }
    row.readCity = median(total);
    row.readCityCpu = median(cpu);
    row.readPart = median(readPart);
    row.buildPart = median(buildPart);
    if (haveOsmium) {
      std::vector<double> exportTimes;
      std::vector<double> exportCpu;
      const std::string command = "osmium export '" + path + "' -o '" + exportPath + "' --overwrite > /dev/null 2>&1";
      for (int run = 0; run < kRuns; ++run) {
        const double cpuStart = cpuSeconds(RUSAGE_CHILDREN);
        const auto start = std::chrono::steady_clock::now();
        if (std::system(command.c_str()) != 0) {
          std::fprintf(stderr, "bench_ingest: `%s` failed\n", command.c_str());
          break;
        }
        exportTimes.push_back(secondsSince(start));
        exportCpu.push_back(cpuSeconds(RUSAGE_CHILDREN) - cpuStart);
      }
      if (exportTimes.size() == kRuns) {
        row.osmiumExport = median(exportTimes);
        row.osmiumExportCpu = median(exportCpu);
      }
    }
    rows.push_back(row);
  }
  std::error_code ec;
  std::filesystem::remove(exportPath, ec);

  std::printf("readCity vs `osmium export` (median of %d runs each; wall and CPU seconds)\n\n", kRuns);
  std::printf(
      "| file | buildings | vertices | readCity wall | (read | build) | readCity CPU | osmium export wall | "
      "osmium export CPU | wall ratio | CPU ratio |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const Row& r : rows) {
    std::printf("| %s | %zu | %llu | %.3f | %.3f | %.3f | %.3f | ", r.file.c_str(), r.buildings,
                static_cast<unsigned long long>(r.points), r.readCity, r.readPart, r.buildPart, r.readCityCpu);
    if (r.osmiumExport > 0.0) {
      std::printf("%.3f | %.3f | %.2fx | %.2fx |\n", r.osmiumExport, r.osmiumExportCpu, r.readCity / r.osmiumExport,
                  r.readCityCpu / r.osmiumExportCpu);
    } else {
      std::printf("n/a | n/a | n/a | n/a |\n");
    }
  }
  std::printf(
      "\nPython + GeoPandas (the paper) on manhattan-midtown-buildings.osm: %.1f s -> readCity is %.1fx faster\n",
      kPythonGeoPandasSeconds, kPythonGeoPandasSeconds / rows[0].readCity);
  return 0;
}
