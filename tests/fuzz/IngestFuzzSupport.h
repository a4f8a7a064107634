// The ingest fuzzers feed readCity through a file (the readers take paths, and libosmium picks its
// parser by file name). The files live in one private temporary folder per process.
#pragma once

#include <dirent.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "FuzzSupport.h"
#include "qv/prep/Ingest.h"

namespace qv::fuzz {

/// Writes `bytes` to <private temp folder>/<fileName> and returns the path.
inline std::string writeInput(std::string_view bytes, const std::string& fileName) {
  static const std::string folder = [] {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/quakeview-fuzz-XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) contractBroken("cannot create a temporary folder");
    return pattern;
  }();
  const std::string path = folder + "/" + fileName;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) contractBroken("cannot write", path);
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) {
    contractBroken("cannot write", path);
  }
  std::fclose(file);
  return path;
}

/// Closes this process's descriptors still open on `path`. libosmium 2.18's PBF parser closes the
/// file only when parsing succeeds: every corrupt PBF leaves its descriptor open (harmless in the
/// one-shot quakeview-prep, which exits with the error), and a fuzzer, which reads a hundred
/// thousand corrupt files in one process, runs out of descriptors ("cannot write").
inline void closeLeakedDescriptors(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path wanted = std::filesystem::absolute(path, ec);
  DIR* dir = opendir("/proc/self/fd");
  if (dir == nullptr) return;
  std::vector<int> leaked;
  while (const dirent* entry = readdir(dir)) {
    const int fd = std::atoi(entry->d_name);
    if (fd <= 2 || fd == dirfd(dir)) continue;
    const auto target = std::filesystem::read_symlink(std::filesystem::path("/proc/self/fd") / entry->d_name, ec);
    if (!ec && target == wanted) leaked.push_back(fd);
  }
  closedir(dir);
  for (const int fd : leaked) close(fd);
}

/// Reads one file through the whole ingest (readers, projection, cleaning, attributes) and checks
/// the result: an error names the file; a city has sane buildings.
inline void ingestOne(const std::string& path) {
  prep::IngestOptions options;
  options.threads = 1;
  const Result<prep::CityModel> city = prep::readCity({path}, options);
  closeLeakedDescriptors(path);
  if (!city.ok()) {
    check(city.error().find(path) != std::string::npos, "ingest error does not name the file:", city.error());
    return;
  }
  for (const prep::Building& b : city->buildings) {
    check(!b.parts.empty() && !b.attributes.id.empty(), "a building without parts or id");
    check(std::isfinite(b.attributes.heightM) && b.attributes.heightM >= b.attributes.minHeightM &&
              b.attributes.storeys >= 1,
          "a building with invalid height or storeys", b.attributes.id);
    for (const prep::BuildingPart& p : b.parts) {
      check(!p.ringEnds.empty() && p.ringEnds.back() == p.points.size(), "part rings do not match the points");
      for (const auto& point : p.points) {
        check(std::isfinite(point.x) && std::isfinite(point.y), "a non-finite projected point", b.attributes.id);
      }
    }
  }
  std::remove(path.c_str());
}

}  // namespace qv::fuzz
