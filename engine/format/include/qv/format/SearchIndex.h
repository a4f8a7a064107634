// The search index (search.qvi): the city-wide building table. Every building of the city (the
// coarse tiles hold only the most significant ones of large cities) with its id, name, address,
// use, importance, position, height and storeys and the leaf tile that holds it, in "index
// order" (leaf by leaf in manifest order, each leaf's buildings in its tile's order). Lets the
// viewer search, list, filter and locate any building without loading its leaf; the response
// step writes a summary in the same order (docs/formats.md "Response tiles").
// Specification: docs/formats.md ("Search index").
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"
#include "qv/format/FacilityCategory.h"

namespace qv {

/// Version 4 adds the facility kind, version 3 the facility category; version 2 and 3 files still
/// decode (a version 2 category, and a version 2 or 3 kind, are derived from the use alone).
inline constexpr std::uint16_t kSearchIndexVersion = 4;

struct SearchEntry {
  std::string id;
  std::string name;
  std::string address;
  std::string use;                              ///< normalized use (BuildingAttributes::use)
  float x = 0.0f, y = 0.0f;                     ///< centroid, metres in the city frame
  float heightM = 0.0f;                         ///< top above ground
  std::uint16_t storeys = 1;                    ///< BuildingAttributes::storeys
  Importance importance = Importance::General;  ///< the stored importance (old meaning: see BuildingAttributes)
  /// classifyFacility of the building: the "critical facilities" and category filters.
  FacilityCategory facility = FacilityCategory::None;
  /// The kind that gave the category (FacilityClass::kind: "hospital", "fuel", ...); empty for None
  /// (a kind without a category is refused) and where unknown (older indexes).
  std::string facilityKind;
  std::uint8_t lod = 1;    ///< 1 extruded footprint, 2 detailed model
  std::uint32_t leaf = 0;  ///< index into Tileset::nodes of its leaf tile

  bool operator==(const SearchEntry&) const = default;
};

std::vector<std::uint8_t> encodeSearchIndex(std::span<const SearchEntry> entries);
/// Checks magic, version, size, CRC, counts and every value (finite positions within 1e7 m,
/// heights within [0, 1e4] m, importance, facility category and lod known); errors name `name` and the byte offset.
/// Leaf indices are checked against the manifest by the reader that has it.
Result<std::vector<SearchEntry>> decodeSearchIndex(std::span<const std::uint8_t> bytes, std::string_view name);

/// Case-insensitive (ASCII) containment of every word of `query` in `text`.
bool matchesQuery(std::string_view text, std::string_view query);

/// How well `text` matches `query` (case-insensitive, ASCII; words separated by spaces), best
/// first: 0 the same words, 1 `text` starts with the query, 2 every query word is a whole word of
/// `text`, 3 every query word starts a word of `text`, 4 every query word is inside `text`
/// (matchesQuery); -1 no match. A word is a run of letters and digits.
int queryMatchRank(std::string_view text, std::string_view query);

}  // namespace qv
