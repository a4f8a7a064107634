#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"

using namespace qv;

TEST_CASE("CRC-32 matches zlib's check value", "[core][crc]") {
  const std::string text = "123456789";
  const auto bytes = std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  CHECK(crc32(bytes) == 0xCBF43926u);
  // Incremental use gives the same result.
  CHECK(crc32(bytes.subspan(4), crc32(bytes.subspan(0, 4))) == 0xCBF43926u);
  CHECK(crc32({}) == 0u);
}

TEST_CASE("CRC-32 equals the bit-by-bit definition for every length and split", "[core][crc]") {
  std::vector<std::uint8_t> data(300);
  std::uint32_t state = 12345u;
  for (auto& b : data) {
    state = state * 1664525u + 1013904223u;
    b = static_cast<std::uint8_t>(state >> 24);
  }
  auto reference = [](std::span<const std::uint8_t> bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::uint8_t b : bytes) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xFFFFFFFFu;
  };
  const std::span<const std::uint8_t> all(data);
  for (std::size_t n = 0; n <= data.size(); n += 7) {
    const std::uint32_t expected = reference(all.first(n));
    CHECK(crc32(all.first(n)) == expected);
    CHECK(crc32(all.subspan(n / 3, n - n / 3), crc32(all.first(n / 3))) == expected);
  }
}

TEST_CASE("ByteWriter writes little-endian and ByteReader reads it back", "[core][bytes]") {
  ByteWriter w;
  w.u8(0x01);
  w.u16(0x0302);
  w.u32(0x07060504);
  w.f32(1.5f);
  w.f64(-2.25);
  w.varint(300);
  w.string("Empire");
  const auto& d = w.data();
  REQUIRE(d.size() == 1 + 2 + 4 + 4 + 8 + 2 + 7);
  CHECK(d[1] == 0x02);
  CHECK(d[2] == 0x03);
  CHECK(d[3] == 0x04);
  CHECK(d[19] == 0xAC);  // 300 = 0b1_0010_1100 -> AC 02
  CHECK(d[20] == 0x02);
  ByteReader r(d);
  CHECK(r.u8("a") == 0x01);
  CHECK(r.u16("b") == 0x0302);
  CHECK(r.u32("c") == 0x07060504u);
  CHECK(r.f32("d") == 1.5f);
  CHECK(r.f64("e") == -2.25);
  CHECK(r.varint("f") == 300);
  CHECK(r.string("g") == "Empire");
  CHECK(r.ok());
  CHECK(r.remaining() == 0);
}

TEST_CASE("ByteReader reports the first short read with what and where", "[core][bytes]") {
  const std::uint8_t data[] = {1, 2, 3};
  ByteReader r(data, 100);
  r.u16("first");
  r.u32("second");
  CHECK_FALSE(r.ok());
  CHECK(r.error() == "truncated: second needs 4 bytes, 1 left at byte 102");
  CHECK(r.u32("third") == 0);
  CHECK(r.error().find("second") != std::string::npos);

  const std::uint8_t hugeLength[] = {0xFF, 0xFF, 0xFF, 0x7F};
  ByteReader s(hugeLength);
  CHECK(s.string("name").empty());
  CHECK(s.error().find("limit") != std::string::npos);

  const std::uint8_t endless[] = {0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01};
  ByteReader v(endless);
  v.varint("count");
  CHECK(v.error().find("malformed varint") != std::string::npos);

  const std::uint8_t tooWide[] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02};
  ByteReader w(tooWide);
  CHECK(w.varint("length") == 0);
  CHECK(w.error() == "varint in length overflows 64 bits at byte 10");

  const std::uint8_t largest[] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x01};
  ByteReader x(largest);
  CHECK(x.varint("length") == 0xFFFFFFFFFFFFFFFFull);
  CHECK(x.ok());
}
