// Ground tiles (.qvg, docs/formats.md "Ground tile"): golden bytes of version 1, round trips of
// both index widths and of UTF-8 names, every refusal with its message, and truncation and
// corruption at every byte ending in a clean error or a tile that re-encodes to the same bytes.
#include <zstd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "../fuzz/FuzzInputs.h"
#include "qv/format/GroundTile.h"

using namespace qv;

namespace {

constexpr const char* kName = "ground/3-1-2.qvg";
const float kHalfPi = static_cast<float>(std::numbers::pi / 2.0);

// The smallest tile with every section: one street triangle and its name.
GroundTile tinyTile() {
  GroundTile t;
  t.originX = 100.0;
  t.originY = 200.0;
  t.extent = 10.0f;
  t.vertices = {{0.0f, 0.0f}, {10.0f, 0.0f}, {0.0f, 10.0f}};
  t.triangles = {0, 1, 2};
  t.runs = {{GroundClass::Street, 0, 1}};
  GroundLabel label;
  label.kind = GroundLabelKind::Street;
  label.rank = 5;
  label.position = {2.5f, 7.5f};
  label.angleRad = 0.5f;
  label.lengthM = 8.0f;
  label.text = "Elm";
  t.labels = {label};
  return t;
}

GroundLabel label(GroundLabelKind kind, std::uint8_t rank, glm::vec2 position, float angleRad, float lengthM,
                  std::string text) {
  GroundLabel l;
  l.kind = kind;
  l.rank = rank;
  l.position = position;
  l.angleRad = angleRad;
  l.lengthM = lengthM;
  l.text = std::move(text);
  return l;
}

// A park (two triangles), a river, a street, and names in several scripts.
GroundTile sampleTile() {
  GroundTile t;
  t.originX = 1200.0;
  t.originY = -600.0;
  t.extent = 600.0f;
  t.vertices = {{0.0f, 0.0f},     {300.0f, 0.0f},  {300.0f, 250.0f}, {0.0f, 250.0f},   {400.0f, 10.0f},
                {590.5f, 10.25f}, {400.0f, 30.0f}, {10.0f, 500.0f},  {599.9f, 510.0f}, {10.0f, 520.0f}};
  t.triangles = {0, 1, 2, 0, 2, 3, 4, 5, 6, 7, 8, 9};
  t.runs = {{GroundClass::Park, 0, 2}, {GroundClass::Water, 2, 1}, {GroundClass::Street, 3, 1}};
  t.labels = {label(GroundLabelKind::Settlement, 0, {300.0f, 300.0f}, 0.0f, 0.0f, "東京"),
              label(GroundLabelKind::Street, 40, {305.0f, 515.0f}, kHalfPi, 580.0f, "Avenue of the Americas"),
              label(GroundLabelKind::Street, 90, {305.0f, 505.0f}, -0.3f, 120.5f, "Straße"),
              label(GroundLabelKind::Park, 120, {150.0f, 125.0f}, 0.0f, 0.0f, "Jardin du Luxembourg"),
              label(GroundLabelKind::Water, 200, {500.0f, 20.0f}, 1.0f, 0.0f, "Ėlbe – ąžuolas")};
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

/// `bytes` with `values` written at `offset`, size and checksum made right again.
std::vector<std::uint8_t> patched(std::vector<std::uint8_t> bytes, std::size_t offset,
                                  const std::vector<std::uint8_t>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) bytes.at(offset + i) = values[i];
  return fuzz::withValidSizeAndCrc(bytes);
}

std::vector<std::uint8_t> le32(std::uint32_t v) {
  return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v >> 16),
          static_cast<std::uint8_t>(v >> 24)};
}

std::vector<std::uint8_t> f32(float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return le32(bits);
}

std::vector<std::uint8_t> f64(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  auto out = le32(static_cast<std::uint32_t>(bits));
  const auto high = le32(static_cast<std::uint32_t>(bits >> 32));
  out.insert(out.end(), high.begin(), high.end());
  return out;
}

/// The error of decoding `bytes`, which must fail and name the file.
std::string errorOf(const std::vector<std::uint8_t>& bytes, const GroundTileLimits& limits = {}) {
  const auto r = decodeGroundTile(bytes, kName, limits);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().rfind(std::string(kName) + ": ", 0) == 0);
  return r.error();
}

std::string errorOf(const GroundTile& tile) {
  return errorOf(encodeGroundTile(tile));
}

std::vector<std::uint8_t> frameOf(const std::vector<std::uint8_t>& bytes) {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, 6);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
  std::vector<std::uint8_t> out(ZSTD_compressBound(bytes.size()) + 64);
  const std::size_t n = ZSTD_compress2(cctx, out.data(), out.size(), bytes.data(), bytes.size());
  ZSTD_freeCCtx(cctx);
  REQUIRE_FALSE(ZSTD_isError(n));
  out.resize(n);
  return out;
}

void checkSameTile(const GroundTile& in, const GroundTile& out) {
  const float step = in.extent / 65535.0f;
  CHECK(out.originX == in.originX);
  CHECK(out.originY == in.originY);
  CHECK(out.extent == in.extent);
  REQUIRE(out.vertices.size() == in.vertices.size());
  for (std::size_t i = 0; i < in.vertices.size(); ++i) {
    CHECK(out.vertices[i].x == Approx(in.vertices[i].x).margin(step));
    CHECK(out.vertices[i].y == Approx(in.vertices[i].y).margin(step));
  }
  CHECK(out.triangles == in.triangles);
  REQUIRE(out.runs.size() == in.runs.size());
  for (std::size_t i = 0; i < in.runs.size(); ++i) {
    CHECK(out.runs[i].groundClass == in.runs[i].groundClass);
    CHECK(out.runs[i].firstTriangle == in.runs[i].firstTriangle);
    CHECK(out.runs[i].triangleCount == in.runs[i].triangleCount);
  }
  REQUIRE(out.labels.size() == in.labels.size());
  for (std::size_t i = 0; i < in.labels.size(); ++i) {
    const GroundLabel& a = in.labels[i];
    const GroundLabel& b = out.labels[i];
    CHECK(b.kind == a.kind);
    CHECK(b.rank == a.rank);
    CHECK(b.position.x == Approx(a.position.x).margin(step));
    CHECK(b.position.y == Approx(a.position.y).margin(step));
    CHECK(b.angleRad == a.angleRad);
    CHECK(b.lengthM == a.lengthM);
    CHECK(b.text == a.text);
  }
}

}  // namespace

TEST_CASE("Ground tile format version 1 is pinned by golden bytes", "[format][ground]") {
  // Every field checked by hand against docs/formats.md ("Ground tile").
  const std::string golden =
      "51564754"
      "0100"
      "0000"
      "9c000000"
      "75add526"  // "QVGT", version 1, flags 0 (u16 indices), 156 bytes, CRC-32
      "03000000"
      "01000000"
      "01000000"  // 3 vertices, 1 triangle, 1 label
      "0100"
      "0400"  // 1 run, 4 sections
      "0000000000005940"
      "0000000000006940"  // origin (100.0, 200.0) float64
      "00002041"
      "00000000"  // extent 10.0f, reserved
      "56455254"
      "68000000"
      "0c000000"  // VERT at 104, 12 bytes
      "54524953"
      "74000000"
      "06000000"  // TRIS at 116, 6 bytes
      "52554e53"
      "7c000000"
      "09000000"  // RUNS at 124, 9 bytes
      "4c41424c"
      "88000000"
      "12000000"  // LABL at 136, 18 bytes
      "00000000"
      "ffff0000"
      "0000ffff"  // VERT: (0,0) (65535,0) (0,65535)
      "0000"
      "0100"
      "0200"
      "0000"  // TRIS: 0 1 2, padding
      "07"
      "00000000"
      "01000000"
      "000000"  // RUNS: street, first triangle 0, 1 triangle, padding
      "00"
      "05"
      "0040"
      "ffbf"      // LABL: street, rank 5, position (16384, 49151) = (2.5, 7.5) m
      "0000003f"  // angle 0.5f rad
      "00000041"  // length 8.0f m
      "03"
      "456c6d"
      "0000";  // "Elm", padding
  const std::vector<std::uint8_t> bytes = encodeGroundTile(tinyTile());
  CHECK(hex(bytes) == golden);
  const auto decoded = decodeGroundTile(bytes, "golden");
  REQUIRE(decoded.ok());
  checkSameTile(tinyTile(), *decoded);
  CHECK(decoded->labels[0].position == glm::vec2(16384.0f * (10.0f / 65535.0f), 49151.0f * (10.0f / 65535.0f)));
}

TEST_CASE("Ground tiles round-trip through the codec with 16-bit indices and UTF-8 names", "[format][ground]") {
  const GroundTile t = sampleTile();
  const std::vector<std::uint8_t> bytes = encodeGroundTile(t);
  CHECK((bytes[6] | bytes[7]) == 0);  // no flag: 16-bit indices
  const auto decoded = decodeGroundTile(bytes, kName);
  INFO((decoded.ok() ? std::string() : decoded.error()));
  REQUIRE(decoded.ok());
  checkSameTile(t, *decoded);
  CHECK(decoded->labels[2].text == "Straße");
  CHECK(decoded->labels[1].text == "Avenue of the Americas");
  CHECK(decoded->labels[1].angleRad == kHalfPi);  // the upper end of (-pi/2, pi/2] is kept
  // A decoded tile is written back byte for byte.
  CHECK(encodeGroundTile(*decoded) == bytes);

  SECTION("from its stored form, a Zstandard frame") {
    const auto stored = decodeGroundTile(frameOf(bytes), kName);
    REQUIRE(stored.ok());
    CHECK(encodeGroundTile(*stored) == bytes);
  }
  SECTION("a tile with nothing in it") {
    GroundTile empty;
    empty.extent = 25.0f;
    const auto e = decodeGroundTile(encodeGroundTile(empty), kName);
    REQUIRE(e.ok());
    CHECK(e->vertices.empty());
    CHECK(e->triangles.empty());
    CHECK(e->runs.empty());
    CHECK(e->labels.empty());
    CHECK(e->extent == 25.0f);
  }
  SECTION("labels only, and empty runs") {
    GroundTile named;
    named.extent = 100.0f;
    named.runs = {{GroundClass::Land, 0, 0}, {GroundClass::Motorway, 0, 0}};
    named.labels = {label(GroundLabelKind::Neighbourhood, 3, {50.0f, 50.0f}, 0.0f, 0.0f, "Hell's Kitchen")};
    const auto n = decodeGroundTile(encodeGroundTile(named), kName);
    REQUIRE(n.ok());
    checkSameTile(named, *n);
  }
}

TEST_CASE("Ground tiles with more than 65535 vertices use 32-bit indices", "[format][ground]") {
  for (const std::uint32_t vertexCount : {65535u, 65536u, 70000u}) {
    GroundTile t;
    t.originX = -5000.0;
    t.originY = 12000.5;
    t.extent = 2400.0f;
    t.vertices.resize(vertexCount);
    for (std::uint32_t i = 0; i < vertexCount; ++i) {
      t.vertices[i] = {static_cast<float>(i % 1000) * 2.4f, static_cast<float>(i / 1000) * 2.4f};
    }
    t.triangles = {0, vertexCount - 1, vertexCount / 2, 1, 2, vertexCount - 2};
    t.runs = {{GroundClass::Green, 0, 1}, {GroundClass::Rail, 1, 1}};
    const std::vector<std::uint8_t> bytes = encodeGroundTile(t);
    const bool wide = vertexCount > 65535;
    INFO(vertexCount);
    CHECK(bytes[6] == (wide ? 1 : 0));
    // TRIS holds 6 indices of 4 or 2 bytes (its size is in the third section table entry).
    CHECK(bytes[68 + 8] == (wide ? 24 : 12));
    const auto decoded = decodeGroundTile(bytes, kName);
    REQUIRE(decoded.ok());
    CHECK(decoded->triangles == t.triangles);
    REQUIRE(decoded->vertices.size() == vertexCount);
    const float step = t.extent / 65535.0f;
    for (const std::uint32_t i : {0u, 1u, vertexCount / 2, vertexCount - 1}) {
      CHECK(decoded->vertices[i].x == Approx(t.vertices[i].x).margin(step));
      CHECK(decoded->vertices[i].y == Approx(t.vertices[i].y).margin(step));
    }
    CHECK(encodeGroundTile(*decoded) == bytes);
  }
}

TEST_CASE("The ground tile encoder clamps vertices to the cell and clips long names", "[format][ground]") {
  GroundTile t = tinyTile();
  t.vertices = {{-3.0f, 12.0f}, {std::numeric_limits<float>::quiet_NaN(), 5.0f}, {10.0f, 10.0f}};
  std::string longName;
  while (longName.size() < 300) longName += "ß";  // 2 bytes each: 254 bytes fit whole characters
  t.labels[0].text = longName;
  const auto decoded = decodeGroundTile(encodeGroundTile(t), kName);
  REQUIRE(decoded.ok());
  CHECK(decoded->vertices[0].x == 0.0f);
  CHECK(decoded->vertices[0].y == Approx(10.0f));
  CHECK(decoded->vertices[1].x == 0.0f);
  CHECK(decoded->labels[0].text == longName.substr(0, 254));

  t.labels[0].text = std::string(255, 'a');  // the longest name fits exactly
  const auto longest = decodeGroundTile(encodeGroundTile(t), kName);
  REQUIRE(longest.ok());
  CHECK(longest->labels[0].text.size() == 255);
}

TEST_CASE("Ground class and label kind names", "[format][ground]") {
  const char* classes[] = {"land", "green", "forest", "park", "water", "path", "rail", "street", "major", "motorway"};
  for (std::uint8_t c = 0; c < static_cast<std::uint8_t>(GroundClass::Count); ++c) {
    CHECK(groundClassName(static_cast<GroundClass>(c)) == classes[c]);
  }
  CHECK(groundClassName(GroundClass::Count) == "unknown");
  const char* kinds[] = {"street", "water", "park", "neighbourhood", "settlement"};
  for (std::uint8_t k = 0; k < static_cast<std::uint8_t>(GroundLabelKind::Count); ++k) {
    CHECK(groundLabelKindName(static_cast<GroundLabelKind>(k)) == kinds[k]);
  }
  CHECK(groundLabelKindName(GroundLabelKind::Count) == "unknown");
}

TEST_CASE("Ground tile headers and section tables that are not version 1's are refused", "[format][ground]") {
  const std::vector<std::uint8_t> good = encodeGroundTile(tinyTile());
  REQUIRE(good.size() == 156);
  struct Case {
    const char* what;
    std::vector<std::uint8_t> bytes;
    const char* message;
  };
  std::vector<std::uint8_t> shortFile(good.begin(), good.begin() + 20);
  std::vector<std::uint8_t> longer = good;
  longer.push_back(0);
  std::vector<std::uint8_t> flipped = good;
  flipped[120] ^= 0x10;
  std::vector<std::uint8_t> badMagic = good;
  badMagic[2] = 'C';
  std::vector<std::uint8_t> trailing = good;
  trailing.insert(trailing.end(), 4, 0);
  const std::vector<std::uint8_t> lastByteCut(good.begin(), good.end() - 1);
  const Case cases[] = {
      {"shorter than the header", shortFile, "not a ground tile: 20 bytes is shorter than the 56-byte header"},
      {"another magic", badMagic, "not a ground tile: the file does not start with \"QVGT\""},
      {"another version", patched(good, 4, {2, 0}), "unsupported ground tile version 2 (this build reads version 1)"},
      {"version 0", patched(good, 4, {0, 0}), "unsupported ground tile version 0"},
      {"a byte more", longer, "truncated or padded: the header says 156 bytes, the file has 157"},
      {"a flipped bit", flipped, "checksum mismatch"},
      {"an unknown flag", patched(good, 6, {2, 0}), "header at byte 6: unknown flags 0x0002"},
      {"an unknown high flag", patched(good, 6, {1, 0x80}), "header at byte 6: unknown flags 0x8000"},
      {"wide indices for 3 vertices", patched(good, 6, {1, 0}),
       "header at byte 6: the wide-index flag is set for 3 vertices"},
      {"absurd vertex count with 16-bit indices", patched(good, 16, le32(0xFFFFFFFFu)),
       "the wide-index flag is clear for 4294967295 vertices"},
      {"absurd vertex count", patched(patched(good, 16, le32(0xFFFFFFFFu)), 6, {1, 0}),
       "header at byte 16: 4294967295 vertices exceeds the limit of 4194304"},
      {"absurd triangle count", patched(good, 20, le32(0xFFFFFFFFu)),
       "header at byte 20: 4294967295 triangles exceeds the limit of 4194304"},
      {"absurd label count", patched(good, 24, le32(0x10001u)),
       "header at byte 24: 65537 labels exceeds the limit of 65536"},
      {"more runs than classes", patched(good, 28, {11, 0}), "header at byte 28: 11 runs, more than the 10 ground"},
      {"five sections", patched(good, 30, {5, 0}), "header at byte 30: 5 sections, a version 1 ground tile has 4"},
      {"origin beyond 1e7 m", patched(good, 32, f64(2.0e7)), "header at byte 32: origin (20000000"},
      {"origin NaN", patched(good, 40, f64(std::numeric_limits<double>::quiet_NaN())), "header at byte 32: origin"},
      {"origin infinite", patched(good, 32, f64(-std::numeric_limits<double>::infinity())),
       "header at byte 32: origin"},
      {"extent 0", patched(good, 48, f32(0.0f)), "header at byte 48: extent 0.000000 m is outside [1e-6, 1e8] m"},
      {"denormal extent", patched(good, 48, f32(1.0e-38f)), "header at byte 48: extent"},
      {"extent below a micrometre", patched(good, 48, f32(1.0e-7f)), "header at byte 48: extent"},
      {"extent beyond 1e8 m", patched(good, 48, f32(1.0e9f)), "header at byte 48: extent"},
      {"extent NaN", patched(good, 48, f32(std::numeric_limits<float>::quiet_NaN())), "header at byte 48: extent"},
      {"extent infinite", patched(good, 48, f32(std::numeric_limits<float>::infinity())), "header at byte 48: extent"},
      {"reserved not 0", patched(good, 52, {1}), "header at byte 52: reserved field is 1, not 0"},
      {"an unknown section", patched(good, 56, {'X'}),
       "section table at byte 56: section XERT where VERT belongs (a version 1 ground tile holds VERT, TRIS, RUNS, "
       "LABL in this order)"},
      {"sections swapped", patched(patched(good, 68, {'R', 'U', 'N', 'S'}), 80, {'T', 'R', 'I', 'S'}),
       "section table at byte 68: section RUNS where TRIS belongs"},
      {"a section elsewhere", patched(good, 72, le32(120)),
       "section table at byte 68: section TRIS at byte 120, expected at byte 116"},
      {"a section past the end", patched(good, 100, le32(1000)),
       "section LABL at byte 136 with 1000 bytes lies outside the file of 156 bytes"},
      {"VERT of another size", patched(good, 64, le32(8)),
       "section VERT at byte 104 holds 8 bytes, the header declares 3 vertices (12 bytes)"},
      {"TRIS of another size", patched(good, 76, le32(8)),
       "section TRIS at byte 116 holds 8 bytes, the header declares 1 triangles (6 bytes)"},
      {"RUNS of another size", patched(good, 88, le32(12)),
       "section RUNS at byte 124 holds 12 bytes, the header declares 1 runs (9 bytes)"},
      {"LABL too small for its labels", patched(good, 24, le32(2)),
       "section LABL at byte 136 holds 18 bytes, too few for the 2 labels"},
      {"padding not zero", patched(good, 122, {7}), "padding at byte 122 after TRIS is not 0"},
      {"padding at the end not zero", patched(good, 155, {1}), "padding at byte 155 after LABL is not 0"},
      {"LABL padding past the end", fuzz::withValidSizeAndCrc(lastByteCut),
       "section LABL at byte 136: its padding runs past the end of the file"},
      {"bytes after the last section", fuzz::withValidSizeAndCrc(trailing),
       "section LABL at byte 136: 4 bytes after the last section"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    CHECK_THAT(errorOf(c.bytes), Catch::Contains(c.message));
  }
}

TEST_CASE("Ground tile limits are the caller's", "[format][ground]") {
  const std::vector<std::uint8_t> good = encodeGroundTile(tinyTile());
  CHECK_THAT(errorOf(good, GroundTileLimits{2, 100, 100}), Catch::Contains("3 vertices exceeds the limit of 2"));
  CHECK_THAT(errorOf(good, GroundTileLimits{100, 0, 100}), Catch::Contains("1 triangles exceeds the limit of 0"));
  CHECK_THAT(errorOf(good, GroundTileLimits{100, 100, 0}), Catch::Contains("1 labels exceeds the limit of 0"));
  CHECK(decodeGroundTile(good, kName, GroundTileLimits{3, 1, 1}).ok());
}

TEST_CASE("Ground tile triangles and runs that break the contract are refused", "[format][ground]") {
  struct Case {
    const char* what;
    void (*change)(GroundTile&);
    const char* message;
  };
  const Case cases[] = {
      {"an index beyond the vertices", [](GroundTile& t) { t.triangles[2] = 3; },
       "section TRIS at byte 120: triangle index 3 beyond the 3 vertices"},
      {"an unknown class", [](GroundTile& t) { t.runs[0].groundClass = GroundClass::Count; },
       "section RUNS at byte 124: run 0: unknown ground class 10"},
      {"class 255", [](GroundTile& t) { t.runs[0].groundClass = static_cast<GroundClass>(255); },
       "run 0: unknown ground class 255"},
      {"a run that starts late", [](GroundTile& t) { t.runs[0].firstTriangle = 1; },
       "section RUNS at byte 124: run 0 starts at triangle 1, the runs before it end at 0"},
      {"a run beyond the triangles", [](GroundTile& t) { t.runs[0].triangleCount = 2; },
       "run 0 ends at triangle 2, beyond the 1 triangles"},
      {"a run of an absurd length", [](GroundTile& t) { t.runs[0].triangleCount = 0xFFFFFFFFu; },
       "run 0 ends at triangle 4294967295, beyond the 1 triangles"},
      {"runs that cover too little", [](GroundTile& t) { t.runs[0].triangleCount = 0; },
       "section RUNS at byte 124: the runs cover 0 of the 1 triangles"},
      {"no runs", [](GroundTile& t) { t.runs.clear(); }, "the runs cover 0 of the 1 triangles"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    GroundTile t = tinyTile();
    c.change(t);
    CHECK_THAT(errorOf(t), Catch::Contains(c.message));
  }

  // Two and three runs: order, uniqueness and continuity.
  GroundTile t = tinyTile();
  t.vertices.push_back({5.0f, 5.0f});
  t.triangles = {0, 1, 2, 1, 3, 2, 0, 3, 2};
  t.runs = {{GroundClass::Water, 0, 1}, {GroundClass::Path, 1, 1}, {GroundClass::Street, 2, 1}};
  REQUIRE(decodeGroundTile(encodeGroundTile(t), kName).ok());
  GroundTile swapped = t;
  std::swap(swapped.runs[1].groundClass, swapped.runs[2].groundClass);
  CHECK_THAT(errorOf(swapped), Catch::Contains("run 2: class path after street (runs are in increasing class order, "
                                               "each class once)"));
  GroundTile twice = t;
  twice.runs[1].groundClass = GroundClass::Water;
  CHECK_THAT(errorOf(twice), Catch::Contains("run 1: class water after water"));
  GroundTile gap = t;
  gap.runs[2].firstTriangle = 3;
  gap.runs[2].triangleCount = 0;
  CHECK_THAT(errorOf(gap), Catch::Contains("run 2 starts at triangle 3, the runs before it end at 2"));
  GroundTile overlap = t;
  overlap.runs[1].triangleCount = 2;
  CHECK_THAT(errorOf(overlap), Catch::Contains("run 2 starts at triangle 2, the runs before it end at 3"));
}

TEST_CASE("Ground labels that break the contract are refused", "[format][ground]") {
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  struct Case {
    const char* what;
    GroundLabel label;
    const char* message;
  };
  auto street = [](float angle, float length, std::string text) {
    return label(GroundLabelKind::Street, 1, {1.0f, 1.0f}, angle, length, std::move(text));
  };
  const Case cases[] = {
      {"an unknown kind", label(GroundLabelKind::Count, 1, {}, 0.0f, 0.0f, "x"),
       "section LABL at byte 136: label 0: unknown label kind 5"},
      {"kind 255", label(static_cast<GroundLabelKind>(255), 1, {}, 0.0f, 0.0f, "x"), "unknown label kind 255"},
      {"angle -pi/2", street(-kHalfPi, 0.0f, "x"), "section LABL at byte 136: label 0: angle -1.570796 rad is outside"},
      {"angle above pi/2", street(1.6f, 0.0f, "x"), "angle 1.600000 rad is outside (-pi/2, pi/2]"},
      {"angle just above pi/2", street(std::nextafter(kHalfPi, 2.0f), 0.0f, "x"), "rad is outside (-pi/2, pi/2]"},
      {"angle NaN", street(kNaN, 0.0f, "x"), "rad is outside (-pi/2, pi/2]"},
      {"angle infinite", street(-kInf, 0.0f, "x"), "rad is outside (-pi/2, pi/2]"},
      {"length negative", street(0.0f, -1.0f, "x"), "label 0: length -1.000000 m is outside [0, 1e8] m"},
      {"length NaN", street(0.0f, kNaN, "x"), "m is outside [0, 1e8] m"},
      {"length infinite", street(0.0f, kInf, "x"), "m is outside [0, 1e8] m"},
      {"empty text", street(0.0f, 0.0f, ""), "section LABL at byte 151: label 0: empty text"},
      {"a stray continuation byte", street(0.0f, 0.0f, "a\x80"), "label 0: text is not valid UTF-8"},
      {"a truncated sequence", street(0.0f, 0.0f, "Stra\xC3"), "text is not valid UTF-8"},
      {"an overlong slash", street(0.0f, 0.0f, "\xC0\xAF"), "text is not valid UTF-8"},
      {"a surrogate", street(0.0f, 0.0f, "\xED\xA0\x80"), "text is not valid UTF-8"},
      {"beyond U+10FFFF", street(0.0f, 0.0f, "\xF4\x90\x80\x80"), "text is not valid UTF-8"},
      {"byte FF", street(0.0f, 0.0f, "\xFF"), "text is not valid UTF-8"},
      {"NUL", street(0.0f, 0.0f, std::string("a\0b", 3)), "label 0: text holds a control character"},
      {"a tab", street(0.0f, 0.0f, "a\tb"), "text holds a control character"},
      {"a line feed", street(0.0f, 0.0f, "a\n"), "text holds a control character"},
      {"unit separator", street(0.0f, 0.0f, "\x1F"), "text holds a control character"},
      {"DEL", street(0.0f, 0.0f, "\x7F"), "text holds a control character"},
      {"C1 U+0080", street(0.0f, 0.0f, "\xC2\x80"), "text holds a control character"},
      {"C1 NEL U+0085", street(0.0f, 0.0f, "x\xC2\x85y"), "text holds a control character"},
      {"C1 U+009F", street(0.0f, 0.0f, "\xC2\x9F"), "text holds a control character"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    GroundTile t = tinyTile();
    t.labels = {c.label};
    CHECK_THAT(errorOf(t), Catch::Contains(c.message));
  }

  // Just inside every bound.
  GroundTile t = tinyTile();
  t.labels = {street(kHalfPi, 0.0f, "\xC2\xA0no-break space, U+00A0"),
              street(std::nextafter(-kHalfPi, 0.0f), 1.0e8f, "Ωμέγα 🏙"), street(-0.0f, 0.0f, " ")};
  const auto inside = decodeGroundTile(encodeGroundTile(t), kName);
  INFO((inside.ok() ? std::string() : inside.error()));
  REQUIRE(inside.ok());
  checkSameTile(t, *inside);

  SECTION("the second label's error names it and its offset") {
    GroundTile two = tinyTile();
    two.labels.push_back(street(0.0f, 0.0f, "\x01"));
    // The first label takes 15 + 3 bytes from byte 136; the second's text starts at 154 + 15.
    CHECK_THAT(errorOf(two), Catch::Contains("section LABL at byte 169: label 1: text holds a control character"));
  }
  SECTION("text lengths that disagree with the section") {
    const std::vector<std::uint8_t> good = encodeGroundTile(tinyTile());
    // Text length 2 leaves a byte after the label; 4 runs past the section.
    CHECK_THAT(errorOf(patched(good, 150, {2})), Catch::Contains("section LABL at byte 153: 1 bytes after the last"));
    CHECK_THAT(errorOf(patched(good, 150, {4})), Catch::Contains("section LABL: label 0: "));
    CHECK_THAT(errorOf(patched(good, 150, {0})), Catch::Contains("label 0: empty text"));
  }
}

TEST_CASE("A ground tile cut at any length is refused cleanly", "[format][ground]") {
  const std::vector<std::uint8_t> whole = encodeGroundTile(sampleTile());
  REQUIRE(decodeGroundTile(whole, kName).ok());
  for (std::size_t n = 0; n < whole.size(); ++n) {
    INFO(n);
    const std::vector<std::uint8_t> cut(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(n));
    errorOf(cut);
    // With the size and checksum made right, what lies behind them must refuse the cut too.
    errorOf(fuzz::withValidSizeAndCrc(cut));
  }
}

TEST_CASE("A ground tile with any byte changed is refused or re-encodes to the same bytes", "[format][ground]") {
  const std::vector<std::uint8_t> whole = encodeGroundTile(sampleTile());
  std::size_t decoded = 0, refused = 0;
  for (std::size_t i = 0; i < whole.size(); ++i) {
    if (i >= 8 && i < 16) continue;  // size and checksum: made right below
    for (const unsigned mask : {0x01u, 0x10u, 0x80u, 0xFFu}) {
      std::vector<std::uint8_t> changed = whole;
      changed[i] = static_cast<std::uint8_t>(changed[i] ^ mask);
      changed = fuzz::withValidSizeAndCrc(changed);
      const auto r = decodeGroundTile(changed, kName);
      INFO("byte " << i << " xor " << mask);
      if (r.ok()) {
        ++decoded;
        CHECK(encodeGroundTile(*r) == changed);
      } else {
        ++refused;
        CHECK(r.error().rfind(std::string(kName) + ": ", 0) == 0);
      }
    }
  }
  // Vertex and index bytes, ranks and names change the tile without breaking it; the rest refuses.
  CHECK(decoded > 0);
  CHECK(refused > 0);
}
