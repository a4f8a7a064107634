// `quakeview-prep import-response`: floor displacement histories computed by another solver
// (OpenSees, an FE model, an integrated earthquake simulation) read from JSON or CSV, keyed by the
// city's building ids, and written as the same response tiles as `response` (ResponseWriter,
// HistoryEncoder): drifts, peak drift per storey, peak roof displacement and the Hazus damage state
// are computed here from the histories. Schemas: docs/import-response.md.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"
#include "qv/prep/ResponseWriter.h"

namespace qv::prep {

/// Length units of imported displacements.
enum class DisplacementUnit { Metre, Centimetre, Millimetre, Inch, Foot };
/// "m", "cm", "mm", "in", "ft" (also "metre(s)"/"meter(s)", "inch(es)", "foot"/"feet"); nullopt otherwise.
std::optional<DisplacementUnit> parseDisplacementUnit(std::string_view text);
double metresPerDisplacementUnit(DisplacementUnit unit);

/// One building's imported histories.
struct ImportedBuilding {
  std::string id;
  std::string place;  ///< where it was read, for messages: "a.json: buildings[3]" or "a.csv:17"
  std::size_t floors = 0;
  std::size_t frames = 0;
  double startSeconds = 0.0;  ///< time of frame 0 (>= 0)
  std::vector<float> x, y;    ///< metres relative to the ground, [frame * floors + i]; y may be empty
  std::optional<double> pgaG;
};

/// What the input files hold: one time step for all of them.
struct ImportedResults {
  double timeStepS = 0.0;
  std::string timeStepPlace;  ///< where the time step was first set
  std::string motion;         ///< the files' "motion" descriptions, joined
  std::vector<ImportedBuilding> buildings;
};

/// Reads a JSON (by content: starts with '{') or CSV file and appends its buildings to `results`.
/// `units` applies to files that do not name their units (a file that does and disagrees is an
/// error). Errors name the file and the JSON path or line.
Status readImportedResponse(const std::string& path, std::optional<DisplacementUnit> units, ImportedResults& results);

/// The writer's result of one building from its floor displacements (frame-major, metres; `y` may
/// be empty), frames `timeStepS` apart starting at `startSeconds`: drifts against the storey heights
/// of the building's model, Hazus damage for its type and era, the encoded history.
struct DisplacementSummary {
  BuildingResult result;
  double relativeError = 0.0;  ///< history reconstruction error / peak roof displacement
};
DisplacementSummary summarizeDisplacements(const BuildingAttributes& attributes, std::span<const float> x,
                                           std::span<const float> y, std::size_t floors, std::size_t frames,
                                           double timeStepS, double startSeconds, double historyTolerance);

struct ImportOptions {
  std::vector<std::string> inputs;
  std::optional<DisplacementUnit> units;
  double historyTolerance = 0.019;
  std::size_t listMissing = 10;  ///< ids without a result named in the report (all counted)
};

struct ImportReport {
  std::uint64_t buildings = 0;
  std::uint64_t imported = 0;
  std::uint64_t damage[6] = {0, 0, 0, 0, 0, 0};  ///< none … complete, no_result
  std::vector<std::string> missing;              ///< the first listMissing ids without a result
  std::uint64_t summaryBytes = 0, historyBytes = 0;
  double worstRelativeError = 0.0, p99RelativeError = 0.0;
  double timeStepS = 0.0, durationSeconds = 0.0;
  std::string motion, folder;
  double seconds = 0.0;
};

Result<ImportReport> runImportResponse(const std::string& cityDir, const ImportOptions& options);

}  // namespace qv::prep
