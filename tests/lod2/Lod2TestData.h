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

#include "qv/anim/FloorBlend.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Import.h"
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

/// Asserts how the viewer skins every vertex of a finished mesh (qv::floorBlendAt, the vertex
/// shader's rule) given these floors: a vertex on a floor level follows that floor alone, one between
/// two levels follows both in proportion to its height (level k + weight × storey height gives its
/// height back), below the base the ground, at and above the roof the roof. Returns how many
/// vertices lie exactly on a floor level.
inline std::size_t requireSkinningRule(const SkinnedMesh& skinned, const FloorLevels& floors) {
  REQUIRE(skinned.finished);
  // Floor displacements that tell every floor apart (not linear in k, so a wrong pair of floors
  // or a wrong weight shows).
  std::vector<float> displacement(floors.storeys + 1u);
  for (std::size_t k = 0; k < displacement.size(); ++k) displacement[k] = static_cast<float>(k * k) * 0.01f;
  const auto baseZ = static_cast<float>(floors.baseM);
  const auto storeyHeight = static_cast<float>(floors.storeyHeightM);
  std::size_t onFloor = 0;
  std::size_t bad = 0;
  for (const glm::dvec3& p : skinned.mesh.positions) {
    const double z = p.z;
    const FloorBlend blend = floorBlendAt(static_cast<float>(z), baseZ, storeyHeight, floors.storeys);
    const float moved = blendedDisplacement(blend, displacement);
    if (blend.lower < 0 || blend.upper > floors.storeys || !(blend.upperWeight >= 0.0f && blend.upperWeight <= 1.0f))
      ++bad;
    const double nearest = std::round((z - floors.baseM) / floors.storeyHeightM);
    const bool atLevel =
        nearest >= 0 && nearest <= floors.storeys && std::abs(z - floors.levelM(static_cast<int>(nearest))) <= 1e-9;
    // The viewer computes in float: a vertex on a floor may take up to about 1e-5 of its neighbour's.
    const float tolerance = 1e-5f * displacement.back() + 1e-7f;
    if (atLevel) {
      ++onFloor;
      if (std::abs(moved - displacement[static_cast<std::size_t>(nearest)]) > tolerance) ++bad;
    }
    if (z <= floors.baseM) {
      if (std::abs(moved - displacement.front()) > tolerance) ++bad;
    } else if (z >= floors.levelM(floors.storeys)) {
      if (std::abs(moved - displacement.back()) > tolerance) ++bad;
    } else if (std::abs(floors.levelM(blend.lower) + static_cast<double>(blend.upperWeight) * floors.storeyHeightM -
                        z) > 1e-5 * (1.0 + std::abs(z))) {
      ++bad;
    }
  }
  CHECK(bad == 0);
  return onFloor;
}

}  // namespace qv::prep::test
