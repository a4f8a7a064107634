#include "qv/scene/CityIndex.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numeric>

namespace qv {
namespace {

// What malloc holds for a request of `n` bytes: the request and one size word, rounded up to two
// words, at least four (dlmalloc's chunks, which Emscripten's malloc and glibc's share).
std::uint64_t heapBlockBytes(std::uint64_t n) {
  constexpr std::uint64_t kWord = sizeof(void*);
  return std::max<std::uint64_t>(4 * kWord, (n + kWord + 2 * kWord - 1) / (2 * kWord) * (2 * kWord));
}

// What a string holds outside its object: nothing while its text lives in the object (the small
// string buffer: up to 10 characters in WASM's libc++, 22 in native libc++, 15 in libstdc++), else
// its capacity and the terminating zero as malloc holds them.
std::uint64_t stringHeapBytes(const std::string& s) {
  const auto text = reinterpret_cast<std::uintptr_t>(s.data());
  const auto object = reinterpret_cast<std::uintptr_t>(&s);
  if (text >= object && text < object + sizeof(std::string)) return 0;
  return heapBlockBytes(s.capacity() + 1);
}

// What a summary in the index's order holds, before it is fetched: the sections `quakeview-prep
// response` writes for every building (its result, scaling, spread over the suite, HAZUS losses
// and drawing odds) and for every storey (peak drift and its spread). The site (SITE, with a
// ShakeMap or a scenario) is not counted: the check after decoding has it.
std::uint64_t citySummaryEstimateBytes(std::uint64_t buildings, std::uint64_t storeys) {
  return buildings * (sizeof(BuildingResponse) + sizeof(BuildingScaling) + sizeof(BuildingSpread) +
                      sizeof(BuildingLoss) + sizeof(BuildingDamageOdds)) +
         storeys * (sizeof(float) + sizeof(StoreySpread));
}

std::string megabytesText(std::uint64_t bytes) {
  return std::to_string((bytes + (1u << 19)) >> 20) + " MB";
}

}  // namespace

std::uint64_t searchIndexHeapBytes(const std::vector<SearchEntry>& entries) {
  std::uint64_t total = heapBlockBytes(entries.capacity() * sizeof(SearchEntry));
  for (const SearchEntry& e : entries) {
    for (const std::string* text : {&e.id, &e.name, &e.address, &e.use, &e.facilityKind})
      total += stringHeapBytes(*text);
  }
  return total;
}

bool BuildingFilters::usePasses(std::string_view buildingUse) const {
  if (use.empty()) return true;
  std::string_view rest = use;
  while (true) {
    const std::size_t plus = rest.find('+');
    if (rest.substr(0, plus) == buildingUse) return true;
    if (plus == std::string_view::npos) return false;
    rest.remove_prefix(plus + 1);
  }
}

bool BuildingFilters::passes(FacilityCategory facility, std::string_view buildingUse, const BuildingResponse* r,
                             const BuildingLoss* loss) const {
  if (loss == nullptr) return passes(facility, buildingUse, r, static_cast<const BuildingDamageOdds*>(nullptr));
  const BuildingDamageOdds odds = BuildingDamageOdds::of(*loss);
  return passes(facility, buildingUse, r, &odds);
}

bool BuildingFilters::passes(FacilityCategory facility, std::string_view buildingUse, const BuildingResponse* r,
                             const BuildingDamageOdds* loss) const {
  if (const unsigned mask = categoryMask(); mask != 0 && (mask & facilityCategoryBit(facility)) == 0) return false;
  if (!usePasses(buildingUse)) return false;
  if (minDamage >= 0) {
    if (r == nullptr || r->damage == DamageState::NoResult) return false;
    if (static_cast<int>(r->damage) < minDamage) return false;
  }
  if (probabilityActive()) {
    if (loss == nullptr || r == nullptr || r->source == ResponseSource::None) return false;
    // Compared in whole hundredths of a percent, so 10 % passes a probability printed as "10 %".
    const double percent = static_cast<double>(loss->structuralAtLeast(probabilityState)) * 100.0;
    if (std::round(percent * 100.0) < static_cast<double>(minProbabilityPercent) * 100.0) return false;
  }
  return true;
}

int listProbabilityState(const BuildingFilters& filters) {
  if (filters.probabilityActive()) return filters.probabilityState;
  return std::clamp(filters.minDamage, 1, 4);
}

std::string_view listName(const BuildingListEntry& entry) {
  if (!entry.name.empty()) return entry.name;
  if (!entry.address.empty()) return entry.address;
  return entry.id;
}

std::string useAndFacilityText(const BuildingListEntry& entry) {
  const bool genericUse = entry.use.empty() || entry.use == "unknown" || entry.use == "other";
  const bool facility = entry.facility != FacilityCategory::None;
  const std::string kind = facilityKindLabel(entry.facilityKind);
  if (!facility) return entry.use.empty() ? std::string("unknown use") : entry.use;
  const std::string category(facilityCategoryLabel(entry.facility));
  if (genericUse && !kind.empty()) return kind + " (" + category + ")";
  if (kind.empty() || kind == facilityKindLabel(entry.use)) {
    return (genericUse ? std::string("unknown use") : entry.use) + " (" + category + ")";
  }
  return entry.use + " (" + category + ": " + kind + ")";
}

std::string listRowText(const BuildingListEntry& entry, double fromX, double fromY, int probabilityState) {
  std::string text(listName(entry));
  text += " | ";
  if (entry.loss && probabilityState >= 1 && probabilityState <= 4) {
    char probability[64];
    std::snprintf(probability, sizeof probability, "P(>= %s) %.0f %%, ",
                  std::string(damageStateName(static_cast<DamageState>(probabilityState))).c_str(),
                  static_cast<double>(entry.loss->structuralAtLeast(probabilityState)) * 100.0);
    text += probability;
  }
  text += damageStateName(entry.damage);
  if (entry.damage != DamageState::NoResult) {
    char drift[32];
    std::snprintf(drift, sizeof drift, " %.2f %%", static_cast<double>(entry.peakDriftRatio) * 100.0);
    text += drift;
  }
  text += " | " + useAndFacilityText(entry);
  const double distanceM = std::hypot(entry.x - fromX, entry.y - fromY);
  char distance[32];
  if (distanceM < 999.5)
    std::snprintf(distance, sizeof distance, " | %.0f m", distanceM);
  else
    std::snprintf(distance, sizeof distance, " | %.1f km", distanceM / 1000.0);
  return text + distance;
}

CityIndex::CityIndex(FileLoader& loader, std::string manifestUrl)
    : loader_(loader), manifestUrl_(std::move(manifestUrl)) {}

CityIndex::~CityIndex() {
  loader_.cancel(search_);
  loader_.cancel(summaryLoad_);
  loader_.cancel(consequencesLoad_);
}

std::uint32_t CityIndex::pendingFiles() const {
  return (search_.state == TileState::Loading ? 1u : 0u) + (summaryLoad_.state == TileState::Loading ? 1u : 0u) +
         (consequencesLoad_.state == TileState::Loading ? 1u : 0u);
}

const SearchEntry* CityIndex::entry(std::string_view id) const {
  const auto at = position(id);
  return at ? &entries_[*at] : nullptr;
}

std::optional<std::uint32_t> CityIndex::position(std::string_view id) const {
  if (!loaded()) return std::nullopt;
  // The first position with this id (byId_ is ordered by id, then position).
  const auto it = std::lower_bound(byId_.begin(), byId_.end(), id,
                                   [&](std::uint32_t p, std::string_view key) { return entries_[p].id < key; });
  if (it == byId_.end() || entries_[*it].id != id) return std::nullopt;
  return *it;
}

const ResponseSummaryTile* CityIndex::summary() const {
  return summary_ ? &*summary_ : nullptr;
}

void CityIndex::fetch(FileLoad& load, FileKind kind, const CityFile& file,
                      std::function<std::string(std::vector<std::uint8_t>&, const std::string&)> accept) {
  const FileSpec spec{kind, resolveUrl(manifestUrl_, file.file), file.bytes, file.crc32, {}};
  loader_.start(load, spec, [url = spec.url, accept = std::move(accept)](std::vector<std::uint8_t>& bytes) {
    std::string problem = accept(bytes, url);
    return problem.empty() ? Verdict::loaded() : Verdict::rejected(std::move(problem), false);
  });
}

void CityIndex::retry() {
  // Retried with backoff, as tiles are (the server may recover).
  if (search_.failures > 0 && loader_.due(search_)) request();
  // The response summary in the index's order follows the index (it is useless without it).
  requestSummary();
  if (consequencesLoad_.failures > 0) requestConsequences();
}

void CityIndex::requestConsequences() {
  if (!tileset_ || !tileset_->response || !tileset_->response->consequences || tileset_->responseOutOfDate() ||
      !loader_.due(consequencesLoad_)) {
    return;
  }
  fetch(consequencesLoad_, FileKind::Consequences, *tileset_->response->consequences,
        [this](std::vector<std::uint8_t>& bytes, const std::string& url) -> std::string {
          const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          auto parsed = seismic::parseConsequences(text, url);
          if (!parsed.ok()) return parsed.error();
          consequences_ = std::make_unique<seismic::ConsequenceTotals>(std::move(parsed).value());
          bytes_ += sizeof(seismic::ConsequenceTotals) +
                    consequences_->districts.size() * sizeof(seismic::ConsequenceTotals::District);
          return {};
        });
}

void CityIndex::setMemoryAllowance(std::uint64_t bytes) {
  if (bytes == allowanceBytes_) return;
  allowanceBytes_ = bytes;
  // A file left out that fits now is fetched again (by the next request or retry).
  if (searchNeedsBytes_ > 0 && searchNeedsBytes_ <= bytes) {
    loader_.cancel(search_);
    search_ = FileLoad{};
    searchNeedsBytes_ = 0;
  }
  if (summaryNeedsBytes_ > 0 && bytes_ + summaryNeedsBytes_ <= bytes) {
    loader_.cancel(summaryLoad_);
    summaryLoad_ = FileLoad{};
    summaryNeedsBytes_ = 0;
  }
  updateMemoryNotice();
}

void CityIndex::updateMemoryNotice() {
  memoryNotice_.clear();
  if (searchNeedsBytes_ > 0) {
    memoryNotice_ = "Search, the city-wide list and the report are off: the search index of " +
                    std::to_string(tileset_ != nullptr ? tileset_->buildings : 0) + " buildings needs about " +
                    megabytesText(searchNeedsBytes_) + ", more than the " + megabytesText(allowanceBytes_) +
                    " the memory budget leaves the city-wide files.";
  } else if (summaryNeedsBytes_ > 0) {
    memoryNotice_ =
        "Damage in the city-wide list, the search results and the report's building tables is off: every "
        "building's response in one file needs about " +
        megabytesText(summaryNeedsBytes_) + " beside the search index's " + megabytesText(bytes_) + ", more than the " +
        megabytesText(allowanceBytes_) +
        " the memory budget leaves the city-wide files. The buildings drawn still show theirs.";
  }
}

void CityIndex::request() {
  requestConsequences();
  if (!tileset_ || !tileset_->search || searchNeedsBytes_ > 0) return;
  if (search_.state != TileState::Loaded && search_.state != TileState::Loading) {
    // At least its table and its id order; the texts too long for a string object come on top.
    const std::uint64_t least = tileset_->buildings * (sizeof(SearchEntry) + sizeof(std::uint32_t));
    if (least > allowanceBytes_) {
      searchNeedsBytes_ = least;
      updateMemoryNotice();
      return;
    }
  }
  fetch(search_, FileKind::SearchIndex, *tileset_->search,
        [this](std::vector<std::uint8_t>& bytes, const std::string& url) -> std::string {
          auto decoded = decodeSearchIndex(bytes, url);
          if (!decoded.ok()) return decoded.error();
          if (decoded->size() != tileset_->buildings) {
            return url + ": " + std::to_string(decoded->size()) + " entries, but the manifest says the city has " +
                   std::to_string(tileset_->buildings) + " buildings";
          }
          for (std::size_t i = 0; i < decoded->size(); ++i) {
            const std::uint32_t leaf = (*decoded)[i].leaf;
            if (leaf >= tileset_->nodes.size() || !tileset_->nodes[leaf].children.empty()) {
              return url + ": entry " + std::to_string(i) + " names tile " + std::to_string(leaf) +
                     ", which is not a leaf of this city";
            }
          }
          entries_ = std::move(decoded).value();
          byId_.resize(entries_.size());
          std::iota(byId_.begin(), byId_.end(), 0u);
          std::stable_sort(byId_.begin(), byId_.end(),
                           [&](std::uint32_t a, std::uint32_t b) { return entries_[a].id < entries_[b].id; });
          bytes_ = searchIndexHeapBytes(entries_) + heapBlockBytes(byId_.capacity() * sizeof(std::uint32_t));
          if (bytes_ > allowanceBytes_) {
            // More than the estimate allowed for (long names and addresses): let go.
            searchNeedsBytes_ = bytes_;
            bytes_ = 0;
            std::vector<SearchEntry>().swap(entries_);
            std::vector<std::uint32_t>().swap(byId_);
            updateMemoryNotice();
          }
          return {};
        });
}

void CityIndex::requestSummary() {
  if (!tileset_ || !tileset_->response || !tileset_->response->summaryIndex || tileset_->responseOutOfDate() ||
      !loaded() || summaryNeedsBytes_ > 0) {
    return;
  }
  if (summaryLoad_.state != TileState::Loaded && summaryLoad_.state != TileState::Loading) {
    std::uint64_t storeys = 0;
    for (const SearchEntry& e : entries_) storeys += e.storeys;
    const std::uint64_t estimate = citySummaryEstimateBytes(entries_.size(), storeys);
    if (bytes_ + estimate > allowanceBytes_) {
      summaryNeedsBytes_ = estimate;
      updateMemoryNotice();
      return;
    }
  }
  fetch(summaryLoad_, FileKind::CitySummary, *tileset_->response->summaryIndex,
        [this](std::vector<std::uint8_t>& bytes, const std::string& url) -> std::string {
          auto decoded = decodeResponseSummary(bytes, url);
          if (!decoded.ok()) return decoded.error();
          if (decoded->buildings.size() != entries_.size()) {
            return url + ": " + std::to_string(decoded->buildings.size()) + " buildings, the search index has " +
                   std::to_string(entries_.size());
          }
          const ResponseSummaryTile& d = *decoded;
          const std::uint64_t summaryBytes =
              d.buildings.size() * sizeof(BuildingResponse) + d.storeyPeakDrift.size() * sizeof(float) +
              d.scaling.size() * sizeof(BuildingScaling) + d.sites.size() * sizeof(BuildingSite) +
              d.spread.size() * sizeof(BuildingSpread) + d.storeySpread.size() * sizeof(StoreySpread) +
              d.losses.size() * sizeof(BuildingLoss) + d.odds.size() * sizeof(BuildingDamageOdds);
          if (bytes_ + summaryBytes > allowanceBytes_) {
            summaryNeedsBytes_ = summaryBytes;  // more than estimated (e.g. with sites): let go
            updateMemoryNotice();
            return {};
          }
          summary_ = std::move(decoded).value();
          // The suite's spread over the city: the median of the buildings' drift log standard deviations.
          std::vector<float> betas;
          for (std::size_t i = 0; i < summary_->spread.size(); ++i) {
            if (summary_->spread[i].records > 1) betas.push_back(summary_->spread[i].driftBeta);
          }
          if (!betas.empty()) {
            std::nth_element(betas.begin(), betas.begin() + static_cast<std::ptrdiff_t>(betas.size() / 2), betas.end());
            medianDriftBeta_ = betas[betas.size() / 2];
          }
          bytes_ += summaryBytes;
          return {};
        });
}

bool CityIndex::settled() const {
  if (!tileset_) return false;
  const bool consequencesExpected =
      tileset_->response && tileset_->response->consequences && !tileset_->responseOutOfDate();
  if (consequencesExpected && consequencesLoad_.state != TileState::Loaded &&
      consequencesLoad_.state != TileState::Failed) {
    return false;
  }
  if (!tileset_->search || search_.state == TileState::Failed || searchNeedsBytes_ > 0) return true;
  if (search_.state != TileState::Loaded) return false;
  const bool summaryExpected = tileset_->response && tileset_->response->summaryIndex && !tileset_->responseOutOfDate();
  return !summaryExpected || summaryLoad_.state == TileState::Loaded || summaryLoad_.state == TileState::Failed ||
         summaryNeedsBytes_ > 0;
}

const BuildingResponse* CityIndex::response(std::uint32_t index) const {
  return summary_ && index < summary_->buildings.size() ? &summary_->buildings[index] : nullptr;
}

std::optional<BuildingListEntry> CityIndex::listEntryOf(std::string_view id) const {
  const auto at = position(id);
  if (!at) return std::nullopt;
  return listEntry(*at);
}

const BuildingLoss* CityIndex::lossAt(std::uint32_t index) const {
  const BuildingResponse* r = response(index);
  if (r == nullptr || r->source == ResponseSource::None || !summary_ || index >= summary_->losses.size())
    return nullptr;
  return &summary_->losses[index];
}

BuildingListEntry CityIndex::listEntry(std::uint32_t index) const {
  const SearchEntry& s = entries_[index];
  BuildingListEntry e;
  e.id = s.id;
  e.name = s.name;
  e.address = s.address;
  e.use = s.use;
  e.importance = s.importance;
  e.facility = s.facility;
  e.facilityKind = s.facilityKind;
  e.heightM = s.heightM;
  e.storeys = s.storeys;
  e.x = s.x;
  e.y = s.y;
  if (const BuildingResponse* r = response(index)) {
    e.damage = r->damage;
    e.peakDriftRatio = r->peakDriftRatio;
    e.peakRoofDisplacementM = r->peakRoofDisplacementM;
    e.pgaG = r->pgaG;
    if (const BuildingLoss* l = lossAt(index)) e.loss = *l;
  }
  if (summary_ && index < summary_->sites.size()) e.site = summary_->sites[index];
  return e;
}

std::vector<BuildingListEntry> CityIndex::search(std::string_view query, std::size_t limit) const {
  std::vector<BuildingListEntry> out;
  if (!loaded()) return out;
  if (query != searchedQuery_ || searchedEntries_ != entries_.data()) {
    searchedQuery_ = std::string(query);
    searchedEntries_ = entries_.data();
    struct Match {
      int rank;
      float heightM;
      std::uint32_t index;
    };
    std::vector<Match> matches;
    constexpr int kOthers = 5;  // after every name rank
    for (std::uint32_t i = 0; i < entries_.size(); ++i) {
      const SearchEntry& e = entries_[i];
      const int idRank = queryMatchRank(e.id, query);
      const int nameRank = queryMatchRank(e.name, query);
      const int addressRank = queryMatchRank(e.address, query);
      int rank = INT_MAX;
      if (idRank == 0) rank = 0;
      if (nameRank >= 0) rank = std::min(rank, nameRank);
      if (addressRank >= 0) rank = std::min(rank, kOthers + addressRank);
      if (idRank > 0) rank = std::min(rank, kOthers + idRank);
      if (rank != INT_MAX) matches.push_back({rank, e.heightM, i});
    }
    std::sort(matches.begin(), matches.end(), [](const Match& a, const Match& b) {
      if (a.rank != b.rank) return a.rank < b.rank;
      if (a.heightM != b.heightM) return a.heightM > b.heightM;
      return a.index < b.index;
    });
    searchOrder_.clear();
    for (const Match& m : matches) searchOrder_.push_back(m.index);
  }
  for (std::size_t k = 0; k < searchOrder_.size() && out.size() < limit; ++k) out.push_back(listEntry(searchOrder_[k]));
  return out;
}

std::vector<std::pair<std::string, std::size_t>> CityIndex::useCounts() const {
  std::vector<std::pair<std::string, std::size_t>> out;
  if (!loaded()) return out;
  std::map<std::string_view, std::size_t> counts;
  for (const SearchEntry& e : entries_) ++counts[e.use];
  out.reserve(counts.size());
  for (const auto& [use, n] : counts) out.emplace_back(std::string(use), n);
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

std::vector<BuildingListEntry> CityIndex::filteredList(const BuildingFilters& filters, std::size_t limit,
                                                       std::size_t* total) const {
  std::vector<BuildingListEntry> out;
  if (total != nullptr) *total = 0;
  if (!loaded()) return out;
  // Most likely damaged first: with probabilities by P(>= the list's state), then the expected
  // state; without (e.g. imported results) after them, by the deterministic state.
  struct Key {
    bool probabilities;
    double probability;
    double expected;
    int damage;
    float drift;
    std::uint32_t index;
  };
  const int state = listProbabilityState(filters);
  std::vector<Key> keys;
  for (std::uint32_t i = 0; i < entries_.size(); ++i) {
    const BuildingResponse* r = response(i);
    const BuildingLoss* loss = lossAt(i);
    if (!filters.passes(entries_[i].facility, entries_[i].use, r, loss)) continue;
    const int damage = r != nullptr && r->damage != DamageState::NoResult ? static_cast<int>(r->damage) : -1;
    keys.push_back({loss != nullptr, loss != nullptr ? static_cast<double>(loss->structuralAtLeast(state)) : 0.0,
                    loss != nullptr ? static_cast<double>(loss->expectedState()) : 0.0, damage,
                    r != nullptr ? r->peakDriftRatio : 0.0f, i});
  }
  if (total != nullptr) *total = keys.size();
  const std::size_t n = std::min(limit, keys.size());
  std::partial_sort(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(n), keys.end(),
                    [](const Key& a, const Key& b) {
                      if (a.probabilities != b.probabilities) return a.probabilities;
                      if (a.probability != b.probability) return a.probability > b.probability;
                      if (a.expected != b.expected) return a.expected > b.expected;
                      if (a.damage != b.damage) return a.damage > b.damage;
                      if (a.drift != b.drift) return a.drift > b.drift;
                      return a.index < b.index;
                    });
  for (std::size_t k = 0; k < n; ++k) out.push_back(listEntry(keys[k].index));
  return out;
}

}  // namespace qv
