// Shared by the ingest tests: where the data is, and the real files read once per test process
// (reading the Manhattan PBF under AddressSanitizer takes a few seconds).
#pragma once

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "qv/prep/Ingest.h"

namespace qv::prep::test {

/// True when some warning of `model` contains `text`.
inline bool hasWarning(const CityModel& model, const std::string& text) {
  return std::any_of(model.warnings.begin(), model.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

inline std::string sharedData(const std::string& relative) {
  return std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/" + relative;
}
inline std::string fixture(const std::string& name) {
  return std::string(QUAKEVIEW_INGEST_DATA_DIR) + "/" + name;
}

struct Ingested {
  Result<CityModel> model;
  IngestStats stats;
};

inline Ingested ingest(const std::vector<std::string>& paths, const IngestOptions& options = {}) {
  IngestStats stats;
  Result<CityModel> model = readCity(paths, options, &stats);
  return {std::move(model), stats};
}

/// fixture-midtown-empire-state.osm, read once.
inline const Ingested& midtownFixture() {
  static const Ingested ingested = ingest({sharedData("osm/fixture-midtown-empire-state.osm")});
  return ingested;
}

/// nyc-manhattan-south-buildings.osm.pbf, read once.
inline const Ingested& manhattanSouth() {
  static const Ingested ingested = ingest({sharedData("osm/nyc-manhattan-south-buildings.osm.pbf")});
  return ingested;
}

/// A fresh folder under the system's temporary folder, removed with its files at the end.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("qv-ingest-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// Writes `content` to a file of that name in the folder and returns its path.
  std::string write(const std::string& name, const std::string& content) const {
    const std::string file = (path_ / name).string();
    std::ofstream(file, std::ios::binary) << content;
    return file;
  }
  [[nodiscard]] std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

inline const Building* findBuilding(const CityModel& model, const std::string& id) {
  for (const Building& b : model.buildings) {
    if (b.attributes.id == id) return &b;
  }
  return nullptr;
}

}  // namespace qv::prep::test
