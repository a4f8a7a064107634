// Engine benchmark without a GPU: streams a prepared city from disk into the viewer with the null
// render device and reports the engine's per-frame CPU time (cull, LOD, animate, upload) for an
// overview of the whole city and for a street-level camera, plus the visible-set query against
// a linear scan. Runs natively and in WASM under node (the product's numbers are the WASM ones):
//
//   bench_engine CITY_DIR [--radius M] [--frames N] [--animated N,N...]
//   bench_engine CITY_DIR --flight N [--memory MB]
//
// --flight flies bench-memory.mjs's path instead (overview, the city index, a low pass over an
// N x N grid, the overview again) and prints, per stop, the scene's own memory account (what the
// budget is enforced on) beside the live heap that malloc reports: the browser's heapBytes
// without a browser (the null device keeps no meshes, as WebGL keeps them outside the heap).
#include <malloc.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "FileFetcher.h"
#include "qv/format/CityTile.h"
#include "qv/format/Tileset.h"
#include "qv/geometry/OrbitCamera.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/scene/Viewer.h"
#include "qv/spatial/BoxTree.h"

using namespace qv;

namespace {

struct Row {
  std::string name;
  StatsSummary stats;
  std::uint64_t heap = 0;
};

void print(const Row& r) {
  const auto& s = r.stats;
  std::printf("| %-34s | %7.3f | %7.3f | %7.3f | %7.3f | %8.3f | %5.0f | %9.0f | %7u | %7u | %6u | %6u | %8.1f |\n",
              r.name.c_str(), s.frameMs.cull, s.frameMs.lod, s.frameMs.animate, s.frameMs.upload,
              s.frameMs.cull + s.frameMs.lod + s.frameMs.animate, s.drawCalls, s.triangles, s.latest.buildingsLoaded,
              s.latest.buildingsVisible, s.latest.buildingsAnimated, s.latest.modelsAnimated, s.uploadBytes / 1024.0);
}

std::uint64_t liveHeapBytes() {
#if defined(__GLIBC__)
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
#else
  const struct mallinfo m = mallinfo();  // dlmalloc (Emscripten): allocated bytes
  return static_cast<std::uint64_t>(static_cast<unsigned>(m.uordblks));
#endif
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// The visible-set query over every building of the city (the root tile holds them all): the
/// bounding-volume tree against a linear scan of the same boxes, for the same cameras.
void benchVisibleSet(const std::string& dir, const Tileset& tileset, const std::vector<CameraState>& cameras,
                     const std::vector<std::string>& names) {
  const std::string path = dir + "/" + tileset.nodes[0].file;
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto decoded = decodeCityTile(bytes, path);
  if (!decoded.ok()) {
    std::printf("visible-set query: %s\n", decoded.error().c_str());
    return;
  }
  const CityTile& tile = decoded.value();
  std::vector<Box> boxes(tile.buildings.size());
  for (std::size_t b = 0; b < tile.buildings.size(); ++b) {
    const TileBuilding& tb = tile.buildings[b];
    for (std::uint32_t p = tb.firstPart; p < tb.firstPart + tb.partCount; ++p) {
      const TilePart& part = tile.parts[p];
      for (std::uint32_t v = part.firstVertex; v < part.firstVertex + part.vertexCount; ++v) {
        boxes[b].expand(static_cast<float>(tile.originX) + tile.vertices[v].x,
                        static_cast<float>(tile.originY) + tile.vertices[v].y, part.minHeightM);
      }
      boxes[b].expand(boxes[b].minX, boxes[b].minY, part.heightM);
    }
  }
  BoxTree tree;
  tree.build(boxes);
  std::printf("\nVisible-set query over %zu buildings (ms per query, median of 200; same run, same boxes)\n\n",
              boxes.size());
  std::printf("| %-34s | %9s | %9s | %9s | %8s |\n", "camera", "visible", "tree ms", "linear ms", "speed-up");
  std::printf("|%s|\n", std::string(82, '-').c_str());
  std::vector<IndexRange> ranges;
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    const CameraView view(cameras[c], 1280, 720);
    const Frustum& frustum = view.frustum();
    std::vector<double> treeMs;
    std::vector<double> linearMs;
    std::uint32_t visibleTree = 0;
    std::uint32_t visibleLinear = 0;
    for (int i = 0; i < 200; ++i) {
      auto t0 = std::chrono::steady_clock::now();
      ranges.clear();
      tree.query(frustum, ranges);
      std::uint32_t n = 0;
      for (const IndexRange& r : ranges) n += r.end - r.begin;
      treeMs.push_back(msSince(t0));
      visibleTree = n;
      t0 = std::chrono::steady_clock::now();
      n = 0;
      for (const Box& box : boxes) n += frustum.intersects(box) ? 1u : 0u;
      linearMs.push_back(msSince(t0));
      visibleLinear = n;
    }
    std::sort(treeMs.begin(), treeMs.end());
    std::sort(linearMs.begin(), linearMs.end());
    const double tm = treeMs[treeMs.size() / 2];
    const double lm = linearMs[linearMs.size() / 2];
    std::printf("| %-34s | %9u | %9.4f | %9.4f | %7.0fx |\n", names[c].c_str(), visibleTree, tm, lm,
                lm / std::max(tm, 1e-6));
    // The tree answers in node ranges (a superset at leaf granularity is allowed); it never misses
    // a building the linear scan sees.
    if (visibleTree < visibleLinear) std::printf("  WARNING: the tree reports fewer buildings than the scan\n");
  }
}

/// bench-memory.mjs's flight; returns the process exit code.
int flight(const std::string& dir, int grid, double memoryMb) {
  bench::FileFetcher fetcher;
  NullRenderDevice device;
  Viewer viewer(device);
  CitySceneOptions options;
  if (memoryMb > 0.0) options.memoryBudgetBytes = static_cast<std::uint64_t>(memoryMb * 1048576.0);
  viewer.openCity(dir + "/tileset.json", fetcher, options);
  viewer.setViewport(1280, 720, 1280.0, 720.0);
  viewer.frame(1.0 / 60.0);
  viewer.frame(1.0 / 60.0);
  if (!viewer.city() || !viewer.city()->manifestLoaded()) {
    std::fprintf(stderr, "bench_engine: cannot load %s/tileset.json\n", dir.c_str());
    return 1;
  }
  const std::uint64_t baseline = liveHeapBytes();
  std::printf("\nMemory over a flight of %s (budget %.0f MB; MB)\n\n", dir.c_str(),
              static_cast<double>(viewer.city()->mutableOptions().memoryBudgetBytes) / 1048576.0);
  std::printf("| %-28s | %6s | %11s | %11s | %9s | %11s | %6s | %8s | %7s |\n", "stop", "tiles", "scene bytes",
              "of it: GPU", "live heap", "heap-GPU-sc", "draws", "visible", "index");
  std::printf("|%s|\n", std::string(118, '-').c_str());
  double peakHeap = 0.0;
  auto settle = [&](const CameraState& camera, const std::string& name) {
    viewer.setCamera(camera);
    for (int i = 0; i < 20000 && !(i > 4 && viewer.settled() && viewer.city()->tileCounts().pending == 0); ++i)
      viewer.frame(1.0 / 60.0);
    const StatsSummary s = viewer.stats();
    const double scene = static_cast<double>(viewer.city()->memoryBytes()) / 1048576.0;
    const double gpu = static_cast<double>(device.gpuBytes()) / 1048576.0;
    const double heap = static_cast<double>(liveHeapBytes() - std::min(liveHeapBytes(), baseline)) / 1048576.0;
    peakHeap = std::max(peakHeap, heap);
    std::printf("| %-28s | %6u | %11.1f | %11.1f | %9.1f | %11.1f | %6.0f | %8u | %7s |\n", name.c_str(),
                viewer.city()->tileCounts().loaded, scene, gpu, heap, heap - (scene - gpu), s.drawCalls,
                s.latest.buildingsVisible, viewer.city()->searchIndexLoaded() ? "loaded" : "-");
  };
  const CameraState overview = viewer.city()->overviewCamera();
  settle(overview, "overview");
  (void)viewer.city()->search("", 1);  // requests the city index
  for (int i = 0; i < 20000 && !viewer.city()->searchIndexSettled(); ++i) viewer.frame(1.0 / 60.0);
  settle(overview, "overview, city index loaded");
  const Tileset* tileset = viewer.city()->tileset();
  if (tileset == nullptr) return 1;
  const Rect b = tileset->bounds;
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      CameraState c = overview;
      const int col = j % 2 ? grid - 1 - i : i;
      c.x = b.minX + (b.maxX - b.minX) * (col + 0.5) / grid;
      c.y = b.minY + (b.maxY - b.minY) * (j + 0.5) / grid;
      c.distance = 600.0;
      c.headingDeg = 30.0;
      c.pitchDeg = 45.0;
      settle(c, "low pass " + std::to_string(j * grid + i + 1));
    }
  }
  settle(overview, "overview again");
  std::printf("\npeak live heap above the start %.1f MB; errors: %zu\n", peakHeap, viewer.errors().size());
  for (const auto& e : viewer.errors()) std::printf("  %s\n", e.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: bench_engine CITY_DIR [--radius M] [--frames N] [--animated N,N...]\n"
                 "       bench_engine CITY_DIR --flight N [--memory MB]\n");
    return 2;
  }
  const std::string dir = argv[1];
  float radius = 1200.0f;
  int frames = 120;
  // The whole city in view with the nearest N buildings animated: 10,000 (the case) and
  // 20,000 by default; a city with detailed towers (synth-city --detailed-towers) measures the
  // skeletal animation of LOD2 models with, e.g., --animated 1000,10000.
  std::vector<std::uint32_t> animatedCounts = {10000u, 20000u};
  int flightGrid = 0;
  double memoryMb = 0.0;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--flight") == 0) flightGrid = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--memory") == 0) memoryMb = std::strtod(argv[i + 1], nullptr);
    if (std::strcmp(argv[i], "--radius") == 0) radius = std::strtof(argv[i + 1], nullptr);
    if (std::strcmp(argv[i], "--frames") == 0) frames = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--animated") == 0) {
      animatedCounts.clear();
      for (const char* p = argv[i + 1]; *p != '\0';) {
        char* end = nullptr;
        const unsigned long n = std::strtoul(p, &end, 10);
        if (end == p || n == 0 || n > 10000000) {
          std::fprintf(stderr, "bench_engine: --animated takes counts such as 1000,10000\n");
          return 2;
        }
        animatedCounts.push_back(static_cast<std::uint32_t>(n));
        p = *end == ',' ? end + 1 : end;
      }
    }
  }
  if (flightGrid > 0) return flight(dir, flightGrid, memoryMb);
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
  // The whole city in view with N buildings moved floor by floor on the CPU (the radius reaches the
  // city from the overview's eye, so their full-detail tiles and histories stream in; every sway
  // counts, swayPixels 0, where the viewer moves only those that reach a pixel: the CPU's worst case).
  for (const std::uint32_t animated : animatedCounts) {
    CitySceneOptions& o = viewer.city()->mutableOptions();
    const float saved = o.animationRadiusM;
    const std::uint32_t savedMax = o.maxAnimatedBuildings;
    const float savedPixels = o.swayPixels;
    o.animationRadiusM = static_cast<float>(overview.distance) * 1.1f;
    o.maxAnimatedBuildings = animated;
    o.swayPixels = 0.0f;
    settle(overview);
    measure("overview, " + (animated % 1000 == 0 ? std::to_string(animated / 1000) + "k" : std::to_string(animated)) +
            " moved floor by floor");
    o.animationRadiusM = saved;
    o.maxAnimatedBuildings = savedMax;
    o.swayPixels = savedPixels;
  }
  CameraState street = overview;
  street.distance = 350.0;
  street.pitchDeg = 25.0;
  settle(street);
  measure("street level at the centre");

  std::printf("\nEngine CPU per frame (ms, medians of %d frames), %s, animation radius %.0f m\n\n", frames, dir.c_str(),
              static_cast<double>(radius));
  std::printf("| %-34s | %7s | %7s | %7s | %7s | %8s | %5s | %9s | %7s | %7s | %6s | %6s | %8s |\n", "camera", "cull",
              "lod", "animate", "upload", "c+l+a", "draws", "triangles", "loaded", "visible", "anim", "LOD2",
              "KB/frame");
  std::printf("|%s|\n", std::string(169, '-').c_str());
  for (const Row& r : rows) print(r);
  std::printf("\nerrors: %zu; tiles loaded %u failed %u; GPU bytes %.1f MB; scene bytes %.1f MB\n",
              viewer.errors().size(), viewer.city()->tileCounts().loaded, viewer.city()->tileCounts().failed,
              static_cast<double>(device.gpuBytes()) / 1048576.0,
              static_cast<double>(viewer.city()->memoryBytes()) / 1048576.0);
  for (const auto& e : viewer.errors()) std::printf("  %s\n", e.c_str());
  benchVisibleSet(dir, *viewer.city()->tileset(), {overview, street},
                  {"overview, whole city in view", "street level at the centre"});
  return 0;
}
