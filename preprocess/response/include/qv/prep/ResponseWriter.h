// Writing a city's response: per-building results (computed by the MDOF solver or imported from
// another solver) become response summary tiles for every tile and history tiles for the leaves,
// in a new folder `response-<n>/`, then the manifest is replaced (the commit point) and the
// previous response folder removed. A failure before the manifest is replaced leaves the city as
// it was.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/Tileset.h"

namespace qv::prep {

/// The result of one building, as the writer needs it.
struct BuildingResult {
  BuildingResponse summary;            ///< firstStorey is ignored (the writer lays storeys out)
  std::vector<float> storeyPeakDrift;  ///< summary.storeys values, ground up
  // Optional per-building values (summary sections SPEC, SITE, SUIT, SSPR, LOSS): a section is written
  // when some building of the response has its value; the others then get zeros.
  std::optional<BuildingScaling> scaling;
  /// The shaking field's values at the building (section SITE), with or without a result.
  std::optional<BuildingSite> site;
  std::optional<BuildingSpread> spread;
  std::vector<StoreySpread> storeySpread;  ///< empty, or summary.storeys values
  std::optional<BuildingLoss> loss;
  BuildingHistory history;  ///< floors == 0 when there is no history
  /// The far view's drift series (DriftSeries, section DSER), made by writeLeaf from the history.
  float driftStartSeconds = 0.0f;
  std::vector<std::uint8_t> driftCodes;
  /// Without a result: the details of summary.noResultReason (e.g. why the model is invalid),
  /// kept in the response notes for `info --building`.
  std::string noResultDetail;
};

/// The response notes (`response-<n>/notes.json`, docs/formats.md): per building without a result
/// its reason and details, per approximate building its unconverged steps and largest residual.
struct ResponseNotes {
  struct NoResult {
    std::string id;
    NoResultReason reason = NoResultReason::Unknown;
    std::string detail;
  };
  struct Approximate {
    std::string id;
    std::uint32_t unconvergedSteps = 0;
    float worstResidualRatio = 0.0f;
  };
  std::vector<NoResult> noResult;        ///< sorted by id
  std::vector<Approximate> approximate;  ///< sorted by largest residual, then id
};
std::string responseNotesToJson(const ResponseNotes& notes);
Result<ResponseNotes> parseResponseNotes(std::string_view json, const std::string& name);
/// The notes of a city's response (empty notes when the manifest names none: older responses).
Result<ResponseNotes> loadResponseNotes(const std::string& cityDir, const Tileset& tileset);

struct ResponseWriteReport {
  std::uint64_t summaryBytes = 0;
  /// Of summaryBytes, the far view's drift series (DSER) in the tile summaries, and how many
  /// buildings' series they hold (a building counts once per tile that holds it).
  std::uint64_t driftSeriesBytes = 0;
  std::uint64_t driftSeriesBuildings = 0;
  std::uint64_t historyBytes = 0;
  /// The summaries and histories before compression (the files are stored as Zstandard frames).
  std::uint64_t uncompressedBytes = 0;
  std::uint64_t damage[6] = {0, 0, 0, 0, 0, 0};             ///< none … complete, no_result
  std::map<NoResultReason, std::uint64_t> noResultReasons;  ///< buildings without a result, by reason
  std::uint64_t approximate = 0;                            ///< buildings with an approximate result
  std::string folder;                                       ///< response-<n>
};

/// The response-<n> folder a manifest's response is in ("" when it names none or cannot be read).
std::string responseFolderOf(const std::string& manifestPath);

class ResponseWriter {
 public:
  /// Prepares a new response folder in `cityDir` for `tileset` (the manifest as read).
  static Result<std::unique_ptr<ResponseWriter>> create(const std::string& cityDir, const Tileset& tileset);
  /// A writer for one part of a sharded run (`response --shard`, ResponseParts.h): the leaves go
  /// into `folder` (relative to `cityDir`, created here), each leaf's full summary is kept for
  /// partSummaries(), and commit() is not called: the part is published by renaming the folder
  /// (keep() then stops the destructor removing it).
  static Result<std::unique_ptr<ResponseWriter>> createPart(const std::string& cityDir, const Tileset& tileset,
                                                            const std::string& folder);
  /// Removes the new folder unless commit() succeeded.
  ~ResponseWriter();
  ResponseWriter(const ResponseWriter&) = delete;
  ResponseWriter& operator=(const ResponseWriter&) = delete;

  /// Writes the history and summary tiles of leaf `node` from `results` (one per building of the
  /// leaf, in file order; thread-safe across different leaves) and remembers the summaries for
  /// the inner tiles.
  Status writeLeaf(std::uint32_t node, const CityTile& tile, std::vector<BuildingResult>& results);
  /// A leaf written by a part (ResponseParts.h), taken into this response: its files `files` (paths
  /// relative to the city) are linked (copied across file systems) into the new folder, its results
  /// remembered as writeLeaf does (`results`: one per building of `tile`, from the part's full
  /// summary; their notes come separately, addNotes). `stats` are what writeLeaf counted for it.
  struct LeafStats {
    std::uint64_t uncompressedBytes = 0, driftSeriesBytes = 0, driftSeriesBuildings = 0;
  };
  Status adoptLeaf(std::uint32_t node, const TileResponseFiles& files, const CityTile& tile,
                   std::vector<BuildingResult>& results, const LeafStats& stats);
  /// Publishes the response as scenario `index` (1-based) of a catalogue whose scenarios are
  /// `names` (ResponseCatalogue.h): commit() writes scenario-<index>.json (and tileset.json for
  /// scenario 1) and scenarios.json, and removes only this scenario's previous folder.
  void setScenario(std::size_t index, std::vector<std::string> names);
  /// Notes of adopted leaves (sorted at commit()).
  void addNotes(const ResponseNotes& notes);

  /// Writes the inner tiles' summaries (by building id from the leaves), then the manifest with
  /// `info`, and removes the previous response folder. Call once, after every leaf.
  Result<ResponseWriteReport> commit(ResponseInfo info);

  /// Writes `text` as `<folder>/<name>` (e.g. consequences.json) before commit(); returns its entry
  /// for the manifest.
  Result<CityFile> writeFile(const std::string& name, const std::string& text);

  [[nodiscard]] const std::string& folder() const { return folder_; }
  /// Part writers: the leaves written so far, with their files, counts and full summaries (every
  /// section, as a response without a city-wide index keeps them: what adoptLeaf rebuilds the
  /// results from).
  struct PartLeaf {
    std::uint32_t node = 0;
    TileResponseFiles files;
    LeafStats stats;
    std::vector<std::uint8_t> fullSummary;  ///< encodeResponseSummary, uncompressed
  };
  [[nodiscard]] const std::vector<PartLeaf>& partLeaves() const { return partLeaves_; }
  [[nodiscard]] const ResponseNotes& notes() const { return notes_; }
  [[nodiscard]] const ResponseWriteReport& report() const { return report_; }
  /// Stops the destructor removing the folder (a part writer whose folder was published).
  void keep() { committed_ = true; }

 private:
  ResponseWriter(std::string cityDir, Tileset tileset, std::string folder);
  /// writeLeaf's and adoptLeaf's bookkeeping under the lock: the counts, the summaries by id for
  /// the inner tiles, and (writeLeaf) the notes.
  void remember(std::uint32_t node, const TileResponseFiles& files, const CityTile& tile,
                std::vector<BuildingResult>& results, const LeafStats& stats, bool withNotes);
  std::string cityDir_;
  Tileset tileset_;
  std::string folder_;
  std::vector<std::string> previousFolders_;
  std::mutex mutex_;
  std::map<std::string, BuildingResult> byId_;  ///< summaries (no histories) for the inner tiles and index
  ResponseWriteReport report_;
  ResponseNotes notes_;
  bool committed_ = false;
  bool part_ = false;
  std::size_t scenario_ = 0;  ///< 0: not a catalogue's scenario
  std::vector<std::string> scenarioNames_;
  std::vector<PartLeaf> partLeaves_;
};

}  // namespace qv::prep
