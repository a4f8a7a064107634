#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "qv/geometry/BuildingMesh.h"

using namespace qv;

namespace {

const std::vector<glm::vec2> kSquare = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};

glm::vec3 normalOf(const BuildingVertex& v) {
  return glm::vec3(v.nx, v.ny, v.nz) / 127.0f;
}

}  // namespace

TEST_CASE("A square extruded over three storeys has a ring per floor level and a roof", "[geometry][mesh]") {
  MeshData mesh;
  std::vector<float> levels;
  floorLevelsBetween(0.0f, 9.0f, 3.0f, levels);
  REQUIRE(levels == std::vector<float>{3.0f, 6.0f});
  const std::vector<std::uint32_t> ringEnds = {4};
  const std::vector<std::uint32_t> roof = {0, 1, 2, 0, 2, 3};
  ExtrusionInput in;
  in.points = kSquare;
  in.ringEnds = ringEnds;
  in.roofTriangles = roof;
  in.baseZ = 0.0f;
  in.topZ = 9.0f;
  in.levels = levels;
  in.slot = 42;
  const std::size_t triangles = appendExtrusion(mesh, in);
  // 4 walls × 3 storeys × 2 triangles + 2 roof triangles.
  CHECK(triangles == 26);
  CHECK(mesh.triangleCount() == 26);
  // 4 edges × 2 corners × 4 levels + 4 roof points.
  CHECK(mesh.vertices.size() == 36);
  for (const BuildingVertex& v : mesh.vertices) CHECK(v.slot == 42);

  // Every wall normal points away from the square's centre; roof normals point up.
  for (const BuildingVertex& v : mesh.vertices) {
    const glm::vec3 n = normalOf(v);
    if (v.kind == kRoof) {
      CHECK(n.z == Approx(1.0f));
      CHECK(v.z == 9.0f);
    } else {
      const glm::vec2 outward(v.x - 5.0f, v.y - 5.0f);
      CHECK(n.x * outward.x + n.y * outward.y > 0.0f);
    }
  }
}

TEST_CASE("Wall triangles are counter-clockwise from outside and end on their storey's bottom ring",
          "[geometry][mesh]") {
  MeshData mesh;
  std::vector<float> levels = {3.0f, 6.0f};
  const std::vector<std::uint32_t> ringEnds = {4};
  ExtrusionInput in;
  in.points = kSquare;
  in.ringEnds = ringEnds;
  in.topZ = 9.0f;
  in.levels = levels;
  appendExtrusion(mesh, in);
  REQUIRE(mesh.indices.size() % 3 == 0);
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const BuildingVertex& a = mesh.vertices[mesh.indices[t]];
    const BuildingVertex& b = mesh.vertices[mesh.indices[t + 1]];
    const BuildingVertex& c = mesh.vertices[mesh.indices[t + 2]];
    const glm::vec3 pa(a.x, a.y, a.z), pb(b.x, b.y, b.z), pc(c.x, c.y, c.z);
    const glm::vec3 faceNormal = glm::cross(pb - pa, pc - pa);
    CHECK(glm::dot(faceNormal, normalOf(a)) > 0.0f);  // front face = outside
    // The provoking (last) vertex is the lowest of the triangle: its storey's bottom ring.
    CHECK(c.z <= std::min(a.z, b.z));
  }
}

TEST_CASE("Hole walls face into the courtyard and stacked parts start at their base", "[geometry][mesh]") {
  // Outer 20×20 counter-clockwise, hole 10×10 clockwise.
  const std::vector<glm::vec2> pts = {{0, 0}, {20, 0}, {20, 20}, {0, 20}, {5, 5}, {5, 15}, {15, 15}, {15, 5}};
  const std::vector<std::uint32_t> ringEnds = {4, 8};
  std::vector<float> levels;
  floorLevelsBetween(12.0f, 20.0f, 4.0f, levels);  // a part from 12 m to 20 m, storeys of 4 m
  CHECK(levels == std::vector<float>{16.0f});
  MeshData mesh;
  ExtrusionInput in;
  in.points = pts;
  in.ringEnds = ringEnds;
  in.baseZ = 12.0f;
  in.topZ = 20.0f;
  in.levels = levels;
  appendExtrusion(mesh, in);
  CHECK(mesh.vertices.size() == 8 * 2 * 3);
  for (const BuildingVertex& v : mesh.vertices) {
    CHECK(v.z >= 12.0f);
    const glm::vec3 n = normalOf(v);
    const bool onHole = v.x >= 5 && v.x <= 15 && v.y >= 5 && v.y <= 15;
    const glm::vec2 fromCentre(v.x - 10.0f, v.y - 10.0f);
    const float d = n.x * fromCentre.x + n.y * fromCentre.y;
    if (onHole)
      CHECK(d < 0.0f);
    else
      CHECK(d > 0.0f);
  }
}

TEST_CASE("Degenerate input yields nothing rather than garbage", "[geometry][mesh]") {
  MeshData mesh;
  const std::vector<std::uint32_t> ringEnds = {4};
  const std::vector<std::uint32_t> badRoof = {0, 1, 99};
  ExtrusionInput in;
  in.points = kSquare;
  in.ringEnds = ringEnds;
  in.roofTriangles = badRoof;
  in.baseZ = 5.0f;
  in.topZ = 5.0f;  // zero height
  CHECK(appendExtrusion(mesh, in) == 0);
  in.topZ = 8.0f;
  appendExtrusion(mesh, in);
  for (std::uint32_t index : mesh.indices) CHECK(index < mesh.vertices.size());
  std::vector<float> levels;
  floorLevelsBetween(0.0f, 1.0e9f, 3.0f, levels);
  CHECK(levels.size() < 1000);
}

TEST_CASE("Floor levels of a building standing on another start from its own lowest floor", "[geometry][mesh]") {
  // A building on a podium: its lowest floor at 12 m, three storeys of 4 m (roof at 24 m).
  const FloorGrid floors{12.0f, 4.0f, 3};
  std::vector<float> levels;
  floorLevelsBetween(floors, 12.0f, 24.0f, 0.01f, levels);
  CHECK(levels == std::vector<float>{16.0f, 20.0f});
  // A part of it from 14 m up, and one above its last storey: the storey count ends the levels.
  levels.clear();
  floorLevelsBetween(floors, 14.0f, 30.0f, 0.01f, levels);
  CHECK(levels == std::vector<float>{16.0f, 20.0f});
  // Appended, not replaced.
  floorLevelsBetween(floors, 12.0f, 17.0f, 0.01f, levels);
  CHECK(levels == std::vector<float>{16.0f, 20.0f, 16.0f});
}

TEST_CASE("Floor levels keep their margin from a part's base and top", "[geometry][mesh]") {
  const FloorGrid floors{0.0f, 3.0f, 1000};
  std::vector<float> levels;
  // A part whose base is 5 mm under the 3 m floor: the floor counts with a 1 mm margin only.
  floorLevelsBetween(floors, 2.995f, 9.0f, 0.01f, levels);
  CHECK(levels == std::vector<float>{6.0f});
  levels.clear();
  floorLevelsBetween(floors, 2.995f, 9.0f, 0.001f, levels);
  CHECK(levels == std::vector<float>{3.0f, 6.0f});
  // The same at the top: 6 m is 5 mm under a top of 6.005 m.
  levels.clear();
  floorLevelsBetween(floors, 0.0f, 6.005f, 0.01f, levels);
  CHECK(levels == std::vector<float>{3.0f});
  // The short form is a building at z = 0 with a 1 mm margin.
  std::vector<float> shortForm;
  floorLevelsBetween(2.995f, 9.0f, 3.0f, shortForm);
  CHECK(shortForm == std::vector<float>{3.0f, 6.0f});
}

TEST_CASE("Floor levels of corrupt heights stay few and defined", "[geometry][mesh]") {
  std::vector<float> levels;
  floorLevelsBetween(FloorGrid{0.0f, 0.05f, 1000}, 0.0f, 10.0f, 0.01f, levels);  // storeys of 5 cm
  CHECK(levels.empty());
  floorLevelsBetween(FloorGrid{0.0f, 3.0f, 1000}, 1.0e30f, 3.0e30f, 0.01f, levels);  // far above
  CHECK(levels.empty());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  floorLevelsBetween(FloorGrid{nan, 3.0f, 1000}, 0.0f, 10.0f, 0.01f, levels);
  CHECK(levels.empty());
  floorLevelsBetween(FloorGrid{0.0f, 3.0f, 1000000}, 0.0f, 1.0e9f, 0.01f, levels);
  CHECK(levels.size() == 999);  // levels 1 to 999 at most
}
