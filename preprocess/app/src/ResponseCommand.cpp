// quakeview-prep response --city DIR (--motion FILE [--dt S] [--units U] [--motion-y FILE] |
//   --synthetic SEED) [--pga G] [--epicentre LON,LAT,DEPTH_KM --magnitude M]
#include <cstdio>

#include "Commands.h"
#include "Summary.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseRun.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep response --city DIR (--motion FILE [--dt S] [--units g|m/s2|cm/s2] [--motion-y FILE]\n"
    "                               | --synthetic SEED) [--pga G]\n"
    "                               [--epicentre LON,LAT,DEPTH_KM --magnitude M [--vs30 M_PER_S]\n"
    "                                [--site-factor F] [--wave-speed KM_PER_S]] [--threads N]\n"
    "  Analyses every building of the city as an MDOF shear building with Bouc-Wen storeys (X and Y)\n"
    "  and writes the response tiles into DIR (new files first, the manifest last).\n"
    "  --motion FILE      a ground-motion record (PEER AT2, one value per line, or time,acceleration);\n"
    "                     --dt and --units for files that do not say; --motion-y a second component\n"
    "  --synthetic SEED   a synthetic Kanai-Tajimi motion (two components) instead of a record\n"
    "  --pga G            scale the record(s) to this peak ground acceleration (g)\n"
    "  --epicentre ...    a scenario: each building's record is scaled to the PGA the BSSA14 model\n"
    "                     predicts at its distance and delayed by the S-wave travel time\n";

}  // namespace

int runResponse(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv,
                                {{"city"},
                                 {"motion"},
                                 {"motion-y"},
                                 {"dt"},
                                 {"units"},
                                 {"synthetic"},
                                 {"pga"},
                                 {"epicentre"},
                                 {"epicenter"},
                                 {"magnitude"},
                                 {"vs30"},
                                 {"site-factor"},
                                 {"wave-speed"},
                                 {"threads"},
                                 {"help", false}},
                                error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "response: %s\n", error.c_str());
    std::fputs(kUsage, args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "response: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
  };
  if (!args->positional().empty()) return usage("unexpected argument '" + args->positional()[0] + "'");
  const auto city = args->value("city");
  if (!city) return usage("--city DIR is required");
  ResponseRunOptions options;
  const bool hasMotion = args->has("motion"), hasSynthetic = args->has("synthetic");
  if (hasMotion == hasSynthetic) return usage("give exactly one of --motion FILE and --synthetic SEED");
  if (hasSynthetic) {
    const auto seed = parseInteger(*args->value("synthetic"));
    if (!seed || *seed < 0) return usage("--synthetic SEED must be a whole number >= 0");
    options.syntheticSeed = static_cast<std::uint64_t>(*seed);
    if (args->has("motion-y") || args->has("dt") || args->has("units")) {
      return usage("--motion-y, --dt and --units go with --motion, not --synthetic");
    }
  } else {
    options.motionX = *args->value("motion");
    options.motionY = args->value("motion-y").value_or("");
  }
  if (const auto dt = args->value("dt")) {
    const auto v = parseDouble(*dt);
    if (!v || !(*v > 0.0 && *v <= 1.0)) return usage("--dt must be a time step in seconds (0 < dt <= 1)");
    options.timeStepS = *v;
  }
  if (const auto units = args->value("units")) {
    options.units = seismic::parseAccelerationUnit(*units);
    if (!options.units) return usage("--units must be g, m/s2 or cm/s2");
  }
  if (const auto pga = args->value("pga")) {
    const auto v = parseDouble(*pga);
    if (!v || !(*v > 0.0 && *v <= 5.0)) return usage("--pga must be a peak acceleration in g (0 < PGA <= 5)");
    options.pgaG = *v;
  }
  const auto epicentre = args->has("epicentre") ? args->value("epicentre") : args->value("epicenter");
  if (epicentre || args->has("magnitude")) {
    if (!epicentre || !args->has("magnitude")) return usage("--epicentre and --magnitude go together");
    const auto e = parseNumberList(*epicentre, 3);
    if (!e || std::abs((*e)[0]) > 180.0 || std::abs((*e)[1]) > 85.0 || (*e)[2] < 0.0 || (*e)[2] > 700.0) {
      return usage("--epicentre must be LON,LAT,DEPTH_KM (|lon| <= 180, |lat| <= 85, depth 0..700 km)");
    }
    const auto m = parseDouble(*args->value("magnitude"));
    if (!m || *m < 3.0 || *m > 8.5) return usage("--magnitude must be a moment magnitude from 3 to 8.5");
    seismic::Scenario s;
    s.epicentreLongitudeDeg = (*e)[0];
    s.epicentreLatitudeDeg = (*e)[1];
    s.depthKm = (*e)[2];
    s.magnitude = *m;
    if (const auto v = args->value("vs30")) {
      const auto x = parseDouble(*v);
      if (!x || *x < 100.0 || *x > 2000.0) return usage("--vs30 must be in m/s from 100 to 2000");
      s.vs30MetresPerSecond = *x;
    }
    if (const auto v = args->value("site-factor")) {
      const auto x = parseDouble(*v);
      if (!x || *x <= 0.0 || *x > 10.0) return usage("--site-factor must be from 0 to 10");
      s.siteFactor = *x;
    }
    if (const auto v = args->value("wave-speed")) {
      const auto x = parseDouble(*v);
      if (!x || *x <= 0.1 || *x > 10.0) return usage("--wave-speed must be in km/s from 0.1 to 10");
      s.shearWaveSpeedKmPerS = *x;
    }
    options.scenario = s;
  }
  if (const auto threads = args->value("threads")) {
    const auto v = parseInteger(*threads);
    if (!v || *v < 1 || *v > 256) return usage("--threads must be from 1 to 256");
    options.threads = static_cast<unsigned>(*v);
  }

  installInterruptHandler();
  const auto report = runCityResponse(*city, options);
  if (!report.ok()) {
    std::fprintf(stderr, "response: %s\n", report.error().c_str());
    return kExitDataError;
  }
  const ResponseRunReport& r = *report;
  std::printf("response written to %s/%s\n", city->c_str(), r.folder.c_str());
  std::printf("motion      %s\n", r.motion.c_str());
  if (!r.scenario.empty()) std::printf("scenario    %s\n", r.scenario.c_str());
  std::printf(
      "buildings   %llu: none %llu, slight %llu, moderate %llu, extensive %llu, complete %llu, no result %llu\n",
      static_cast<unsigned long long>(r.buildings), static_cast<unsigned long long>(r.damage[0]),
      static_cast<unsigned long long>(r.damage[1]), static_cast<unsigned long long>(r.damage[2]),
      static_cast<unsigned long long>(r.damage[3]), static_cast<unsigned long long>(r.damage[4]),
      static_cast<unsigned long long>(r.damage[5]));
  if (!r.noResultReasons.empty()) {
    std::printf("no result  ");
    for (const auto& [reason, count] : r.noResultReasons) {
      std::printf(" %s: %llu;", std::string(noResultReasonName(reason)).c_str(),
                  static_cast<unsigned long long>(count));
    }
    std::printf(" (`info --building ID` gives the details)\n");
  }
  std::printf("frames      %zu at %.3f s (%.1f s)\n", r.frames, r.timeStepS,
              static_cast<double>(r.frames - 1) * r.timeStepS);
  std::printf("bytes       %s summaries, %s histories (%.0f B per building), mean rate %.1f Hz\n",
              humanBytes(r.summaryBytes).c_str(), humanBytes(r.historyBytes).c_str(),
              r.buildings > 0 ? static_cast<double>(r.historyBytes) / static_cast<double>(r.buildings) : 0.0,
              r.meanSampleRateHz);
  std::printf(
      "histories   worst error %.2f %% of peak roof displacement, 99th percentile %.2f %% (%.2f encodings a "
      "building)\n",
      100.0 * r.worstRelativeError, 100.0 * r.p99RelativeError,
      r.buildings > 0 ? static_cast<double>(r.encodingAttempts) / static_cast<double>(r.buildings) : 0.0);
  std::printf(
      "speed       %.1f million storey-steps/s (%llu storey-steps; solving %.1f s, encoding %.1f s over threads)\n",
      r.seconds > 0.0 ? static_cast<double>(r.storeySteps) / r.seconds / 1e6 : 0.0,
      static_cast<unsigned long long>(r.storeySteps), r.solveSeconds, r.encodeSeconds);
  if (r.nonConvergedSteps > 0) {
    std::printf(
        "note        %llu buildings are approximate: %llu solver steps were accepted without Newton convergence "
        "even after splitting them (`info --json` lists the buildings and their residuals)\n",
        static_cast<unsigned long long>(r.approximateBuildings), static_cast<unsigned long long>(r.nonConvergedSteps));
  }
  std::printf("time        %.2f s\n", r.seconds);
  return kExitOk;
}

}  // namespace qv::prep
