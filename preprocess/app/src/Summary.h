// Printing helpers shared by the commands: the tiling summary and drop/warning counts.
#pragma once

#include <cstdio>
#include <string>

#include "qv/prep/CityModel.h"
#include "qv/prep/Tiler.h"

namespace qv::prep {

/// "1.2 MB", "350 KB", "12 B".
std::string humanBytes(std::uint64_t bytes);

/// Prints what was written: buildings, tiles, bytes, bytes per building, drops by reason and
/// warnings (at most `maxWarnings` listed, all counted).
void printTilingSummary(std::FILE* out, const CityModel& model, const TilerReport& report, double seconds,
                        std::size_t maxWarnings = 10);

}  // namespace qv::prep
