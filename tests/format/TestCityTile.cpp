#include <catch2/catch.hpp>

#include <limits>
#include <string>

#include "qv/core/Crc32.h"
#include "qv/format/CityTile.h"

using namespace qv;

namespace {

// The smallest interesting tile: one building with one triangular part.
CityTile tinyTile() {
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
  p.minHeightM = 0.0f;
  p.heightM = 12.0f;
  t.parts = {p};
  TileBuilding b;
  b.partCount = 1;
  b.attributes.id = "s1";
  b.attributes.use = "office";
  b.attributes.heightM = 12.0f;
  b.attributes.storeys = 4;
  b.attributes.heightSource = ValueSource::Tagged;
  b.attributes.structuralType = StructuralType::C1M;
  b.attributes.codeEra = CodeEra::ModerateCode;
  b.attributes.footprintAreaM2 = 50.0f;
  b.attributes.centroidX = 3.25;
  b.attributes.centroidY = 3.25;
  t.buildings = {b};
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

}  // namespace

TEST_CASE("City tile format version 2 is pinned by golden bytes", "[format][tile]") {
  // Every field checked by hand against docs/formats.md ("City tile"). Without a MESH section a
  // version 2 tile differs from version 1 in the version field only (the CRC starts at byte 16).
  const std::string golden =
      "51564354"
      "0200"
      "0000"
      "dc000000"
      "af959a75"  // "QVCT", version 2, flags 0, 220 bytes, CRC-32
      "01000000"
      "01000000"  // 1 building, 1 part
      "0000000000005940"
      "0000000000006940"  // origin (100.0, 200.0) float64
      "00002041"
      "0600"
      "0000"  // extent 10.0f, 6 sections, reserved
      "424c4447"
      "78000000"
      "28000000"  // BLDG at 120, 40 bytes
      "50415254"
      "a0000000"
      "14000000"  // PART at 160, 20 bytes
      "52494e47"
      "b4000000"
      "02000000"  // RING at 180, 2 bytes
      "56455254"
      "b8000000"
      "0c000000"  // VERT at 184, 12 bytes
      "54524953"
      "c4000000"
      "06000000"  // TRIS at 196, 6 bytes
      "53545253"
      "cc000000"
      "0f000000"  // STRS at 204, 15 bytes
      // BLDG: 1 part, flags (height tagged), height 12.0f, min height 0, 4 storeys, year 0,
      // C1M (10), moderate code (3), general, no reasons, LOD 1, reserved, area 50.0f,
      // centroid (3.25f, 3.25f), reserved
      "0100"
      "0100"
      "00004041"
      "00000000"
      "0400"
      "0000"
      "0a"
      "03"
      "00"
      "00"
      "01"
      "00"
      "0000"
      "00004842"
      "00005040"
      "00005040"
      "00000000"
      // PART: 1 ring, flat roof, reserved, 1 triangle, min 0, height 12.0f, roof height 0
      "0100"
      "00"
      "00"
      "01000000"
      "00000000"
      "00004041"
      "00000000"
      "0300"
      "0000"  // RING: 3 vertices, padding
      "00000000"
      "ffff0000"
      "0000ffff"  // VERT: (0,0) (65535,0) (0,65535)
      "0000"
      "0100"
      "0200"
      "0000"  // TRIS: 0 1 2, padding
      "02"
      "7331"
      "00"
      "06"
      "6f6666696365"
      "00"
      "00"
      "00"
      "00"
      "00";  // STRS: "s1" "" "office" "" "" "" "", pad
  CHECK(hex(encodeCityTile(tinyTile())) == golden);
  const auto decoded = decodeCityTile(encodeCityTile(tinyTile()), "golden");
  REQUIRE(decoded.ok());
  CHECK(decoded->buildings[0].attributes.use == "office");

  SECTION("the same tile written as version 1 is still read") {
    std::vector<std::uint8_t> version1 = encodeCityTile(tinyTile());
    version1[4] = 1;
    const auto old = decodeCityTile(version1, "version 1");
    REQUIRE(old.ok());
    CHECK(old->buildings[0].attributes.use == "office");
    CHECK(old->vertices == decoded->vertices);
  }
}

TEST_CASE("City tiles round-trip through the codec", "[format][tile]") {
  CityTile t = tinyTile();
  // A second building with a hole and two parts to exercise the ranges.
  t.vertices.insert(t.vertices.end(),
                    {{1, 1}, {9, 1}, {9, 9}, {1, 9}, {3, 3}, {3, 7}, {7, 7}, {7, 3}, {2, 2}, {4, 2}, {3, 4}});
  t.ringVertexCounts.insert(t.ringVertexCounts.end(), {4, 4, 3});
  t.roofTriangles.insert(t.roofTriangles.end(), {0, 1, 7, 0, 7, 4, 0, 1, 2});
  TilePart courtyard;
  courtyard.ringCount = 2;
  courtyard.triangleCount = 2;
  courtyard.heightM = 20.0f;
  courtyard.roofShape = RoofShape::Hipped;
  TilePart top;
  top.ringCount = 1;
  top.triangleCount = 1;
  top.minHeightM = 20.0f;
  top.heightM = 35.5f;
  t.parts.push_back(courtyard);
  t.parts.push_back(top);
  TileBuilding b;
  b.partCount = 2;
  b.attributes.id = "r2098969";
  b.attributes.name = "Tower \"A\" — ünïcode";
  b.attributes.address = "350 5th Avenue, 10118 New York";
  b.attributes.heightM = 35.5f;
  b.attributes.storeys = 9;
  b.attributes.storeysSource = ValueSource::Tagged;
  b.attributes.startYear = 1931;
  b.attributes.importance = Importance::Critical;
  b.attributes.importanceReasons = kReasonTall | kReasonComplex;
  b.attributes.lod = 2;
  b.attributes.notes = kNoteStoreysFromNave | kNotePreFrameMasonry;
  b.attributes.occupants = 1234;
  b.attributes.replacementValueUsd = 2.5e7f;
  t.buildings.push_back(b);

  const auto bytes = encodeCityTile(t);
  const Result<CityTile> decoded = decodeCityTile(bytes, "round-trip");
  REQUIRE(decoded.ok());
  const CityTile& d = *decoded;
  CHECK(d.originX == 100.0);
  CHECK(d.originY == 200.0);
  REQUIRE(d.vertices.size() == t.vertices.size());
  for (std::size_t i = 0; i < d.vertices.size(); ++i) {
    CHECK(d.vertices[i].x == Approx(t.vertices[i].x).margin(10.0 / 65535));
    CHECK(d.vertices[i].y == Approx(t.vertices[i].y).margin(10.0 / 65535));
  }
  CHECK(d.ringVertexCounts == t.ringVertexCounts);
  CHECK(d.roofTriangles == t.roofTriangles);
  REQUIRE(d.parts.size() == 3);
  CHECK(d.parts[1].firstVertex == 3);
  CHECK(d.parts[1].vertexCount == 8);
  CHECK(d.parts[1].firstRing == 1);
  CHECK(d.parts[1].roofShape == RoofShape::Hipped);
  CHECK(d.parts[2].firstVertex == 11);
  CHECK(d.parts[2].firstTriangle == 3);
  CHECK(d.parts[2].minHeightM == 20.0f);
  REQUIRE(d.buildings.size() == 2);
  const BuildingAttributes& a = d.buildings[1].attributes;
  CHECK(d.buildings[1].firstPart == 1);
  CHECK(d.buildings[1].partCount == 2);
  CHECK(a.id == "r2098969");
  CHECK(a.name == b.attributes.name);
  CHECK(a.address == "350 5th Avenue, 10118 New York");
  CHECK(a.startYear == 1931);
  CHECK(a.storeysSource == ValueSource::Tagged);
  CHECK(a.heightSource == ValueSource::Inferred);
  CHECK(a.importanceReasons == (kReasonTall | kReasonComplex));
  CHECK(a.lod == 2);
  // The attribute notes (docs/formats.md, BLDG byte 21): why values were inferred.
  CHECK(a.notes == (kNoteStoreysFromNave | kNotePreFrameMasonry));
  CHECK(a.occupants == 1234);  // given by the data (0: not given, in older tiles too)
  CHECK(a.replacementValueUsd == 2.5e7f);
  CHECK(d.buildings[0].attributes.notes == kNoteNone);
  CHECK(attributeNoteNames(a.notes) == std::vector<std::string_view>{"storeys-from-nave", "pre-frame-masonry"});
  CHECK(d.buildings[0].attributes.structuralType == StructuralType::C1M);
  CHECK(d.buildings[0].attributes.centroidX == 3.25);
}

TEST_CASE("Corrupt, truncated and wrong-version tiles are rejected with a specific message", "[format][tile]") {
  const std::vector<std::uint8_t> good = encodeCityTile(tinyTile());
  auto messageFor = [](const std::vector<std::uint8_t>& bytes) {
    const auto r = decodeCityTile(bytes, "tiles/3-1-2.qvt");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("tiles/3-1-2.qvt: ", 0) == 0);
    return r.error();
  };

  SECTION("truncated") {
    std::vector<std::uint8_t> cut(good.begin(), good.begin() + 100);
    CHECK(messageFor(cut).find("truncated or padded: the header says 220 bytes, the file has 100") !=
          std::string::npos);
    std::vector<std::uint8_t> tiny(good.begin(), good.begin() + 10);
    CHECK(messageFor(tiny).find("shorter than the 48-byte header") != std::string::npos);
  }
  SECTION("a flipped bit fails the checksum") {
    auto bad = good;
    bad[150] ^= 0x10;
    CHECK(messageFor(bad).find("checksum mismatch") != std::string::npos);
  }
  SECTION("wrong magic") {
    auto bad = good;
    bad[0] = 'X';
    CHECK(messageFor(bad).find("does not start with \"QVCT\"") != std::string::npos);
  }
  SECTION("another version") {
    auto bad = good;
    bad[4] = 3;
    CHECK(messageFor(bad).find("unsupported city tile version 3 (this build reads versions 1 to 2)") !=
          std::string::npos);
    bad[4] = 0;
    CHECK(messageFor(bad).find("unsupported city tile version 0 (this build reads versions 1 to 2)") !=
          std::string::npos);
  }
  SECTION("counts that do not match the sections, with a valid checksum") {
    auto bad = good;
    bad[16] = 0xFF;  // building count 255
    const std::uint32_t crc = crc32(std::span(bad).subspan(16));
    for (std::size_t i = 0; i < 4; ++i) bad[12 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    CHECK(messageFor(bad).find("section BLDG at byte 120 holds 40 bytes, expected 255 records") != std::string::npos);
  }
  SECTION("an absurd count is refused before allocating") {
    auto bad = good;
    bad[16] = 0xFF;
    bad[17] = 0xFF;
    bad[18] = 0xFF;
    bad[19] = 0xFF;
    const std::uint32_t crc = crc32(std::span(bad).subspan(16));
    for (std::size_t i = 0; i < 4; ++i) bad[12 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    CHECK(messageFor(bad).find("4294967295 buildings exceeds the limit") != std::string::npos);
  }
  SECTION("a triangle index beyond its part") {
    auto bad = good;
    bad[196 + 4] = 9;  // third index of the roof triangle
    const std::uint32_t crc = crc32(std::span(bad).subspan(16));
    for (std::size_t i = 0; i < 4; ++i) bad[12 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    CHECK(messageFor(bad).find("triangle index 9 beyond its part's 3 vertices") != std::string::npos);
  }
}

TEST_CASE("Values outside their ranges are refused, NaN included", "[format][tile]") {
  struct Case {
    const char* what;
    void (*change)(CityTile&);
    const char* message;
  };
  const Case cases[] = {
      {"denormal extent", [](CityTile& t) { t.extent = 1.0e-38f; }, "header at byte 40: extent"},
      {"huge extent", [](CityTile& t) { t.extent = 1.0e9f; }, "header at byte 40: extent"},
      {"origin far away", [](CityTile& t) { t.originX = 2.0e7; }, "header at byte 24: invalid origin"},
      {"NaN roof height", [](CityTile& t) { t.parts[0].roofHeightM = std::numeric_limits<float>::quiet_NaN(); },
       "section PART near byte"},
      {"negative roof height", [](CityTile& t) { t.parts[0].roofHeightM = -1.0f; }, "invalid part heights"},
      {"NaN building height",
       [](CityTile& t) { t.buildings[0].attributes.heightM = std::numeric_limits<float>::quiet_NaN(); },
       "invalid building"},
      {"building above 10 km", [](CityTile& t) { t.buildings[0].attributes.heightM = 20000.0f; }, "invalid building"},
      {"negative footprint", [](CityTile& t) { t.buildings[0].attributes.footprintAreaM2 = -1.0f; },
       "invalid building"},
  };
  for (const Case& c : cases) {
    SECTION(c.what) {
      CityTile t = tinyTile();
      c.change(t);
      const auto r = decodeCityTile(encodeCityTile(t), "tiles/0-0-0.qvt");
      REQUIRE_FALSE(r.ok());
      CHECK(r.error().rfind("tiles/0-0-0.qvt: ", 0) == 0);
      CHECK(r.error().find(c.message) != std::string::npos);
    }
  }
}
