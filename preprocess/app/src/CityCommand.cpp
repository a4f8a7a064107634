// quakeview-prep city --input FILE... --out DIR [GeoJSON property options] [--origin LON,LAT] [--no-ground]
#include <chrono>
#include <cstdio>

#include "Commands.h"
#include "Summary.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/Ingest.h"
#include "qv/prep/Lod2OsmParts.h"
#include "qv/prep/Tiler.h"

namespace qv::prep {
namespace {

const std::string kUsage =
    std::string(
        "usage: quakeview-prep city --input FILE... --out DIR [options]\n"
        "  Reads building footprints (OpenStreetMap .osm, .osm.bz2, .osm.pbf; GeoJSON FeatureCollections\n"
        "  .geojson/.json), cleans and projects them, infers storeys and seismic attributes, and writes\n"
        "  the city's tiles to DIR (replacing a previous city there only when everything succeeded),\n"
        "  with the map under it from the OSM inputs (streets, railways, water, parks, place names).\n"
        "  --origin LON,LAT            projection centre in degrees (default: the centre of the data)\n") +
    kLeafOptionsUsage + kNameOptionUsage + kNoGroundOptionUsage +
    std::string(
        "  --no-lod2                   keep OSM buildings with building:part members as LOD1 prisms (by\n"
        "                              default each becomes one LOD2 model, re-meshed and skinned per floor)\n"
        "  GeoJSON properties (defaults are OSM's keys, as written by `osmium export`):\n"
        "  --id-property NAME          (id)           --name-property NAME     (name)\n"
        "  --height-property NAME      (height)       --height-unit m|ft       (m)\n"
        "  --levels-property NAME      (building:levels)\n"
        "  --min-height-property NAME  (min_height)   --year-property NAME     (start_date)\n"
        "  --use-property NAME         (building)\n"
        "  --occupants-property NAME   (occupants)    people at peak occupancy, else inferred from floor area\n"
        "  --value-property NAME       (replacement_value)  replacement value in USD, else inferred\n"
        "  NYC building footprints: --height-property heightroof --height-unit ft --year-property cnstrct_yr\n");

}  // namespace

int runCity(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv,
                                {{"input", true, true},
                                 {"out"},
                                 {"origin"},
                                 {"max-leaf-buildings"},
                                 {"max-leaf-kib"},
                                 {"max-coarse-buildings"},
                                 {"id-property"},
                                 {"name-property"},
                                 {"height-property"},
                                 {"height-unit"},
                                 {"levels-property"},
                                 {"min-height-property"},
                                 {"occupants-property"},
                                 {"value-property"},
                                 {"year-property"},
                                 {"use-property"},
                                 {"no-lod2", false},
                                 {"no-ground", false},
                                 {"name"},
                                 {"help", false}},
                                error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "city: %s\n", error.c_str());
    std::fputs(kUsage.c_str(), args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "city: %s\n%s", message.c_str(), kUsage.c_str());
    return kExitUsage;
  };
  if (!args->positional().empty()) return usage("unexpected argument '" + args->positional()[0] + "'");
  const std::vector<std::string>& inputs = args->values("input");
  if (inputs.empty()) return usage("--input FILE... is required");
  const auto out = args->value("out");
  if (!out || out->empty()) return usage("--out DIR is required");

  IngestOptions options;
  if (auto v = args->value("id-property")) options.idProperty = *v;
  if (auto v = args->value("name-property")) options.nameProperty = *v;
  if (auto v = args->value("height-property")) options.heightProperty = *v;
  if (auto v = args->value("height-unit")) {
    if (*v != "m" && *v != "ft" && *v != "metres" && *v != "meters" && *v != "feet") {
      return usage("--height-unit must be m or ft");
    }
    options.heightUnit = *v;
  }
  if (auto v = args->value("levels-property")) options.levelsProperty = *v;
  if (auto v = args->value("min-height-property")) options.minHeightProperty = *v;
  if (auto v = args->value("occupants-property")) options.occupantsProperty = *v;
  if (auto v = args->value("value-property")) options.valueProperty = *v;
  if (auto v = args->value("year-property")) options.yearProperty = *v;
  if (auto v = args->value("use-property")) options.useProperty = *v;
  if (const auto origin = args->value("origin")) {
    const auto lonLat = parseNumberList(*origin, 2);
    if (!lonLat || std::abs((*lonLat)[0]) > 180.0 || std::abs((*lonLat)[1]) > 85.0) {
      return usage("--origin must be LON,LAT in degrees");
    }
    options.originLonLat = std::array<double, 2>{(*lonLat)[0], (*lonLat)[1]};
  }
  options.ground = !args->has("no-ground");
  TilerOptions tiler;
  tiler.generator = "quakeview-prep city";
  tiler.ground = options.ground;
  tiler.districtsOrigin = "OpenStreetMap";
  if (std::string leafError; !readLeafOptions(*args, tiler, leafError)) return usage(leafError);
  if (std::string nameError; !readCityName(*args, *out, {}, tiler, nameError)) return usage(nameError);

  installInterruptHandler();
  const auto start = std::chrono::steady_clock::now();
  IngestStats stats;
  auto model = readCity(inputs, options, &stats);
  if (!model.ok()) {
    std::fprintf(stderr, "city: %s\n", model.error().c_str());
    return kExitDataError;
  }
  if (interrupted()) {
    std::fprintf(stderr, "city: interrupted; nothing was written\n");
    return kExitDataError;
  }
  OsmPartsReport lod2;
  if (!args->has("no-lod2")) {
    FinishOptions finish;
    finish.remesh.maxEdgeM = kPartModelMaxEdgeM;
    lod2 = assembleOsmPartModels(*model, finish);
    if (interrupted()) {
      std::fprintf(stderr, "city: interrupted; nothing was written\n");
      return kExitDataError;
    }
  }
  const auto tilingStart = std::chrono::steady_clock::now();
  const auto report = writeCityTiles(*model, *out, tiler);
  if (!report.ok()) {
    std::fprintf(stderr, "city: %s\n", report.error().c_str());
    return kExitDataError;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("city written to %s\n", out->c_str());
  std::printf(
      "read        %llu OSM building ways, %llu multipolygons, %llu parts attached (%llu standalone), %llu GeoJSON "
      "features\n",
      static_cast<unsigned long long>(stats.osmWays), static_cast<unsigned long long>(stats.osmRelations),
      static_cast<unsigned long long>(stats.partsAttached), static_cast<unsigned long long>(stats.partsStandalone),
      static_cast<unsigned long long>(stats.geojsonFeatures));
  printTilingSummary(stdout, *model, *report, seconds);
  if (lod2.candidates > 0) {
    std::printf(
        "lod2        %llu of %llu buildings with building:parts are LOD2 models (%llu vertices before "
        "re-meshing, %llu after; %.2f s)\n",
        static_cast<unsigned long long>(lod2.assembled), static_cast<unsigned long long>(lod2.candidates),
        static_cast<unsigned long long>(lod2.verticesBefore), static_cast<unsigned long long>(lod2.verticesAfter),
        lod2.seconds);
  }
  for (const std::string& w : lod2.warnings) std::fprintf(stderr, "city: warning: %s\n", w.c_str());
  std::printf("            (reading %.2f s, cleaning, inference and LOD2 %.2f s, tiling and writing %.2f s)\n",
              stats.readSeconds, stats.buildSeconds + lod2.seconds,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - tilingStart).count());
  return kExitOk;
}

}  // namespace qv::prep
