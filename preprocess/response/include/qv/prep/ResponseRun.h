// `quakeview-prep response`: every building of a city analysed as an MDOF shear building with
// Bouc–Wen storeys, in X and Y, under every record of a suite (record files, or synthetic records),
// each scaled per building and direction to the shaking field (a ShakeMap grid or a BSSA14 scenario:
// by default to the target Sa at the model's first-mode period, or to the PGA) and delayed by the
// S-wave travel time; across the suite, medians and log standard deviations of the peaks; HAZUS
// probabilities of damage and their consequences; results written as response tiles
// (ResponseWriter) and the totals as consequences.json.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/ResponseTile.h"
#include "qv/prep/DefaultSuite.h"
#include "qv/seismic/ConsequencesFile.h"
#include "qv/seismic/GroundMotion.h"
#include "qv/seismic/GroundMotionModel.h"
#include "qv/seismic/Loss.h"

namespace qv::prep {

enum class ScaleBy { SpectralAcceleration, Pga };

enum class OutsideGrid { Error, Skip };

/// `--shard K/N`: the K-th (1-based) of N parts of the city (ResponseParts.h).
struct ShardSpec {
  unsigned part = 1, parts = 1;
};

struct ResponseRunOptions {
  /// Record files or folders of records (--motion, repeatable): the suite. Every building is analysed
  /// under every record. Empty with syntheticSeeds.
  std::vector<std::string> motions;
  std::string motionY;                             ///< optional second component (one record only)
  std::optional<double> timeStepS;                 ///< --dt for files without one
  std::optional<seismic::AccelerationUnit> units;  ///< --units for files that do not say
  std::vector<std::uint64_t> syntheticSeeds;       ///< --synthetic SEED...: one two-component record each
  bool defaultSuite = false;   ///< syntheticSeeds are kDefaultSuiteSeeds, chosen for a field without records
  std::optional<double> pgaG;  ///< --pga: scale the record(s) to this peak (g)
  std::optional<seismic::Scenario> scenario;               ///< --epicentre ... --magnitude ...
  std::string shakemap;                                    ///< --shakemap grid.xml
  ScaleBy scaleBy = ScaleBy::SpectralAcceleration;         ///< with a scenario or a ShakeMap
  OutsideGrid outsideGrid = OutsideGrid::Error;            ///< buildings outside the ShakeMap's grid
  double shearWaveSpeedKmPerS = 3.5;                       ///< travel time from a ShakeMap's epicentre
  seismic::TimeOfDay timeOfDay = seismic::TimeOfDay::Day;  ///< for the occupants of the consequences
  /// --districts FILE.geojson: totals per district; "" : the city's own districts.geojson when its
  /// manifest lists one (made by `city` / `synth-city` from the input, qv/prep/DefaultDistricts.h).
  std::string districts;
  /// --population-night/-day/-source: the published population the occupants are shown against
  seismic::PopulationFigures population;
  /// --accurate-steps: accepted and ignored. The solver's defaults are the accurate path (the exact
  /// Bouc–Wen update; yielding frames within 0.5 % of converged peaks, docs/seismic.md
  /// "Sub-stepping"); the flag once turned on the hysteretic error bound, now the default.
  bool accurateSubsteps = false;
  /// --shard K/N: analyse only part K of the city's N parts and write it into the staging area
  /// (ResponseParts.h); `response --merge` publishes the parts as one response.
  std::optional<ShardSpec> shard;
  /// --catalogue FILE --scenario I: scenario I (1-based; 0: none) of a catalogue whose scenarios are
  /// named scenarioNames, published beside the others (ResponseWriter::setScenario).
  std::size_t scenarioIndex = 0;
  std::vector<std::string> scenarioNames;
  unsigned threads = 0;             ///< 0: all cores
  double historyTolerance = 0.019;  ///< of each building's peak roof displacement
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
  /// Of solveSeconds: pass one (a suite's every record, peaks only; 0 for one record) and pass two
  /// (each building's stored history under its shown record, with its losses).
  double passOneSeconds = 0.0, passTwoSeconds = 0.0;
  unsigned part = 0, parts = 0;  ///< a part of a sharded run (K of N), or a merge of N parts (0 of N)
  std::uint64_t summaryBytes = 0, historyBytes = 0;              ///< as stored (Zstandard frames)
  std::uint64_t uncompressedBytes = 0;                           ///< the same before compression
  std::uint64_t driftSeriesBytes = 0, driftSeriesBuildings = 0;  ///< the far view's series (ResponseWriteReport)
  double worstRelativeError = 0.0;                               ///< history vs full rate, / peak roof
  double p99RelativeError = 0.0;
  double meanSampleRateHz = 0.0;
  std::uint64_t encodingAttempts = 0;  ///< history encodings tried, over all buildings
  std::size_t frames = 0;
  double timeStepS = 0.0;
  std::string motion;
  std::string scenario;
  std::string folder;
  std::size_t records = 0;                    ///< records in the suite
  std::string scaling;                        ///< how the records were scaled, for people
  std::string eventType;                      ///< "SCENARIO" or "ACTUAL"
  std::string timeOfDay;                      ///< of the consequences' occupants: night, day, commute
  std::uint64_t outsideGrid = 0;              ///< buildings skipped outside the ShakeMap (--outside-grid skip)
  std::optional<seismic::LossTotals> losses;  ///< the city's consequences
  double lossSeconds = 0.0;
  /// Without --districts: what the city's own districts were made from ("" : none used).
  std::string districtsSource;
};

Result<ResponseRunReport> runCityResponse(const std::string& cityDir, const ResponseRunOptions& options);

}  // namespace qv::prep
