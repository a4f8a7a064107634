// Helpers shared by the commands that write a city: the tiling options they all take, the tiling
// summary and drop/warning counts.
#pragma once

#include <cstdio>
#include <string>

#include "qv/prep/CityModel.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Tiler.h"

namespace qv::prep {

/// The lines of a command's usage text for the tile-size options (--max-leaf-buildings,
/// --max-leaf-kib, --max-coarse-buildings), which the commands that tile a city take.
inline constexpr const char* kLeafOptionsUsage =
    "  --max-leaf-buildings N      buildings per leaf tile at most (default 1000)\n"
    "  --max-leaf-kib N            leaf tile size in KiB above which a leaf is split (default 150;\n"
    "                              larger leaves hold more LOD2 models per draw call)\n"
    "  --max-coarse-buildings N    buildings an inner (far-view) tile draws at most: the largest of\n"
    "                              its subtree (default 100000)\n";

/// Reads the tile-size options into `tiler`; false with `error` set for a bad value.
bool readLeafOptions(const Args& args, TilerOptions& tiler, std::string& error);

/// The usage line of --name, which the commands that create a city take.
inline constexpr const char* kNameOptionUsage =
    "  --name TEXT                 the city's name, shown by the viewer with where its files come\n"
    "                              from (default: the output folder's name; synth-city: its size)\n";

/// Reads --name into `tiler.name`, else `defaultName`, else the last component of the output
/// folder `out`; false with `error` set for a name that is empty, longer than 200 bytes, not UTF-8
/// or holds control characters.
bool readCityName(const Args& args, const std::string& out, const std::string& defaultName, TilerOptions& tiler,
                  std::string& error);

/// "1.2 MB", "350 KB", "12 B".
std::string humanBytes(std::uint64_t bytes);

/// The usage line of --no-ground, which the commands that create a city take.
inline constexpr const char* kNoGroundOptionUsage =
    "  --no-ground                 no map under the city (streets, railways, water, parks, open land\n"
    "                              and place names: read from OSM inputs; synth-city makes its own)\n";

/// "ground      1,234 streets, 56 paths, 3 railways, 12 water, 30 parks and green land, 40 names
/// in 85 files, 1.2 MiB": one line on the city's ground layer (`tileset.ground`), or that the input
/// had none, or that --no-ground left it out.
std::string groundSummaryLine(const Tileset& tileset);
/// "districts   12 (districts.geojson, 100.0 % of the buildings): ...": the districts the
/// consequences are totalled by without --districts (`tileset.districts`), or why there are none.
std::string districtsSummaryLine(const Tileset& tileset);

/// Prints what was written: buildings, tiles, bytes, bytes per building, drops by reason,
/// warnings (at most `maxWarnings` listed, all counted) and the ground (groundSummaryLine).
void printTilingSummary(std::FILE* out, const CityModel& model, const TilerReport& report, double seconds,
                        std::size_t maxWarnings = 10);

}  // namespace qv::prep
