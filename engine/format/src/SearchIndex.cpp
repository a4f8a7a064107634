#include "qv/format/SearchIndex.h"

#include <cctype>
#include <cstdio>
#include <cstring>

#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"

namespace qv {
namespace {
constexpr std::size_t kHeaderSize = 20;
constexpr std::uint32_t kMaxEntries = 10u << 20;
}  // namespace

// Layout: "QVSI", version u16, flags u16, file size u32, CRC-32 of [16, end) u32, entry count
// u32; then per entry three LEB128-length UTF-8 strings (id, name, address).
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
  }
  w.patchU32(8, static_cast<std::uint32_t>(w.size()));
  w.patchU32(12, crc32(std::span(w.data()).subspan(16)));
  return w.take();
}

Result<std::vector<SearchEntry>> decodeSearchIndex(std::span<const std::uint8_t> bytes, std::string_view name) {
  const std::string prefix = std::string(name) + ": ";
  if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), "QVSI", 4) != 0) {
    return Error{prefix + "not a search index"};
  }
  ByteReader h(bytes.subspan(4, kHeaderSize - 4), 4);
  const std::uint16_t version = h.u16("version");
  if (version != kSearchIndexVersion) {
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
  // Each entry needs at least three bytes (three empty strings).
  if (count > kMaxEntries || count > (bytes.size() - kHeaderSize) / 3) {
    return Error{prefix + "header at byte 16: " + std::to_string(count) + " entries cannot fit in " +
                 std::to_string(bytes.size()) + " bytes"};
  }
  std::vector<SearchEntry> entries(count);
  ByteReader r(bytes.subspan(kHeaderSize), kHeaderSize);
  for (SearchEntry& e : entries) {
    e.id = r.string("id", 256);
    e.name = r.string("name", 1024);
    e.address = r.string("address", 1024);
  }
  if (!r.ok()) return Error{prefix + "entries: " + r.error()};
  return entries;
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

}  // namespace qv
