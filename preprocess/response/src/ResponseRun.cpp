#include "qv/prep/ResponseRun.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>

#include <time.h>

#include "qv/format/CityTile.h"
#include "qv/format/Tileset.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Files.h"
#include "qv/prep/HistoryEncoder.h"
#include "qv/prep/Projection.h"
#include "qv/prep/ResponseWriter.h"
#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/GroundMotionReader.h"
#include "qv/seismic/ResponseSolver.h"
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

DamageState toFormat(seismic::DamageState d) {
  return static_cast<DamageState>(static_cast<std::uint8_t>(d));
}

}  // namespace

Result<ResponseRunReport> runCityResponse(const std::string& dir, const ResponseRunOptions& options) {
  const auto start = Clock::now();
  ResponseRunReport report;
  auto text = readTextFile(dir + "/tileset.json", 256ull << 20);
  if (!text.ok()) return Error{text.error() + " (is " + dir + " a QuakeView city directory?)"};
  auto parsed = parseTileset(*text, dir + "/tileset.json");
  if (!parsed.ok()) return Error{parsed.error()};
  const Tileset tileset = std::move(parsed).value();

  // The ground motion (two components when available).
  seismic::GroundMotion motionX, motionY;
  bool hasY = false;
  if (options.syntheticSeed) {
    seismic::SyntheticMotionParameters p;
    p.seed = *options.syntheticSeed;
    p.peakGroundAccelerationG = options.pgaG.value_or(0.35);
    auto pair = seismic::generateSyntheticPair(p);
    if (!pair.ok()) return Error{pair.error()};
    motionX = std::move(pair->first);
    motionY = std::move(pair->second);
    hasY = true;
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, "synthetic Kanai-Tajimi, seed %llu, PGA %.2f g, %.0f s",
                  static_cast<unsigned long long>(p.seed), p.peakGroundAccelerationG, p.durationS);
    report.motion = buffer;
  } else {
    seismic::GroundMotionReadOptions read;
    read.units = options.units;
    read.timeStepS = options.timeStepS;
    auto x = seismic::readGroundMotionFile(options.motionX, read);
    if (!x.ok()) return Error{x.error()};
    motionX = std::move(x).value();
    report.motion = describeRecord(options.motionX);
    if (!options.motionY.empty()) {
      auto y = seismic::readGroundMotionFile(options.motionY, read);
      if (!y.ok()) return Error{y.error()};
      motionY = std::move(y).value();
      if (std::abs(motionY.timeStepS - motionX.timeStepS) > 1e-9) {
        return Error{options.motionY + ": time step " + std::to_string(motionY.timeStepS) + " s differs from " +
                     options.motionX + "'s " + std::to_string(motionX.timeStepS) + " s"};
      }
      hasY = true;
      report.motion += " + " + describeRecord(options.motionY);
    }
    if (options.pgaG) {
      // Both components scaled by the same factor, so their ratio is kept.
      const double peak = std::max(motionX.peakAbsMps2(), hasY ? motionY.peakAbsMps2() : 0.0);
      if (!(peak > 0.0)) return Error{options.motionX + ": the record is all zeros, it cannot be scaled to a PGA"};
      const double factor = *options.pgaG * seismic::kGravityMps2 / peak;
      for (double& a : motionX.accelerationMps2) a *= factor;
      for (double& a : motionY.accelerationMps2) a *= factor;
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, ", scaled to PGA %.3f g", *options.pgaG);
      report.motion += buffer;
    }
  }
  const double recordPeakG =
      std::max(motionX.peakAbsMps2(), hasY ? motionY.peakAbsMps2() : 0.0) / seismic::kGravityMps2;
  if (!(recordPeakG > 0.0)) return Error{report.motion + ": the record is all zeros"};
  const double dt = motionX.timeStepS;

  // Scenario: the epicentre in the city frame, and the largest delay (farthest corner).
  glm::dvec2 epicentre(0.0);
  double maxDelay = 0.0;
  if (options.scenario) {
    const CityProjection projection(tileset.originLon, tileset.originLat);
    epicentre = projection.forward(options.scenario->epicentreLongitudeDeg, options.scenario->epicentreLatitudeDeg);
    for (const auto& [cx, cy] :
         {std::pair{tileset.bounds.minX, tileset.bounds.minY}, std::pair{tileset.bounds.maxX, tileset.bounds.minY},
          std::pair{tileset.bounds.minX, tileset.bounds.maxY}, std::pair{tileset.bounds.maxX, tileset.bounds.maxY}}) {
      const double km = std::hypot(cx - epicentre.x, cy - epicentre.y) / 1000.0;
      auto site = seismic::shakingAtSite(*options.scenario, km, recordPeakG);
      if (!site.ok()) return Error{"scenario: " + site.error()};
      maxDelay = std::max(maxDelay, site->delaySeconds);
    }
    report.scenario = describeScenario(*options.scenario);
  }
  const double record = std::max(motionX.durationS(), hasY ? motionY.durationS() : 0.0) + dt;
  const auto frames = static_cast<std::size_t>(std::ceil((maxDelay + record + kTailSeconds) / dt)) + 1;
  report.frames = frames;
  report.timeStepS = dt;

  auto writer = ResponseWriter::create(dir, tileset);
  if (!writer.ok()) return Error{writer.error()};

  std::vector<std::uint32_t> leaves;
  std::uint64_t totalBuildings = 0;
  for (std::uint32_t i = 0; i < tileset.nodes.size(); ++i) {
    if (tileset.nodes[i].children.empty()) {
      leaves.push_back(i);
      totalBuildings += tileset.nodes[i].buildings;
    }
  }
  // Big tiles first, for an even finish across threads.
  std::sort(leaves.begin(), leaves.end(),
            [&](std::uint32_t a, std::uint32_t b) { return tileset.nodes[a].buildings > tileset.nodes[b].buildings; });

  const unsigned threads = options.threads > 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  std::atomic<std::size_t> next{0};
  std::atomic<std::uint64_t> buildingsDone{0};
  std::mutex mutex;
  std::string firstError;
  std::vector<double> relativeErrors;
  relativeErrors.reserve(static_cast<std::size_t>(totalBuildings));
  double rateSum = 0.0;
  std::uint64_t rateCount = 0;
  Progress progress("solving buildings", totalBuildings);

  auto worker = [&] {
    seismic::ResponseOptions solverOptions;
    solverOptions.outputStepS = dt;
    solverOptions.frameCount = frames;
    solverOptions.floorDisplacements = true;
    seismic::ResponseSolver solver(solverOptions);
    HistoryEncodingOptions encoding;
    encoding.toleranceFraction = options.historyTolerance;
    std::vector<double> localErrors;
    double localSolve = 0.0, localEncode = 0.0, localRate = 0.0;
    std::uint64_t localRateCount = 0;
    std::uint64_t localStoreySteps = 0;  // storeys × record steps × directions
    std::uint64_t localAttempts = 0;
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
      if (!tile.ok()) {
        const std::lock_guard lock(mutex);
        if (firstError.empty()) firstError = tile.error();
        return;
      }
      std::vector<BuildingResult> results(tile->buildings.size());
      std::vector<seismic::ShearBuilding> modelsX, modelsY;
      std::vector<seismic::BuildingShaking> shaking;
      std::vector<std::size_t> indexOf;  // solver index -> building index
      for (std::size_t b = 0; b < tile->buildings.size(); ++b) {
        const BuildingAttributes& a = tile->buildings[b].attributes;
        BuildingResult& result = results[b];
        auto noResult = [&](NoResultReason reason, std::string detail) {
          result.summary.noResultReason = reason;
          result.noResultDetail = std::move(detail);
        };
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
        seismic::BuildingShaking s;
        double pga = recordPeakG;
        if (options.scenario) {
          const double km =
              std::hypot(a.centroidX + tile->originX - epicentre.x, a.centroidY + tile->originY - epicentre.y) / 1000.0;
          auto site = seismic::shakingAtSite(*options.scenario, km, recordPeakG);
          if (!site.ok()) {
            noResult(NoResultReason::OutsideField, site.error());
            continue;
          }
          s.scale = site->scale;
          s.delaySeconds = site->delaySeconds;
          pga = site->pgaG;
        }
        results[b].summary.pgaG = static_cast<float>(pga);
        modelsX.push_back(std::move(mx).value());
        modelsY.push_back(std::move(my).value());
        shaking.push_back(s);
        indexOf.push_back(b);
      }
      const double solveStart = threadCpuSeconds();
      double encodeTime = 0.0;
      const Status solved = solver.solve(
          modelsX, shaking, motionX, hasY ? &motionY : nullptr,
          [&](std::size_t i, const seismic::BuildingResponse& r) {
            const double encodeStart = threadCpuSeconds();
            BuildingResult& out = results[indexOf[i]];
            const std::span<const float> y =
                r.hasY ? std::span<const float>(r.y.floorDisplacementM) : std::span<const float>();
            EncodedHistory h = encodeHistory(r.x.floorDisplacementM, y, r.storeys, r.frames, r.timeStepS, encoding);
            out.history = std::move(h.history);
            out.summary.source = ResponseSource::Model;
            out.summary.storeys = static_cast<std::uint16_t>(r.storeys);
            out.summary.damage = toFormat(r.damage);
            out.summary.peakDriftRatio = r.maxDriftRatio;
            out.summary.peakRoofDisplacementM = static_cast<float>(h.peakRoofM);
            out.summary.peakFloorAccelerationMs2 =
                std::max(r.x.peakFloorAccelerationMps2, r.hasY ? r.y.peakFloorAccelerationMps2 : 0.0f);
            float residual = 0.0f;
            out.storeyPeakDrift.assign(r.storeys, 0.0f);
            for (std::size_t s = 0; s < r.storeys; ++s) {
              float peak = s < r.x.peakDriftRatio.size() ? r.x.peakDriftRatio[s] : 0.0f;
              float res = s < r.x.residualDriftRatio.size() ? std::abs(r.x.residualDriftRatio[s]) : 0.0f;
              if (r.hasY) {
                if (s < r.y.peakDriftRatio.size()) peak = std::max(peak, r.y.peakDriftRatio[s]);
                if (s < r.y.residualDriftRatio.size()) res = std::max(res, std::abs(r.y.residualDriftRatio[s]));
              }
              out.storeyPeakDrift[s] = peak;
              residual = std::max(residual, res);
            }
            out.summary.residualDriftRatio = residual;
            out.summary.noResultReason = NoResultReason::None;
            out.summary.approximate = r.nonConvergedSteps > 0;
            out.summary.unconvergedSteps = r.nonConvergedSteps;
            out.summary.worstResidualRatio = r.worstResidualRatio;
            localErrors.push_back(h.relativeError());
            localAttempts += static_cast<std::uint64_t>(h.attempts);
            localRate += out.history.sampleRateHz;
            localStoreySteps += r.storeys * r.frames * (r.hasY ? 2u : 1u);
            ++localRateCount;
            encodeTime += threadCpuSeconds() - encodeStart;
            progress.update(++buildingsDone);
          },
          modelsY);
      localSolve += threadCpuSeconds() - solveStart - encodeTime;
      localEncode += encodeTime;
      if (!solved.ok()) {
        const std::lock_guard lock(mutex);
        if (firstError.empty()) firstError = "tile " + n.key() + ": " + solved.error();
        return;
      }
      if (Status s = (*writer)->writeLeaf(node, *tile, results); !s.ok()) {
        const std::lock_guard lock(mutex);
        if (firstError.empty()) firstError = s.error();
        return;
      }
    }
    const std::lock_guard lock(mutex);
    relativeErrors.insert(relativeErrors.end(), localErrors.begin(), localErrors.end());
    report.solveSeconds += localSolve;
    report.encodeSeconds += localEncode;
    report.storeySteps += localStoreySteps;
    report.encodingAttempts += localAttempts;
    rateSum += localRate;
    rateCount += localRateCount;
    report.nonConvergedSteps += solver.stats().nonConvergedSteps;
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  progress.finish();
  if (interrupted()) return Error{"interrupted; the city's previous response is unchanged"};
  if (!firstError.empty()) return Error{firstError};

  ResponseInfo info;
  info.motion = report.motion;
  info.scenario = report.scenario;
  info.method = "MDOF shear building, Bouc-Wen storeys, Newmark average acceleration";
  info.durationSeconds = static_cast<double>(frames - 1) * dt;
  info.sampleRateHz = rateCount > 0 ? rateSum / static_cast<double>(rateCount) : 0.0;
  // The input record for the viewer's plot: the largest |a| of every 0.1 s, in g.
  info.motionPreviewRateHz = 10.0;
  const auto perWindow = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(0.1 / dt)));
  for (std::size_t i = 0; i < motionX.size(); i += perWindow) {
    double best = 0.0;
    for (std::size_t k = i; k < std::min(motionX.size(), i + perWindow); ++k) {
      if (std::abs(motionX.accelerationMps2[k]) > std::abs(best)) best = motionX.accelerationMps2[k];
    }
    info.motionPreviewG.push_back(static_cast<float>(best / seismic::kGravityMps2));
  }
  auto written = (*writer)->commit(info);
  if (!written.ok()) return Error{written.error()};
  report.buildings = totalBuildings;
  for (int k = 0; k < 6; ++k) report.damage[k] = written->damage[k];
  report.noResultReasons = written->noResultReasons;
  report.approximateBuildings = written->approximate;
  report.summaryBytes = written->summaryBytes;
  report.historyBytes = written->historyBytes;
  report.folder = written->folder;
  report.meanSampleRateHz = info.sampleRateHz;
  if (!relativeErrors.empty()) {
    std::sort(relativeErrors.begin(), relativeErrors.end());
    report.worstRelativeError = relativeErrors.back();
    report.p99RelativeError =
        relativeErrors[static_cast<std::size_t>(0.99 * static_cast<double>(relativeErrors.size() - 1))];
  }
  report.seconds = secondsSince(start);
  return report;
}

}  // namespace qv::prep
