// quakeview-prep synth-city --buildings N --seed S [--origin LON,LAT] --out DIR
#include <chrono>
#include <cstdio>

#include "Commands.h"
#include "Summary.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/SynthCity.h"
#include "qv/prep/Tiler.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep synth-city --buildings N --seed S [--origin LON,LAT] --out DIR\n"
    "  Generates a deterministic synthetic city (street grid, rectangles, L-shapes and courtyards,\n"
    "  a dense tall core) of exactly N buildings (1 .. 10,000,000) and writes its tiles to DIR.\n"
    "  --origin   where the city centre is placed, degrees (default -74.00,40.71)\n"
    "  --max-leaf-buildings N   buildings per leaf tile at most (default 1000)\n";

}  // namespace

int runSynthCity(const CommandArgs& argv) {
  std::string error;
  const auto args =
      Args::parse(argv, {{"buildings"}, {"seed"}, {"origin"}, {"out"}, {"max-leaf-buildings"}, {"help", false}}, error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "synth-city: %s\n", error.c_str());
    std::fputs(kUsage, args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "synth-city: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
  };
  if (!args->positional().empty()) return usage("unexpected argument '" + args->positional()[0] + "'");
  const auto buildings = parseInteger(args->value("buildings").value_or(""));
  if (!buildings || *buildings < 1 || *buildings > 10000000)
    return usage("--buildings must be a whole number from 1 to 10,000,000");
  const auto seed = parseInteger(args->value("seed").value_or(""));
  if (!seed || *seed < 0) return usage("--seed must be a whole number >= 0");
  const auto out = args->value("out");
  if (!out || out->empty()) return usage("--out DIR is required");
  SynthCityOptions options;
  options.buildings = static_cast<std::uint64_t>(*buildings);
  options.seed = static_cast<std::uint64_t>(*seed);
  if (const auto origin = args->value("origin")) {
    const auto lonLat = parseNumberList(*origin, 2);
    if (!lonLat || std::abs((*lonLat)[0]) > 180.0 || std::abs((*lonLat)[1]) > 85.0) {
      return usage("--origin must be LON,LAT in degrees (|lon| <= 180, |lat| <= 85)");
    }
    options.originLon = (*lonLat)[0];
    options.originLat = (*lonLat)[1];
  }
  TilerOptions tiler;
  tiler.generator = "quakeview-prep synth-city";
  if (const auto leaf = args->value("max-leaf-buildings")) {
    const auto v = parseInteger(*leaf);
    if (!v || *v < 1 || *v > 100000) return usage("--max-leaf-buildings must be from 1 to 100000");
    tiler.maxBuildingsPerLeaf = static_cast<std::uint32_t>(*v);
  }

  installInterruptHandler();
  const auto start = std::chrono::steady_clock::now();
  CityModel model = generateSynthCity(options);
  const auto report = writeCityTiles(model, *out, tiler);
  if (!report.ok()) {
    std::fprintf(stderr, "synth-city: %s\n", report.error().c_str());
    return kExitDataError;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("synthetic city written to %s\n", out->c_str());
  printTilingSummary(stdout, model, *report, seconds);
  return kExitOk;
}

}  // namespace qv::prep
