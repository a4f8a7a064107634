// Engine benchmark without a GPU: streams a prepared city from disk into the viewer with the null
// render device and reports the engine's per-frame CPU time (cull, LOD, animate, upload) for an
// overview of the whole city and for a street-level camera, plus the visible-set query against
// a linear scan. Runs natively and in WASM under node (the product's numbers are the WASM ones):
//
//   bench_engine CITY_DIR [--radius M] [--frames N]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "FileFetcher.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/scene/Viewer.h"

using namespace qv;

namespace {

struct Row {
  std::string name;
  StatsSummary stats;
  std::uint64_t heap = 0;
};

void print(const Row& r) {
  const auto& s = r.stats;
  std::printf("| %-34s | %7.3f | %7.3f | %7.3f | %7.3f | %8.3f | %5.0f | %9.0f | %7u | %7u | %6u | %8.1f |\n",
              r.name.c_str(), s.frameMs.cull, s.frameMs.lod, s.frameMs.animate, s.frameMs.upload,
              s.frameMs.cull + s.frameMs.lod + s.frameMs.animate, s.drawCalls, s.triangles, s.latest.buildingsLoaded,
              s.latest.buildingsVisible, s.latest.buildingsAnimated, s.uploadBytes / 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_engine CITY_DIR [--radius M] [--frames N]\n");
    return 2;
  }
  const std::string dir = argv[1];
  float radius = 1200.0f;
  int frames = 120;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--radius") == 0) radius = std::strtof(argv[i + 1], nullptr);
    if (std::strcmp(argv[i], "--frames") == 0) frames = std::atoi(argv[i + 1]);
  }
  bench::FileFetcher fetcher;
  NullRenderDevice device;
  Viewer viewer(device);
  CitySceneOptions options;
  options.animationRadiusM = radius;
  options.maxAnimatedBuildings = 100000;
  options.workBudgetMs = 1.0e9;  // load everything as fast as possible: we time steady frames
  viewer.openCity(dir + "/tileset.json", fetcher, options);
  viewer.setViewport(1280, 720, 1280.0, 720.0);

  std::vector<Row> rows;
  auto settle = [&](const CameraState& camera) {
    viewer.setCamera(camera);
    for (int i = 0; i < 2000 && !(i > 2 && viewer.settled()); ++i) viewer.frame(1.0 / 60.0);
  };
  auto measure = [&](const std::string& name) {
    for (int i = 0; i < frames; ++i) viewer.frame(1.0 / 60.0);
    rows.push_back({name, viewer.stats(), 0});
  };

  viewer.frame(1.0 / 60.0);
  viewer.frame(1.0 / 60.0);
  if (!viewer.city() || !viewer.city()->manifestLoaded()) {
    std::fprintf(stderr, "bench_engine: cannot load %s/tileset.json\n", dir.c_str());
    for (const auto& e : viewer.errors()) std::fprintf(stderr, "  %s\n", e.c_str());
    return 1;
  }
  const CameraState overview = viewer.city()->overviewCamera();
  settle(overview);
  measure("overview, whole city in view");
  CameraState street = overview;
  street.distance = 350.0;
  street.pitchDeg = 25.0;
  settle(street);
  measure("street level at the centre");

  std::printf("\nEngine CPU per frame (ms, medians of %d frames), %s, animation radius %.0f m\n\n", frames, dir.c_str(),
              static_cast<double>(radius));
  std::printf("| %-34s | %7s | %7s | %7s | %7s | %8s | %5s | %9s | %7s | %7s | %6s | %8s |\n", "camera", "cull", "lod",
              "animate", "upload", "c+l+a", "draws", "triangles", "loaded", "visible", "anim", "KB/frame");
  std::printf("|%s|\n", std::string(160, '-').c_str());
  for (const Row& r : rows) print(r);
  std::printf("\nerrors: %zu; tiles loaded %u failed %u; GPU bytes %.1f MB; scene bytes %.1f MB\n",
              viewer.errors().size(), viewer.city()->tileCounts().loaded, viewer.city()->tileCounts().failed,
              static_cast<double>(device.gpuBytes()) / 1048576.0,
              static_cast<double>(viewer.city()->memoryBytes()) / 1048576.0);
  for (const auto& e : viewer.errors()) std::printf("  %s\n", e.c_str());
  return 0;
}
