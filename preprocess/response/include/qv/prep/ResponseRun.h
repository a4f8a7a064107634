// `quakeview-prep response`: every building of a city analysed as an MDOF shear building with
// Bouc–Wen storeys under a ground motion (a record file, or the synthetic generator), optionally
// scaled and delayed per building by an earthquake scenario, in X and Y; results written as
// response tiles (ResponseWriter).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "qv/core/Result.h"
#include "qv/format/ResponseTile.h"
#include "qv/seismic/GroundMotion.h"
#include "qv/seismic/GroundMotionModel.h"

namespace qv::prep {

struct ResponseRunOptions {
  std::string motionX;                             ///< record file; empty with syntheticSeed
  std::string motionY;                             ///< optional second component
  std::optional<double> timeStepS;                 ///< --dt for files without one
  std::optional<seismic::AccelerationUnit> units;  ///< --units for files that do not say
  std::optional<std::uint64_t> syntheticSeed;      ///< --synthetic SEED
  std::optional<double> pgaG;                      ///< --pga: scale the record(s) to this peak (g)
  std::optional<seismic::Scenario> scenario;       ///< --epicentre ... --magnitude ...
  unsigned threads = 0;                            ///< 0: all cores
  double historyTolerance = 0.019;                 ///< of each building's peak roof displacement
};

struct ResponseRunReport {
  std::uint64_t buildings = 0;
  std::uint64_t damage[6] = {0, 0, 0, 0, 0, 0};             ///< none … complete, no_result
  std::uint64_t storeySteps = 0;                            ///< storeys × solver steps × directions
  std::uint64_t nonConvergedSteps = 0;                      ///< steps accepted without convergence after splitting
  std::uint64_t approximateBuildings = 0;                   ///< buildings with such steps (listed in the notes)
  std::map<NoResultReason, std::uint64_t> noResultReasons;  ///< buildings without a result, by reason
  double seconds = 0.0;
  double solveSeconds = 0.0;   ///< CPU time in the solver (the encoder excluded), all threads
  double encodeSeconds = 0.0;  ///< CPU time of the history encoder, all threads
  std::uint64_t summaryBytes = 0, historyBytes = 0;
  double worstRelativeError = 0.0;  ///< history vs full rate, / peak roof
  double p99RelativeError = 0.0;
  double meanSampleRateHz = 0.0;
  std::uint64_t encodingAttempts = 0;  ///< history encodings tried, over all buildings
  std::size_t frames = 0;
  double timeStepS = 0.0;
  std::string motion;
  std::string scenario;
  std::string folder;
};

Result<ResponseRunReport> runCityResponse(const std::string& cityDir, const ResponseRunOptions& options);

}  // namespace qv::prep
