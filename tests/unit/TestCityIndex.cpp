#include <catch2/catch.hpp>

#include "MiniCity.h"
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
