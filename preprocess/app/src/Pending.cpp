// Commands not written yet. Each owner deletes its function here when adding its own file.
#include <cstdio>

#include "Commands.h"
#include "qv/prep/Cli.h"

namespace qv::prep {
namespace {
int pending(const char* name) {
  std::fprintf(stderr, "quakeview-prep %s: not available in this build yet\n", name);
  return kExitUsage;
}
}  // namespace

int runCity(const CommandArgs&) { return pending("city"); }
int runSynthCity(const CommandArgs&) { return pending("synth-city"); }
int runInfo(const CommandArgs&) { return pending("info"); }
int runMdof(const CommandArgs&) { return pending("mdof"); }

}  // namespace qv::prep
