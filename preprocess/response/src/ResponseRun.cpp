#include "qv/prep/ResponseRun.h"

#include "ResponseFinish.h"
#include "ShakingField.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

#include <time.h>

#include "qv/format/CityTile.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Consequences.h"
#include "qv/prep/Files.h"
#include "qv/prep/HistoryEncoder.h"
#include "qv/prep/Projection.h"
#include "qv/prep/ResponseParts.h"
#include "qv/prep/ResponseWriter.h"
#include "qv/prep/ShakeMap.h"
#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/GroundMotionReader.h"
#include "qv/seismic/ResponseSolver.h"
#include "qv/seismic/ResponseSpectrum.h"
#include "qv/seismic/SyntheticMotion.h"

namespace qv::prep {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// CPU seconds of the calling thread: solve and encode times are reported as CPU time, so they
// stay meaningful when other processes share the cores.
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// A base higher than this above ground (minHeightM) is a part resting on another building.
constexpr float kMaxGroundBaseM = 0.5f;

// Free vibration kept after the last building's record ends, so the motion visibly dies down.
constexpr double kTailSeconds = 4.0;
// The Y model is 10 % more flexible than the X model: buildings are rarely equally stiff in both
// directions, and identical models would sway along one diagonal.
constexpr double kYPeriodFactor = 1.1;

std::string describeScenario(const seismic::Scenario& s) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "M%.1f at %.4f, %.4f, depth %.0f km (BSSA14 PGA, S waves %.1f km/s)",
                s.magnitude, s.epicentreLongitudeDeg, s.epicentreLatitudeDeg, s.depthKm, s.shearWaveSpeedKmPerS);
  return buffer;
}

// What the response files say about a record: its file name (never the directory: the files travel
// to every viewer) and, for a PEER file, the title its header gives (e.g. "KOBE, 01/16/1995,
// Takatori, 000").
std::string describeRecord(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string text = slash == std::string::npos ? path : path.substr(slash + 1);
  auto lines = readTextFile(path, 64ull << 20);
  if (!lines.ok()) return text;
  std::vector<std::string> header;
  std::size_t at = 0;
  while (header.size() < 4 && at < lines->size()) {
    const std::size_t end = std::min(lines->find('\n', at), lines->size());
    std::string line = lines->substr(at, end - at);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    header.push_back(first == std::string::npos ? std::string() : line.substr(first));
    at = end + 1;
  }
  // PEER AT2: four header lines, the fourth "NPTS= ..., DT= ..."; the title is the second line of
  // NGA files (the first says "PEER NGA STRONG MOTION DATABASE RECORD"), else the first.
  if (header.size() == 4 && header[3].rfind("NPTS", 0) == 0) {
    const bool nga = header[0].find("PEER") != std::string::npos;
    std::string title = nga ? header[1] : header[0];
    if (title.size() > 120) title.resize(120);
    if (!title.empty()) text += " (" + title + ")";
  }
  return text;
}

// One record of the suite: one or two components, and their spectra when scaling by Sa.
struct Record {
  std::string description;
  seismic::GroundMotion x, y;
  bool hasY = false;
  double peakG = 0.0;  // the larger component's peak
  std::optional<seismic::ResponseSpectrum> spectrumX, spectrumY;
};

// The records of --motion and --synthetic. The default suite under a field it can be matched to is
// made later, per site shape (defaultSuiteRecords); here only when it cannot (a ShakeMap without
// PSA fields): the seeds' Kanai-Tajimi motions as they are.
Result<std::vector<Record>> loadRecords(const ResponseRunOptions& options, bool matchedDefaultSuite) {
  std::vector<Record> records;
  if (matchedDefaultSuite) return records;
  for (const std::uint64_t seed : options.syntheticSeeds) {
    seismic::SyntheticMotionParameters p;
    p.seed = seed;
    p.peakGroundAccelerationG = options.pgaG.value_or(0.35);
    auto pair = seismic::generateSyntheticPair(p);
    if (!pair.ok()) return Error{pair.error()};
    Record r;
    r.x = std::move(pair->first);
    r.y = std::move(pair->second);
    r.hasY = true;
    char buffer[192];
    std::snprintf(
        buffer, sizeof buffer, "%ssynthetic Kanai-Tajimi, seed %llu, PGA %.2f g, %.0f s",
        options.defaultSuite ? "built-in default suite (not spectrum-matched: the ShakeMap has no PSA): " : "",
        static_cast<unsigned long long>(p.seed), p.peakGroundAccelerationG, p.durationS);
    r.description = buffer;
    records.push_back(std::move(r));
  }
  auto files = detail::expandMotionPaths(options.motions);
  if (!files.ok()) return Error{files.error()};
  if (!options.motionY.empty() && files->size() != 1) {
    return Error{"--motion-y goes with exactly one --motion record, not " + std::to_string(files->size())};
  }
  seismic::GroundMotionReadOptions read;
  read.units = options.units;
  read.timeStepS = options.timeStepS;
  for (const std::string& file : *files) {
    auto x = seismic::readGroundMotionFile(file, read);
    if (!x.ok()) return Error{x.error()};
    Record r;
    r.x = std::move(x).value();
    r.description = describeRecord(file);
    if (!options.motionY.empty()) {
      auto y = seismic::readGroundMotionFile(options.motionY, read);
      if (!y.ok()) return Error{y.error()};
      r.y = std::move(y).value();
      if (std::abs(r.y.timeStepS - r.x.timeStepS) > 1e-9) {
        return Error{options.motionY + ": time step " + std::to_string(r.y.timeStepS) + " s differs from " + file +
                     "'s " + std::to_string(r.x.timeStepS) + " s"};
      }
      r.hasY = true;
      r.description += " + " + describeRecord(options.motionY);
    }
    if (options.pgaG) {
      // Both components scaled by the same factor, so their ratio is kept.
      const double peak = std::max(r.x.peakAbsMps2(), r.hasY ? r.y.peakAbsMps2() : 0.0);
      if (!(peak > 0.0)) return Error{file + ": the record is all zeros, it cannot be scaled to a PGA"};
      const double factor = *options.pgaG * seismic::kGravityMps2 / peak;
      for (double& a : r.x.accelerationMps2) a *= factor;
      for (double& a : r.y.accelerationMps2) a *= factor;
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, ", scaled to PGA %.3f g", *options.pgaG);
      r.description += buffer;
    }
    records.push_back(std::move(r));
  }
  if (records.empty()) return Error{"no record: give --motion FILE... or --synthetic SEED..."};
  // A suite mixes one- and two-component records only if every record has the same components.
  for (Record& r : records) {
    if (r.hasY != records.front().hasY) {
      return Error{r.description + ": every record of a suite needs the same components (X only, or X and Y)"};
    }
    r.peakG = std::max(r.x.peakAbsMps2(), r.hasY ? r.y.peakAbsMps2() : 0.0) / seismic::kGravityMps2;
    if (!(r.peakG > 0.0)) return Error{r.description + ": the record is all zeros"};
  }
  return records;
}

// Runs `work` on `threads` threads (0: all cores), this one included, and waits for them all.
template <typename Work>
void runOnThreads(unsigned threads, Work& work) {
  const unsigned n = threads > 0 ? threads : usableCores();
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < n; ++t) pool.emplace_back(std::ref(work));
  work();
  for (std::thread& t : pool) t.join();
}

// The response spectra a record's scaling by Sa(T1) reads.
Status computeSpectra(Record& r) {
  auto x = seismic::ResponseSpectrum::compute(r.x);
  if (!x.ok()) return fail(r.description + ": " + x.error());
  r.spectrumX = std::move(x).value();
  if (r.hasY) {
    auto y = seismic::ResponseSpectrum::compute(r.y);
    if (!y.ok()) return fail(r.description + ": " + y.error());
    r.spectrumY = std::move(y).value();
  }
  return {};
}

// The default suite matched to every site shape of the city (DefaultSuite.h), with the spectra
// for scaling: suites[shapeIndex[shape]][seed's place]. The shapes x seeds are spread over the
// threads; each record depends on its shape and seed only, so the result does not depend on them.
Result<std::vector<std::vector<Record>>> matchDefaultSuite(const std::map<SiteShape, std::size_t>& shapeIndex,
                                                           const ResponseRunOptions& options) {
  const std::size_t seeds = std::size(kDefaultSuiteSeeds);
  std::vector<std::pair<SiteShape, std::size_t>> shapes(shapeIndex.begin(), shapeIndex.end());
  std::vector<std::vector<Record>> suites(shapes.size(), std::vector<Record>(seeds));
  std::vector<TargetSpectrum> targets;
  const seismic::Scenario* scenario = options.scenario ? &*options.scenario : nullptr;
  for (const auto& [shape, index] : shapes) targets.push_back(shapeTarget(shape, scenario));
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::string firstError;
  Progress progress("matching the default suite to " + std::to_string(shapes.size()) + " site shapes",
                    shapes.size() * seeds);
  std::atomic<std::uint64_t> done{0};
  auto work = [&] {
    for (std::size_t task = next++; task < shapes.size() * seeds; task = next++) {
      if (interrupted()) return;
      const std::size_t s = task / seeds, k = task % seeds;
      auto matched = defaultSuiteRecord(kDefaultSuiteSeeds[k], targets[s]);
      Record r;
      if (matched.ok()) {
        r.x = std::move(matched->x);
        r.y = std::move(matched->y);
        r.hasY = true;
        r.peakG = std::max(r.x.peakAbsMps2(), r.y.peakAbsMps2()) / seismic::kGravityMps2;
        char buffer[192];
        std::snprintf(buffer, sizeof buffer,
                      "built-in default suite: synthetic Kanai-Tajimi, seed %llu, spectrum-matched to each site's "
                      "target (%zu site shape%s), %.0f s",
                      static_cast<unsigned long long>(kDefaultSuiteSeeds[k]), shapes.size(),
                      shapes.size() == 1 ? "" : "s", r.x.durationS());
        r.description = buffer;
      }
      const Status status = matched.ok() ? computeSpectra(r) : fail(matched.error());
      if (!status.ok()) {
        const std::lock_guard lock(mutex);
        if (firstError.empty()) firstError = "default suite: " + status.error();
        return;
      }
      suites[shapes[s].second][k] = std::move(r);
      progress.update(++done);
    }
  };
  runOnThreads(options.threads, work);
  progress.finish();
  if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
  if (!firstError.empty()) return Error{firstError};
  return suites;
}

// Geometric mean and standard deviation of the logarithms (values floored at `floor`).
std::pair<double, double> logStats(std::span<const double> values, double floor) {
  if (values.empty()) return {0.0, 0.0};
  if (values.size() == 1) return {values[0], 0.0};  // one record: its own value, exactly
  double sum = 0.0;
  for (const double v : values) sum += std::log(std::max(v, floor));
  const double mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (const double v : values)
    squares += (std::log(std::max(v, floor)) - mean) * (std::log(std::max(v, floor)) - mean);
  const double beta = values.size() > 1 ? std::sqrt(squares / static_cast<double>(values.size() - 1)) : 0.0;
  return {std::exp(mean), beta};
}

// What pass one keeps of a building under one record: peaks only.
struct Peaks {
  std::vector<double> storeyDrift;        // per storey, max over directions
  std::vector<double> floorAcceleration;  // per floor, m/s², max over directions
  double maxDrift = 0.0, maxAcceleration = 0.0, roof = 0.0;
};

Peaks peaksOf(const seismic::BuildingResponse& r) {
  Peaks p;
  p.storeyDrift.assign(r.storeys, 0.0);
  p.floorAcceleration.assign(r.storeys, 0.0);
  for (std::size_t s = 0; s < r.storeys; ++s) {
    double drift = s < r.x.peakDriftRatio.size() ? r.x.peakDriftRatio[s] : 0.0;
    double acceleration =
        s < r.x.peakFloorAccelerationPerFloorMps2.size() ? r.x.peakFloorAccelerationPerFloorMps2[s] : 0.0;
    if (r.hasY) {
      if (s < r.y.peakDriftRatio.size()) drift = std::max(drift, static_cast<double>(r.y.peakDriftRatio[s]));
      if (s < r.y.peakFloorAccelerationPerFloorMps2.size())
        acceleration = std::max(acceleration, static_cast<double>(r.y.peakFloorAccelerationPerFloorMps2[s]));
    }
    p.storeyDrift[s] = drift;
    p.floorAcceleration[s] = acceleration;
    p.maxDrift = std::max(p.maxDrift, drift);
    p.maxAcceleration = std::max(p.maxAcceleration, acceleration);
  }
  p.roof = std::max(r.x.peakRoofDisplacementM, r.hasY ? r.y.peakRoofDisplacementM : 0.0f);
  return p;
}

// A building of a tile that is analysed: its models, site and per-record shaking.
struct Analysed {
  std::size_t index = 0;  // in the tile
  seismic::ShearBuilding x, y;
  double periodS[2] = {0.0, 0.0};
  double targetSaG[2] = {0.0, 0.0};
  std::vector<seismic::BuildingShaking> shaking;  // per record
  std::vector<std::array<double, 2>> recordSaG;   // per record, X and Y
  std::vector<Peaks> peaks;                       // per record (pass one)
  std::size_t shown = 0;                          // the record whose history is stored
  std::size_t shape = 0;                          // its site shape's suite (shapeSuites)
  detail::ShakingField::Site site;
};

constexpr double kDriftFloor = 1e-7;         // log statistics: drift ratios below are taken as this
constexpr double kAccelerationFloor = 1e-4;  // m/s²

}  // namespace

Result<std::vector<std::string>> detail::expandMotionPaths(const std::vector<std::string>& paths) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  for (const std::string& path : paths) {
    std::error_code ec;
    if (!fs::is_directory(path, ec)) {
      out.push_back(path);
      continue;
    }
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(path, ec)) {
      const std::string name = e.path().filename().string();
      if (!name.empty() && name[0] != '.' && e.is_regular_file(ec)) files.push_back(e.path().string());
    }
    if (ec) return Error{path + ": cannot list the folder (" + ec.message() + ")"};
    if (files.empty()) return Error{path + ": the folder holds no record files"};
    std::sort(files.begin(), files.end());
    out.insert(out.end(), files.begin(), files.end());
  }
  if (out.size() > 100) return Error{"--motion: " + std::to_string(out.size()) + " records (at most 100 in a suite)"};
  return out;
}

Result<ResponseRunReport> runCityResponse(const std::string& dir, const ResponseRunOptions& given) {
  const auto start = Clock::now();
  ResponseRunReport report;
  auto text = readTextFile(dir + "/tileset.json", 256ull << 20);
  if (!text.ok()) return Error{text.error() + " (is " + dir + " a QuakeView city directory?)"};
  auto parsed = parseTileset(*text, dir + "/tileset.json");
  if (!parsed.ok()) return Error{parsed.error()};
  const Tileset tileset = std::move(parsed).value();
  // Without --districts, the city's own (made from its input: qv/prep/DefaultDistricts.h). Every
  // part of a sharded run decides the same, so the parts agree on them.
  ResponseRunOptions options = given;
  if (options.districts.empty() && tileset.districts) {
    options.districts = dir + "/" + tileset.districts->file.file;
    report.districtsSource = tileset.districts->source;
  }

  std::optional<ShakeMapGrid> grid;
  if (!options.shakemap.empty()) {
    auto g = readShakeMapGrid(options.shakemap);
    if (!g.ok()) return Error{g.error()};
    if (options.scaleBy == ScaleBy::SpectralAcceleration && !g->hasSpectra()) {
      return Error{options.shakemap +
                   ": the grid has no PSA03, PSA10 and PSA30 fields, which scaling by Sa(T1) needs (or give "
                   "--scale-by pga)"};
    }
    grid = std::move(g).value();
  }
  const detail::ShakingField field(options, tileset, grid);
  const bool matchedSuite = options.defaultSuite && field.matchable();
  auto loaded = loadRecords(options, matchedSuite);
  if (!loaded.ok()) return Error{loaded.error()};
  // The suite of each site shape: one shape (every building under the same records) unless the
  // default suite is matched per shape (DefaultSuite.h).
  std::vector<std::vector<Record>> shapeSuites;
  std::map<SiteShape, std::size_t> shapeIndex;
  std::vector<std::uint32_t> leaves;
  std::uint64_t totalBuildings = 0;
  for (std::uint32_t i = 0; i < tileset.nodes.size(); ++i) {
    if (tileset.nodes[i].children.empty()) {
      leaves.push_back(i);
      totalBuildings += tileset.nodes[i].buildings;
    }
  }
  // One pass over the buildings' sites before the analysis: those outside the ShakeMap (an error
  // naming how many, unless --outside-grid skip) and the shapes the default suite is matched to.
  std::vector<std::uint64_t> shapeBuildings;
  if ((grid && options.outsideGrid == OutsideGrid::Error) || matchedSuite) {
    std::uint64_t outside = 0;
    std::map<SiteShape, std::uint64_t> shapes;
    for (const std::uint32_t node : leaves) {
      const std::string path = dir + "/" + tileset.nodes[node].file;
      auto bytes = readFile(path);
      if (!bytes.ok()) return Error{bytes.error()};
      auto tile = decodeCityTile(*bytes, path);
      if (!tile.ok()) return Error{tile.error()};
      for (const TileBuilding& b : tile->buildings) {
        auto site = field.site(b.attributes.centroidX + tile->originX, b.attributes.centroidY + tile->originY);
        if (site.ok() && !site->has_value()) ++outside;
        if (matchedSuite && site.ok() && site->has_value()) ++shapes[field.shape(**site)];
      }
    }
    if (grid && options.outsideGrid == OutsideGrid::Error && outside > 0) {
      return Error{options.shakemap + ": " + std::to_string(outside) + " of the city's " +
                   std::to_string(totalBuildings) + " buildings lie outside the grid (" + grid->describeExtent() +
                   "); give --outside-grid skip to leave them without a result"};
    }
    for (const auto& [shape, count] : shapes) {
      shapeIndex.emplace(shape, shapeBuildings.size());
      shapeBuildings.push_back(count);
    }
  }
  if (matchedSuite) {
    if (shapeBuildings.empty()) return Error{"no building of the city lies in the shaking field"};
    auto suites = matchDefaultSuite(shapeIndex, options);
    if (!suites.ok()) return Error{suites.error()};
    shapeSuites = std::move(suites).value();
  } else {
    shapeSuites.push_back(std::move(loaded).value());
    if (field.spectral()) {
      for (Record& r : shapeSuites[0]) {
        if (Status s = computeSpectra(r); !s.ok()) return Error{s.error()};
      }
    }
  }
  const std::vector<Record>& records = shapeSuites[0];
  // The record shown as the input's plot: of the shape most buildings have.
  const std::size_t commonShape =
      static_cast<std::size_t>(std::max_element(shapeBuildings.begin(), shapeBuildings.end()) - shapeBuildings.begin());
  report.records = records.size();
  report.motion = records.size() == 1
                      ? records[0].description
                      : std::to_string(records.size()) + " records: " + records[0].description + ", ...";
  if (options.scenario) {
    report.scenario = describeScenario(*options.scenario);
    report.eventType = "SCENARIO";
  } else if (grid) {
    const ShakeMapEvent& e = grid->event;
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "ShakeMap %s version %s (%s): M%.1f at %.4f, %.4f, depth %.0f km",
                  e.eventId.c_str(), e.shakemapVersion.c_str(), std::string(shakeMapEventTypeName(e.type)).c_str(),
                  e.magnitude, e.longitudeDeg, e.latitudeDeg, e.depthKm);
    report.scenario = buffer;
    // Never guessed: a grid that does not say whether it is a scenario leaves the type unstated.
    report.eventType = e.type == ShakeMapEventType::Actual     ? "ACTUAL"
                       : e.type == ShakeMapEventType::Scenario ? "SCENARIO"
                                                               : "";
  } else {
    report.eventType = "SCENARIO";  // records chosen by the user: a scenario, not an event's own shaking
  }
  report.scaling = !field.present() ? "records as given"
                   : field.spectral()
                       ? "each record scaled to the target Sa(T1) at each building's first-mode period, per direction"
                       : "each record scaled to the target PGA at each building";

  // The output step: the finest record step; the time axis covers the last arrival and the longest record.
  double dt = records[0].x.timeStepS;
  double longest = 0.0;
  for (const Record& r : records) {
    dt = std::min(dt, r.x.timeStepS);
    longest = std::max(longest, std::max(r.x.durationS(), r.hasY ? r.y.durationS() : 0.0));
  }
  const double maxDelay = field.maxDelayS(tileset);
  const auto frames = static_cast<std::size_t>(std::ceil((maxDelay + longest + dt + kTailSeconds) / dt)) + 1;
  report.frames = frames;
  report.timeStepS = dt;

  std::optional<Districts> districts;
  if (!options.districts.empty()) {
    auto d = readDistricts(options.districts);
    if (!d.ok()) return Error{d.error()};
    districts = std::move(d).value();
  }

  // A part of a sharded run: its leaves only (ResponseParts.h), written into the city's staging
  // area. Everything above (the suite, the time axis, the outside-grid check) is the whole city's.
  std::optional<detail::PartRun> part;
  if (options.shard) {
    auto begun = detail::PartRun::begin(dir, tileset, options, *options.shard);
    if (!begun.ok()) return Error{begun.error()};
    part.emplace(std::move(begun).value());
    leaves = part->leaves();
    totalBuildings = 0;
    for (const std::uint32_t node : leaves) totalBuildings += tileset.nodes[node].buildings;
  }
  auto writer = part ? ResponseWriter::createPart(dir, tileset, part->folder()) : ResponseWriter::create(dir, tileset);
  if (!writer.ok()) return Error{writer.error()};
  if (options.scenarioIndex > 0) (*writer)->setScenario(options.scenarioIndex, options.scenarioNames);
  // Big tiles first, for an even finish across threads.
  std::sort(leaves.begin(), leaves.end(),
            [&](std::uint32_t a, std::uint32_t b) { return tileset.nodes[a].buildings > tileset.nodes[b].buildings; });

  std::atomic<std::size_t> next{0};
  std::atomic<std::uint64_t> buildingsDone{0};
  std::mutex mutex;
  std::string firstError;
  std::vector<double> relativeErrors;
  relativeErrors.reserve(static_cast<std::size_t>(totalBuildings));
  std::vector<seismic::BuildingLoss> losses;                      // every building with a result
  std::vector<int> lossDistrict;                                  // its district (-1: none)
  std::vector<std::uint64_t> lossKey;                             // its leaf and index there (the order of the totals)
  std::vector<LossClass> lossClass;                               // its occupancy class, type and inferred attributes
  std::vector<detail::LeafRate> leafRates(tileset.nodes.size());  // written per leaf by its one thread
  const bool suite = records.size() > 1;
  Progress progress("solving buildings", totalBuildings);

  auto worker = [&] {
    seismic::ResponseOptions historyOptions;
    historyOptions.outputStepS = dt;
    historyOptions.frameCount = frames;
    historyOptions.floorDisplacements = true;
    seismic::ResponseSolver historySolver(historyOptions);
    seismic::ResponseOptions peakOptions = historyOptions;
    peakOptions.floorDisplacements = false;
    seismic::ResponseSolver peakSolver(peakOptions);
    HistoryEncodingOptions encoding;
    encoding.toleranceFraction = options.historyTolerance;
    std::vector<double> localErrors;
    std::vector<seismic::BuildingLoss> localLosses;
    std::vector<int> localDistricts;
    std::vector<std::uint64_t> localKeys;
    std::vector<LossClass> localClasses;
    double localSolve = 0.0, localEncode = 0.0, localLoss = 0.0, localPassOne = 0.0;
    std::uint64_t localStoreySteps = 0;  // storeys × record steps × directions
    std::uint64_t localAttempts = 0;
    std::uint64_t localOutside = 0;
    auto setError = [&](std::string message) {
      const std::lock_guard lock(mutex);
      if (firstError.empty()) firstError = std::move(message);
    };
    for (std::size_t k = next++; k < leaves.size(); k = next++) {
      if (interrupted()) return;
      {
        const std::lock_guard lock(mutex);
        if (!firstError.empty()) return;
      }
      const std::uint32_t node = leaves[k];
      const TileNode& n = tileset.nodes[node];
      auto bytes = readFile(dir + "/" + n.file);
      Result<CityTile> tile =
          bytes.ok() ? decodeCityTile(*bytes, dir + "/" + n.file) : Result<CityTile>(Error{bytes.error()});
      if (!tile.ok()) return setError(tile.error());
      std::vector<BuildingResult> results(tile->buildings.size());
      std::vector<Analysed> analysed;
      for (std::size_t b = 0; b < tile->buildings.size(); ++b) {
        const BuildingAttributes& a = tile->buildings[b].attributes;
        BuildingResult& result = results[b];
        auto noResult = [&](NoResultReason reason, std::string detail) {
          result.summary.noResultReason = reason;
          result.noResultDetail = std::move(detail);
        };
        // The field at the site, kept with or without a result (an engineer checking a building
        // that could not be modelled still reads the shaking there).
        auto site = field.site(a.centroidX + tile->originX, a.centroidY + tile->originY);
        if (site.ok() && site->has_value() && (**site).intensity.given()) result.site = (**site).intensity;
        // A part whose base is above ground (a rooftop structure on another building) would be
        // shaken by that building's roof motion, not by the ground's: not analysed.
        if (a.minHeightM > kMaxGroundBaseM) {
          char detail[96];
          std::snprintf(detail, sizeof detail, "base %.1f m above ground", static_cast<double>(a.minHeightM));
          noResult(NoResultReason::BaseAboveGround, detail);
          continue;
        }
        seismic::BuildingModelOptions modelOptions;
        auto mx = seismic::buildingModelFromAttributes(a, modelOptions);
        modelOptions.periodFactor = kYPeriodFactor;
        auto my = seismic::buildingModelFromAttributes(a, modelOptions);
        if (!mx.ok() || !my.ok()) {
          noResult(NoResultReason::ModelInvalid, !mx.ok() ? mx.error() : my.error());
          continue;
        }
        if (!site.ok()) {
          noResult(NoResultReason::OutsideField, site.error());
          continue;
        }
        if (!site->has_value()) {
          ++localOutside;
          noResult(NoResultReason::OutsideField, "outside the ShakeMap grid (" + grid->describeExtent() + ")");
          continue;
        }
        Analysed item;
        item.index = b;
        item.site = **site;
        item.x = std::move(mx).value();
        item.y = std::move(my).value();
        if (field.spectral()) {
          for (int d = 0; d < 2; ++d) {
            auto period = seismic::firstModePeriodS(d == 0 ? item.x : item.y);
            if (!period.ok()) return setError("building " + a.id + ": " + period.error());
            item.periodS[d] = *period;
            item.targetSaG[d] = field.targetSaG(item.site, *period);
          }
        }
        if (matchedSuite) item.shape = shapeIndex.at(field.shape(item.site));
        bool scalable = true;
        for (const Record& r : shapeSuites[item.shape]) {
          seismic::BuildingShaking shaking;
          shaking.delaySeconds = item.site.delayS;
          std::array<double, 2> recordSa{0.0, 0.0};
          if (field.spectral()) {
            std::array<double, 2> scale{0.0, 0.0};
            for (int d = 0; d < (r.hasY ? 2 : 1); ++d) {
              const auto axis = static_cast<std::size_t>(d);
              recordSa[axis] = (d == 0 ? r.spectrumX : r.spectrumY)->saG(item.periodS[d]);
              const auto scaling = seismic::spectralScaling(item.targetSaG[d], recordSa[axis]);
              if (scaling.ok())
                scale[axis] = scaling->scale;
              else
                scalable = false;
            }
            if (scalable) {
              shaking.scale = scale[0];
              if (r.hasY) shaking.scaleY = scale[1];
            }
          } else if (field.present()) {
            shaking.scale = item.site.pgaG / r.peakG;
          }
          item.shaking.push_back(shaking);
          item.recordSaG.push_back(recordSa);
        }
        if (!scalable) {
          noResult(NoResultReason::OutsideField, "no positive target or record Sa at the building's period");
          continue;
        }
        analysed.push_back(std::move(item));
      }

      // Pass one (suites): every record, peaks only.
      const double solveStart = threadCpuSeconds();
      double encodeTime = 0.0;
      std::vector<seismic::ShearBuilding> modelsX, modelsY;
      std::vector<seismic::BuildingShaking> shaking;
      std::vector<std::size_t> members;
      auto gather = [&](std::size_t record, const std::vector<std::size_t>& which) {
        modelsX.clear();
        modelsY.clear();
        shaking.clear();
        for (const std::size_t i : which) {
          modelsX.push_back(analysed[i].x);
          modelsY.push_back(analysed[i].y);
          shaking.push_back(analysed[i].shaking[record]);
        }
      };
      std::vector<std::uint32_t> unconverged(analysed.size(), 0);
      std::vector<float> worstResidual(analysed.size(), 0.0f);
      if (suite) {
        for (std::size_t r = 0; r < records.size(); ++r) {
          for (std::size_t c = 0; c < shapeSuites.size(); ++c) {
            members.clear();
            for (std::size_t i = 0; i < analysed.size(); ++i) {
              if (analysed[i].shape == c) members.push_back(i);
            }
            if (members.empty()) continue;
            gather(r, members);
            const Record& record = shapeSuites[c][r];
            const Status solved = peakSolver.solve(
                modelsX, shaking, record.x, record.hasY ? &record.y : nullptr,
                [&](std::size_t m, const seismic::BuildingResponse& response) {
                  const std::size_t i = members[m];
                  analysed[i].peaks.push_back(peaksOf(response));
                  unconverged[i] += response.nonConvergedSteps;
                  worstResidual[i] = std::max(worstResidual[i], response.worstResidualRatio);
                  localStoreySteps += response.storeys * response.frames * (response.hasY ? 2u : 1u);
                },
                modelsY);
            if (!solved.ok()) return setError("tile " + n.key() + ": " + solved.error());
          }
        }
        for (Analysed& item : analysed) {
          std::vector<double> roofs;
          for (const Peaks& p : item.peaks) roofs.push_back(p.roof);
          const double median = logStats(roofs, 1e-9).first;
          double best = std::numeric_limits<double>::infinity();
          for (std::size_t r = 0; r < roofs.size(); ++r) {
            const double distance = std::abs(std::log(std::max(roofs[r], 1e-9)) - std::log(median));
            if (distance < best) {
              best = distance;
              item.shown = r;
            }
          }
        }
      }

      localPassOne += threadCpuSeconds() - solveStart;

      // Pass two: the stored history, each building under its shown record.
      for (std::size_t r = 0; r < records.size(); ++r) {
        for (std::size_t c = 0; c < shapeSuites.size(); ++c) {
          members.clear();
          for (std::size_t i = 0; i < analysed.size(); ++i) {
            if (analysed[i].shown == r && analysed[i].shape == c) members.push_back(i);
          }
          if (members.empty()) continue;
          gather(r, members);
          const Record& record = shapeSuites[c][r];
          const Status solved = historySolver.solve(
              modelsX, shaking, record.x, record.hasY ? &record.y : nullptr,
              [&](std::size_t m, const seismic::BuildingResponse& response) {
                const double encodeStart = threadCpuSeconds();
                const std::size_t i = members[m];
                Analysed& item = analysed[i];
                if (!suite) {
                  item.peaks = {peaksOf(response)};
                  unconverged[i] = response.nonConvergedSteps;
                  worstResidual[i] = response.worstResidualRatio;
                  localStoreySteps += response.storeys * response.frames * (response.hasY ? 2u : 1u);
                }
                BuildingResult& out = results[item.index];
                const std::span<const float> y =
                    response.hasY ? std::span<const float>(response.y.floorDisplacementM) : std::span<const float>();
                EncodedHistory h = encodeHistory(response.x.floorDisplacementM, y, response.storeys, response.frames,
                                                 response.timeStepS, encoding);
                out.history = std::move(h.history);
                // Across the suite: medians and log standard deviations of the peaks.
                std::vector<double> values(item.peaks.size());
                auto stats = [&](auto pick, double floor) {
                  for (std::size_t q = 0; q < item.peaks.size(); ++q) values[q] = pick(item.peaks[q]);
                  return logStats(values, floor);
                };
                const auto [medianDrift, driftBeta] = stats([](const Peaks& p) { return p.maxDrift; }, kDriftFloor);
                const auto [medianAcceleration, accelerationBeta] =
                    stats([](const Peaks& p) { return p.maxAcceleration; }, kAccelerationFloor);
                out.summary.source = ResponseSource::Model;
                out.summary.storeys = static_cast<std::uint16_t>(response.storeys);
                out.summary.damage = seismic::classifyDamage(medianDrift, item.x.damageDriftThresholds);
                out.summary.peakDriftRatio = static_cast<float>(medianDrift);
                out.summary.peakRoofDisplacementM = static_cast<float>(h.peakRoofM);
                out.summary.peakFloorAccelerationMs2 = static_cast<float>(medianAcceleration);
                const double appliedX = record.x.peakAbsMps2() * item.shaking[r].scale;
                const double appliedY =
                    record.hasY ? record.y.peakAbsMps2() *
                                      (item.shaking[r].scaleY > 0.0 ? item.shaking[r].scaleY : item.shaking[r].scale)
                                : 0.0;
                out.summary.pgaG = static_cast<float>(std::max(appliedX, appliedY) / seismic::kGravityMps2);
                out.storeyPeakDrift.assign(response.storeys, 0.0f);
                out.storeySpread.assign(response.storeys, StoreySpread{});
                float residual = 0.0f;
                for (std::size_t s = 0; s < response.storeys; ++s) {
                  const auto [drift, beta] = stats([s](const Peaks& p) { return p.storeyDrift[s]; }, kDriftFloor);
                  const auto [acceleration, aBeta] =
                      stats([s](const Peaks& p) { return p.floorAcceleration[s]; }, kAccelerationFloor);
                  out.storeyPeakDrift[s] = static_cast<float>(drift);
                  out.storeySpread[s] = {static_cast<float>(beta), static_cast<float>(acceleration),
                                         static_cast<float>(aBeta)};
                  float res =
                      s < response.x.residualDriftRatio.size() ? std::abs(response.x.residualDriftRatio[s]) : 0.0f;
                  if (response.hasY && s < response.y.residualDriftRatio.size())
                    res = std::max(res, std::abs(response.y.residualDriftRatio[s]));
                  residual = std::max(residual, res);
                }
                out.summary.residualDriftRatio = residual;
                out.summary.noResultReason = NoResultReason::None;
                out.summary.approximate = unconverged[i] > 0;
                out.summary.unconvergedSteps = unconverged[i];
                out.summary.worstResidualRatio = worstResidual[i];
                out.spread = BuildingSpread{static_cast<std::uint16_t>(records.size()), static_cast<std::uint16_t>(r),
                                            static_cast<float>(driftBeta), static_cast<float>(accelerationBeta)};
                BuildingScaling scaling;
                for (int d = 0; d < (record.hasY ? 2 : 1); ++d) {  // one component: Y is not analysed
                  scaling.periodS[d] = static_cast<float>(item.periodS[d]);
                  scaling.targetSaG[d] = static_cast<float>(item.targetSaG[d]);
                  scaling.recordSaG[d] = static_cast<float>(item.recordSaG[r][static_cast<std::size_t>(d)]);
                  scaling.scale[d] = static_cast<float>(d == 1 && item.shaking[r].scaleY > 0.0 ? item.shaking[r].scaleY
                                                                                               : item.shaking[r].scale);
                }
                out.scaling = scaling;
                localErrors.push_back(h.relativeError());
                localAttempts += static_cast<std::uint64_t>(h.attempts);
                leafRates[node].sum += out.history.sampleRateHz;
                ++leafRates[node].count;
                encodeTime += threadCpuSeconds() - encodeStart;
                // HAZUS probabilities and consequences from the suite's medians and spread.
                const double lossStart = threadCpuSeconds();
                const BuildingAttributes& a = tile->buildings[item.index].attributes;
                const seismic::Exposure exposure = seismic::exposureFromAttributes(
                    a, static_cast<int>(response.storeys), buildingFloorAreaM2(*tile, tile->buildings[item.index]));
                const seismic::BuildingLoss loss =
                    seismic::assessLoss(exposure, medianDrift, medianAcceleration / seismic::kGravityMps2, driftBeta,
                                        accelerationBeta, options.timeOfDay);
                out.loss = toSummaryLoss(loss);
                localLosses.push_back(loss);
                localKeys.push_back((std::uint64_t{node} << 32) | static_cast<std::uint64_t>(item.index));
                localClasses.push_back(LossClass::of(exposure));
                if (districts) {
                  const auto lonLat =
                      field.projection().reverse({a.centroidX + tile->originX, a.centroidY + tile->originY});
                  localDistricts.push_back(districts->find(lonLat[0], lonLat[1]));
                }
                localLoss += threadCpuSeconds() - lossStart;
                progress.update(++buildingsDone);
              },
              modelsY);
          if (!solved.ok()) return setError("tile " + n.key() + ": " + solved.error());
        }
      }
      localSolve += threadCpuSeconds() - solveStart - encodeTime;
      localEncode += encodeTime;
      if (Status s = (*writer)->writeLeaf(node, *tile, results); !s.ok()) return setError(s.error());
    }
    const std::lock_guard lock(mutex);
    relativeErrors.insert(relativeErrors.end(), localErrors.begin(), localErrors.end());
    losses.insert(losses.end(), localLosses.begin(), localLosses.end());
    lossDistrict.insert(lossDistrict.end(), localDistricts.begin(), localDistricts.end());
    lossKey.insert(lossKey.end(), localKeys.begin(), localKeys.end());
    lossClass.insert(lossClass.end(), localClasses.begin(), localClasses.end());
    report.solveSeconds += localSolve;
    report.encodeSeconds += localEncode;
    report.lossSeconds += localLoss;
    report.storeySteps += localStoreySteps;
    report.encodingAttempts += localAttempts;
    report.outsideGrid += localOutside;
    report.passOneSeconds += localPassOne;
    report.nonConvergedSteps += historySolver.stats().nonConvergedSteps + peakSolver.stats().nonConvergedSteps;
  };
  runOnThreads(options.threads, worker);
  progress.finish();
  if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
  if (!firstError.empty()) return Error{firstError};

  ResponseInfo info;
  info.motion = report.motion;
  info.scenario = report.scenario;
  info.method = suite ? "MDOF shear building, Bouc-Wen storeys, Newmark average acceleration; medians over " +
                            std::to_string(records.size()) + " records"
                      : "MDOF shear building, Bouc-Wen storeys, Newmark average acceleration";
  info.eventType = report.eventType;
  info.shakingField = options.scenario ? "scenario" : grid ? "shakemap" : "record";
  info.scaling = !field.present() ? "" : field.spectral() ? "sa" : "pga";
  for (const Record& r : records) info.records.push_back(r.description);
  info.timeOfDay = std::string(seismic::timeOfDayName(options.timeOfDay));
  if (grid) {
    const ShakeMapEvent& e = grid->event;
    ResponseInfo::ShakeMap m;
    m.eventId = e.eventId;
    m.version = e.shakemapVersion;
    m.processTimestamp = e.processTimestamp;
    m.eventTimestamp = e.eventTimestamp;
    m.description = e.description;
    m.source = e.network;
    m.magnitude = std::isfinite(e.magnitude) ? e.magnitude : 0.0;
    m.depthKm = std::isfinite(e.depthKm) ? e.depthKm : 0.0;
    m.latitudeDeg = std::isfinite(e.latitudeDeg) ? e.latitudeDeg : 0.0;
    m.longitudeDeg = std::isfinite(e.longitudeDeg) ? e.longitudeDeg : 0.0;
    info.shakemap = m;
  }
  info.durationSeconds = static_cast<double>(frames - 1) * dt;
  // The input record for the viewer's plot: the largest |a| of every 0.1 s, in g.
  info.motionPreviewRateHz = 10.0;
  const seismic::GroundMotion& preview = shapeSuites[commonShape][0].x;
  const auto perWindow = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.1 / preview.timeStepS)));
  for (std::size_t i = 0; i < preview.size(); i += perWindow) {
    double best = 0.0;
    for (std::size_t k = i; k < std::min(preview.size(), i + perWindow); ++k) {
      if (std::abs(preview.accelerationMps2[k]) > std::abs(best)) best = preview.accelerationMps2[k];
    }
    info.motionPreviewG.push_back(static_cast<float>(best / seismic::kGravityMps2));
  }
  report.passTwoSeconds = report.solveSeconds - report.passOneSeconds;
  if (!relativeErrors.empty()) {
    std::sort(relativeErrors.begin(), relativeErrors.end());
    report.worstRelativeError = relativeErrors.back();
    report.p99RelativeError =
        relativeErrors[static_cast<std::size_t>(0.99 * static_cast<double>(relativeErrors.size() - 1))];
  }
  detail::FinishInputs finish;
  finish.info = std::move(info);
  finish.losses.losses = std::move(losses);
  finish.losses.district = std::move(lossDistrict);
  finish.losses.key = std::move(lossKey);
  finish.losses.classes = std::move(lossClass);
  finish.leafRates = std::move(leafRates);
  finish.districts = districts ? &*districts : nullptr;
  finish.population = options.population;
  report.buildings = totalBuildings;
  if (part) {
    report.part = options.shard->part;
    report.parts = options.shard->parts;
    report.seconds = secondsSince(start);
    if (Status s = part->publish(**writer, finish, report); !s.ok()) return Error{s.error()};
  } else if (Status s = detail::finishResponse(**writer, std::move(finish), report); !s.ok()) {
    return Error{s.error()};
  }
  report.seconds = secondsSince(start);
  return report;
}

}  // namespace qv::prep
