// Shared by the LOD2 tests: where the data is, the synthetic city the models are placed into (near
// lon -74.00, lat 40.71, as with `--place`), imports of the real files done once per test process
// (Zurich takes a few seconds under AddressSanitizer), and mesh checks.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "qv/prep/Lod2Import.h"
#include "qv/prep/Lod2Skinning.h"
#include "qv/prep/SynthCity.h"

namespace qv::prep::test {

inline std::string sharedData(const std::string& relative) {
  return std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/" + relative;
}
inline std::string fixture(const std::string& name) {
  return std::string(QUAKEVIEW_LOD2_DATA_DIR) + "/" + name;
}

inline constexpr double kPlaceLon = -74.00;
inline constexpr double kPlaceLat = 40.71;

/// A file in the system's temporary folder, removed at the end of the scope.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& content)
      : path_((std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "-" + name)).string()) {
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A small synthetic city (300 buildings around lon -74.00, lat 40.71) and its extent.
struct SyntheticCity {
  CityModel model;
  Rect extent;
  std::vector<ExistingBuilding> existing;
};

inline const SyntheticCity& syntheticCity() {
  static const SyntheticCity city = [] {
    SyntheticCity c;
    SynthCityOptions options;
    options.buildings = 300;
    options.originLon = kPlaceLon;
    options.originLat = kPlaceLat;
    c.model = generateSynthCity(options);
    for (const Building& b : c.model.buildings) {
      for (const BuildingPart& part : b.parts) {
        for (const glm::dvec2& p : part.points) c.extent.expand(static_cast<float>(p.x), static_cast<float>(p.y));
      }
    }
    c.existing = existingBuildings(c.model);
    return c;
  }();
  return city;
}

/// Import options for the synthetic city: its origin and extent, with `--place LON,LAT[,ROTATION]`.
inline Lod2ImportOptions placedInSyntheticCity(double rotationDeg = 0.0) {
  Lod2ImportOptions options;
  options.originLon = syntheticCity().model.originLon;
  options.originLat = syntheticCity().model.originLat;
  options.extent = syntheticCity().extent;
  options.placement = Placement{kPlaceLon, kPlaceLat, rotationDeg};
  return options;
}

/// importModels(shared cityjson/<file>) placed in the synthetic city, once per file.
inline const Result<Lod2Import>& placedImport(const std::string& file) {
  static std::map<std::string, Result<Lod2Import>> cache;
  auto it = cache.find(file);
  if (it == cache.end()) {
    it = cache.emplace(file, importModels(sharedData("cityjson/" + file), placedInSyntheticCity())).first;
  }
  return it->second;
}

/// Asserts that no triangle spans two storey bands: its z-range lies between two consecutive floor
/// levels (or below the base, or above the roof), within `toleranceM`.
inline void requireWithinStoreyBands(const Lod2Mesh& mesh, const FloorLevels& floors, double toleranceM = 1e-5) {
  std::size_t bad = 0;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    double lo = mesh.positions[mesh.triangles[t]].z;
    double hi = lo;
    for (std::size_t i = 1; i < 3; ++i) {
      lo = std::min(lo, mesh.positions[mesh.triangles[t + i]].z);
      hi = std::max(hi, mesh.positions[mesh.triangles[t + i]].z);
    }
    const double mid = 0.5 * (lo + hi);
    const int k = static_cast<int>(std::floor((mid - floors.baseM) / floors.storeyHeightM));
    const double bandLo = k < 0 ? -1e300 : (k >= floors.storeys ? floors.levelM(floors.storeys) : floors.levelM(k));
    const double bandHi = k < 0 ? floors.baseM : (k >= floors.storeys ? 1e300 : floors.levelM(k + 1));
    if (lo < bandLo - toleranceM || hi > bandHi + toleranceM) ++bad;
  }
  CHECK(bad == 0);
}

/// Asserts the skinning rule on every vertex: bone in [0, storeys], weight in [0, 1], the height
/// rebuilt from (bone, weight) equals the vertex's (linear weights between the floors), weight 0 at
/// and beyond the ends. Returns how many vertices lie exactly on a floor level.
inline std::size_t requireSkinningRule(const SkinnedMesh& skinned, const FloorLevels& floors) {
  REQUIRE(skinned.bone.size() == skinned.mesh.positions.size());
  REQUIRE(skinned.weight.size() == skinned.mesh.positions.size());
  std::size_t onFloor = 0;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < skinned.mesh.positions.size(); ++i) {
    const double z = skinned.mesh.positions[i].z;
    const int bone = skinned.bone[i];
    const float w = skinned.weight[i];
    // Bone k gets 1 - w and bone k + 1 gets w. The weights on bones that exist sum to 1 only when
    // w is in [0, 1) and bone k + 1 exists whenever w > 0 (no weight on a bone above the roof).
    if (bone > floors.storeys || !(w >= 0.0f && w < 1.0f) || (w > 0.0f && bone + 1 > floors.storeys)) ++bad;
    const double nearest = std::round((z - floors.baseM) / floors.storeyHeightM);
    const bool atLevel =
        nearest >= 0 && nearest <= floors.storeys && std::abs(z - floors.levelM(static_cast<int>(nearest))) <= 1e-9;
    if (atLevel) {
      ++onFloor;
      if (bone != static_cast<int>(nearest) || w != 0.0f) ++bad;  // follows its bone exactly
    }
    if (z <= floors.baseM) {
      if (bone != 0 || w != 0.0f) ++bad;
    } else if (z >= floors.levelM(floors.storeys)) {
      if (bone != floors.storeys || w != 0.0f) ++bad;
    } else if (std::abs(floors.levelM(bone) + static_cast<double>(w) * floors.storeyHeightM - z) > 1e-4) {
      ++bad;
    }
  }
  CHECK(bad == 0);
  return onFloor;
}

}  // namespace qv::prep::test
