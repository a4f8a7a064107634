// The search index codec (search.qvi, docs/formats.md): golden bytes pin version 4 (and versions 2 and 3 still decode),
// entries round-trip, and corrupt, truncated, old-version and out-of-range files are refused by name.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "../fuzz/FuzzInputs.h"
#include "qv/format/SearchIndex.h"

using namespace qv;

namespace {

SearchEntry tinyEntry() {
  SearchEntry e;
  e.id = "w1";
  e.name = "A";
  e.use = "office";
  e.x = 1.5f;
  e.y = -2.0f;
  e.heightM = 10.0f;
  e.storeys = 3;
  e.importance = Importance::Critical;
  e.lod = 1;
  e.leaf = 4;
  return e;
}

void requireError(const std::vector<std::uint8_t>& bytes, const std::string& fragment) {
  const auto r = decodeSearchIndex(bytes, "city/search.qvi");
  REQUIRE_FALSE(r.ok());
  INFO(r.error());
  CHECK(r.error().rfind("city/search.qvi: ", 0) == 0);
  CHECK(r.error().find(fragment) != std::string::npos);
}

}  // namespace

TEST_CASE("A version 3 search index still decodes, its facility kind derived from the use", "[format][search]") {
  const std::vector<std::uint8_t> golden = {
      0x51, 0x56, 0x53, 0x49, 0x03, 0x00, 0x00, 0x00, 0x36, 0x00, 0x00, 0x00, 0x82, 0x67, 0xa9, 0x1d, 0x01, 0x00,
      0x00, 0x00, 0x02, 0x77, 0x31, 0x01, 0x41, 0x00, 0x06, 0x6f, 0x66, 0x66, 0x69, 0x63, 0x65, 0x00, 0x00, 0xc0,
      0x3f, 0x00, 0x00, 0x00, 0xc0, 0x00, 0x00, 0x20, 0x41, 0x03, 0x00, 0x01, 0x01, 0x04, 0x00, 0x00, 0x00, 0x01};
  SearchEntry entry = tinyEntry();
  entry.facility = FacilityCategory::Essential;
  const auto decoded = decodeSearchIndex(golden, "golden.qvi");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->size() == 1);
  CHECK((*decoded)[0] == entry);  // an office: its use does not give the kind, left unknown
  CHECK((*decoded)[0].facilityKind.empty());
  // A school's kind comes from its use.
  const std::vector<SearchEntry> v3 = {[] {
    SearchEntry e = tinyEntry();
    e.use = "school";
    e.facility = FacilityCategory::SchoolShelter;
    return e;
  }()};
  auto bytes = encodeSearchIndex(v3);
  bytes.pop_back();  // the empty kind's length: a version 3 entry ends after the category
  bytes[4] = 3;
  const auto school = decodeSearchIndex(fuzz::withValidSizeAndCrc(bytes), "v3.qvi");
  REQUIRE(school.ok());
  CHECK((*school)[0].facilityKind == "school");
}

TEST_CASE("Search index version 4 is pinned by golden bytes", "[format][search]") {
  // x 1.5, y -2, height 10, storeys 3, critical, lod 1, leaf 4, essential, then the kind "hospital".
  const std::vector<std::uint8_t> golden = {
      0x51, 0x56, 0x53, 0x49, 0x04, 0x00, 0x00, 0x00, 0x41, 0x00, 0x00, 0x00, 0xd0, 0xe9, 0x87, 0x56, 0x01,
      0x00, 0x00, 0x00, 0x02, 0x77, 0x31, 0x01, 0x41, 0x00, 0x08, 0x68, 0x6f, 0x73, 0x70, 0x69, 0x74, 0x61,
      0x6c, 0x00, 0x00, 0xc0, 0x3f, 0x00, 0x00, 0x00, 0xc0, 0x00, 0x00, 0x20, 0x41, 0x03, 0x00, 0x01, 0x01,
      0x04, 0x00, 0x00, 0x00, 0x01, 0x08, 0x68, 0x6f, 0x73, 0x70, 0x69, 0x74, 0x61, 0x6c};
  SearchEntry entry = tinyEntry();
  entry.use = "hospital";
  entry.facility = FacilityCategory::Essential;
  entry.facilityKind = "hospital";
  const std::vector<SearchEntry> entries = {entry};
  CHECK(encodeSearchIndex(entries) == golden);
  const auto decoded = decodeSearchIndex(golden, "golden.qvi");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->size() == 1);
  CHECK((*decoded)[0] == entry);
}

TEST_CASE("A version 2 search index still decodes, its facility category derived from the use", "[format][search]") {
  const std::vector<std::uint8_t> golden = {
      0x51, 0x56, 0x53, 0x49, 0x02, 0x00, 0x00, 0x00, 0x35, 0x00, 0x00, 0x00, 0x37, 0x96, 0x1d, 0x11, 0x01, 0x00,
      0x00, 0x00, 0x02, 0x77, 0x31, 0x01, 0x41, 0x00, 0x06, 0x6f, 0x66, 0x66, 0x69, 0x63, 0x65, 0x00, 0x00, 0xc0,
      0x3f, 0x00, 0x00, 0x00, 0xc0, 0x00, 0x00, 0x20, 0x41, 0x03, 0x00, 0x01, 0x01, 0x04, 0x00, 0x00, 0x00};
  const auto decoded = decodeSearchIndex(golden, "golden.qvi");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->size() == 1);
  CHECK((*decoded)[0] == tinyEntry());  // an office: no facility category, though "critical" was stored
  CHECK((*decoded)[0].facility == FacilityCategory::None);
}

TEST_CASE("Search entries round-trip, long strings and many entries included", "[format][search]") {
  std::vector<SearchEntry> entries;
  for (std::uint32_t i = 0; i < 2000; ++i) {
    SearchEntry e = tinyEntry();
    e.id = "s" + std::to_string(i + 1);
    e.name = i % 3 == 0 ? std::string(300, static_cast<char>('a' + i % 26)) : "";
    e.address = i % 5 == 0 ? std::to_string(i) + " Broadway, New York" : "";
    e.x = static_cast<float>(i) * 3.25f - 5000.0f;
    e.y = -static_cast<float>(i) * 1.5f;
    e.heightM = static_cast<float>(i % 400);
    e.storeys = static_cast<std::uint16_t>(1 + i % 120);
    e.importance = i % 7 == 0 ? Importance::Critical : Importance::General;
    e.lod = i % 11 == 0 ? 2 : 1;
    e.leaf = i / 100;
    e.facility = static_cast<FacilityCategory>(i % static_cast<unsigned>(FacilityCategory::Count));
    if (e.facility != FacilityCategory::None && i % 2 == 0) e.facilityKind = "kind_" + std::to_string(i % 13);
    entries.push_back(e);
  }
  const auto decoded = decodeSearchIndex(encodeSearchIndex(entries), "many.qvi");
  REQUIRE(decoded.ok());
  CHECK(*decoded == entries);
}

TEST_CASE("Corrupt, truncated, old and out-of-range search indexes are refused with the reason", "[format][search]") {
  const std::vector<SearchEntry> entries = {tinyEntry(), tinyEntry()};
  const std::vector<std::uint8_t> good = encodeSearchIndex(entries);
  REQUIRE(decodeSearchIndex(good, "x").ok());

  SECTION("not an index") {
    requireError({'Q', 'V', 'T', '1'}, "not a search index");
  }
  SECTION("version 1 (written before the index held positions)") {
    auto b = good;
    b[4] = 1;
    requireError(b, "unsupported search index version 1");
  }
  SECTION("truncated") {
    auto b = good;
    b.resize(b.size() - 3);
    requireError(b, "truncated");
  }
  SECTION("a flipped byte") {
    auto b = good;
    b[30] ^= 0x40;
    requireError(b, "checksum mismatch");
  }
  SECTION("more entries than the bytes can hold") {
    auto b = good;
    b[16] = 0xff;
    b[17] = 0xff;
    requireError(fuzz::withValidSizeAndCrc(b), "entries cannot fit");
  }
  SECTION("a position that is not a number") {
    SearchEntry e = tinyEntry();
    e.x = NAN;
    requireError(encodeSearchIndex(std::vector<SearchEntry>{e}), "entry 0 at byte 20: position");
  }
  SECTION("a negative height") {
    SearchEntry e = tinyEntry();
    e.heightM = -1.0f;
    requireError(encodeSearchIndex(std::vector<SearchEntry>{tinyEntry(), e}), "entry 1 at byte");
  }
  SECTION("an unknown facility category") {
    auto b = good;
    b[b.size() - 2] = 9;  // the last entry's category, before its empty kind
    requireError(fuzz::withValidSizeAndCrc(b), "entry 1 at byte");
    requireError(fuzz::withValidSizeAndCrc(b), "unknown facility category");
  }
  SECTION("a facility kind without a category") {
    SearchEntry e = tinyEntry();
    e.facilityKind = "hospital";
    requireError(encodeSearchIndex(std::vector<SearchEntry>{e}), "a facility kind without a facility category");
  }
  SECTION("a facility kind longer than 32 bytes") {
    SearchEntry e = tinyEntry();
    e.facility = FacilityCategory::Hazardous;
    e.facilityKind = std::string(40, 'k');
    requireError(encodeSearchIndex(std::vector<SearchEntry>{e}), "facility kind");
  }
  SECTION("an unknown level of detail") {
    SearchEntry e = tinyEntry();
    e.lod = 3;
    requireError(encodeSearchIndex(std::vector<SearchEntry>{e}), "lod is neither 1 nor 2");
  }
}

TEST_CASE("Search matches rank the same words, then name starts, whole words, word starts, inside words",
          "[format][search]") {
  CHECK(queryMatchRank("Empire State Building", "empire  STATE building") == 0);
  CHECK(queryMatchRank("Building 3-4", "building 3-4") == 0);
  CHECK(queryMatchRank("Empire State Building", "Empire") == 1);
  CHECK(queryMatchRank("Empire State Building", "emp") == 1);
  CHECK(queryMatchRank("The Empire Building", "empire") == 2);
  CHECK(queryMatchRank("Empire State Building", "building state") == 2);
  CHECK(queryMatchRank("Empire State Building", "sta") == 3);
  CHECK(queryMatchRank("Empire State Building", "state bui") == 3);
  CHECK(queryMatchRank("Empire State Building", "pire") == 4);
  CHECK(queryMatchRank("Empire State Building", "empire nowhere") == -1);
  CHECK(queryMatchRank("", "x") == -1);
  CHECK(queryMatchRank("anything", "   ") == -1);
  // Whatever ranks, matches: the rank agrees with matchesQuery.
  for (const char* q : {"empire", "e", "ding", "state empire", "x"}) {
    INFO(q);
    CHECK((queryMatchRank("Empire State Building", q) >= 0) == matchesQuery("Empire State Building", q));
  }
}
