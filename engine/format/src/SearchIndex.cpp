#include "qv/format/SearchIndex.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"
#include "qv/format/StoredFile.h"

namespace qv {
namespace {
constexpr std::size_t kHeaderSize = 20;
constexpr std::uint32_t kMaxEntries = 10u << 20;
constexpr std::size_t kMinEntryBytes = 4 + 20;  // four empty strings and the fixed fields (version 2)
}  // namespace

// Layout: "QVSI", version u16, flags u16, file size u32, CRC-32 of [16, end) u32, entry count
// u32; then per entry four LEB128-length UTF-8 strings (id, name, address, use) and x, y,
// height (f32), storeys (u16), importance (u8), lod (u8), leaf (u32), from version 3 the
// facility category (u8) and from version 4 the facility kind (a LEB128-length string).
std::vector<std::uint8_t> encodeSearchIndex(std::span<const SearchEntry> entries) {
  ByteWriter w;
  w.fourcc("QVSI");
  w.u16(kSearchIndexVersion);
  w.u16(0);
  w.u32(0);
  w.u32(0);
  w.u32(static_cast<std::uint32_t>(entries.size()));
  for (const SearchEntry& e : entries) {
    w.string(e.id);
    w.string(e.name);
    w.string(e.address);
    w.string(e.use);
    w.f32(e.x);
    w.f32(e.y);
    w.f32(e.heightM);
    w.u16(e.storeys);
    w.u8(static_cast<std::uint8_t>(e.importance));
    w.u8(e.lod);
    w.u32(e.leaf);
    w.u8(static_cast<std::uint8_t>(e.facility));
    w.string(e.facilityKind);
  }
  w.patchU32(8, static_cast<std::uint32_t>(w.size()));
  w.patchU32(12, crc32(std::span(w.data()).subspan(16)));
  return w.take();
}

namespace {
Result<std::vector<SearchEntry>> decodeIndexFile(std::span<const std::uint8_t> bytes, std::string_view name) {
  const std::string prefix = std::string(name) + ": ";
  if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), "QVSI", 4) != 0) {
    return Error{prefix + "not a search index"};
  }
  ByteReader h(bytes.subspan(4, kHeaderSize - 4), 4);
  const std::uint16_t version = h.u16("version");
  if (version != kSearchIndexVersion && version != 3 && version != 2) {
    return Error{prefix + "unsupported search index version " + std::to_string(version) +
                 " (this build reads version " + std::to_string(kSearchIndexVersion) + ")"};
  }
  h.u16("flags");
  const std::uint32_t size = h.u32("file size");
  const std::uint32_t stored = h.u32("checksum");
  const std::uint32_t count = h.u32("entry count");
  if (size != bytes.size()) {
    return Error{prefix + "truncated or padded: the header says " + std::to_string(size) + " bytes, the file has " +
                 std::to_string(bytes.size())};
  }
  if (const std::uint32_t crc = crc32(bytes.subspan(16)); crc != stored) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "checksum mismatch: stored %08x, computed %08x (corrupt file)", stored, crc);
    return Error{prefix + buffer};
  }
  if (count > kMaxEntries || count > (bytes.size() - kHeaderSize) / kMinEntryBytes) {
    return Error{prefix + "header at byte 16: " + std::to_string(count) + " entries cannot fit in " +
                 std::to_string(bytes.size()) + " bytes"};
  }
  std::vector<SearchEntry> entries(count);
  ByteReader r(bytes.subspan(kHeaderSize), kHeaderSize);
  for (std::uint32_t i = 0; i < count && r.ok(); ++i) {
    SearchEntry& e = entries[i];
    const std::size_t at = r.offset();
    e.id = r.string("id", 256);
    e.name = r.string("name", 1024);
    e.address = r.string("address", 1024);
    e.use = r.string("use", 64);
    e.x = r.f32("x");
    e.y = r.f32("y");
    e.heightM = r.f32("height");
    e.storeys = r.u16("storeys");
    const std::uint8_t importance = r.u8("importance");
    e.lod = r.u8("lod");
    e.leaf = r.u32("leaf");
    const std::uint8_t facility =
        version >= 3 ? r.u8("facility") : static_cast<std::uint8_t>(classifyFacility(e.use, {}, 0.0f, 0, 0).category);
    if (version >= 4) {
      e.facilityKind = r.string("facility kind", 32);
    } else if (const FacilityClass derived = classifyFacility(e.use, {}, 0.0f, 0, 0);
               derived.category == static_cast<FacilityCategory>(facility)) {
      e.facilityKind = std::string(derived.kind);
    }
    if (!r.ok()) break;
    const char* bad = nullptr;
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || std::abs(e.x) > 1e7f || std::abs(e.y) > 1e7f)
      bad = "position is not finite or beyond 1e7 m";
    else if (!(e.heightM >= 0.0f && e.heightM <= 1e4f))
      bad = "height is not in [0, 10000] m";
    else if (importance > static_cast<std::uint8_t>(Importance::Critical))
      bad = "unknown importance";
    else if (facility >= static_cast<std::uint8_t>(FacilityCategory::Count))
      bad = "unknown facility category";
    else if (e.lod != 1 && e.lod != 2)
      bad = "lod is neither 1 nor 2";
    else if (facility == 0 && !e.facilityKind.empty())
      bad = "a facility kind without a facility category";
    if (bad != nullptr) {
      return Error{prefix + "entry " + std::to_string(i) + " at byte " + std::to_string(at) + ": " + bad};
    }
    e.importance = static_cast<Importance>(importance);
    e.facility = static_cast<FacilityCategory>(facility);
  }
  if (!r.ok()) return Error{prefix + "entries: " + r.error()};
  return entries;
}
}  // namespace

Result<std::vector<SearchEntry>> decodeSearchIndex(std::span<const std::uint8_t> bytes, std::string_view name) {
  std::vector<std::uint8_t> storage;
  auto file = storedFileBytes(bytes, name, storage);
  if (!file.ok()) return Error{file.error()};
  return decodeIndexFile(*file, name);
}

bool matchesQuery(std::string_view text, std::string_view query) {
  auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::size_t i = 0;
  bool any = false;
  while (i < query.size()) {
    while (i < query.size() && query[i] == ' ') ++i;
    std::size_t j = i;
    while (j < query.size() && query[j] != ' ') ++j;
    if (j > i) {
      any = true;
      const std::string_view word = query.substr(i, j - i);
      bool found = false;
      for (std::size_t k = 0; k + word.size() <= text.size() && !found; ++k) {
        std::size_t m = 0;
        while (m < word.size() && lower(text[k + m]) == lower(word[m])) ++m;
        found = m == word.size();
      }
      if (!found) return false;
    }
    i = j;
  }
  return any;
}

namespace {

char lowerAscii(char c) {
  return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
}
bool wordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || static_cast<unsigned char>(c) >= 0x80;
}

// The query's words, lower case.
std::vector<std::string> queryWords(std::string_view query) {
  std::vector<std::string> words;
  std::string word;
  for (char c : query) {
    if (c == ' ') {
      if (!word.empty()) words.push_back(std::move(word));
      word.clear();
    } else {
      word += lowerAscii(c);
    }
  }
  if (!word.empty()) words.push_back(std::move(word));
  return words;
}

// Where `word` (lower case) occurs in `text`: 2 as a whole word, 1 at a word's start, 0 inside a
// word, -1 nowhere (the best occurrence).
int wordPlace(std::string_view text, std::string_view word) {
  int best = -1;
  for (std::size_t k = 0; k + word.size() <= text.size() && best < 2; ++k) {
    std::size_t m = 0;
    while (m < word.size() && lowerAscii(text[k + m]) == word[m]) ++m;
    if (m != word.size()) continue;
    const bool starts = k == 0 || !wordChar(text[k - 1]) || !wordChar(word.front());
    const bool ends = k + m == text.size() || !wordChar(text[k + m]) || !wordChar(word.back());
    best = std::max(best, starts ? (ends ? 2 : 1) : 0);
  }
  return best;
}

}  // namespace

int queryMatchRank(std::string_view text, std::string_view query) {
  const std::vector<std::string> words = queryWords(query);
  if (words.empty()) return -1;
  int worst = 2;
  for (const std::string& w : words) {
    const int place = wordPlace(text, w);
    if (place < 0) return -1;
    worst = std::min(worst, place);
  }
  // The text's own words, to compare with the query's as a whole.
  std::string joined;
  for (const std::string& w : words) joined += (joined.empty() ? "" : " ") + w;
  std::vector<std::string> textWords = queryWords(text);
  std::string textJoined;
  for (const std::string& w : textWords) textJoined += (textJoined.empty() ? "" : " ") + w;
  if (textJoined == joined) return 0;
  if (textJoined.compare(0, joined.size(), joined) == 0) return 1;
  return worst == 2 ? 2 : (worst == 1 ? 3 : 4);
}

}  // namespace qv
