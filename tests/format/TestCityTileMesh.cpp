// The optional MESH section of city tiles (LOD2 models): docs/formats.md, "MESH".
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "qv/core/Crc32.h"
#include "qv/format/CityTile.h"

using namespace qv;

namespace {

// One building of 4 storeys, 12 m tall, on a triangular part.
CityTile tileWithoutMesh() {
  CityTile t;
  t.originX = 100.0;
  t.originY = 200.0;
  t.extent = 10.0f;
  t.vertices = {{0.0f, 0.0f}, {10.0f, 0.0f}, {0.0f, 10.0f}};
  t.ringVertexCounts = {3};
  t.roofTriangles = {0, 1, 2};
  TilePart p;
  p.ringCount = 1;
  p.triangleCount = 1;
  p.heightM = 12.0f;
  t.parts = {p};
  TileBuilding b;
  b.partCount = 1;
  b.attributes.id = "s1";
  b.attributes.heightM = 12.0f;
  b.attributes.storeys = 4;
  b.attributes.lod = 2;
  b.attributes.footprintAreaM2 = 50.0f;
  t.buildings = {b};
  return t;
}

// A tetrahedron from the ground to the roof of its 4-storey building, with a one-triangle far mesh.
CityTile tinyMeshTile() {
  CityTile t = tileWithoutMesh();
  TileMesh m;
  m.building = 0;
  m.source = MeshSource::CityJson;
  m.storeys = 4;
  m.verticesBefore = 4;
  m.topM = 12.0f;
  m.positions = {{0.0f, 0.0f, 0.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 10.0f, 0.0f}, {0.0f, 0.0f, 12.0f}};
  m.triangles = {0, 1, 3, 1, 2, 3, 2, 0, 3, 0, 2, 1};  // 2 walls, 1 roof, 1 ground
  m.trianglesPerKind = {2, 1, 1, 0};
  m.farPositions = {{0.0f, 0.0f, 0.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 12.0f}};
  m.farTriangles = {0, 1, 2};
  t.meshes = {m};
  return t;
}

std::string hex(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (std::uint8_t b : bytes) {
    out += digits[b >> 4];
    out += digits[b & 15];
  }
  return out;
}

void fixCrc(std::vector<std::uint8_t>& bytes) {
  const std::uint32_t crc = crc32(std::span(bytes).subspan(16));
  for (std::size_t i = 0; i < 4; ++i) bytes[12 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
}

std::uint32_t readU32(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
         static_cast<std::uint32_t>(bytes[at + 2]) << 16 | static_cast<std::uint32_t>(bytes[at + 3]) << 24;
}

/// Offset of the MESH section (the seventh table entry) in an encoded tile.
std::size_t meshOffset(const std::vector<std::uint8_t>& bytes) {
  return readU32(bytes, 48 + 6 * 12 + 4);
}

}  // namespace

TEST_CASE("City tile MESH section is pinned by golden bytes", "[format][tile][mesh]") {
  // Checked by hand against docs/formats.md ("MESH"). The sections before MESH are those of the
  // version 2 golden tile in TestCityTile.cpp (here with no strings but the id, LOD 2).
  const std::string golden =
      "51564354"
      "0200"
      "0000"
      "5c010000"
      "af08de63"  // "QVCT", version 2, flags 0, 348 bytes, CRC-32
      "01000000"
      "01000000"
      "0000000000005940"
      "0000000000006940"
      "00002041"
      "0700"
      "0000"  // extent 10.0f, 7 sections
      "424c4447"
      "84000000"
      "28000000"
      "50415254"
      "ac000000"
      "14000000"
      "52494e47"
      "c0000000"
      "02000000"
      "56455254"
      "c4000000"
      "0c000000"
      "54524953"
      "d0000000"
      "06000000"
      "53545253"
      "d8000000"
      "09000000"
      "4d455348"
      "e4000000"
      "78000000"                                                                          // MESH at 228, 120 bytes
      "01000000000040410000000004000000000000000200000000004842000000000000000000000000"  // BLDG, LOD 2
      "0100000001000000000000000000404100000000"                                          // PART
      "03000000"                                                                          // RING
      "00000000ffff00000000ffff"                                                          // VERT
      "0000010002000000"                                                                  // TRIS
      "027331000000000000000000"  // STRS: "s1" and six empty strings, padding
      // MESH: 1 model
      "01000000"
      // record: building 0, CityJSON, reserved, 4 storeys, 4 vertices, triangles 2 wall 1 roof
      // 1 ground 0 other, 3 far vertices, 1 far triangle, 4 vertices before, top 12.0f
      "00000000"
      "00"
      "00"
      "0400"
      "04000000"
      "02000000"
      "01000000"
      "01000000"
      "00000000"
      "03000000"
      "01000000"
      "04000000"
      "00004041"
      // vertices (qx, qy, qz): 24 bytes, no padding needed
      "000000000000"
      "ffff00000000"
      "0000ffff0000"
      "00000000ffff"
      // triangles, u16 (4 vertices): walls 0 1 3, 1 2 3; roof 2 0 3; ground 0 2 1
      "000001000300"
      "010002000300"
      "020000000300"
      "000002000100"
      // far vertices (qx, qy, qz), far triangle 0 1 2
      "000000000000"
      "ffff00000000"
      "00000000ffff"
      "000001000200";
  const auto bytes = encodeCityTile(tinyMeshTile());
  CHECK(hex(bytes) == golden);
  const auto decoded = decodeCityTile(bytes, "golden");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->meshes.size() == 1);
  CHECK(decoded->meshes[0].positions[3].z == 12.0f);
}

TEST_CASE("Version 1 MESH sections are still read, their bones and weights skipped", "[format][tile][mesh]") {
  // The version 1 golden bytes, as written before version 2: each vertex followed by its bone and
  // weight (the last vertex on the roof: bone 4, weight 0).
  const std::string version1 =
      "51564354"
      "0100"
      "0000"
      "64010000"
      "117f8469"  // "QVCT", version 1, flags 0, 356 bytes, CRC-32
      "01000000"
      "01000000"
      "0000000000005940"
      "0000000000006940"
      "00002041"
      "0700"
      "0000"
      "424c4447"
      "84000000"
      "28000000"
      "50415254"
      "ac000000"
      "14000000"
      "52494e47"
      "c0000000"
      "02000000"
      "56455254"
      "c4000000"
      "0c000000"
      "54524953"
      "d0000000"
      "06000000"
      "53545253"
      "d8000000"
      "09000000"
      "4d455348"
      "e4000000"
      "80000000"  // MESH at 228, 128 bytes
      "01000000000040410000000004000000000000000200000000004842000000000000000000000000"
      "0100000001000000000000000000404100000000"
      "03000000"
      "00000000ffff00000000ffff"
      "0000010002000000"
      "027331000000000000000000"
      "01000000"
      "00000000000004000400000002000000010000000100000000000000030000000100000004000000"
      "00004041"          // the record, as in version 2
      "0000000000000000"  // qx, qy, qz, bone, weight
      "ffff000000000000"
      "0000ffff00000000"
      "00000000ffff0400"
      "000001000300010002000300020000000300000002000100"
      "000000000000ffff0000000000000000ffff000001000200";
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = 0; i + 1 < version1.size(); i += 2)
    bytes.push_back(static_cast<std::uint8_t>(std::stoi(version1.substr(i, 2), nullptr, 16)));
  REQUIRE(bytes.size() == 356);
  const auto old = decodeCityTile(bytes, "version 1");
  REQUIRE(old.ok());
  REQUIRE(old->meshes.size() == 1);
  const TileMesh& m = old->meshes[0];
  const TileMesh expected = tinyMeshTile().meshes[0];
  CHECK(m.positions == expected.positions);
  CHECK(m.triangles == expected.triangles);
  CHECK(m.trianglesPerKind == expected.trianglesPerKind);
  CHECK(m.farPositions == expected.farPositions);
  CHECK(m.farTriangles == expected.farTriangles);
  // Written again, it is the version 2 tile: the same model without the skin.
  CHECK(encodeCityTile(*old) == encodeCityTile(tinyMeshTile()));
}

TEST_CASE("Tiles with LOD2 meshes round-trip through the codec", "[format][tile][mesh]") {
  const bool wide = GENERATE(false, true);
  CityTile t = tinyMeshTile();
  // A second building with 3 storeys and a mesh with vertices between its floors.
  t.vertices.insert(t.vertices.end(), {{1, 1}, {9, 1}, {9, 9}});
  t.ringVertexCounts.push_back(3);
  t.roofTriangles.insert(t.roofTriangles.end(), {0, 1, 2});
  TilePart p;
  p.ringCount = 1;
  p.triangleCount = 1;
  p.heightM = 9.0f;
  t.parts.push_back(p);
  TileBuilding b;
  b.partCount = 1;
  b.firstPart = 1;
  b.attributes.id = "cj:x";
  b.attributes.heightM = 9.0f;
  b.attributes.storeys = 3;
  b.attributes.lod = 2;
  t.buildings.push_back(b);
  TileMesh m;
  m.building = 1;
  m.source = MeshSource::OsmParts;
  m.storeys = 3;
  m.verticesBefore = 6;
  m.topM = 9.0f;
  // Enough vertices for u32 indices in the wide case.
  const std::size_t n = wide ? 70000 : 300;
  for (std::size_t i = 0; i < n; ++i) {
    const float z = 9.0f * static_cast<float>(i) / static_cast<float>(n - 1);
    m.positions.push_back({static_cast<float>(i % 10), static_cast<float>(i % 7), z});
  }
  for (std::uint32_t i = 0; i + 2 < n; i += 3) m.triangles.insert(m.triangles.end(), {i, i + 1, i + 2});
  m.triangles.insert(m.triangles.end(), {static_cast<std::uint32_t>(n - 1), 0, 1});
  const auto triangles = static_cast<std::uint32_t>(m.triangles.size() / 3);
  m.trianglesPerKind = {triangles - 3, 1, 0, 2};
  m.farPositions = {{1, 1, 0}, {9, 1, 0}, {9, 9, 9}, {1, 9, 9}};
  m.farTriangles = {0, 1, 2, 0, 2, 3};
  t.meshes.push_back(m);

  const auto decoded = decodeCityTile(encodeCityTile(t), "round-trip");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->meshes.size() == 2);
  CHECK(decoded->buildings.size() == 2);
  const TileMesh& d = decoded->meshes[1];
  CHECK(d.building == 1);
  CHECK(d.source == MeshSource::OsmParts);
  CHECK(meshSourceName(d.source) == "osm-parts");
  CHECK(d.storeys == 3);
  CHECK(d.verticesBefore == 6);
  CHECK(d.topM == 9.0f);
  CHECK(d.triangles == m.triangles);
  CHECK(d.trianglesPerKind == m.trianglesPerKind);
  CHECK(d.farTriangles == m.farTriangles);
  REQUIRE(d.positions.size() == n);
  float worstXY = 0.0f, worstZ = 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    worstXY = std::max(
        {worstXY, std::fabs(d.positions[i].x - m.positions[i].x), std::fabs(d.positions[i].y - m.positions[i].y)});
    worstZ = std::max(worstZ, std::fabs(d.positions[i].z - m.positions[i].z));
  }
  CHECK(worstXY <= 10.0f / 65535.0f);
  CHECK(worstZ <= 9.0f / 65535.0f);
  REQUIRE(d.farPositions.size() == 4);
  CHECK(d.farPositions[2].z == 9.0f);
  // Encoding the decoded tile again gives the same bytes (quantization is idempotent).
  CHECK(encodeCityTile(*decoded) == encodeCityTile(t));
}

TEST_CASE("Tiles without meshes have no MESH section and readers skip unknown sections", "[format][tile][mesh]") {
  const auto plain = encodeCityTile(tileWithoutMesh());
  CHECK(plain[44] == 6);  // section count: no MESH
  const auto decoded = decodeCityTile(plain, "plain");
  REQUIRE(decoded.ok());
  CHECK(decoded->meshes.empty());
}

TEST_CASE("Corrupt and truncated MESH sections are rejected with a specific message", "[format][tile][mesh]") {
  const std::vector<std::uint8_t> good = encodeCityTile(tinyMeshTile());
  const std::size_t mesh = meshOffset(good);
  REQUIRE(mesh == 228);
  const std::size_t record = mesh + 4;
  const std::size_t vertices = record + 44;
  const std::size_t triangles = vertices + 4 * 6;
  const std::size_t farTriangles = triangles + 24 + 18;
  auto messageFor = [](std::vector<std::uint8_t> bytes) {
    fixCrc(bytes);
    const auto r = decodeCityTile(bytes, "tiles/3-1-2.qvt");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("tiles/3-1-2.qvt: section MESH", 0) == 0);
    return r.error();
  };
  auto setU32 = [](std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v) {
    for (std::size_t i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
  };

  SECTION("an absurd model count is refused before allocating") {
    auto bad = good;
    setU32(bad, mesh, 0xFFFFFFFFu);
    CHECK(messageFor(bad) == "tiles/3-1-2.qvt: section MESH at byte 228: 4294967295 models exceeds the limit of 65536");
  }
  SECTION("more model records than bytes") {
    auto bad = good;
    setU32(bad, mesh, 3);
    CHECK(messageFor(bad) ==
          "tiles/3-1-2.qvt: section MESH at byte 228: 3 models need 132 bytes of records, the section holds 116");
  }
  SECTION("a vertex count beyond the bytes present") {
    auto bad = good;
    setU32(bad, record + 8, 1000);
    const std::string message = messageFor(bad);
    INFO(message);
    CHECK(message.find("section MESH at byte 276: the models declare 6048 bytes of vertices and "
                       "triangles, the section holds 72") != std::string::npos);
  }
  SECTION("a vertex count beyond the limits") {
    auto bad = good;
    setU32(bad, record + 8, 0xFFFFFFF0u);
    CHECK(messageFor(bad).find("section MESH at byte 232: the models declare 4294967283 vertices") !=
          std::string::npos);
  }
  SECTION("a section cut short (the table says fewer bytes)") {
    auto bad = good;
    setU32(bad, 48 + 6 * 12 + 8, 92);  // MESH size 120 -> 92
    CHECK(messageFor(bad).find("section MESH at byte 276: the models declare 72 bytes of vertices and triangles, "
                               "the section holds 44") != std::string::npos);
  }
  SECTION("a building index beyond BLDG") {
    auto bad = good;
    setU32(bad, record, 1);
    CHECK(messageFor(bad) == "tiles/3-1-2.qvt: section MESH at byte 232: model 0 names building 1 of 1");
  }
  SECTION("storeys other than the building's") {
    auto bad = good;
    bad[record + 6] = 5;
    CHECK(messageFor(bad) ==
          "tiles/3-1-2.qvt: section MESH at byte 232: model 0 has 5 storeys, its building 4 (at most 255)");
  }
  SECTION("a NaN top") {
    auto bad = good;
    setU32(bad, record + 40, 0x7FC00000u);
    CHECK(messageFor(bad).find("section MESH at byte 232: model 0: top nan m is outside [0.01, 10000] m") !=
          std::string::npos);
  }
  SECTION("a denormal top") {
    auto bad = good;
    setU32(bad, record + 40, 0x00404000u);
    CHECK(messageFor(bad).find("model 0: top 0.000000 m is outside [0.01, 10000] m") != std::string::npos);
  }
  SECTION("a triangle index beyond the vertices") {
    auto bad = good;
    bad[triangles + 2] = 4;
    CHECK(messageFor(bad) ==
          "tiles/3-1-2.qvt: section MESH at byte 302: model 0: triangle index 4 beyond its 4 vertices");
  }
  SECTION("a far triangle index beyond the far vertices") {
    auto bad = good;
    bad[farTriangles + 4] = 3;
    CHECK(messageFor(bad) ==
          "tiles/3-1-2.qvt: section MESH at byte 346: model 0: far triangle index 3 beyond its 3 far vertices");
  }
  SECTION("too many far vertices for u16 indices") {
    auto bad = good;
    setU32(bad, record + 28, 70000);
    CHECK(messageFor(bad) == "tiles/3-1-2.qvt: section MESH at byte 232: model 0: 70000 far vertices (at most 65535)");
  }
  SECTION("the whole section truncated") {
    auto bad = good;
    setU32(bad, 48 + 6 * 12 + 8, 2);
    CHECK(messageFor(bad).find("section MESH: ") != std::string::npos);
  }
}

TEST_CASE("Meshes of two models must name increasing buildings", "[format][tile][mesh]") {
  CityTile t = tinyMeshTile();
  t.meshes.push_back(t.meshes[0]);
  const auto r = decodeCityTile(encodeCityTile(t), "tiles/0-0-0.qvt");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error() == "tiles/0-0-0.qvt: section MESH at byte 276: model 1: building indices are not increasing");
}

TEST_CASE("MESH indices are u16 up to 65535 vertices and u32 beyond", "[format][tile][mesh]") {
  struct Case {
    std::uint32_t vertices;
    std::size_t sectionBytes;
    std::string indexBytes;
  };
  // 4-byte count + 44-byte record + 6 bytes per vertex padded to 4, then one triangle (last, 0,
  // 1): three u16 and 2 bytes of padding, or three u32.
  const Case cases[] = {{65535, 4 + 44 + 65535 * 6 + 2 + 8, "feff000001000000"},
                        {65536, 4 + 44 + 65536 * 6 + 12, "ffff00000000000001000000"}};
  for (const Case& c : cases) {
    CityTile t = tileWithoutMesh();
    TileMesh m;
    m.storeys = 4;
    m.topM = 12.0f;
    m.positions.assign(c.vertices, glm::vec3(1.0f, 2.0f, 3.0f));
    m.triangles = {c.vertices - 1, 0, 1};
    m.trianglesPerKind = {1, 0, 0, 0};
    t.meshes = {m};
    const auto bytes = encodeCityTile(t);
    const std::size_t mesh = meshOffset(bytes);
    CHECK(readU32(bytes, 48 + 6 * 12 + 8) == c.sectionBytes);
    const std::size_t indices = mesh + 4 + 44 + (std::size_t{c.vertices} * 6 + 3) / 4 * 4;
    CHECK(hex(std::vector<std::uint8_t>(
              bytes.begin() + static_cast<std::ptrdiff_t>(indices),
              bytes.begin() + static_cast<std::ptrdiff_t>(indices + c.indexBytes.size() / 2))) == c.indexBytes);
    const auto decoded = decodeCityTile(bytes, "wide");
    REQUIRE(decoded.ok());
    CHECK(decoded->meshes[0].triangles == m.triangles);
  }
}
