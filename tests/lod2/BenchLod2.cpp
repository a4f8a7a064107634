// Not a ctest: imports the shared CityJSON files and the Empire State Building's OSM parts and
// prints a table of counts and times (run the release build: build/native-release/tests/lod2/bench_lod2).
#include <chrono>
#include <cstdio>
#include <string>

#include "qv/prep/Ingest.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Import.h"
#include "qv/prep/Lod2OsmParts.h"

namespace {

std::string sharedData(const std::string& relative) {
  return std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/" + relative;
}

}  // namespace

int main() {
  using qv::prep::Lod2ImportOptions;
  std::printf("%-26s %7s %6s %11s %10s %10s %10s %8s %9s\n", "file", "models", "parts", "geometries", "verts in",
              "verts out", "tris out", "far/orig", "seconds");
  for (const char* file : {"DH_01_subs.city.json", "zurich_subset_lod2.json", "multi_lod.json", "delft.json"}) {
    Lod2ImportOptions options;
    options.originLon = -74.00;
    options.originLat = 40.71;
    options.extent = qv::Rect{-2000.0f, -2000.0f, 2000.0f, 2000.0f};
    options.placement = qv::prep::Placement{-74.00, 40.71, 0.0};
    const auto result = qv::prep::importModels(sharedData(std::string("cityjson/") + file), options);
    if (!result.ok()) {
      std::printf("%s: %s\n", file, result.error().c_str());
      return 1;
    }
    const auto& r = result->report;
    std::uint64_t geometries = 0;
    for (const auto& [type, n] : r.geometries) geometries += n;
    std::printf("%-26s %7llu %6llu %11llu %10llu %10llu %10llu %3llu/%-4llu %9.3f\n", file,
                static_cast<unsigned long long>(r.imported), static_cast<unsigned long long>(r.partsMerged),
                static_cast<unsigned long long>(geometries), static_cast<unsigned long long>(r.verticesBefore),
                static_cast<unsigned long long>(r.verticesAfter), static_cast<unsigned long long>(r.trianglesAfter),
                static_cast<unsigned long long>(r.farTriangles), static_cast<unsigned long long>(r.originalTriangles),
                r.seconds);
  }
  const auto start = std::chrono::steady_clock::now();
  const auto city = qv::prep::readCity({sharedData("osm/fixture-midtown-empire-state.osm")}, {});
  if (!city.ok()) {
    std::printf("%s\n", city.error().c_str());
    return 1;
  }
  const auto read = std::chrono::steady_clock::now();
  for (const auto& building : city->buildings) {
    if (building.attributes.id != "w34633854") continue;
    // The default target edge (half a storey), then edges of up to one storey.
    for (const double storeys : {0.5, 1.0}) {
      const auto begin = std::chrono::steady_clock::now();
      auto model = qv::prep::modelFromOsmParts(building);
      qv::prep::FinishOptions options;
      options.remesh.maxEdgeM = storeys * static_cast<double>(building.attributes.storeyHeightM());
      if (!model.ok() || !qv::prep::finishModel(*model, options)) return 1;
      const auto done = std::chrono::steady_clock::now();
      std::printf("%-17s %4.1f st %7d %6zu %11s %10u %10u %10zu %8zu %9.3f\n", "Empire State edge", storeys, 1,
                  building.parts.size(), "-", model->verticesBefore, model->verticesAfter,
                  model->skinned.mesh.triangleCount(), model->farMesh.triangleCount(),
                  std::chrono::duration<double>(done - begin).count());
    }
  }
  std::printf("(reading fixture-midtown-empire-state.osm: %.3f s)\n",
              std::chrono::duration<double>(read - start).count());
  return 0;
}
