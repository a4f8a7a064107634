// bench_seismic: nonlinear X/Y time histories of a synthetic city under the Kobe record (TAK000.AT2,
// 4096 points at 0.01 s), the way the response command runs them: tiles of buildings shared by
// worker threads, one ResponseSolver per thread, results streamed and discarded tile by tile (only
// per-building peaks are kept). Prints a table.
//
// usage: bench_seismic [--buildings N[,N...]] [--threads T] [--precision float|double|both]
//                      [--no-histories] [--tile N] [--compare-bound] [--compare-all]
// Solver variants ("update" column): exact = the defaults (exact Bouc–Wen update, n in {1, 2}, γ̂ = β̂);
// be-off = backward-Euler update with sub-steps from the periods alone (`response`'s default before
// issue 21); be-bound = backward Euler with the hysteretic error bound (the library's default before).
// --bound E: ResponseOptions::maxHystereticError for be-bound (default: its default).
// --accuracy N: first, N buildings spread over the city solved with every variant, their peaks
// (base shear, roof displacement, largest drift ratio, X and Y) against 64 equal sub-steps in double
// precision (converged to ~0.05 %): relative errors, median / 99th percentile / largest.
// --compare-bound: each row twice in one run, be-off then exact, so the CPU times of the old and the
// new default of `response` compare under the same load; --compare-all: be-off, be-bound and exact.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

#include "qv/core/SplitMix64.h"
#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/GroundMotionModel.h"
#include "qv/seismic/GroundMotionReader.h"
#include "qv/seismic/ResponseSolver.h"

using namespace qv;
using namespace qv::seismic;

namespace {

// splitmix64: the benchmark's own reproducible random numbers.
struct Random {
  SplitMix64 bits;
  double uniform() { return bits.uniformOpen(); }
  double normal() {
    const double u1 = uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
};

struct CityBuilding {
  BuildingAttributes attributes;
  BuildingShaking shaking;
};

// A synthetic city: storeys lognormal (median 4, heavy tail to 100), types by material and height
// class, eras uniform, footprints lognormal, sites uniform in 10 km × 10 km; M 6.9 scenario 8 km
// south-west of the corner at 15 km depth (BSSA14 PGA, S-wave delay).
std::vector<CityBuilding> synthesizeCity(std::size_t count, double recordPeakG) {
  Random random{SplitMix64{20240517}};
  std::vector<CityBuilding> city(count);
  Scenario scenario;
  scenario.magnitude = 6.9;
  scenario.depthKm = 15.0;
  for (std::size_t i = 0; i < count; ++i) {
    BuildingAttributes& a = city[i].attributes;
    a.id = std::to_string(i);
    const double storeys = std::floor(std::exp(std::log(4.0) + 0.75 * random.normal())) + 1.0;
    a.storeys = static_cast<std::uint16_t>(std::clamp(storeys, 1.0, 100.0));
    const int n = a.storeys;
    a.heightM = static_cast<float>(n * (3.0 + 0.8 * random.uniform()));
    a.footprintAreaM2 = static_cast<float>(std::exp(std::log(250.0) + 0.6 * random.normal()));
    const double material = random.uniform();
    const int heightClass = n <= 3 ? 0 : (n <= 7 ? 1 : 2);
    if (n <= 3 && material < 0.35) {
      a.structuralType = material < 0.3 ? StructuralType::W1 : StructuralType::W2;
    } else if (n <= 3 && material < 0.45) {
      a.structuralType = n <= 2 ? StructuralType::URML : StructuralType::URMM;
    } else if (material < 0.65) {
      const StructuralType c1[] = {StructuralType::C1L, StructuralType::C1M, StructuralType::C1H};
      a.structuralType = c1[heightClass];
    } else if (material < 0.8) {
      const StructuralType c2[] = {StructuralType::C2L, StructuralType::C2M, StructuralType::C2H};
      a.structuralType = c2[heightClass];
    } else if (material < 0.92) {
      const StructuralType s1[] = {StructuralType::S1L, StructuralType::S1M, StructuralType::S1H};
      a.structuralType = s1[heightClass];
    } else {
      const StructuralType s2[] = {StructuralType::S2L, StructuralType::S2M, StructuralType::S2H};
      a.structuralType = s2[heightClass];
    }
    a.codeEra = static_cast<CodeEra>(1 + static_cast<int>(random.uniform() * 4.0));
    const double x = 10.0 * random.uniform() + 8.0;
    const double y = 10.0 * random.uniform() + 8.0;
    const auto shaking = shakingAtSite(scenario, std::sqrt(x * x + y * y), recordPeakG);
    city[i].shaking = shaking ? BuildingShaking{shaking->scale, shaking->delaySeconds} : BuildingShaking{};
  }
  return city;
}

double peakMemoryMiB() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return 0.0;
  char line[256];
  double kib = 0.0;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::strncmp(line, "VmHWM:", 6) == 0) kib = std::strtod(line + 6, nullptr);
  }
  std::fclose(f);
  return kib / 1024.0;
}

struct RunResult {
  double wallS = 0.0;
  double cpuS = 0.0;  // process CPU time (all threads)
  double modelS = 0.0;
  double storeySteps = 0.0;  // storeys × record steps × directions
  std::size_t storeys = 0;
  std::size_t solved = 0;
  std::size_t failedModels = 0;
  SolverStats stats;
  std::array<std::size_t, 5> damage{};
  double maxDrift = 0.0;
  std::size_t historyFloats = 0;  // floor displacement values streamed (and discarded)
};

enum class Variant { Exact, BackwardEulerOff, BackwardEulerBound };

const char* variantName(Variant v) {
  return v == Variant::Exact ? "exact" : v == Variant::BackwardEulerOff ? "be-off" : "be-bound";
}

void applyVariant(ResponseOptions& options, Variant variant, double bound) {
  if (variant == Variant::Exact) return;
  options.exactHystereticUpdate = false;
  options.maxHystereticError = variant == Variant::BackwardEulerOff ? 1.0
                               : bound > 0.0                        ? bound
                                                                    : kDefaultMaxHystereticError;
}

RunResult runCity(const std::vector<CityBuilding>& city, std::size_t count, int threads, Precision precision,
                  bool histories, std::size_t tile, const GroundMotion& record, Variant variant, double bound) {
  RunResult total;
  std::atomic<std::size_t> nextTile{0};
  std::vector<RunResult> perThread(static_cast<std::size_t>(threads));
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  auto worker = [&](std::size_t t) {
    RunResult& mine = perThread[t];
    ResponseOptions options;
    options.precision = precision;
    options.floorDisplacements = histories;
    applyVariant(options, variant, bound);
    // One time axis for the whole city: the largest delay plus the record.
    double maxDelay = 0.0;
    for (std::size_t i = 0; i < count; ++i) maxDelay = std::max(maxDelay, city[i].shaking.delaySeconds);
    options.frameCount = static_cast<std::size_t>(std::ceil((maxDelay + record.durationS()) / record.timeStepS)) + 1;
    ResponseSolver solver(options);
    std::vector<ShearBuilding> modelsX;
    std::vector<ShearBuilding> modelsY;
    std::vector<BuildingShaking> shaking;
    BuildingModelOptions yOptions;
    yOptions.periodFactor = 1.1;  // the Y direction slightly more flexible
    while (true) {
      const std::size_t first = nextTile.fetch_add(tile);
      if (first >= count) break;
      const std::size_t last = std::min(count, first + tile);
      const auto modelStart = std::chrono::steady_clock::now();
      modelsX.clear();
      modelsY.clear();
      shaking.clear();
      for (std::size_t i = first; i < last; ++i) {
        auto x = buildingModelFromAttributes(city[i].attributes);
        auto y = buildingModelFromAttributes(city[i].attributes, yOptions);
        if (!x || !y) {
          ++mine.failedModels;
          continue;
        }
        mine.storeys += x->storeys();
        modelsX.push_back(std::move(x).value());
        modelsY.push_back(std::move(y).value());
        shaking.push_back(city[i].shaking);
      }
      mine.modelS += std::chrono::duration<double>(std::chrono::steady_clock::now() - modelStart).count();
      const Status s = solver.solve(
          modelsX, shaking, record, &record,
          [&](std::size_t, const BuildingResponse& r) {
            ++mine.solved;
            mine.damage[static_cast<std::size_t>(r.damage)]++;
            mine.maxDrift = std::max(mine.maxDrift, static_cast<double>(r.maxDriftRatio));
            mine.historyFloats += r.x.floorDisplacementM.size() + r.y.floorDisplacementM.size();
          },
          modelsY);
      if (!s) {
        std::fprintf(stderr, "bench_seismic: %s\n", s.error().c_str());
        std::exit(1);
      }
    }
    mine.stats = solver.stats();
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker, static_cast<std::size_t>(t));
  for (auto& th : pool) th.join();
  total.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  total.cpuS = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  for (const RunResult& r : perThread) {
    total.modelS += r.modelS;
    total.storeys += r.storeys;
    total.solved += r.solved;
    total.failedModels += r.failedModels;
    total.stats.steps += r.stats.steps;
    total.stats.newtonIterations += r.stats.newtonIterations;
    total.stats.nonConvergedSteps += r.stats.nonConvergedSteps;
    total.stats.refinedSteps += r.stats.refinedSteps;
    total.stats.splitSteps += r.stats.splitSteps;
    for (std::size_t k = 0; k < 5; ++k) total.damage[k] += r.damage[k];
    total.maxDrift = std::max(total.maxDrift, r.maxDrift);
    total.historyFloats += r.historyFloats;
  }
  total.storeySteps = static_cast<double>(total.storeys) * static_cast<double>(record.size()) * 2.0;
  return total;
}

// Relative errors of the peaks of `sample` buildings against a converged solve (see --accuracy).
void reportAccuracy(const std::vector<CityBuilding>& city, std::size_t sample, const GroundMotion& record,
                    double bound) {
  std::vector<ShearBuilding> modelsX;
  std::vector<ShearBuilding> modelsY;
  std::vector<BuildingShaking> shaking;
  BuildingModelOptions yOptions;
  yOptions.periodFactor = 1.1;
  const std::size_t stride = std::max<std::size_t>(1, city.size() / std::max<std::size_t>(1, sample));
  for (std::size_t i = 0; i < city.size() && modelsX.size() < sample; i += stride) {
    auto x = buildingModelFromAttributes(city[i].attributes);
    auto y = buildingModelFromAttributes(city[i].attributes, yOptions);
    if (!x || !y) continue;
    modelsX.push_back(std::move(x).value());
    modelsY.push_back(std::move(y).value());
    shaking.push_back(city[i].shaking);
  }
  auto solveAll = [&](const ResponseOptions& o, SolverStats& stats) {
    std::vector<BuildingResponse> out(modelsX.size());
    ResponseSolver solver(o);
    const Status s = solver.solve(
        modelsX, shaking, record, &record, [&](std::size_t b, const BuildingResponse& r) { out[b] = r; }, modelsY);
    if (!s) {
      std::fprintf(stderr, "bench_seismic: %s\n", s.error().c_str());
      std::exit(1);
    }
    stats = solver.stats();
    return out;
  };
  ResponseOptions base;
  base.floorDisplacements = false;
  base.driftRatios = false;
  ResponseOptions converged = base;
  converged.precision = Precision::Double;
  converged.fixedSubsteps = 64;
  SolverStats convergedStats;
  const auto reference = solveAll(converged, convergedStats);
  std::printf("accuracy: %zu buildings (X and Y) against 64 equal sub-steps in double precision\n", modelsX.size());
  std::printf("%8s %9s %8s %8s  %-26s %-26s %-26s\n", "update", "precision", "Msteps", "Msolves",
              "base shear % med/p99/max", "roof % med/p99/max", "drift % med/p99/max");
  for (const Variant variant : {Variant::BackwardEulerOff, Variant::BackwardEulerBound, Variant::Exact}) {
    ResponseOptions o = base;
    applyVariant(o, variant, bound);
    SolverStats stats;
    const auto result = solveAll(o, stats);
    std::array<std::vector<double>, 3> errors;
    auto add = [&](const DirectionResponse& d, const DirectionResponse& r) {
      auto relative = [](double value, double exact) {
        return exact > 0.0 ? 100.0 * std::fabs(value - exact) / exact : 0.0;
      };
      errors[0].push_back(relative(d.peakBaseShearN, r.peakBaseShearN));
      errors[1].push_back(relative(d.peakRoofDisplacementM, r.peakRoofDisplacementM));
      const double drift = *std::max_element(d.peakDriftM.begin(), d.peakDriftM.end());
      const double exact = *std::max_element(r.peakDriftM.begin(), r.peakDriftM.end());
      errors[2].push_back(relative(drift, exact));
    };
    for (std::size_t b = 0; b < result.size(); ++b) {
      add(result[b].x, reference[b].x);
      add(result[b].y, reference[b].y);
    }
    std::printf("%8s %9s %8.2f %8.2f ", variantName(variant), "float", static_cast<double>(stats.steps) / 1e6,
                static_cast<double>(stats.newtonIterations) / 1e6);
    for (auto& e : errors) {
      std::sort(e.begin(), e.end());
      const auto at = [&](double q) { return e[static_cast<std::size_t>(q * static_cast<double>(e.size() - 1))]; };
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.3f / %.3f / %.3f", at(0.5), at(0.99), e.back());
      std::printf(" %-26s", cell);
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  std::printf("\n");
}

std::vector<std::size_t> parseCounts(const char* text) {
  std::vector<std::size_t> out;
  std::string s(text);
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t comma = s.find(',', start);
    const std::string piece = s.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    out.push_back(static_cast<std::size_t>(std::strtoull(piece.c_str(), nullptr, 10)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> counts = {10000, 100000};
  int threads = 2;
  std::vector<Precision> precisions = {Precision::Float};
  bool histories = true;
  std::size_t tile = 1000;
  std::vector<Variant> variants = {Variant::Exact};
  double bound = 0.0;  // 0: the default
  std::size_t accuracySample = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc;
    if (a == "--buildings" && hasValue) {
      counts = parseCounts(argv[++i]);
    } else if (a == "--threads" && hasValue) {
      threads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--precision" && hasValue) {
      const std::string p = argv[++i];
      precisions = p == "double" ? std::vector<Precision>{Precision::Double}
                   : p == "both" ? std::vector<Precision>{Precision::Float, Precision::Double}
                                 : std::vector<Precision>{Precision::Float};
    } else if (a == "--no-histories") {
      histories = false;
    } else if (a == "--bound" && hasValue) {
      bound = std::atof(argv[++i]);
    } else if (a == "--accuracy" && hasValue) {
      accuracySample = static_cast<std::size_t>(std::atoll(argv[++i]));
    } else if (a == "--compare-bound") {
      variants = {Variant::BackwardEulerOff, Variant::Exact};
    } else if (a == "--compare-all") {
      variants = {Variant::BackwardEulerOff, Variant::BackwardEulerBound, Variant::Exact};
    } else if (a == "--tile" && hasValue) {
      tile = std::max<std::size_t>(1, static_cast<std::size_t>(std::atoll(argv[++i])));
    } else {
      std::fprintf(stderr,
                   "usage: bench_seismic [--buildings N[,N...]] [--threads T] [--precision float|double|both] "
                   "[--no-histories] [--tile N] [--compare-bound] [--compare-all] [--bound E] [--accuracy N]\n");
      return 2;
    }
  }
  const auto record = readGroundMotionFile(std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/ground-motions/TAK000.AT2");
  if (!record) {
    std::fprintf(stderr, "bench_seismic: %s\n", record.error().c_str());
    return 1;
  }
  const std::size_t largest = *std::max_element(counts.begin(), counts.end());
  const auto city = synthesizeCity(largest, record->peakAbsMps2() / kGravityMps2);
  std::size_t storeyTotal = 0;
  std::size_t tallest = 0;
  std::size_t over30 = 0;
  for (const auto& b : city) {
    storeyTotal += b.attributes.storeys;
    tallest = std::max<std::size_t>(tallest, b.attributes.storeys);
    over30 += b.attributes.storeys > 30 ? 1 : 0;
  }
  std::printf("bench_seismic: %s (%zu points at %.3g s), X and Y (Y model 10 %% longer period), Bouc-Wen storeys\n",
              record->name.c_str(), record->size(), record->timeStepS);
  std::printf("city: %zu buildings, mean %.2f storeys, tallest %zu, %zu above 30 storeys; %d threads, tiles of %zu\n\n",
              largest, static_cast<double>(storeyTotal) / static_cast<double>(largest), tallest, over30, threads, tile);
  if (accuracySample > 0) reportAccuracy(city, accuracySample, *record, bound);
  std::printf("%9s %9s %10s %8s %8s %8s %8s %11s %14s %14s %11s %11s %8s %10s %9s  %s\n", "buildings", "precision",
              "histories", "update", "wall s", "cpu s", "models s", "buildings/s", "storey-steps/s", "per cpu-second",
              "solves/step", "Msteps", "unconv.", "floats MiB", "VmHWM MiB",
              "damage none/slight/moderate/extensive/complete");
  for (const Precision precision : precisions) {
    for (const std::size_t count : counts) {
      for (const Variant variant : variants) {
        const RunResult r = runCity(city, count, threads, precision, histories, tile, *record, variant, bound);
        const double solvesPerStep =
            r.stats.steps > 0 ? static_cast<double>(r.stats.newtonIterations) / static_cast<double>(r.stats.steps)
                              : 0.0;
        std::printf(
            "%9zu %9s %10s %8s %8.2f %8.2f %8.2f %11.0f %13.1fM %13.1fM %11.2f %11.2f %8zu %10.0f %9.0f  "
            "%zu/%zu/%zu/%zu/%zu\n",
            count, precision == Precision::Float ? "float" : "double", histories ? "streamed" : "off",
            variantName(variant), r.wallS, r.cpuS, r.modelS / threads, static_cast<double>(r.solved) / r.wallS,
            r.storeySteps / r.wallS / 1e6, r.storeySteps / r.cpuS / 1e6, solvesPerStep,
            static_cast<double>(r.stats.steps) / 1e6, r.stats.nonConvergedSteps,
            static_cast<double>(r.historyFloats) * 4.0 / (1024.0 * 1024.0), peakMemoryMiB(), r.damage[0], r.damage[1],
            r.damage[2], r.damage[3], r.damage[4]);
        std::fflush(stdout);
      }
    }
  }
  std::printf(
      "\nstorey-steps/s = storeys x 4096 record steps x 2 directions / wall time (sub-steps, arrival skipping and\n"
      "the tail after the record not counted); per cpu-second: the same over the CPU time of all threads (wall\n"
      "time above cpu time / threads means other processes shared the cores); floats MiB = floor displacements\n"
      "streamed to the sink and discarded tile by tile; update: exact (the defaults), be-off (backward Euler, "
      "sub-steps\n"
      "from the periods alone), be-bound (backward Euler, hysteretic error bound); Msteps: system steps taken, "
      "millions.\n");
  return 0;
}
