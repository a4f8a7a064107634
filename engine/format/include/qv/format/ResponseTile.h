// Response tiles, aligned with the city tiles (same buildings, same order):
//   summary (.qvs): for every tile — damage state and peaks per building, peak drift per storey;
//     the viewer always loads it (colours, inspection, counts);
//   history (.qvh): for leaf tiles — floor displacement histories, loaded only for the buildings
//     the viewer animates.
// Specification: docs/formats.md ("Response tiles"). One codec for writer and reader.
//
// Histories are stored compactly as a per-building basis over the floors (the leading singular
// vectors of the building's displacement history, close to its mode shapes) times coordinate
// series sampled at a per-building rate and quantized with a per-series scale: floor f at time t
// is Σ_k shape[f][k] · scale[k] · q_k(t), q_k interpolated between samples by uniform Catmull-Rom
// cubics (end samples repeated).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/DamageState.h"

namespace qv {

/// The summary (.qvs) is written as version 2 (per-building status); version 1 is still read. The
/// history (.qvh) is version 1.
inline constexpr std::uint16_t kResponseSummaryVersion = 2;
inline constexpr std::uint16_t kResponseHistoryVersion = 1;

enum class ResponseSource : std::uint8_t { None = 0, Model = 1, Imported = 2 };
std::string_view responseSourceName(ResponseSource source);  ///< "none", "model", "imported"

/// Why a building has no result (stored as a number: values are only ever added; a reader maps
/// values it does not know to Unknown).
enum class NoResultReason : std::uint8_t {
  None = 0,             ///< the building has a result
  ModelInvalid = 1,     ///< no structural model could be made from its attributes
  OutsideField = 2,     ///< outside the area where the shaking is defined
  SkippedByOption = 3,  ///< left out by an option of the command that made the response
  BaseAboveGround = 4,  ///< a part resting on another building (base above ground): not analysed
  NotInImport = 5,      ///< imported results did not include it
  Unknown = 255         ///< no reason recorded (summary version 1, or a value this build does not know)
};
/// "none", "model_invalid", "outside_field", "skipped_by_option", "base_above_ground",
/// "not_in_import", "unknown".
std::string_view noResultReasonName(NoResultReason reason);
/// A sentence for people, e.g. "base above ground (rooftop structure resting on another building;
/// not analysed)".
std::string_view noResultReasonDescription(NoResultReason reason);

struct BuildingResponse {
  DamageState damage = DamageState::NoResult;
  ResponseSource source = ResponseSource::None;
  std::uint16_t storeys = 0;              ///< storeys the result has (0 without a result)
  float peakDriftRatio = 0.0f;            ///< max over storeys and directions
  float peakRoofDisplacementM = 0.0f;     ///< relative to the ground, max over time of |(x, y)|
  float pgaG = 0.0f;                      ///< peak ground acceleration applied to this building
  float peakFloorAccelerationMs2 = 0.0f;  ///< absolute, max over floors
  float residualDriftRatio = 0.0f;        ///< max over storeys, after the motion
  /// Without a result: why (None when the building has one). Version 1 files: Unknown.
  NoResultReason noResultReason = NoResultReason::None;
  /// The solver accepted some steps without converging (after splitting them): the result is
  /// approximate. `unconvergedSteps` counts them (X + Y) and `worstResidualRatio` is their largest
  /// residual relative to the size of the force terms.
  bool approximate = false;
  std::uint32_t unconvergedSteps = 0;
  float worstResidualRatio = 0.0f;
  std::uint32_t firstStorey = 0;  ///< into ResponseSummaryTile::storeyPeakDrift
};

/// How a building's record was scaled (optional section SPEC; quakeview-prep response). Index 0 is
/// X, 1 is Y. Spectral scaling: the record is scaled so that its 5 %-damped pseudo-spectral
/// acceleration at the model's first-mode period equals the target there; PGA scaling leaves the
/// period and Sa values 0.
struct BuildingScaling {
  float periodS[2] = {0.0f, 0.0f};    ///< first-mode period T1 of the X and Y models (s)
  float targetSaG[2] = {0.0f, 0.0f};  ///< target Sa(T1) (g), from the shaking field
  float recordSaG[2] = {0.0f, 0.0f};  ///< the animated record's own Sa(T1) before scaling (g)
  float scale[2] = {0.0f, 0.0f};      ///< factor applied to that record (> 0 with a result)
  bool operator==(const BuildingScaling&) const = default;
};

/// Where a building's site intensity comes from (optional section SITE).
enum class SiteSource : std::uint8_t {
  None = 0,      ///< no shaking field (records as given, or an import): no site values
  ShakeMap = 1,  ///< the ShakeMap grid's values, interpolated bilinearly at the building
  Scenario = 2,  ///< the scenario's ground-motion model (BSSA14) medians at the building
};
/// "none", "shakemap", "scenario" (values this build does not know read as "none").
std::string_view siteSourceName(SiteSource source);

/// The shaking at the building's site as the field gives it (optional section SITE), before any
/// record is scaled to it: what an engineer compares with a code spectrum or a fragility. A value
/// the field does not give is NaN (a ShakeMap without PGV or MMI; a scenario gives no PGV, MMI or
/// Vs30 here). Written for every building inside the field, with or without a result.
struct BuildingSite {
  SiteSource source = SiteSource::None;
  float pgaG = kNotGiven;     ///< peak ground acceleration (g)
  float pgvCmS = kNotGiven;   ///< peak ground velocity (cm/s)
  float psa03G = kNotGiven;   ///< 5 %-damped pseudo-spectral acceleration at 0.3 s (g)
  float psa10G = kNotGiven;   ///< ... at 1.0 s (g)
  float psa30G = kNotGiven;   ///< ... at 3.0 s (g)
  float mmi = kNotGiven;      ///< modified Mercalli intensity
  float vs30Mps = kNotGiven;  ///< the site's Vs30 the field assumed (m/s)
  static constexpr float kNotGiven = std::numeric_limits<float>::quiet_NaN();
  [[nodiscard]] bool given() const { return source != SiteSource::None; }
};

/// The values a site's field gives, for people: "PGA 0.304 g, PGV 6.9 cm/s, PSA 0.3 s 0.281 g,
/// PSA 1.0 s 0.076 g, PSA 3.0 s 0.015 g, MMI 6.5, Vs30 446 m/s" (values not given are left out;
/// empty when none is).
std::string siteShakingText(const BuildingSite& site);
/// Where the values come from, for people: "ShakeMap", "scenario median (BSSA14)", "".
std::string_view siteSourceLabel(SiteSource source);

/// Record-to-record spread across a suite (optional section SUIT). Medians are geometric means
/// over the records; betas are the standard deviations of the natural logarithms (0 for one record).
struct BuildingSpread {
  std::uint16_t records = 0;      ///< records the building was analysed under (0 without a result)
  std::uint16_t shownRecord = 0;  ///< the record whose history is stored (roof peak nearest the median)
  float driftBeta = 0.0f;         ///< of the building's peak drift ratio (max over storeys)
  float accelerationBeta = 0.0f;  ///< of its peak floor acceleration (max over floors)
  bool operator==(const BuildingSpread&) const = default;
};

/// Per storey, aligned with ResponseSummaryTile::storeyPeakDrift (optional section SSPR).
struct StoreySpread {
  float driftBeta = 0.0f;              ///< of the storey's peak drift ratio
  float accelerationMedianMs2 = 0.0f;  ///< median peak absolute acceleration of the floor above
  float accelerationBeta = 0.0f;
  bool operator==(const StoreySpread&) const = default;
};

/// Bits of BuildingLoss::flags.
enum LossFlag : std::uint8_t {
  kLossOccupantsInferred = 1,  ///< occupants from floor area and use (no occupant count given)
  kLossValueInferred = 2,      ///< replacement value from floor area and use (no value given)
};

/// Probabilistic damage and its consequences (HAZUS 5.1; optional section LOSS). Probabilities are
/// of each damage state, none .. complete (each set sums to 1); people and money are expected values
/// for the scenario's time of day.
struct BuildingLoss {
  float structural[5] = {0, 0, 0, 0, 0};
  float nonStructuralDrift[5] = {0, 0, 0, 0, 0};
  float nonStructuralAcceleration[5] = {0, 0, 0, 0, 0};
  float collapse = 0.0f;             ///< probability of collapse
  float occupants = 0.0f;            ///< present at the time of day
  float injuries[4] = {0, 0, 0, 0};  ///< expected people, severity 1 .. 4 (4: deaths)
  float replacementValueUsd = 0.0f;
  float repairCostUsd = 0.0f;
  float repairTimeDays = 0.0f;
  float tag[3] = {0, 0, 0};  ///< probability of a green, yellow, red inspection tag
  /// Standard deviations of the building's repair cost and injuries over its damage states (the
  /// spread the view's totals add up, buildings taken as independent).
  float repairCostStdUsd = 0.0f;
  float injuriesStd[4] = {0, 0, 0, 0};
  std::uint8_t flags = 0;  ///< LossFlag bits
  bool operator==(const BuildingLoss&) const = default;
  /// Σ k · P(DS = k) of the structural states, 0 .. 4.
  [[nodiscard]] float expectedState() const;
  /// P(structural DS >= k) = Σ_{j >= k} P(DS = j): 1 for k <= 0, 0 for k > 4.
  [[nodiscard]] float structuralAtLeast(int k) const;
};

/// The damage probabilities a building is drawn and filtered by (optional summary section DPRB):
/// what the tile summaries of a response with a city-wide index carry instead of LOSS, whose full
/// values index.qvs holds (the viewer inspects and totals from there). Stored as 16-bit fractions,
/// read back to within 1/131070. A reader derives them from LOSS where a file has LOSS.
struct BuildingDamageOdds {
  float atLeast[4] = {0, 0, 0, 0};  ///< P(structural DS >= slight, moderate, extensive, complete)
  float tag[3] = {0, 0, 0};         ///< P(green, yellow, red inspection tag)
  bool operator==(const BuildingDamageOdds&) const = default;
  /// P(structural DS >= k): 1 for k <= 0, 0 for k > 4 (as BuildingLoss::structuralAtLeast).
  [[nodiscard]] float structuralAtLeast(int k) const;
  /// E[DS] = Σ_k P(DS >= k), 0 .. 4.
  [[nodiscard]] float expectedState() const;
  /// The most likely tag: 0 green, 1 yellow, 2 red (the first of equal ones).
  [[nodiscard]] int likelyTag() const;
  [[nodiscard]] static BuildingDamageOdds of(const BuildingLoss& loss);
};

/// The far view's drift series (optional summary section DSER), for every drawn building to follow
/// the shaking without its full history: per building, the largest inter-storey drift ratio over
/// its storeys and the two directions in each window [start + i / rateHz, start + (i + 1) / rateHz),
/// quantized to one byte on a square-root scale: code = round(255 sqrt(min(drift, fullScale) /
/// fullScale)) (driftSeriesCode), so small drifts keep their resolution. A building without a
/// history has count 0. `first` indexes `codes`; spans are laid out in building order.
struct DriftSpan {
  float startSeconds = 0.0f;  ///< scene time of its first window (the shaking's arrival)
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  bool operator==(const DriftSpan&) const = default;
};
struct DriftSeries {
  float rateHz = 0.0f;              ///< windows per second
  float fullScale = 0.0f;           ///< drift ratio of code 255
  std::vector<DriftSpan> spans;     ///< one per building, or empty (no series)
  std::vector<std::uint8_t> codes;  ///< every building's codes, one after another
  [[nodiscard]] bool empty() const { return spans.empty(); }
  bool operator==(const DriftSeries&) const = default;
};
/// What quakeview-prep response writes: 4 windows a second, 5 % drift at code 255.
inline constexpr float kDriftSeriesRateHz = 4.0f;
inline constexpr float kDriftSeriesFullScale = 0.05f;
[[nodiscard]] std::uint8_t driftSeriesCode(float driftRatio, float fullScale);
[[nodiscard]] float driftSeriesValue(std::uint8_t code, float fullScale);

struct ResponseSummaryTile {
  std::vector<BuildingResponse> buildings;
  std::vector<float> storeyPeakDrift;  ///< per building with a result, `storeys` values, ground up
  // Optional sections: each empty (not stored) or holding one value per building (storeySpread: one
  // per storey value). Readers that do not know a section ignore it.
  std::vector<BuildingScaling> scaling;    ///< SPEC
  std::vector<BuildingSite> sites;         ///< SITE
  std::vector<BuildingSpread> spread;      ///< SUIT
  std::vector<StoreySpread> storeySpread;  ///< SSPR
  std::vector<BuildingLoss> losses;        ///< LOSS
  /// DPRB, or derived from LOSS on reading a file with LOSS (the two never share a file: the encoder
  /// writes DPRB only for a tile without losses).
  std::vector<BuildingDamageOdds> odds;
  DriftSeries driftSeries;  ///< DSER (tile summaries; not the city-wide index)
};

std::vector<std::uint8_t> encodeResponseSummary(const ResponseSummaryTile& tile);
Result<ResponseSummaryTile> decodeResponseSummary(std::span<const std::uint8_t> bytes, std::string_view name);

/// One direction of one building's history.
struct HistoryDirection {
  std::uint8_t modes = 0;                 ///< basis vectors (0: no motion in this direction)
  std::vector<float> shapes;              ///< floors × modes, floor-major (floor 1 first), metres per unit
  std::vector<float> scales;              ///< modes: coordinate value of one quantization step
  std::vector<std::int16_t> coordinates;  ///< sampleCount × modes, time-major (in memory; files are mode-major)
};

struct BuildingHistory {
  std::uint16_t floors = 0;  ///< floor levels above ground (= storeys); 0: no history
  float sampleRateHz = 0.0f;
  float startSeconds = 0.0f;      ///< the building is at rest before this time (its shaking arrives)
  std::uint32_t sampleCount = 0;  ///< samples at t = start + i / rate, i = 0 .. sampleCount-1
  std::uint8_t bits = 16;         ///< 8 or 16: stored width of the coordinates
  HistoryDirection x, y;
};

struct ResponseHistoryTile {
  float durationSeconds = 0.0f;
  std::vector<BuildingHistory> buildings;
};

std::vector<std::uint8_t> encodeResponseHistory(const ResponseHistoryTile& tile);
Result<ResponseHistoryTile> decodeResponseHistory(std::span<const std::uint8_t> bytes, std::string_view name);

/// Displacements (metres, x and y) of floor levels 0 .. floors at time t seconds (floor 0, the
/// ground, is 0), Catmull-Rom interpolated; times beyond the history hold its last sample. What
/// the encoder's error measure and the fuzzers reconstruct; the interpolation itself is
/// engine::anim's (qv/anim/HistorySampling.h), which the viewer's frame loop uses directly.
void sampleHistory(const BuildingHistory& history, double timeSeconds, std::span<float> floorsX,
                   std::span<float> floorsY);

/// Appends the drift series of `history` (DriftSeries: windows of 1 / series.rateHz seconds from
/// its start, each the largest inter-storey drift ratio over its storeys and the two directions,
/// |dx| / storeyHeightM or |dy| / storeyHeightM, as the summary's peak drift and the HAZUS
/// thresholds have it, at the history's stored samples; a window between two samples takes the
/// larger of theirs) to `series.codes` and returns its span. A history without samples or floors
/// gives count 0. series.rateHz and fullScale must be set (> 0).
DriftSpan appendDriftSeries(const BuildingHistory& history, float storeyHeightM, DriftSeries& series);

}  // namespace qv
