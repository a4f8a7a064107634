// Re-meshing, skinning and the far mesh: no triangle spans two storeys, area and enclosed volume
// are kept, skin weights follow the rule, on a synthetic tower and on real CityJSON models.
#include <map>
#include <numbers>
#include <utility>

#include <catch2/catch.hpp>

#include "Lod2TestData.h"
#include "qv/prep/Lod2CityJson.h"
#include "qv/prep/Lod2FarMesh.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Remesh.h"

namespace qv::prep::test {
namespace {

/// A closed tower: an octagonal prism (circumradius 12 m) from 0 to 50 m with a pyramid roof to 58 m,
/// its ground face included, away from the origin; outward-oriented.
Lod2Mesh syntheticTower() {
  Lod2Mesh mesh;
  const glm::dvec2 centre(1234.5, -678.25);
  constexpr int kSides = 8;
  for (int level = 0; level < 2; ++level) {
    for (int i = 0; i < kSides; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / kSides + 0.3;
      mesh.positions.emplace_back(centre.x + 12.0 * std::cos(angle), centre.y + 12.0 * std::sin(angle),
                                  level == 0 ? 0.0 : 50.0);
    }
  }
  const auto apex = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(centre.x, centre.y, 58.0);
  const auto groundCentre = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(centre.x, centre.y, 0.0);
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, SurfaceKind kind) {
    mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
    mesh.kinds.push_back(kind);
  };
  for (std::uint32_t i = 0; i < kSides; ++i) {
    const std::uint32_t j = (i + 1) % kSides;
    add(i, j, kSides + j, SurfaceKind::Wall);
    add(i, kSides + j, kSides + i, SurfaceKind::Wall);
    add(kSides + i, kSides + j, apex, SurfaceKind::Roof);
    add(groundCentre, j, i, SurfaceKind::Ground);
  }
  return mesh;
}

/// Directed edges (a, b) of the mesh without exactly one reverse edge (b, a): 0 for a closed,
/// consistently oriented mesh without T-junctions.
std::size_t unmatchedDirectedEdges(const Lod2Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    for (std::size_t i = 0; i < 3; ++i) ++uses[{mesh.triangles[t + i], mesh.triangles[t + (i + 1) % 3]}];
  }
  std::size_t unmatched = 0;
  for (const auto& [edge, n] : uses) {
    const auto reverse = uses.find({edge.second, edge.first});
    if (n != 1 || reverse == uses.end() || reverse->second != 1) ++unmatched;
  }
  return unmatched;
}

}  // namespace

TEST_CASE("lod2: A synthetic tower: cut at every floor, split, skinned, area and volume kept", "[lod2][remesh]") {
  const Lod2Mesh tower = syntheticTower();
  const double area = surfaceAreaM2(tower);
  const double volume = enclosedVolumeM3(tower);
  // Octagon of circumradius r: area 2 sqrt(2) r^2; prism + pyramid (a third of base x height).
  const double base = 2.0 * std::sqrt(2.0) * 144.0;
  CHECK(volume == Approx(base * 50.0 + base * 8.0 / 3.0).epsilon(1e-12));

  const FloorLevels floors{0.0, 58.0 / 15.0, 15};  // the pyramid spans the top three storeys
  const Result<Lod2Mesh> remeshed = remeshForFloors(tower, floors);
  REQUIRE(remeshed.ok());
  INFO("vertices " << tower.positions.size() << " -> " << remeshed->positions.size());
  CHECK(remeshed->positions.size() > 20 * tower.positions.size());
  CHECK(surfaceAreaM2(*remeshed) == Approx(area).epsilon(1e-3));
  CHECK(enclosedVolumeM3(*remeshed) == Approx(volume).epsilon(1e-3));
  CHECK(surfaceAreaM2(*remeshed) == Approx(area).epsilon(1e-9));  // exact up to rounding, in fact
  requireWithinStoreyBands(*remeshed, floors);
  // Still closed: cut points and midpoints are shared by both triangles of an edge, so every
  // directed edge has its reverse exactly once (a crack or T-junction would leave one unmatched).
  CHECK(unmatchedDirectedEdges(tower) == 0);
  CHECK(unmatchedDirectedEdges(*remeshed) == 0);
  // No edge longer than half a storey, except on the flat ground face's inside (moves as a whole).
  const double target = targetEdgeLengthM(floors, {});
  CHECK(target == Approx(58.0 / 30.0));
  std::size_t longEdges = 0;
  for (std::size_t t = 0; t < remeshed->kinds.size(); ++t) {
    if (remeshed->kinds[t] == SurfaceKind::Ground) continue;
    for (std::size_t i = 0; i < 3; ++i) {
      const glm::dvec3 a = remeshed->positions[remeshed->triangles[3 * t + i]];
      const glm::dvec3 b = remeshed->positions[remeshed->triangles[3 * t + (i + 1) % 3]];
      if (glm::length(b - a) > target * (1.0 + 1e-6)) ++longEdges;
    }
  }
  CHECK(longEdges == 0);
  // Semantics per triangle are kept: the roof's triangles are all above 50 m, walls below.
  for (std::size_t t = 0; t < remeshed->kinds.size(); ++t) {
    const double z = remeshed->positions[remeshed->triangles[3 * t]].z;
    if (remeshed->kinds[t] == SurfaceKind::Roof) CHECK(z >= 50.0 - 1e-9);
    if (remeshed->kinds[t] == SurfaceKind::Wall) CHECK(z <= 50.0 + 1e-9);
  }

  SkinnedMesh skinned;
  skinned.mesh = *remeshed;
  skinned.finished = true;
  const std::size_t onFloors = requireSkinningRule(skinned, floors);
  CHECK(onFloors > 8 * 16);                                            // at least the octagon's corners at every level
  CHECK(heightRange(skinned.mesh).maxZ == Approx(floors.levelM(15)));  // the apex follows the roof
}

TEST_CASE("lod2: Real CityJSON models keep area and volume through re-meshing", "[lod2][remesh][data]") {
  for (const char* name : {"DH_01_subs.city.json", "zurich_subset_lod2.json"}) {
    INFO(name);
    const Result<CityJsonFile> file = readCityJson(sharedData(std::string("cityjson/") + name));
    REQUIRE(file.ok());
    Result<std::vector<Lod2Model>> models = georeferenceCityJson(*file, name, placedInSyntheticCity(), nullptr);
    REQUIRE(models.ok());
    double areaBefore = 0.0;
    double areaAfter = 0.0;
    std::size_t closed = 0;
    for (Lod2Model& model : *models) {
      const Lod2Mesh original = model.skinned.mesh;
      REQUIRE(finishModel(model).ok());
      const FloorLevels floors = floorLevels(model.attributes);
      requireWithinStoreyBands(model.skinned.mesh, floors);
      requireSkinningRule(model.skinned, floors);
      CHECK(model.verticesAfter == model.skinned.mesh.positions.size());
      CHECK(model.verticesAfter > model.verticesBefore);
      const double before = surfaceAreaM2(original);
      const double after = surfaceAreaM2(model.skinned.mesh);
      CHECK(after == Approx(before).epsilon(1e-3));
      areaBefore += before;
      areaAfter += after;
      // The Den Haag models are closed Solids: their volume (a sum of signed tetrahedra) is kept.
      if (std::string(name) == "DH_01_subs.city.json") {
        const double volume = enclosedVolumeM3(original);
        CHECK(volume > 100.0);
        CHECK(enclosedVolumeM3(model.skinned.mesh) == Approx(volume).epsilon(1e-3));
        ++closed;
      }
    }
    CHECK(areaAfter == Approx(areaBefore).epsilon(1e-3));
    if (std::string(name) == "DH_01_subs.city.json") CHECK(closed == 4);
  }
}

TEST_CASE("lod2: The far mesh is a simplification within the error bound", "[lod2][far]") {
  SECTION("a box cannot lose a triangle") {
    Lod2Mesh box;
    for (int i = 0; i < 8; ++i) box.positions.emplace_back(i & 1 ? 10.0 : 0.0, i & 2 ? 10.0 : 0.0, i & 4 ? 10.0 : 0.0);
    const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {1, 3, 7, 5}, {3, 2, 6, 7}, {2, 0, 4, 6}};
    for (const auto& f : faces) {
      box.triangles.insert(box.triangles.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
      box.kinds.insert(box.kinds.end(), 2, SurfaceKind::Wall);
    }
    CHECK(enclosedVolumeM3(box) == Approx(1000.0));
    const Lod2Mesh far = simplifyFarMesh(box);
    CHECK(far.triangleCount() == 12);
    CHECK(enclosedVolumeM3(far) == Approx(1000.0));
    CHECK(far.kinds == box.kinds);  // nothing collapsed: the source's kinds stay
  }
  SECTION("a finely re-meshed tower collapses back to about its shape") {
    const Lod2Mesh tower = syntheticTower();
    const Result<Lod2Mesh> fine = remeshForFloors(tower, FloorLevels{0.0, 58.0 / 15.0, 15});
    REQUIRE(fine.ok());
    const Lod2Mesh far = simplifyFarMesh(*fine);
    INFO(fine->triangleCount() << " -> " << far.triangleCount() << " triangles");
    CHECK(far.triangleCount() <= fine->triangleCount() / 5 + 1);  // the 20 % target reached
    CHECK(enclosedVolumeM3(far) == Approx(enclosedVolumeM3(tower)).epsilon(0.05));
    CHECK(heightRange(far).maxZ == Approx(58.0).epsilon(0.02));
    CHECK(std::count(far.kinds.begin(), far.kinds.end(), SurfaceKind::Roof) > 0);
    CHECK(std::count(far.kinds.begin(), far.kinds.end(), SurfaceKind::Wall) > 0);
  }
}

TEST_CASE("lod2: Re-meshing and finishing refuse what they cannot do", "[lod2][remesh]") {
  const Lod2Mesh tower = syntheticTower();
  RemeshOptions tiny;
  tiny.maxEdgeM = 0.01;
  tiny.maxVertices = 20000;
  const Result<Lod2Mesh> tooMany = remeshForFloors(tower, FloorLevels{0.0, 3.0, 19}, tiny);
  REQUIRE_FALSE(tooMany.ok());
  CHECK(tooMany.error().find("would exceed 20000 vertices") != std::string::npos);
  Lod2Model flat;
  flat.id = "cj:flat";
  flat.skinned.mesh = tower;
  flat.attributes.heightM = 0.0f;
  const Status s = finishModel(flat);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().rfind("cj:flat: height 0", 0) == 0);
}

}  // namespace qv::prep::test
