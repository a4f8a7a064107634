#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <utility>

#include "MiniCity.h"
#include "qv/core/Crc32.h"
#include "qv/scene/CityIndex.h"

using namespace qv;
using test::FakeFetcher;
using test::MiniCity;

namespace {

// The city index of a MiniCity over a fake server and clock, its manifest already loaded.
struct IndexRig {
  MiniCity city;
  FakeFetcher fetcher;
  FakeClock clock;
  std::vector<LoadError> errors;
  FileLoader loader{fetcher, clock, [this](const LoadError& e) { errors.push_back(e); }};
  CityIndex index{loader, "city/tileset.json"};
  IndexRig() {
    city.serve(fetcher);
    index.open(city.tileset);
  }
  /// A few frames: the index on request, then the summary in its order.
  void load() {
    index.request();
    for (int i = 0; i < 4; ++i) {
      fetcher.poll();
      index.retry();
    }
  }
};

}  // namespace

TEST_CASE("The city index searches every word in ids, names and addresses", "[scene][index]") {
  IndexRig rig;
  CHECK(rig.index.search("Building", 100).empty());  // not loaded yet
  CHECK_FALSE(rig.index.settled());
  rig.load();
  REQUIRE(rig.index.loaded());
  CHECK(rig.index.settled());
  CHECK(rig.index.search("Building", 1000).size() == MiniCity::kSide * MiniCity::kSide);
  CHECK(rig.index.search("Building", 5).size() == 5);
  const auto one = rig.index.search("building 3-4", 10);  // any case, every word
  REQUIRE(one.size() == 1);
  CHECK(one[0].id == MiniCity::idOf(3, 4));
  CHECK(one[0].x == Approx(MiniCity::centreX(3)));
  CHECK(one[0].damage == MiniCity::responseOf(3, 4).damage);
  CHECK(rig.index.search("Building 3-4 nowhere", 10).empty());
  REQUIRE(rig.index.entry(MiniCity::idOf(7, 7)) != nullptr);
  CHECK(rig.index.entry("no such building") == nullptr);
  CHECK(rig.index.bytes() > 0);
}

TEST_CASE("Search results come best match first: the id, name starts, whole words, then the tallest",
          "[scene][index]") {
  IndexRig rig;
  rig.load();
  REQUIRE(rig.index.loaded());
  // "Building 1": the names starting with it ("Building 1-j") first, tallest first; then those
  // where "1" is a whole word elsewhere ("Building i-1").
  const auto hits = rig.index.search("Building 1", 1000);
  std::size_t starting = 0;
  while (starting < hits.size() && hits[starting].name.rfind("Building 1-", 0) == 0) ++starting;
  CHECK(starting == static_cast<std::size_t>(MiniCity::kSide));
  for (std::size_t k = 1; k < starting; ++k) CHECK(hits[k - 1].heightM >= hits[k].heightM);
  for (std::size_t k = starting; k < hits.size(); ++k) CHECK(hits[k].name.find("-1") != std::string::npos);
  CHECK(hits.size() == static_cast<std::size_t>(2 * MiniCity::kSide - 1));
  // An id typed in full comes first.
  const auto byId = rig.index.search(MiniCity::idOf(5, 6), 3);
  REQUIRE_FALSE(byId.empty());
  CHECK(byId[0].id == MiniCity::idOf(5, 6));
  // The same query again gives the same order (the panel asks every frame).
  const auto again = rig.index.search("Building 1", 1000);
  REQUIRE(again.size() == hits.size());
  for (std::size_t k = 0; k < hits.size(); ++k) CHECK(again[k].id == hits[k].id);
}

TEST_CASE("The city-wide list holds the buildings passing the filters, most damaged first", "[scene][index]") {
  IndexRig rig;
  rig.load();
  BuildingFilters filters;
  filters.minDamage = static_cast<int>(DamageState::Extensive);
  std::size_t expected = 0;
  for (int i = 0; i < MiniCity::kSide; ++i) {
    for (int j = 0; j < MiniCity::kSide; ++j) {
      expected += static_cast<int>(MiniCity::responseOf(i, j).damage) >= filters.minDamage ? 1u : 0u;
    }
  }
  std::size_t total = 0;
  const auto list = rig.index.filteredList(filters, 1000, &total);
  CHECK(total == expected);
  REQUIRE(list.size() == expected);
  CHECK(list.front().damage == DamageState::Complete);
  for (std::size_t k = 1; k < list.size(); ++k) {
    const bool ordered = list[k - 1].damage > list[k].damage ||
                         (list[k - 1].damage == list[k].damage && list[k - 1].peakDriftRatio >= list[k].peakDriftRatio);
    CHECK(ordered);
  }
  const auto top = rig.index.filteredList(filters, 3, &total);
  CHECK(top.size() == 3);
  CHECK(total == expected);
}

TEST_CASE("A search index that does not match the manifest is refused with why", "[scene][index][errors]") {
  IndexRig rig;
  rig.city.tileset.buildings += 1;  // the manifest promises one building more than the index has
  rig.load();
  CHECK_FALSE(rig.index.loaded());
  CHECK(rig.index.settled());
  REQUIRE(rig.errors.size() == 1);
  CHECK(rig.errors[0].key == "city/search.qvi");
  CHECK(rig.errors[0].message.find("64 entries, but the manifest says the city has 65 buildings") != std::string::npos);
  CHECK(rig.index.search("Building", 10).empty());
}

TEST_CASE("Every building is found by its id, a repeated id by its first entry", "[scene][index]") {
  IndexRig rig;
  // The served index in reverse id order, with the last entry repeating the first one's id: the
  // lookup must not depend on the index's order, and a repeated id names its first position.
  auto& bytes = rig.fetcher.files.at("city/search.qvi");
  auto entries = decodeSearchIndex(bytes, "served");
  REQUIRE(entries.ok());
  std::reverse(entries->begin(), entries->end());
  const std::string repeated = entries->front().id;
  entries->back().id = repeated;
  const std::string dropped = MiniCity::idOf(0, 0);  // the reversed index's last entry, replaced
  REQUIRE(std::none_of(entries->begin(), entries->end(), [&](const SearchEntry& e) { return e.id == dropped; }));
  bytes = encodeSearchIndex(*entries);
  rig.city.tileset.search->bytes = bytes.size();
  rig.city.tileset.search->crc32 = crc32(bytes);
  rig.city.tileset.response.reset();  // the summary in the old order would not match
  rig.load();
  REQUIRE(rig.index.loaded());
  for (std::uint32_t i = 0; i + 1 < entries->size(); ++i) {
    const auto at = rig.index.position((*entries)[i].id);
    REQUIRE(at);
    CHECK(*at == i);
  }
  CHECK(rig.index.position(repeated) == std::optional<std::uint32_t>(0));
  CHECK_FALSE(rig.index.position(dropped));
  CHECK_FALSE(rig.index.position(""));
  CHECK_FALSE(rig.index.position("s"));
  CHECK_FALSE(rig.index.position("zzz"));
}

TEST_CASE("The index counts its heap as malloc holds it: the table, long texts, the id order",
          "[scene][index][memory]") {
  std::vector<SearchEntry> entries(3);
  for (std::size_t i = 0; i < entries.size(); ++i) entries[i].id = "s" + std::to_string(i);
  entries.shrink_to_fit();
  const std::uint64_t shortTexts = searchIndexHeapBytes(entries);
  // The table alone: short texts live inside the string objects.
  CHECK(shortTexts >= entries.size() * sizeof(SearchEntry));
  CHECK(shortTexts <= entries.size() * sizeof(SearchEntry) + 4 * sizeof(void*));
  // A text too long for the string object costs its capacity, a size word and malloc's rounding.
  entries[1].address = std::string(100, 'a');
  const std::uint64_t withAddress = searchIndexHeapBytes(entries);
  CHECK(withAddress - shortTexts >= entries[1].address.capacity() + 1);
  CHECK(withAddress - shortTexts <= entries[1].address.capacity() + 1 + 3 * sizeof(void*));

  IndexRig rig;
  rig.city.tileset.response.reset();
  rig.load();
  REQUIRE(rig.index.loaded());
  const auto served = decodeSearchIndex(rig.fetcher.files.at("city/search.qvi"), "served");
  REQUIRE(served.ok());
  // The entries and the id order (four bytes a building).
  CHECK(rig.index.bytes() >= searchIndexHeapBytes(*served) + served->size() * sizeof(std::uint32_t));
  CHECK(rig.index.bytes() <= searchIndexHeapBytes(*served) + served->size() * sizeof(std::uint32_t) + 64);
}

TEST_CASE("City-wide files that would not fit the memory allowance are left out, saying why, and load once it grows",
          "[scene][index][memory]") {
  constexpr std::uint64_t kBuildings = MiniCity::kSide * MiniCity::kSide;
  SECTION("the search index, before it is fetched") {
    IndexRig rig;
    rig.index.setMemoryAllowance(1000);  // under its table alone
    rig.load();
    CHECK_FALSE(rig.index.loaded());
    CHECK(rig.index.settled());  // nothing to wait for: the list and the report go without it
    CHECK(rig.fetcher.count("city/search.qvi") == 0);
    CHECK(rig.fetcher.count("city/response/index.qvs") == 0);
    CHECK(rig.index.bytes() == 0);
    CHECK(rig.index.search("Building", 10).empty());
    CHECK(rig.errors.empty());  // not an error of the server's
    const std::string& notice = rig.index.memoryNotice();
    CHECK(notice.find("search index of 64 buildings") != std::string::npos);
    CHECK(notice.find("MB") != std::string::npos);
    rig.index.setMemoryAllowance(1ull << 30);
    rig.load();
    CHECK(rig.index.loaded());
    CHECK(rig.index.summary() != nullptr);
    CHECK(rig.index.memoryNotice().empty());
  }
  SECTION("the search index, let go after decoding when it holds more than its table") {
    IndexRig rig;
    // Exactly the estimate before the fetch: the malloc headers of the table and the id order
    // make the decoded index larger.
    rig.index.setMemoryAllowance(kBuildings * (sizeof(SearchEntry) + sizeof(std::uint32_t)));
    rig.load();
    CHECK(rig.fetcher.count("city/search.qvi") == 1);
    CHECK_FALSE(rig.index.loaded());
    CHECK(rig.index.settled());
    CHECK(rig.index.bytes() == 0);
    CHECK_FALSE(rig.index.position(MiniCity::idOf(1, 1)));
    CHECK(rig.errors.empty());
    CHECK_FALSE(rig.index.memoryNotice().empty());
    rig.index.setMemoryAllowance(1ull << 30);
    rig.load();
    CHECK(rig.index.loaded());
    CHECK(rig.fetcher.count("city/search.qvi") == 2);
    CHECK(rig.index.position(MiniCity::idOf(1, 1)));
  }
  SECTION("the response in the index's order, beside the index") {
    std::uint64_t indexBytes = 0;
    {
      IndexRig alone;
      alone.city.tileset.response.reset();
      alone.load();
      REQUIRE(alone.index.loaded());
      indexBytes = alone.index.bytes();
    }
    IndexRig rig;
    rig.index.setMemoryAllowance(indexBytes);  // the index fits, nothing beside it
    rig.load();
    REQUIRE(rig.index.loaded());
    CHECK(rig.index.bytes() == indexBytes);
    CHECK(rig.index.summary() == nullptr);
    CHECK(rig.fetcher.count("city/response/index.qvs") == 0);
    CHECK(rig.index.settled());
    CHECK(rig.errors.empty());
    CHECK(rig.index.memoryNotice().find("response") != std::string::npos);
    // Search and the list still work, without damage.
    CHECK(rig.index.search("Building 3-4", 10).size() == 1);
    CHECK(rig.index.search("Building 3-4", 10)[0].damage == DamageState::NoResult);
    rig.index.setMemoryAllowance(1ull << 30);
    rig.load();
    CHECK(rig.index.summary() != nullptr);
    CHECK(rig.index.search("Building 3-4", 10)[0].damage == MiniCity::responseOf(3, 4).damage);
    CHECK(rig.index.memoryNotice().empty());
  }
}

TEST_CASE("The list filters by several uses and facility categories at once", "[scene][index][filters]") {
  IndexRig rig;
  // Plant uses and categories in the served index: (0, j) hospitals, (1, j) schools, (2, j) fire
  // stations, (3, 0) a stadium; the rest stay offices.
  auto& bytes = rig.fetcher.files.at("city/search.qvi");
  auto entries = decodeSearchIndex(bytes, "planted");
  REQUIRE(entries.ok());
  std::size_t hospitals = 0, schools = 0, fireStations = 0;
  for (SearchEntry& e : *entries) {
    for (int j = 0; j < MiniCity::kSide; ++j) {
      const auto planted = [&](int i, const char* use, FacilityCategory category, std::size_t& count) {
        if (e.id != MiniCity::idOf(i, j)) return;
        e.use = use;
        e.facility = category;
        ++count;
      };
      planted(0, "hospital", FacilityCategory::Essential, hospitals);
      planted(1, "school", FacilityCategory::SchoolShelter, schools);
      planted(2, "fire_station", FacilityCategory::Essential, fireStations);
    }
    if (e.id == MiniCity::idOf(3, 0)) {
      e.use = "sports";
      e.facility = FacilityCategory::HighOccupancy;
    }
  }
  bytes = encodeSearchIndex(*entries);
  rig.city.tileset.search->bytes = bytes.size();
  rig.city.tileset.search->crc32 = crc32(bytes);
  rig.load();
  REQUIRE(rig.index.loaded());
  REQUIRE(hospitals > 0);

  auto idsOf = [&rig](const BuildingFilters& f) {
    std::size_t total = 0;
    std::set<std::string> uses;
    for (const BuildingListEntry& e : rig.index.filteredList(f, 100000, &total)) uses.insert(e.use);
    return std::pair{total, uses};
  };
  BuildingFilters several;
  several.use = "hospital+school";
  const auto [total, uses] = idsOf(several);
  CHECK(total == hospitals + schools);
  CHECK(uses == std::set<std::string>{"hospital", "school"});

  BuildingFilters critical;
  critical.criticalOnly = true;
  const auto [criticalTotal, criticalUses] = idsOf(critical);
  CHECK(criticalTotal == hospitals + schools + fireStations);
  CHECK(criticalUses == std::set<std::string>{"fire_station", "hospital", "school"});

  BuildingFilters highOccupancy;
  highOccupancy.categories = facilityCategoryBit(FacilityCategory::HighOccupancy);
  CHECK(idsOf(highOccupancy).second == std::set<std::string>{"sports"});

  BuildingFilters criticalFireStations = critical;
  criticalFireStations.use = "fire_station+office";  // both filters apply: no office is critical
  CHECK(idsOf(criticalFireStations).first == fireStations);

  // The use filter's choices: the uses present, most first, with their counts.
  const auto counts = rig.index.useCounts();
  REQUIRE(!counts.empty());
  CHECK(counts.front().first == "office");
  std::size_t sum = 0;
  for (const auto& [use, n] : counts) sum += n;
  CHECK(sum == static_cast<std::size_t>(MiniCity::kSide * MiniCity::kSide));
}

TEST_CASE("List rows name a building by its name, else its address, never only an id that has one", "[scene][index]") {
  BuildingListEntry e;
  e.id = "w42";
  e.address = "12 Main Street, 10001 New York";
  e.use = "hospital";
  e.facility = FacilityCategory::Essential;
  e.damage = DamageState::Moderate;
  e.peakDriftRatio = 0.0042f;
  e.x = 300.0;
  e.y = 400.0;
  CHECK(listName(e) == e.address);
  const std::string row = listRowText(e, 0.0, 0.0);
  CHECK(row.find("12 Main Street") == 0);
  CHECK(row.find("w42") == std::string::npos);
  CHECK(row.find("moderate 0.42 %") != std::string::npos);
  CHECK(row.find("hospital (essential)") != std::string::npos);
  CHECK(row.find("500 m") != std::string::npos);  // a 3-4-5 triangle from the camera target
  CHECK(listRowText(e, 3000.0, 4000.0).find("4.5 km") != std::string::npos);
  e.name = "City Hospital";
  CHECK(listName(e) == "City Hospital");
  e.name.clear();
  e.address.clear();
  CHECK(listName(e) == "w42");
  e.damage = DamageState::NoResult;
  e.facility = FacilityCategory::None;
  e.use = "office";
  const std::string plain = listRowText(e, 300.0, 400.0);
  CHECK(plain.find("(") == std::string::npos);  // no category for general stock
  CHECK(plain.find("| 0 m") != std::string::npos);
  // A facility whose building tag is generic: its kind stands for the use.
  e.use = "unknown";
  e.facility = FacilityCategory::Hazardous;
  e.facilityKind = "fuel";
  CHECK(useAndFacilityText(e) == "fuel (hazardous)");
  CHECK(listRowText(e, 0.0, 0.0).find("| fuel (hazardous) |") != std::string::npos);
  e.use = "";
  e.facility = FacilityCategory::Essential;
  e.facilityKind = "ambulance_station";
  CHECK(useAndFacilityText(e) == "ambulance station (essential)");
  // A kind that says more than the use is added; one that says the same is not repeated.
  e.use = "civic";
  e.facility = FacilityCategory::SchoolShelter;
  e.facilityKind = "community_centre";
  CHECK(useAndFacilityText(e) == "civic (school or shelter: community centre)");
  e.use = "hospital";
  e.facility = FacilityCategory::Essential;
  e.facilityKind = "hospital";
  CHECK(useAndFacilityText(e) == "hospital (essential)");
  // A category without a kind (a version 3 index whose use did not give it) keeps the old text.
  e.use = "unknown";
  e.facilityKind.clear();
  CHECK(useAndFacilityText(e) == "unknown use (essential)");
}

TEST_CASE("With HAZUS probabilities the list filters and sorts by the probability of damage",
          "[scene][index][filters]") {
  IndexRig rig;
  // Plant probabilities in the served summary: building k (index order) has P(>= slight) = k / 100
  // and P(>= moderate) = k / 400, so the most likely damaged are the last ones, whatever their
  // deterministic state (MiniCity's states cycle through none .. complete).
  auto& bytes = rig.fetcher.files.at("city/response/index.qvs");
  auto summary = decodeResponseSummary(bytes, "planted");
  REQUIRE(summary.ok());
  const std::size_t n = summary->buildings.size();
  REQUIRE(n == static_cast<std::size_t>(MiniCity::kSide * MiniCity::kSide));
  summary->losses.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    BuildingLoss& l = summary->losses[k];
    const float slight = static_cast<float>(k) / 100.0f, moderate = static_cast<float>(k) / 400.0f;
    l.structural[0] = 1.0f - slight;
    l.structural[1] = slight - moderate;
    l.structural[2] = moderate;
  }
  bytes = encodeResponseSummary(*summary);
  rig.city.tileset.response->summaryIndex->bytes = bytes.size();
  rig.city.tileset.response->summaryIndex->crc32 = crc32(bytes);
  rig.index.open(rig.city.tileset);
  rig.load();
  REQUIRE(rig.index.loaded());

  // No filter: every building, most likely damaged (P >= slight) first.
  std::size_t total = 0;
  const auto all = rig.index.filteredList(BuildingFilters{}, 1000, &total);
  REQUIRE(all.size() == n);
  for (std::size_t k = 1; k < all.size(); ++k) {
    REQUIRE(all[k - 1].loss.has_value());
    CHECK(all[k - 1].loss->structuralAtLeast(1) >= all[k].loss->structuralAtLeast(1));
  }
  CHECK(all.front().loss->structuralAtLeast(1) == Approx(static_cast<float>(n - 1) / 100.0f));

  // P(>= moderate) at least 10 %: k / 400 >= 0.10, k >= 40.
  BuildingFilters likely;
  likely.probabilityState = 2;
  likely.minProbabilityPercent = 10;
  const auto top = rig.index.filteredList(likely, 5, &total);
  CHECK(total == n - 40);
  REQUIRE(top.size() == 5);
  CHECK(top.front().loss->structuralAtLeast(2) == Approx(static_cast<float>(n - 1) / 400.0f));
  for (const BuildingListEntry& e : top) CHECK(e.loss->structuralAtLeast(2) >= 0.0999f);
  // Its rows say the probability the list is sorted by.
  const std::string row = listRowText(top.front(), 0.0, 0.0, listProbabilityState(likely));
  CHECK_THAT(row, Catch::Contains("P(>= moderate) 16 %"));
  CHECK_THAT(listRowText(top.front(), 0.0, 0.0), Catch::Contains("P(>= slight) 63 %"));
}
