// The search index (search.qvi): every building's id, name and address, in the order of the root
// tile's buildings (so the root tile gives positions and the root's response summary damage).
// Lets the viewer find any building of the city by name, address or id without loading its leaf.
// Specification: docs/formats.md ("Search index").
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"

namespace qv {

inline constexpr std::uint16_t kSearchIndexVersion = 1;

struct SearchEntry {
  std::string id;
  std::string name;
  std::string address;
};

std::vector<std::uint8_t> encodeSearchIndex(std::span<const SearchEntry> entries);
Result<std::vector<SearchEntry>> decodeSearchIndex(std::span<const std::uint8_t> bytes, std::string_view name);

/// Case-insensitive (ASCII) containment of every word of `query` in `text`.
bool matchesQuery(std::string_view text, std::string_view query);

}  // namespace qv
