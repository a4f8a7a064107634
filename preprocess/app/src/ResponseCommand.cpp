// quakeview-prep response --city DIR [--motion FILE|FOLDER... [--dt S] [--units U] [--motion-y FILE] |
//   --synthetic SEED...] [--pga G] [--epicentre LON,LAT,DEPTH_KM --magnitude M | --shakemap grid.xml]
//   [--scale-by sa|pga] [--outside-grid error|skip] [--time-of-day night|day|commute] [--districts F]
//   [--population-night N] [--population-day N] [--population-source TEXT] [--shard K/N]
// quakeview-prep response --city DIR --merge
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

#include "Commands.h"
#include "Summary.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseCatalogue.h"
#include "qv/prep/ResponseParts.h"
#include "qv/prep/ResponseRun.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep response --city DIR [--motion FILE|FOLDER... [--dt S] [--units g|m/s2|cm/s2]\n"
    "                               [--motion-y FILE] | --synthetic SEED...] [--pga G]\n"
    "                               [--shakemap GRID.xml [--outside-grid error|skip]\n"
    "                                | --epicentre LON,LAT,DEPTH_KM --magnitude M [--vs30 M_PER_S]\n"
    "                                  [--site-factor F]] [--wave-speed KM_PER_S] [--scale-by sa|pga]\n"
    "                               [--time-of-day night|day|commute] [--districts FILE.geojson]\n"
    "                               [--population-night N] [--population-day N] [--population-source TEXT]\n"
    "                               [--accurate-steps] [--threads N] [--shard K/N]\n"
    "       quakeview-prep response --city DIR --merge [--scenario I] [--threads N]\n"
    "       quakeview-prep response --city DIR --catalogue FILE --scenario I [--shard K/N] [--threads N]\n"
    "       quakeview-prep response --catalogue FILE --list\n"
    "  Analyses every building of the city as an MDOF shear building with Bouc-Wen storeys (X and Y)\n"
    "  under every record of the suite, and writes the response tiles, HAZUS damage probabilities and\n"
    "  consequences into DIR (new files first, the manifest last).\n"
    "  --motion FILE...   ground-motion records (PEER AT2, one value per line, or time,acceleration), or\n"
    "                     folders of them: the suite; --dt and --units for files that do not say;\n"
    "                     --motion-y a second component (with one record)\n"
    "  --synthetic SEED.. synthetic Kanai-Tajimi motions (two components each) instead of records\n"
    "                     (with --shakemap or --epicentre and neither: the built-in default suite,\n"
    "                     seeds 1-5 matched to each site's target spectrum, docs/seismic.md)\n"
    "  --pga G            scale the record(s) to this peak ground acceleration (g), without a field\n"
    "  --shakemap GRID    a USGS ShakeMap grid.xml (3.5 or 4): each building's shaking from the grid at\n"
    "                     its footprint centre, delayed by the S-wave travel time from its epicentre;\n"
    "                     --outside-grid skip leaves buildings outside the grid without a result\n"
    "  --epicentre ...    a scenario: the BSSA14 model at each building's distance\n"
    "  --scale-by sa|pga  with a ShakeMap or a scenario: each record scaled so its 5 %-damped Sa at the\n"
    "                     building's first-mode period equals the target there (sa, the default), or\n"
    "                     to the target PGA (pga)\n"
    "  --time-of-day T    occupants present for the consequences (HAZUS; default day)\n"
    "  --districts FILE   GeoJSON polygons with a \"name\": consequence totals per district (without\n"
    "                     it, the city's own districts.geojson, made from its input, when it has one)\n"
    "  --population-night N, --population-day N, --population-source TEXT\n"
    "                     the area's published residents and daytime population (e.g. a census): shown\n"
    "                     beside the occupants the city holds at night and by day, with the source\n"
    "  --shard K/N        analyse only part K (1..N) of the city's N parts (whole tiles, balanced by\n"
    "                     buildings) into DIR/staging/part-K-of-N, for many machines (docs/cluster.md);\n"
    "                     the city's response is unchanged until --merge\n"
    "  --merge            check that DIR/staging holds every part of one run, complete, then publish\n"
    "                     them as the city's response, byte-identical to the same run on one machine\n"
    "  --threads N        cores to use (default: every core this process may run on)\n"
    "  --catalogue FILE   a scenario catalogue (JSON: each scenario's name and response options, docs/cluster.md):\n"
    "  --scenario I       run its scenario I as its own response, beside the others (scenario-I.json,\n"
    "                     scenarios.json: the viewer switches between them; scenario 1 is also tileset.json);\n"
    "                     with --merge, merge scenario I's parts; --list prints the scenarios\n"
    "  --accurate-steps   accepted for compatibility; no effect: the default solver steps are the\n"
    "                     accurate ones (exact Bouc-Wen update; yielding buildings' peaks within\n"
    "                     about 0.5 % of converged)\n";

int printReport(const std::string& city, const ResponseRunReport& r, const ResponseRunOptions* given);

// The options that say what a run computes: given by a catalogue's scenario or by the parts of a
// merge, never beside --catalogue or --merge.
constexpr const char* kRunOptionNames[] = {"motion",
                                           "shakemap",
                                           "scale-by",
                                           "outside-grid",
                                           "time-of-day",
                                           "districts",
                                           "motion-y",
                                           "dt",
                                           "units",
                                           "synthetic",
                                           "pga",
                                           "epicentre",
                                           "epicenter",
                                           "magnitude",
                                           "vs30",
                                           "site-factor",
                                           "wave-speed",
                                           "population-night",
                                           "population-day",
                                           "population-source"};

// A catalogue's scenario being run: its number and the catalogue's names (ResponseCatalogue.h).
struct ScenarioTarget {
  std::size_t index = 0;
  std::vector<std::string> names;
};

int runResponseWith(const CommandArgs& argv, const ScenarioTarget* target);

// `response --catalogue FILE (--list | --scenario I [--shard K/N] [--threads N])`: the scenario's
// options from the catalogue, run as `response` with them.
int runCatalogue(const Args& args) {
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "response: %s\n%s", message.c_str(), kUsage);
    return kExitUsage;
  };
  for (const char* other : kRunOptionNames) {
    if (args.has(other) || args.has("merge")) {
      if (!args.has(other)) other = "merge";
      return usage(std::string("--catalogue: the scenario's options come from the catalogue, not --") + other +
                   (std::string(other) == "merge" ? " (merge with --city DIR --merge --scenario I)" : ""));
    }
  }
  const auto catalogue = readCatalogue(*args.value("catalogue"));
  if (!catalogue.ok()) {
    std::fprintf(stderr, "response: %s\n", catalogue.error().c_str());
    return kExitDataError;
  }
  const std::size_t count = catalogue->scenarios.size();
  if (args.has("list")) {
    for (std::size_t i = 0; i < count; ++i) std::printf("%zu\t%s\n", i + 1, catalogue->scenarios[i].name.c_str());
    return kExitOk;
  }
  const auto scenario = args.value("scenario");
  const auto index = scenario ? parseInteger(*scenario) : std::nullopt;
  if (!index || *index < 1 || static_cast<std::size_t>(*index) > count) {
    return usage("--catalogue needs --scenario I, from 1 to " + std::to_string(count) + " (or --list)");
  }
  const auto city = args.value("city");
  if (!city) return usage("--city DIR is required");
  ScenarioTarget target;
  target.index = static_cast<std::size_t>(*index);
  for (const CatalogueScenario& s : catalogue->scenarios) target.names.push_back(s.name);
  CommandArgs run = {"--city", *city};
  const CatalogueScenario& chosen = catalogue->scenarios[target.index - 1];
  run.insert(run.end(), chosen.args.begin(), chosen.args.end());
  for (const char* passed : {"shard", "threads"}) {
    if (const auto v = args.value(passed)) {
      run.push_back(std::string("--") + passed);
      run.push_back(*v);
    }
  }
  std::printf("scenario    %zu of %zu: %s\n", target.index, count, chosen.name.c_str());
  return runResponseWith(run, &target);
}

}  // namespace

int runResponse(const CommandArgs& argv) {
  return runResponseWith(argv, nullptr);
}

namespace {

int runResponseWith(const CommandArgs& argv, const ScenarioTarget* target) {
  std::string error;
  const auto args = Args::parse(argv,
                                {{"city"},
                                 {"motion", true, true},
                                 {"shakemap"},
                                 {"scale-by"},
                                 {"outside-grid"},
                                 {"time-of-day"},
                                 {"districts"},
                                 {"motion-y"},
                                 {"dt"},
                                 {"units"},
                                 {"synthetic", true, true},
                                 {"pga"},
                                 {"epicentre"},
                                 {"epicenter"},
                                 {"magnitude"},
                                 {"vs30"},
                                 {"site-factor"},
                                 {"wave-speed"},
                                 {"threads"},
                                 {"population-night"},
                                 {"population-day"},
                                 {"population-source"},
                                 {"shard"},
                                 {"merge", false},
                                 {"catalogue"},
                                 {"scenario"},
                                 {"list", false},
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
  if (args->has("catalogue")) {
    if (target != nullptr) return usage("a catalogue cannot name another catalogue");
    return runCatalogue(*args);
  }
  if (args->has("list")) return usage("--list goes with --catalogue FILE");
  if (!city) return usage("--city DIR is required");
  if (args->has("scenario") && !args->has("merge")) return usage("--scenario goes with --catalogue FILE or --merge");
  if (args->has("merge")) {
    for (const char* other : kRunOptionNames) {
      if (args->has("shard")) other = "shard";
      if (args->has(other)) {
        return usage(std::string("--merge takes only --city (the parts hold the run's options), not --") + other);
      }
    }
    std::size_t scenario = 0;
    if (const auto v = args->value("scenario")) {
      const auto i = parseInteger(*v);
      if (!i || *i < 1 || *i > static_cast<std::int64_t>(kMaxScenarios)) {
        return usage("--scenario must be a scenario's number in its catalogue, not '" + *v + "'");
      }
      scenario = static_cast<std::size_t>(*i);
    }
    unsigned threads = 0;
    if (const auto v = args->value("threads")) {
      const auto t = parseInteger(*v);
      if (!t || *t < 1 || *t > 256) return usage("--threads must be from 1 to 256");
      threads = static_cast<unsigned>(*t);
    }
    installInterruptHandler();
    const auto merged = mergeCityResponse(*city, scenario, threads);
    if (!merged.ok()) {
      std::fprintf(stderr, "response: %s\n", merged.error().c_str());
      return kExitDataError;
    }
    return printReport(*city, *merged, nullptr);
  }
  ResponseRunOptions options;
  const bool hasMotion = args->has("motion"), hasSynthetic = args->has("synthetic");
  const bool hasField = args->has("shakemap") || args->has("epicentre") || args->has("epicenter");
  if (hasMotion && hasSynthetic) return usage("give one of --motion FILE and --synthetic SEED, not both");
  if (!hasMotion && !hasSynthetic && !hasField) {
    return usage(
        "give the records (--motion FILE or --synthetic SEED), or a shaking field (--shakemap or "
        "--epicentre), which uses the built-in default suite");
  }
  if (!hasMotion && !hasSynthetic) {
    // A ShakeMap or a scenario without records: the built-in default suite (docs/seismic.md).
    options.syntheticSeeds.assign(std::begin(kDefaultSuiteSeeds), std::end(kDefaultSuiteSeeds));
    options.defaultSuite = true;
    if (args->has("motion-y") || args->has("dt") || args->has("units")) {
      return usage("--motion-y, --dt and --units go with --motion");
    }
  } else if (hasSynthetic) {
    for (const std::string& text : args->values("synthetic")) {
      const auto seed = parseInteger(text);
      if (!seed || *seed < 0) return usage("--synthetic SEED must be a whole number >= 0, not '" + text + "'");
      options.syntheticSeeds.push_back(static_cast<std::uint64_t>(*seed));
    }
    if (options.syntheticSeeds.empty()) return usage("--synthetic needs at least one SEED");
    if (options.syntheticSeeds.size() > 100) return usage("--synthetic: at most 100 seeds in a suite");
    if (args->has("motion-y") || args->has("dt") || args->has("units")) {
      return usage("--motion-y, --dt and --units go with --motion, not --synthetic");
    }
  } else {
    options.motions = args->values("motion");
    if (options.motions.empty()) return usage("--motion needs at least one FILE or FOLDER");
    options.motionY = args->value("motion-y").value_or("");
  }
  if (const auto shakemap = args->value("shakemap")) options.shakemap = *shakemap;
  if (const auto v = args->value("scale-by")) {
    if (*v == "sa") {
      options.scaleBy = ScaleBy::SpectralAcceleration;
    } else if (*v == "pga") {
      options.scaleBy = ScaleBy::Pga;
    } else {
      return usage("--scale-by must be sa or pga, not '" + *v + "'");
    }
  }
  if (const auto v = args->value("outside-grid")) {
    if (options.shakemap.empty()) return usage("--outside-grid goes with --shakemap");
    if (*v == "error") {
      options.outsideGrid = OutsideGrid::Error;
    } else if (*v == "skip") {
      options.outsideGrid = OutsideGrid::Skip;
    } else {
      return usage("--outside-grid must be error or skip, not '" + *v + "'");
    }
  }
  if (const auto v = args->value("time-of-day")) {
    const auto t = seismic::parseTimeOfDay(*v);
    if (!t.ok()) return usage("--time-of-day must be night, day or commute, not '" + *v + "'");
    options.timeOfDay = *t;
  }
  if (const auto v = args->value("districts")) options.districts = *v;
  for (const char* key : {"population-night", "population-day"}) {
    const auto v = args->value(key);
    if (!v) continue;
    const auto n = parseDouble(*v);
    if (!n || !(*n >= 0 && *n < 1e10)) {
      return usage(std::string("--") + key + " must be a number of people, not '" + *v + "'");
    }
    (key[11] == 'n' ? options.population.night : options.population.day) = *n;
  }
  if (const auto v = args->value("population-source")) {
    if (!options.population.given()) return usage("--population-source needs --population-night or --population-day");
    options.population.source = *v;
  }
  options.accurateSubsteps = args->has("accurate-steps");
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
    if (!options.shakemap.empty()) return usage("give either --shakemap or --epicentre, not both");
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
  } else if (args->has("vs30") || args->has("site-factor")) {
    return usage("--vs30 and --site-factor go with --epicentre");
  }
  if (const auto v = args->value("wave-speed"); v && !options.scenario) {
    const auto x = parseDouble(*v);
    if (!x || *x <= 0.1 || *x > 10.0) return usage("--wave-speed must be in km/s from 0.1 to 10");
    options.shearWaveSpeedKmPerS = *x;
  }
  if (args->has("scale-by") && !options.scenario && options.shakemap.empty()) {
    return usage("--scale-by goes with --shakemap or --epicentre (without them the records are used as given)");
  }
  if (options.pgaG && (options.scenario || !options.shakemap.empty())) {
    return usage(
        "--pga scales the records without a shaking field; with --shakemap or --epicentre the field "
        "sets each building's target");
  }
  if (const auto shard = args->value("shard")) {
    options.shard = parseShardSpec(*shard);
    if (!options.shard) {
      return usage("--shard must be K/N, part K of N parts (1 <= K <= N <= " + std::to_string(kMaxParts) + "), not '" +
                   *shard + "'");
    }
  }
  if (const auto threads = args->value("threads")) {
    const auto v = parseInteger(*threads);
    if (!v || *v < 1 || *v > 256) return usage("--threads must be from 1 to 256");
    options.threads = static_cast<unsigned>(*v);
  }

  if (target != nullptr) {
    options.scenarioIndex = target->index;
    options.scenarioNames = target->names;
  }
  installInterruptHandler();
  const auto report = runCityResponse(*city, options);
  if (!report.ok()) {
    std::fprintf(stderr, "response: %s\n", report.error().c_str());
    return kExitDataError;
  }
  return printReport(*city, *report, &options);
}

int printReport(const std::string& city, const ResponseRunReport& r, const ResponseRunOptions* given) {
  if (r.part > 0) {
    const std::size_t scenario = given != nullptr ? given->scenarioIndex : 0;
    const std::string merge =
        "response --city " + city + " --merge" + (scenario > 0 ? " --scenario " + std::to_string(scenario) : "");
    std::printf("part %u of %u written to %s/%s/%s (%llu buildings); the city's response is unchanged until `%s`\n",
                r.part, r.parts, city.c_str(), stagingFolder(scenario).c_str(),
                partFolderName({r.part, r.parts}).c_str(), static_cast<unsigned long long>(r.buildings), merge.c_str());
  } else if (r.parts > 0) {
    std::printf("response merged from %u parts and written to %s/%s\n", r.parts, city.c_str(), r.folder.c_str());
  } else {
    std::printf("response written to %s/%s\n", city.c_str(), r.folder.c_str());
  }
  if (r.part > 0) {
    std::printf(
        "speed       %.1f million storey-steps/s; CPU %.1f s solving (pass one %.1f s, pass two %.1f s), "
        "%.1f s encoding\n",
        r.seconds > 0.0 ? static_cast<double>(r.storeySteps) / r.seconds / 1e6 : 0.0, r.solveSeconds, r.passOneSeconds,
        r.passTwoSeconds, r.encodeSeconds);
    std::printf("time        %.2f s\n", r.seconds);
    return kExitOk;
  }
  std::printf("motion      %s\n", r.motion.c_str());
  std::printf("shaking     %s%s%s\n",
              r.eventType.empty() ? "NOT STATED whether a scenario or an actual event" : r.eventType.c_str(),
              r.scenario.empty() ? "" : ": ", r.scenario.c_str());
  std::printf("scaling     %s\n", r.scaling.c_str());
  if (r.outsideGrid > 0) {
    std::printf("outside     %llu buildings outside the ShakeMap grid have no result (--outside-grid skip)\n",
                static_cast<unsigned long long>(r.outsideGrid));
  }
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
  if (r.frames > 0) {
    std::printf("frames      %zu at %.3f s (%.1f s)\n", r.frames, r.timeStepS,
                static_cast<double>(r.frames - 1) * r.timeStepS);
  }
  std::printf(
      "bytes       %s summaries, %s histories (%.0f B per building), mean rate %.1f Hz; %s before compression\n",
      humanBytes(r.summaryBytes).c_str(), humanBytes(r.historyBytes).c_str(),
      r.buildings > 0 ? static_cast<double>(r.historyBytes) / static_cast<double>(r.buildings) : 0.0,
      r.meanSampleRateHz, humanBytes(r.uncompressedBytes).c_str());
  std::printf(
      "far series  %s of drift series in the tile summaries (%.0f B per building and tile holding it, %.0f "
      "windows a second)\n",
      humanBytes(r.driftSeriesBytes).c_str(),
      r.driftSeriesBuildings > 0 ? static_cast<double>(r.driftSeriesBytes) / static_cast<double>(r.driftSeriesBuildings)
                                 : 0.0,
      static_cast<double>(kDriftSeriesRateHz));
  std::printf(
      "histories   worst error %.2f %% of peak roof displacement, 99th percentile %.2f %% (%.2f encodings a "
      "building)\n",
      100.0 * r.worstRelativeError, 100.0 * r.p99RelativeError,
      r.buildings > 0 ? static_cast<double>(r.encodingAttempts) / static_cast<double>(r.buildings) : 0.0);
  std::printf(
      "speed       %.1f million storey-steps/s (%llu storey-steps; CPU over threads: solving %.1f s (pass one %.1f s, "
      "pass two %.1f s), encoding %.1f s)\n",
      r.seconds > 0.0 ? static_cast<double>(r.storeySteps) / r.seconds / 1e6 : 0.0,
      static_cast<unsigned long long>(r.storeySteps), r.solveSeconds, r.passOneSeconds, r.passTwoSeconds,
      r.encodeSeconds);
  if (r.nonConvergedSteps > 0) {
    std::printf(
        "note        %llu buildings are approximate: %llu solver steps were accepted without Newton convergence "
        "even after splitting them (`info --json` lists the buildings and their residuals)\n",
        static_cast<unsigned long long>(r.approximateBuildings), static_cast<unsigned long long>(r.nonConvergedSteps));
  }
  if (r.losses) {
    const seismic::LossTotals& t = *r.losses;
    auto line = [](const char* label, const seismic::Estimate& e, const char* unit) {
      std::printf("  %-22s %14.1f  (90 %%: %.1f to %.1f)%s\n", label, e.expected, e.low, e.high, unit);
    };
    std::printf("consequences (HAZUS 5.1, %s occupancy; expected, 90 %% interval):\n", r.timeOfDay.c_str());
    const char* states[5] = {"none", "slight", "moderate", "extensive", "complete"};
    for (std::size_t k = 0; k < 5; ++k) line(states[k], t.damageStates[k], " buildings");
    line("collapsed", t.collapsed, " buildings");
    line("tag green", t.tags[0], " buildings");
    line("tag yellow", t.tags[1], " buildings");
    line("tag red", t.tags[2], " buildings");
    line("occupants present", t.occupants, " people");
    std::printf("  %-22s %14.0f night, %.0f day, %.0f commute%s\n", "occupants by time", t.occupantsAt[0],
                t.occupantsAt[1], t.occupantsAt[2], "");
    if (given != nullptr && given->population.given()) {
      const seismic::PopulationFigures& population = given->population;
      std::printf("  %-22s %14s night, %s day (%s)\n", "population given",
                  population.night >= 0 ? std::to_string(std::llround(population.night)).c_str() : "-",
                  population.day >= 0 ? std::to_string(std::llround(population.day)).c_str() : "-",
                  population.source.empty() ? "no source given" : population.source.c_str());
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const std::string label = "injuries severity " + std::to_string(k + 1);
      line(label.c_str(), t.injuries[k], " people");
    }
    line("deaths", t.injuries[3], " people");
    std::printf("  %-22s %14.3f  (90 %%: %.3f to %.3f) million USD\n", "repair cost", t.repairCostUsd.expected / 1e6,
                t.repairCostUsd.low / 1e6, t.repairCostUsd.high / 1e6);
  }
  if (!r.districtsSource.empty()) std::printf("districts   the city's own: %s\n", r.districtsSource.c_str());
  std::printf("time        %.2f s\n", r.seconds);
  return kExitOk;
}

}  // namespace
}  // namespace qv::prep
