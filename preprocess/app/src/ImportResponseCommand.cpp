// quakeview-prep import-response --city DIR --input FILE... [--units m|cm|mm|in|ft]
#include <cstdio>

#include "Commands.h"
#include "Summary.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseImport.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep import-response --city DIR --input FILE... [--units m|cm|mm|in|ft]\n"
    "  Imports per-building, per-floor displacement histories computed by another solver (OpenSees,\n"
    "  an FE model, ...) and writes them as the city's response tiles, like `response` does: drifts,\n"
    "  peak drift per storey, peak roof displacement and the Hazus damage state of each building's\n"
    "  type and era. Buildings without results count as no_result and stay static.\n"
    "  --input FILE...   JSON (format \"quakeview-response-import\") or CSV (building,time_s,floor,x[,y]);\n"
    "                    schemas in docs/import-response.md. Buildings are keyed by their city ids\n"
    "                    (w123, r45, s7, cj:..., g:...); all files share one time step.\n"
    "  --units U         length unit of files that do not name theirs (m, cm, mm, in, ft)\n"
    "  Errors (unknown ids, storey counts that differ from the city, unknown units, non-uniform or\n"
    "  mismatched time steps) name the file and the line or JSON path; the city is then unchanged.\n";

}  // namespace

int runImportResponse(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv, {{"city"}, {"input", true, true}, {"units"}, {"help", false}}, error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "import-response: %s\n", error.c_str());
    std::fputs(kUsage, args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "import-response: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
  };
  if (!args->positional().empty()) return usage("unexpected argument '" + args->positional()[0] + "'");
  const auto city = args->value("city");
  if (!city) return usage("--city DIR is required");
  ImportOptions options;
  options.inputs = args->values("input");
  if (options.inputs.empty()) return usage("--input FILE is required");
  if (const auto units = args->value("units")) {
    options.units = parseDisplacementUnit(*units);
    if (!options.units) return usage("--units must be m, cm, mm, in or ft");
  }

  installInterruptHandler();
  const auto report = runImportResponse(*city, options);
  if (!report.ok()) {
    std::fprintf(stderr, "import-response: %s\n", report.error().c_str());
    return kExitDataError;
  }
  const ImportReport& r = *report;
  std::printf("response written to %s/%s\n", city->c_str(), r.folder.c_str());
  std::printf("motion      %s\n", r.motion.c_str());
  std::printf(
      "buildings   %llu: none %llu, slight %llu, moderate %llu, extensive %llu, complete %llu, no result %llu\n",
      static_cast<unsigned long long>(r.buildings), static_cast<unsigned long long>(r.damage[0]),
      static_cast<unsigned long long>(r.damage[1]), static_cast<unsigned long long>(r.damage[2]),
      static_cast<unsigned long long>(r.damage[3]), static_cast<unsigned long long>(r.damage[4]),
      static_cast<unsigned long long>(r.damage[5]));
  std::printf("imported    %llu buildings, time step %.4g s, %.1f s\n", static_cast<unsigned long long>(r.imported),
              r.timeStepS, r.durationSeconds);
  const std::uint64_t missing = r.buildings - r.imported;
  if (missing > 0) {
    std::printf("no result   %llu buildings stay static:", static_cast<unsigned long long>(missing));
    for (const std::string& id : r.missing) std::printf(" %s", id.c_str());
    if (missing > r.missing.size()) {
      std::printf(" (and %llu more)", static_cast<unsigned long long>(missing - r.missing.size()));
    }
    std::printf("\n");
  }
  std::printf("bytes       %s summaries, %s histories\n", humanBytes(r.summaryBytes).c_str(),
              humanBytes(r.historyBytes).c_str());
  std::printf("histories   worst error %.2f %% of peak roof displacement, 99th percentile %.2f %%\n",
              100.0 * r.worstRelativeError, 100.0 * r.p99RelativeError);
  std::printf("time        %.2f s\n", r.seconds);
  return kExitOk;
}

}  // namespace qv::prep
