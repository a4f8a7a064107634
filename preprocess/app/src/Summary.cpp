#include "Summary.h"

#include <algorithm>
#include <filesystem>

#include "qv/core/Text.h"

namespace qv::prep {

std::string humanBytes(std::uint64_t bytes) {
  char buffer[32];
  if (bytes >= 1024ull * 1024 * 1024)
    std::snprintf(buffer, sizeof buffer, "%.2f GiB", static_cast<double>(bytes) / (1024.0 * 1024 * 1024));
  else if (bytes >= 1024ull * 1024)
    std::snprintf(buffer, sizeof buffer, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024));
  else if (bytes >= 1024)
    std::snprintf(buffer, sizeof buffer, "%.1f KiB", static_cast<double>(bytes) / 1024.0);
  else
    std::snprintf(buffer, sizeof buffer, "%llu B", static_cast<unsigned long long>(bytes));
  return buffer;
}

namespace {

/// 1234567 -> "1,234,567".
std::string withThousands(std::uint64_t n) {
  std::string digits = std::to_string(n);
  for (std::size_t i = digits.size(); i > 3; i -= 3) digits.insert(i - 3, ",");
  return digits;
}

}  // namespace

std::string districtsSummaryLine(const Tileset& tileset) {
  if (!tileset.districts) {
    return tileset.ground ? "districts   none: the input names no neighbourhoods or areas that divide the city"
                          : "districts   none (--no-ground)";
  }
  const DistrictsInfo& d = *tileset.districts;
  char coverage[32];
  std::snprintf(coverage, sizeof coverage, "%.1f %%", 100.0 * d.coverage);
  return "districts   " + withThousands(d.count) + (d.inferred ? " inferred" : "") + " (" + d.file.file + ", " +
         coverage + " of the buildings): " + d.source;
}

std::string groundSummaryLine(const Tileset& tileset) {
  if (!tileset.ground) return "ground      none (--no-ground)";
  const GroundLayer& g = *tileset.ground;
  auto count = [&g](std::initializer_list<const char*> names) {
    std::uint64_t n = 0;
    for (const char* name : names) {
      const auto it = g.features.find(name);
      if (it != g.features.end()) n += it->second;
    }
    return n;
  };
  std::uint64_t skipped = 0;
  std::string reasons;
  for (const auto& [reason, n] : g.skipped) {
    skipped += n;
    reasons += (reasons.empty() ? "" : ", ") + reason + " " + withThousands(n);
  }
  const std::string skippedText =
      skipped == 0 ? "" : " (" + withThousands(skipped) + " objects left out: " + reasons + ")";
  if (g.nodes.empty()) return "ground      the input has no streets, water or open land" + skippedText;
  std::string line = "ground      " + withThousands(count({"street", "major", "motorway"})) + " streets, ";
  if (const std::uint64_t paths = count({"path"}); paths > 0) line += withThousands(paths) + " paths, ";
  if (const std::uint64_t rail = count({"rail"}); rail > 0) line += withThousands(rail) + " railways, ";
  line += withThousands(count({"water"})) + " water, " + withThousands(count({"park", "green", "forest"})) +
          " parks and green land, ";
  if (const std::uint64_t land = count({"land"}); land > 0) line += withThousands(land) + " land polygons, ";
  line += withThousands(count({"labels"})) + " names in " + withThousands(g.nodes.size()) + " files, " +
          humanBytes(g.bytes) + skippedText;
  return line;
}

void printTilingSummary(std::FILE* out, const CityModel& model, const TilerReport& report, double seconds,
                        std::size_t maxWarnings) {
  std::fprintf(out, "buildings   %llu\n", static_cast<unsigned long long>(report.buildings));
  std::fprintf(out, "tiles       %llu (%llu leaves, depth %d)\n", static_cast<unsigned long long>(report.tiles),
               static_cast<unsigned long long>(report.leaves), report.depth);
  std::fprintf(out, "bytes       %s in all, leaves %s (%s to %s each)\n", humanBytes(report.bytes).c_str(),
               humanBytes(report.leafBytes).c_str(), humanBytes(report.smallestLeafBytes).c_str(),
               humanBytes(report.largestLeafBytes).c_str());
  if (report.buildings > 0) {
    std::fprintf(out, "per building %.0f B in leaves, %.0f B in all tiles\n",
                 static_cast<double>(report.leafBytes) / static_cast<double>(report.buildings),
                 static_cast<double>(report.bytes) / static_cast<double>(report.buildings));
  }
  std::fprintf(out, "origin      %.6f, %.6f (lon, lat)\n", model.originLon, model.originLat);
  if (model.drops.total() > 0) {
    std::fprintf(out, "dropped     %llu:", static_cast<unsigned long long>(model.drops.total()));
    for (const auto& [reason, n] : model.drops.byReason) {
      std::fprintf(out, " %s %llu;", reason.c_str(), static_cast<unsigned long long>(n));
    }
    std::fprintf(out, "\n");
  } else {
    std::fprintf(out, "dropped     none\n");
  }
  if (!model.excluded.empty()) {
    std::fprintf(out, "excluded   ");
    for (const auto& [reason, n] : model.excluded) {
      std::fprintf(out, " %s %llu;", reason.c_str(), static_cast<unsigned long long>(n));
    }
    std::fprintf(out, " (neither drawn nor analysed)\n");
  }
  if (!model.warningCounts.empty()) {
    std::fprintf(out, "warnings   ");
    for (const auto& [what, n] : model.warningCounts) {
      std::fprintf(out, " %s: %llu;", what.c_str(), static_cast<unsigned long long>(n));
    }
    std::fprintf(out, "\n");
    for (std::size_t i = 0; i < model.warnings.size() && i < maxWarnings; ++i) {
      std::fprintf(out, "  warning: %s\n", model.warnings[i].c_str());
    }
    if (model.warnings.size() > maxWarnings) {
      std::fprintf(out, "  (%zu more warnings)\n", model.warnings.size() - maxWarnings);
    }
  }
  std::fprintf(out, "%s\n", groundSummaryLine(report.tileset).c_str());
  std::fprintf(out, "%s\n", districtsSummaryLine(report.tileset).c_str());
  std::fprintf(out, "time        %.2f s\n", seconds);
}

bool readCityName(const Args& args, const std::string& out, const std::string& defaultName, TilerOptions& tiler,
                  std::string& error) {
  std::string name = defaultName;
  if (const auto given = args.value("name")) {
    name = *given;
  } else if (name.empty()) {
    std::filesystem::path folder(out);
    if (!folder.has_filename()) folder = folder.parent_path();  // "out/" names "out"
    name = folder.filename().string();
  }
  const bool control =
      std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  if (name.empty() || name.size() > 200 || !isValidUtf8(name) || control) {
    error = "--name must be 1 to 200 bytes of UTF-8 text without control characters";
    return false;
  }
  tiler.name = name;
  return true;
}

bool readLeafOptions(const Args& args, TilerOptions& tiler, std::string& error) {
  if (const auto leaf = args.value("max-leaf-buildings")) {
    const auto v = parseInteger(*leaf);
    if (!v || *v < 1 || *v > 100000) {
      error = "--max-leaf-buildings must be from 1 to 100000";
      return false;
    }
    tiler.maxBuildingsPerLeaf = static_cast<std::uint32_t>(*v);
  }
  if (const auto kib = args.value("max-leaf-kib")) {
    const auto v = parseInteger(*kib);
    if (!v || *v < 16 || *v > 16384) {
      error = "--max-leaf-kib must be from 16 to 16384";
      return false;
    }
    tiler.maxLeafBytes = static_cast<std::size_t>(*v) * 1024;
  }
  if (const auto coarse = args.value("max-coarse-buildings")) {
    const auto v = parseInteger(*coarse);
    if (!v || *v < 100 || *v > 10000000) {
      error = "--max-coarse-buildings must be from 100 to 10000000";
      return false;
    }
    tiler.maxCoarseBuildings = static_cast<std::size_t>(*v);
  }
  return true;
}

}  // namespace qv::prep
