// quakeview-prep synth-city --buildings N --seed S [--origin LON,LAT] [--detailed-towers N] [--no-ground] --out DIR
#include <chrono>
#include <cstdio>

#include "Commands.h"
#include "Summary.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/Lod2OsmParts.h"
#include "qv/prep/SynthCity.h"
#include "qv/prep/Tiler.h"

namespace qv::prep {
namespace {

const std::string kUsage =
    std::string(
        "usage: quakeview-prep synth-city --buildings N --seed S [options] --out DIR\n"
        "  Generates a deterministic synthetic city (street grid, rectangles, L-shapes and courtyards,\n"
        "  a dense tall core) of exactly N buildings (1 .. 10,000,000) and writes its tiles to DIR,\n"
        "  with its map: named avenues and streets, parks, a river beside it, neighbourhood names.\n"
        "  --origin LON,LAT            where the city centre is placed, degrees (default -74.00,40.71)\n"
        "  --detailed-towers N         the N tallest rectangular or L-shaped buildings (3 storeys or\n"
        "                              more) get setbacks (podium, shaft, crown) and become LOD2 models\n"
        "                              (default 0)\n") +
    kLeafOptionsUsage + kNameOptionUsage + kNoGroundOptionUsage;

}  // namespace

int runSynthCity(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv,
                                {{"buildings"},
                                 {"seed"},
                                 {"origin"},
                                 {"out"},
                                 {"max-leaf-buildings"},
                                 {"max-leaf-kib"},
                                 {"max-coarse-buildings"},
                                 {"detailed-towers"},
                                 {"no-ground", false},
                                 {"name"},
                                 {"help", false}},
                                error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "synth-city: %s\n", error.c_str());
    std::fputs(kUsage.c_str(), args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "synth-city: %s\n%s", message.c_str(), kUsage.c_str());
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
  if (const auto towers = args->value("detailed-towers")) {
    const auto v = parseInteger(*towers);
    if (!v || *v < 0 || *v > 10000000) return usage("--detailed-towers must be a whole number from 0 to 10,000,000");
    options.detailedTowers = static_cast<std::uint64_t>(*v);
  }
  options.ground = !args->has("no-ground");
  TilerOptions tiler;
  tiler.generator = "quakeview-prep synth-city";
  tiler.ground = options.ground;
  tiler.districtsOrigin = "synth-city";
  if (std::string leafError; !readLeafOptions(*args, tiler, leafError)) return usage(leafError);
  if (std::string nameError;
      !readCityName(*args, *out,
                    "Synthetic city, " + std::to_string(*buildings) + " buildings (seed " + std::to_string(*seed) + ")",
                    tiler, nameError))
    return usage(nameError);

  installInterruptHandler();
  const auto start = std::chrono::steady_clock::now();
  CityModel model = generateSynthCity(options);
  OsmPartsReport towers;
  if (options.detailedTowers > 0) {
    FinishOptions finish;
    finish.remesh.maxEdgeM = kPartModelMaxEdgeM;
    towers = assembleOsmPartModels(model, finish, 0, "synthetic");
    if (interrupted()) {
      std::fprintf(stderr, "synth-city: interrupted; nothing was written\n");
      return kExitDataError;
    }
  }
  const auto report = writeCityTiles(model, *out, tiler);
  if (!report.ok()) {
    std::fprintf(stderr, "synth-city: %s\n", report.error().c_str());
    return kExitDataError;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("synthetic city written to %s\n", out->c_str());
  printTilingSummary(stdout, model, *report, seconds);
  if (towers.candidates > 0) {
    std::printf(
        "lod2        %llu detailed towers are LOD2 models (%llu vertices before re-meshing, %llu after; %.2f s)\n",
        static_cast<unsigned long long>(towers.assembled), static_cast<unsigned long long>(towers.verticesBefore),
        static_cast<unsigned long long>(towers.verticesAfter), towers.seconds);
  }
  for (const std::string& w : towers.warnings) std::fprintf(stderr, "synth-city: warning: %s\n", w.c_str());
  return kExitOk;
}

}  // namespace qv::prep
