// The files of a sharded response run's part as the part writes them and the merge reads them
// (ResponseParts.cpp, ResponseMerge.cpp): part.json's contents, and reading a part's files back
// checked against it. Internal to prep_response.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ResponseFinish.h"
#include "qv/core/Result.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseParts.h"
#include "qv/prep/ResponseRun.h"
#include "qv/prep/ResponseWriter.h"

namespace qv::prep::detail {

inline constexpr char kPartManifest[] = "part.json";

struct PartLeafEntry {
  std::uint32_t node = 0;
  TileResponseFiles files;  ///< relative to the part's folder
  ResponseWriter::LeafStats stats;
  detail::LeafRate rate;
};

struct PartManifest {
  ShardSpec shard;
  std::size_t scenario = 0;                ///< of a catalogue (0: none)
  std::vector<std::string> scenarioNames;  ///< the catalogue's
  RunIdentity identity;
  std::string created, host;
  std::vector<PartLeafEntry> leaves;
  CityFile results, notes, info;
  std::optional<CityFile> districts;
  seismic::PopulationFigures population;
  ResponseRunReport report;  ///< the part's times and counts (for the merge's report)
};

/// The city's manifest without any response (what the parts were made from), as one line.
std::string cityManifestIdentity(const Tileset& tileset);
/// part.json read back; errors name `name` and the key.
Result<PartManifest> parsePartManifest(std::string_view json, const std::string& name);
/// Why a part's file is not the one its part.json names.
std::string damagedPartFile(const std::string& part, const std::string& path, const FileDigest& got,
                            std::uint64_t bytes, std::uint32_t crc);
/// A part's file, read and checked against the size and CRC-32 its part.json names.
Result<std::vector<std::uint8_t>> readPartFile(const std::string& folder, const std::string& file, std::uint64_t bytes,
                                               std::uint32_t crc, const std::string& part);
/// Each building's results from a part's full summary of its leaf.
std::vector<BuildingResult> resultsFromSummary(const ResponseSummaryTile& t);
/// "part K of N".
std::string describePart(const ShardSpec& s);

}  // namespace qv::prep::detail
