// CityIndex: the city-wide side of a city: its search index (every building's id, name, address,
// use and leaf tile) and the response summary in the index's order, each loaded once through the
// FileLoader, and what is built from them: search, the filtered list of buildings, lookup by id;
// and the response's consequence totals (consequences.json).
// Until they load, search and lists are empty.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "qv/format/FacilityCategory.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/format/Tileset.h"
#include "qv/scene/FileLoader.h"
#include "qv/seismic/ConsequencesFile.h"

namespace qv {

/// Which buildings are shown at full strength; the others are dimmed.
struct BuildingFilters {
  int minDamage = -1;  ///< -1: any; 0..4: damage state at least this (none .. complete)
  /// The probabilistic damage filter: only buildings whose HAZUS probability of structural damage
  /// at least `probabilityState` (1..4: slight .. complete; -1: off) is at least
  /// `minProbabilityPercent` % (1..100). A building without probabilities does not pass.
  int probabilityState = -1;
  int minProbabilityPercent = 0;
  /// Empty: any; else one normalized use or several joined by '+' ("hospital+school+fire_station").
  std::string use;
  /// Only critical facilities: FacilityCategory Essential or SchoolShelter (kCriticalCategories).
  bool criticalOnly = false;
  /// Only these facility categories (facilityCategoryBit bits); 0: any. With criticalOnly, a
  /// building passes when its category is critical or in this set.
  unsigned categories = 0;
  [[nodiscard]] bool probabilityActive() const {
    return probabilityState >= 1 && probabilityState <= 4 && minProbabilityPercent > 0;
  }
  [[nodiscard]] bool active() const {
    return minDamage >= 0 || probabilityActive() || !use.empty() || criticalOnly || categories != 0;
  }
  [[nodiscard]] bool passes(const BuildingAttributes& a, const BuildingResponse* r,
                            const BuildingDamageOdds* odds) const {
    return passes(classifyFacility(a).category, a.use, r, odds);
  }
  /// `loss`: the building's HAZUS probabilities, nullptr without them (only the probability filter
  /// reads it).
  [[nodiscard]] bool passes(FacilityCategory facility, std::string_view use, const BuildingResponse* r,
                            const BuildingLoss* loss = nullptr) const;
  /// The same with the probabilities a tile summary draws by (DPRB).
  [[nodiscard]] bool passes(FacilityCategory facility, std::string_view use, const BuildingResponse* r,
                            const BuildingDamageOdds* odds) const;
  /// Whether `buildingUse` is one of the uses (true when no use is chosen).
  [[nodiscard]] bool usePasses(std::string_view buildingUse) const;
  /// The category bits a building must match (criticalOnly folded in); 0: any.
  [[nodiscard]] unsigned categoryMask() const { return categories | (criticalOnly ? kCriticalCategories : 0u); }
  friend bool operator==(const BuildingFilters&, const BuildingFilters&) = default;
};

/// The probability the list sorts by and shows: P(structural damage >= the probability filter's
/// state) when that filter is on, else P(>= the damage filter's state) when that one is (at least
/// slight), else P(>= slight).
[[nodiscard]] int listProbabilityState(const BuildingFilters& filters);

/// One row of the city-wide list of (filtered) buildings.
struct BuildingListEntry {
  std::string id;
  std::string name;  ///< from the search index when loaded, else empty
  std::string address;
  std::string use;
  Importance importance = Importance::General;
  FacilityCategory facility = FacilityCategory::None;
  std::string facilityKind;  ///< SearchEntry::facilityKind
  DamageState damage = DamageState::NoResult;
  float peakDriftRatio = 0.0f;
  float peakRoofDisplacementM = 0.0f;
  float pgaG = 0.0f;  ///< the record's peak after scaling (BuildingResponse::pgaG), not the site's
  float heightM = 0.0f;
  std::uint16_t storeys = 0;
  double x = 0.0, y = 0.0;           ///< centroid, metres in the city frame
  std::optional<BuildingLoss> loss;  ///< HAZUS probabilities and consequences, when the response has them
  BuildingSite site;                 ///< the shaking field at the site (source None without one)
};

/// What a list row and a map label say of a building's use and facility: "hospital (essential)";
/// where its use is generic (unknown or other) the facility's kind stands for it, "fuel
/// (hazardous)"; where the kind says more than the use, "civic (school or shelter: community
/// centre)"; the use alone ("unknown use" when none) for a building that is no facility.
std::string useAndFacilityText(const BuildingListEntry& entry);

/// What a list row names a building by: its name, else its address, else (only when it has
/// neither) its id.
std::string_view listName(const BuildingListEntry& entry);
/// The text of one row of the on-screen list: name (listName), damage, use and facility
/// category, and the distance from (fromX, fromY) (metres in the city frame, the camera target):
/// "City Hospital | moderate 0.42 % | hospital (essential) | 1.2 km". With HAZUS probabilities the
/// damage field also gives P(structural damage >= `probabilityState`) (listProbabilityState):
/// "City Hospital | P(>= slight) 21 %, moderate 0.42 % | ...". Distances under 1 km in whole
/// metres, else km with one decimal.
std::string listRowText(const BuildingListEntry& entry, double fromX, double fromY, int probabilityState = 1);

/// The heap a decoded search index holds: the vector's block and every string's text that does not
/// fit in the string object, each as malloc holds it (a request of n bytes takes n plus a size
/// word, rounded up to two words). About 145 bytes a building of the synthetic city in WASM.
[[nodiscard]] std::uint64_t searchIndexHeapBytes(const std::vector<SearchEntry>& entries);

class CityIndex {
 public:
  /// Files are resolved against `manifestUrl`; nothing loads before open().
  CityIndex(FileLoader& loader, std::string manifestUrl);
  ~CityIndex();
  CityIndex(const CityIndex&) = delete;
  CityIndex& operator=(const CityIndex&) = delete;

  /// The city's manifest has loaded; it must outlive this index.
  void open(const Tileset& tileset) { tileset_ = &tileset; }
  /// Fetches the search index and the consequence totals once (cities without them have nothing
  /// to load).
  void request();
  /// Once a frame: a failed file is fetched again after its backoff; the response summary in the
  /// index's order follows the index.
  void retry();

  /// The most the city-wide files may hold on the heap, in bytes (CityScene gives them three
  /// quarters of its memory budget; the tiles keep the rest). The search index and the response
  /// summary in its order are fetched only when what they will hold fits beside what is loaded:
  /// estimated before the fetch (the index: its table and id order for the manifest's building
  /// count; the summary: what `quakeview-prep response` writes per building and storey, the
  /// storeys counted in the index), measured after decoding, when a file that does not fit after
  /// all is let go. So a city of millions of buildings stays within the budget, without what
  /// does not fit (memoryNotice says what), instead of exhausting the page's memory. A file left
  /// out is fetched once the allowance grows enough for it. Unlimited until set.
  void setMemoryAllowance(std::uint64_t bytes);
  /// Why a city-wide file is not loaded ("" while none is left out): what it serves, about how
  /// many MB it needs and how many the allowance gives.
  [[nodiscard]] const std::string& memoryNotice() const { return memoryNotice_; }

  /// The search index has loaded (and is kept: not left out for memory).
  [[nodiscard]] bool loaded() const { return search_.state == TileState::Loaded && searchNeedsBytes_ == 0; }
  /// The response's consequence totals (consequences.json) once loaded, else nullptr.
  [[nodiscard]] const seismic::ConsequenceTotals* consequences() const { return consequences_.get(); }
  [[nodiscard]] bool consequencesFailed() const { return consequencesLoad_.state == TileState::Failed; }
  /// Across a record suite: the median over the city's buildings of their peak drift's log standard
  /// deviation (from the summary in the index's order); nullopt for one record or until loaded.
  [[nodiscard]] std::optional<float> medianDriftBeta() const { return medianDriftBeta_; }
  /// The index (and the summary in its order) has loaded, failed or been left out for memory, or
  /// the city has none.
  [[nodiscard]] bool settled() const;
  /// Files on their way (0 .. 2).
  [[nodiscard]] std::uint32_t pendingFiles() const;
  /// Heap held by the index and its summary: every allocation counted as the allocator holds it
  /// (the memory budget is enforced on this; a 2,000,000-building index is about 300 MB in WASM).
  [[nodiscard]] std::uint64_t bytes() const { return bytes_; }

  /// Every building's entry in the index's order (empty while the index is not loaded).
  [[nodiscard]] std::span<const SearchEntry> entries() const {
    return loaded() ? std::span<const SearchEntry>(entries_) : std::span<const SearchEntry>();
  }
  /// The building's entry (nullptr while the index is not loaded, or for an unknown id).
  [[nodiscard]] const SearchEntry* entry(std::string_view id) const;
  /// The building's position in the index, and in the response summary in its order (nullopt
  /// while the index is not loaded, or for an unknown id). A hash lookup.
  [[nodiscard]] std::optional<std::uint32_t> position(std::string_view id) const;
  /// The response summary in the index's order (index.qvs): every building's full values, which
  /// tile summaries leave out (SITE, SUIT, SSPR, LOSS); nullptr until loaded.
  [[nodiscard]] const ResponseSummaryTile* summary() const;
  /// The HAZUS probabilities and consequences of the building at `position`; nullptr without a
  /// result, without them, or until the summary loads.
  [[nodiscard]] const BuildingLoss* lossAt(std::uint32_t position) const;
  /// The list row of building `id` (with its response), nullopt when the index has none.
  [[nodiscard]] std::optional<BuildingListEntry> listEntryOf(std::string_view id) const;
  /// Buildings whose id, name or address contain every word of `query`, at most `limit`, best
  /// first: the id itself, then names by how they match (queryMatchRank: the same words, starting
  /// with the query, whole words, word starts, inside words), then addresses and partial ids;
  /// within a rank the tallest (the most prominent) first, then index order. The order of the
  /// last query is kept (the panel asks every frame).
  [[nodiscard]] std::vector<BuildingListEntry> search(std::string_view query, std::size_t limit) const;
  /// How many buildings of each use the city has, most first (then by name): the use filter's
  /// choices. Empty until the index loads.
  [[nodiscard]] std::vector<std::pair<std::string, std::size_t>> useCounts() const;
  /// Buildings passing `filters`, most likely damaged first, at most `limit`; `total` receives
  /// how many pass in all. Buildings with HAZUS probabilities come first, by P(structural damage
  /// >= listProbabilityState(filters)), then by their expected damage state; then those without,
  /// by damage state; ties by peak drift, then index order.
  [[nodiscard]] std::vector<BuildingListEntry> filteredList(const BuildingFilters& filters, std::size_t limit,
                                                            std::size_t* total) const;

 private:
  void requestSummary();
  void fetch(FileLoad& load, FileKind kind, const CityFile& file,
             std::function<std::string(std::vector<std::uint8_t>&, const std::string&)> accept);
  [[nodiscard]] const BuildingResponse* response(std::uint32_t index) const;
  [[nodiscard]] BuildingListEntry listEntry(std::uint32_t index) const;

  FileLoader& loader_;
  std::string manifestUrl_;
  const Tileset* tileset_ = nullptr;
  void requestConsequences();
  FileLoad search_;
  std::vector<SearchEntry> entries_;
  // Positions of entries_ ordered by id (then position): lookup by id is a binary search. Four
  // bytes a building, where a hash map of ids took 28 in WASM (56 MB of a 2,000,000-building city).
  std::vector<std::uint32_t> byId_;
  // The last search's query and its matches in order (indices into entries_), for entries_ at
  // searchedEntries_.
  mutable std::string searchedQuery_;
  mutable const SearchEntry* searchedEntries_ = nullptr;
  mutable std::vector<std::uint32_t> searchOrder_;
  FileLoad summaryLoad_;
  std::optional<ResponseSummaryTile> summary_;  // the response, in the index's order
  FileLoad consequencesLoad_;
  std::optional<float> medianDriftBeta_;
  std::unique_ptr<seismic::ConsequenceTotals> consequences_;  // the response's totals
  std::uint64_t bytes_ = 0;
  std::uint64_t allowanceBytes_ = UINT64_MAX;
  // What a file left out for memory needs (0: not left out).
  std::uint64_t searchNeedsBytes_ = 0;
  std::uint64_t summaryNeedsBytes_ = 0;
  std::string memoryNotice_;
  void updateMemoryNotice();
};

}  // namespace qv
