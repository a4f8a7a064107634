// bench_shakemap: parse time of ShakeMap grids, printed as a table: the shared NYC scenario grid
// (161 x 123 nodes, 1 MB) and a generated ShakeMap 4 grid of N x N nodes (default 1000 x 1000,
// 9 fields). Also times 1,000,000 bilinear samples. Build it in the native-release preset:
//   bench_shakemap [--nodes N] [--grid FILE]
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "qv/prep/ShakeMap.h"

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CPU time of this process: on a loaded machine the wall time says little.
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// A ShakeMap 4 grid.xml of n x n nodes, 0.01 degree apart, with plausible values.
std::string generatedGrid(std::size_t n) {
  std::string xml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"yes\"?>\n"
      "<shakemap_grid event_id=\"bench\" shakemap_version=\"1\" code_version=\"4.1.3\" "
      "shakemap_event_type=\"SCENARIO\">\n";
  const double lonMin = -120.0, latMin = 30.0, step = 0.01;
  const double lonMax = lonMin + step * static_cast<double>(n - 1), latMax = latMin + step * static_cast<double>(n - 1);
  char line[512];
  std::snprintf(line, sizeof line,
                "<grid_specification lon_min=\"%.4f\" lat_min=\"%.4f\" lon_max=\"%.4f\" lat_max=\"%.4f\" "
                "nominal_lon_spacing=\"%.4f\" nominal_lat_spacing=\"%.4f\" nlon=\"%zu\" nlat=\"%zu\" />\n",
                lonMin, latMin, lonMax, latMax, step, step, n, n);
  xml += line;
  const char* fields[] = {"LON\" units=\"dd",   "LAT\" units=\"dd",   "MMI\" units=\"intensity",
                          "PGA\" units=\"%g",   "PGV\" units=\"cm/s", "PSA03\" units=\"%g",
                          "PSA10\" units=\"%g", "PSA30\" units=\"%g", "SVEL\" units=\"m/s"};
  for (int i = 0; i < 9; ++i)
    xml += "<grid_field index=\"" + std::to_string(i + 1) + "\" name=\"" + fields[i] + "\" />\n";
  xml += "<grid_data>\n";
  xml.reserve(xml.size() + n * n * 64);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t c = 0; c < n; ++c) {
      const double k = static_cast<double>((r * 7 + c * 13) % 997);
      std::snprintf(line, sizeof line, "%.4f %.4f %.2f %.2f %.2f %.2f %.2f %.2f %.3f\n",
                    lonMin + step * static_cast<double>(c), latMax - step * static_cast<double>(r), 4.0 + k / 400.0,
                    k / 20.0, k / 50.0, k / 10.0, k / 40.0, k / 200.0, 200.0 + k);
      xml += line;
    }
  xml += "</grid_data>\n</shakemap_grid>\n";
  return xml;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t nodes = 1000;
  std::string file = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/shakemap/nyc-m5.8-scenario-grid.xml";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--nodes") == 0) nodes = std::strtoul(argv[i + 1], nullptr, 10);
    if (std::strcmp(argv[i], "--grid") == 0) file = argv[i + 1];
  }
  if (nodes < 2) nodes = 2;
  std::printf("%-40s %12s %12s %10s %10s\n", "grid", "nodes", "MB", "wall ms", "CPU ms");

  auto start = std::chrono::steady_clock::now();
  double cpu = cpuSeconds();
  const auto real = qv::prep::readShakeMapGrid(file);
  double seconds = secondsSince(start);
  if (!real.ok()) {
    std::fprintf(stderr, "%s\n", real.error().c_str());
    return 1;
  }
  std::printf("%-40s %12zu %12s %10.2f %10.2f\n", "grid file (read + parse)", real->lonCount * real->latCount, "-",
              seconds * 1e3, (cpuSeconds() - cpu) * 1e3);

  const std::string xml = generatedGrid(nodes);
  start = std::chrono::steady_clock::now();
  cpu = cpuSeconds();
  const auto big = qv::prep::parseShakeMapGrid(xml, "generated.xml");
  seconds = secondsSince(start);
  if (!big.ok()) {
    std::fprintf(stderr, "%s\n", big.error().c_str());
    return 1;
  }
  const std::string label = "generated " + std::to_string(nodes) + " x " + std::to_string(nodes) + " (parse)";
  std::printf("%-40s %12zu %12.1f %10.2f %10.2f\n", label.c_str(), big->lonCount * big->latCount,
              static_cast<double>(xml.size()) / 1e6, seconds * 1e3, (cpuSeconds() - cpu) * 1e3);

  start = std::chrono::steady_clock::now();
  cpu = cpuSeconds();
  double sum = 0.0;
  const std::size_t samples = 1'000'000;
  for (std::size_t i = 0; i < samples; ++i) {
    const double u = static_cast<double>(i % 1000) / 1000.0, v = static_cast<double>(i / 1000) / 1000.0;
    const auto s = qv::prep::sampleShakeMap(*real, real->lonMin + u * (real->lonMax - real->lonMin),
                                            real->latMin + v * (real->latMax - real->latMin));
    if (s) sum += s->pgaG;
  }
  seconds = secondsSince(start);
  std::printf("%-40s %12zu %12s %10.2f %10.2f   (mean PGA %.4f g)\n", "1,000,000 samples of that grid", samples, "-",
              seconds * 1e3, (cpuSeconds() - cpu) * 1e3, sum / static_cast<double>(samples));
  return 0;
}
