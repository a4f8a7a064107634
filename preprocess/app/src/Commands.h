// The commands of quakeview-prep. Each takes the arguments after its name and returns an exit
// code (see Cli.h): 0 ok, 1 bad data or I/O failure, 2 usage error. Messages go to stderr,
// results to stdout.
#pragma once

#include <string>
#include <vector>

namespace qv::prep {

using CommandArgs = std::vector<std::string>;

int runCity(const CommandArgs& args);            ///< city --input FILE... --out DIR
int runSynthCity(const CommandArgs& args);       ///< synth-city --buildings N --seed S --out DIR
int runInfo(const CommandArgs& args);            ///< info DIR [--json] [--building ID] [--verify]
int runMdof(const CommandArgs& args);            ///< mdof --storeys N --mass KG --stiffness N_PER_M ...
int runResponse(const CommandArgs& args);        ///< response --city DIR (--motion FILE | --synthetic SEED) ...
int runImportResponse(const CommandArgs& args);  ///< import-response --city DIR --input FILE...
int runReport(const CommandArgs& args);          ///< report DIR [--out FILE.html]
int runLod2(const CommandArgs& args);            ///< lod2 --city DIR --input FILE [--place LON,LAT[,ROT]]

}  // namespace qv::prep
