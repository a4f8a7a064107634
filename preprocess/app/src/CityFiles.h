// Reading a city directory: its manifest and tiles, as the tools see them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/CityTile.h"
#include "qv/format/Tileset.h"

namespace qv::prep {

/// Reads and validates DIR/tileset.json.
Result<Tileset> loadTileset(const std::string& dir);

/// Reads one file the manifest lists (a stored file: compressed or not), checking its size and
/// CRC-32 against the manifest's entry.
Result<std::vector<std::uint8_t>> loadCityFile(const std::string& dir, const CityFile& file);

/// Reads and decodes one tile file of a city, checking its size and CRC against the manifest.
Result<CityTile> loadCityTile(const std::string& dir, const TileNode& node);

}  // namespace qv::prep
