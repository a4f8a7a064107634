// quakeview-prep: native tools that turn real city data and earthquake responses into the tiles
// the QuakeView viewer streams.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "Commands.h"
#include "qv/prep/Cli.h"

namespace {

struct Command {
  const char* name;
  int (*run)(const qv::prep::CommandArgs&);
  const char* summary;
};

constexpr Command kCommands[] = {
    {"city", qv::prep::runCity, "city --input FILE... --out DIR: OSM / GeoJSON footprints -> city tiles"},
    {"synth-city", qv::prep::runSynthCity,
     "synth-city --buildings N --seed S [--origin LON,LAT] --out DIR: a deterministic synthetic city"},
    {"info", qv::prep::runInfo, "info DIR [--json] [--building ID] [--verify]: what a city directory holds"},
    {"response", qv::prep::runResponse,
     "response --city DIR (--motion FILE | --synthetic SEED) [--pga G] [--epicentre LON,LAT,DEPTH_KM --magnitude M]"},
    {"import-response", qv::prep::runImportResponse,
     "import-response --city DIR --input FILE... [--units U]: displacement histories from another solver"},
    {"report", qv::prep::runReport,
     "report DIR [--out FILE.html]: the situation report (print-ready HTML), as the viewer's Report"},
    {"lod2", qv::prep::runLod2,
     "lod2 --city DIR --input FILE [--place LON,LAT[,ROT]]: detailed LOD2 models (CityJSON, OBJ) into a city"},
    {"mdof", qv::prep::runMdof, "mdof --storeys N --mass KG --stiffness N_PER_M --motion FILE ...: one shear building"},
};

void usage(std::FILE* out) {
  std::fprintf(out, "usage: quakeview-prep <command> [options]\n\ncommands:\n");
  for (const Command& c : kCommands) std::fprintf(out, "  %s\n", c.summary);
  std::fprintf(out, "\nRun 'quakeview-prep <command> --help' for a command's options.\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(stderr);
    return qv::prep::kExitUsage;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    usage(stdout);
    return qv::prep::kExitOk;
  }
  const qv::prep::CommandArgs args(argv + 2, argv + argc);
  for (const Command& c : kCommands) {
    if (name == c.name) return c.run(args);
  }
  std::fprintf(stderr, "quakeview-prep: unknown command '%s'\n\n", name.c_str());
  usage(stderr);
  return qv::prep::kExitUsage;
}
