// A city larger than its coarse tiles may hold: `synth-city --max-coarse-buildings` caps the root
// (and every other inner tile at a quarter of that) at the largest buildings of its subtree (the
// rest appear when the viewer refines), and
// the city-wide index (search.qvi, and the response's summary in its order) still holds every
// building with its position and leaf. Runs the built quakeview-prep (native only).
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "ToolRun.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/format/Tileset.h"

namespace fs = std::filesystem;
using namespace qv;

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct City {
  std::string dir;
  Tileset tileset;
  std::vector<CityTile> tiles;  // per node
};

City load(const std::string& dir) {
  City c;
  c.dir = dir;
  const auto json = readBytes(dir + "/tileset.json");
  auto parsed = parseTileset(std::string_view(reinterpret_cast<const char*>(json.data()), json.size()), "tileset.json");
  INFO((parsed.ok() ? std::string() : parsed.error()));
  REQUIRE(parsed.ok());
  c.tileset = std::move(parsed).value();
  for (const TileNode& n : c.tileset.nodes) {
    auto tile = decodeCityTile(readBytes(dir + "/" + n.file), n.file);
    REQUIRE(tile.ok());
    c.tiles.push_back(std::move(tile).value());
  }
  return c;
}

}  // namespace

// The city of the test below, made once a process: Catch2 runs a test case from its top for each
// SECTION, and making it (a response under ASan) takes most of the test's time. Removed at exit.
struct MadeCity {
  static constexpr std::size_t kLimit = 100;
  static constexpr std::size_t kBuildings = 500;
  std::string dir;
  int made = -1, responded = -1;
  std::string output;
  MadeCity() : dir((fs::temp_directory_path() / ("qv-index-" + std::to_string(getpid()))).string()) {
    fs::remove_all(dir);
    const auto m = test::runTool(kTool,
                                 "synth-city --buildings " + std::to_string(kBuildings) +
                                     " --seed 3 --max-leaf-buildings 40 --max-coarse-buildings " +
                                     std::to_string(kLimit) + " --out '" + dir + "'",
                                 true);
    made = m.exitCode;
    output = m.output;
    if (made != 0) return;
    const auto r = test::runTool(kTool, "response --city '" + dir + "' --synthetic 1", true);
    responded = r.exitCode;
    output += r.output;
  }
  ~MadeCity() { fs::remove_all(dir); }
  MadeCity(const MadeCity&) = delete;
  MadeCity& operator=(const MadeCity&) = delete;
};

TEST_CASE("Coarse tiles hold at most --max-coarse-buildings and the index holds the whole city",
          "[prep][tiling][index]") {
  static const MadeCity made;
  constexpr std::size_t kLimit = MadeCity::kLimit;
  constexpr std::size_t kBuildings = MadeCity::kBuildings;
  const std::string& dir = made.dir;
  INFO(made.output);
  REQUIRE(made.made == 0);
  REQUIRE(made.responded == 0);
  const City city = load(dir);
  const Tileset& t = city.tileset;
  REQUIRE(t.buildings == kBuildings);

  // Every leaf building, by id: its leaf and attributes.
  std::map<std::string, std::pair<std::uint32_t, BuildingAttributes>> leafOf;
  for (std::uint32_t i = 0; i < t.nodes.size(); ++i) {
    if (!t.nodes[i].children.empty()) continue;
    const CityTile& tile = city.tiles[i];
    for (const TileBuilding& b : tile.buildings) {
      BuildingAttributes a = b.attributes;
      a.centroidX += tile.originX;
      a.centroidY += tile.originY;
      CHECK(leafOf.emplace(a.id, std::make_pair(i, a)).second);
    }
  }
  REQUIRE(leafOf.size() == kBuildings);

  SECTION("inner tiles draw the largest buildings of their subtree, and their error covers the rest") {
    const CityTile& root = city.tiles[0];
    CHECK(root.coarse);
    CHECK(root.buildings.size() == kLimit);
    CHECK(t.nodes[0].buildings == kLimit);
    CHECK(t.nodes[0].subtreeBuildings == kBuildings);
    auto size = [](const BuildingAttributes& a) {
      return std::max(a.footprintAreaM2, 1.0f) * std::max(a.heightM, 1.0f);
    };
    float smallestIn = INFINITY;
    for (const TileBuilding& b : root.buildings)
      smallestIn = std::min(smallestIn, size(leafOf.at(b.attributes.id).second));
    std::map<std::string, bool> inRoot;
    for (const TileBuilding& b : root.buildings) inRoot[b.attributes.id] = true;
    float tallestOut = 0.0f;
    for (const auto& [id, where] : leafOf) {
      if (inRoot.count(id) != 0) continue;
      CHECK(size(where.second) <= smallestIn);
      tallestOut = std::max(tallestOut, where.second.heightM);
    }
    CHECK(t.nodes[0].geometricErrorM >= tallestOut);
    // The root's bounds are still its whole subtree's (the viewer culls and refines by them).
    for (const auto& [id, where] : leafOf) {
      CHECK(t.nodes[0].bounds.contains(static_cast<float>(where.second.centroidX),
                                       static_cast<float>(where.second.centroidY)));
    }
    // Below the root, inner tiles hold a quarter of the limit (four children draw about what
    // their parent did); those with more buildings below them are full.
    std::size_t fullInner = 0;
    for (std::uint32_t i = 1; i < t.nodes.size(); ++i) {
      if (t.nodes[i].children.empty()) continue;
      CHECK(city.tiles[i].buildings.size() <= kLimit / 4);
      CHECK(city.tiles[i].buildings.size() == std::min<std::size_t>(kLimit / 4, t.nodes[i].subtreeBuildings));
      CHECK(city.tiles[i].buildings.size() == t.nodes[i].buildings);
      fullInner += t.nodes[i].subtreeBuildings > kLimit / 4 ? 1u : 0u;
    }
    CHECK(fullInner > 0);
  }

  SECTION("the search index lists every building once, with its leaf, position and attributes") {
    REQUIRE(t.search);
    const auto bytes = readBytes(dir + "/" + t.search->file);
    auto index = decodeSearchIndex(bytes, t.search->file);
    REQUIRE(index.ok());
    REQUIRE(index->size() == kBuildings);
    std::map<std::string, bool> seen;
    for (const SearchEntry& e : *index) {
      REQUIRE(leafOf.count(e.id) == 1);
      CHECK(seen.emplace(e.id, true).second);
      const auto& [leaf, a] = leafOf.at(e.id);
      CHECK(e.leaf == leaf);
      CHECK(std::abs(e.x - a.centroidX) < 0.01);
      CHECK(std::abs(e.y - a.centroidY) < 0.01);
      CHECK(e.heightM == a.heightM);
      CHECK(e.storeys == a.storeys);
      CHECK(e.use == a.use);
      CHECK(e.importance == a.importance);
      CHECK(e.facility == classifyFacility(a).category);
    }
  }

  SECTION("the response's city-wide summary follows the index and agrees with the leaves' summaries") {
    REQUIRE(t.response);
    REQUIRE(t.response->summaryIndex);
    auto index = decodeSearchIndex(readBytes(dir + "/" + t.search->file), t.search->file);
    REQUIRE(index.ok());
    auto all = decodeResponseSummary(readBytes(dir + "/" + t.response->summaryIndex->file), "index.qvs");
    REQUIRE(all.ok());
    REQUIRE(all->buildings.size() == index->size());
    std::map<std::string, BuildingResponse> fromLeaves;
    for (std::uint32_t i = 0; i < t.nodes.size(); ++i) {
      if (!t.nodes[i].children.empty()) continue;
      auto s = decodeResponseSummary(readBytes(dir + "/" + t.nodes[i].response->summaryFile), "leaf");
      REQUIRE(s.ok());
      for (std::size_t b = 0; b < s->buildings.size(); ++b)
        fromLeaves[city.tiles[i].buildings[b].attributes.id] = s->buildings[b];
    }
    std::uint64_t damaged = 0;
    for (std::size_t i = 0; i < index->size(); ++i) {
      const BuildingResponse& a = all->buildings[i];
      const BuildingResponse& b = fromLeaves.at((*index)[i].id);
      CHECK(a.damage == b.damage);
      CHECK(a.peakDriftRatio == b.peakDriftRatio);
      CHECK(a.storeys == b.storeys);
      damaged += a.damage != DamageState::None && a.damage != DamageState::NoResult ? 1 : 0;
    }
    CHECK(damaged > 0);
  }

  SECTION("info --verify accepts the city") {
    const auto verify = test::runTool(kTool, "info '" + dir + "' --verify", true);
    INFO(verify.output);
    CHECK(verify.exitCode == 0);
  }
}

TEST_CASE("An out-of-range --max-coarse-buildings is a usage error", "[prep][tiling][index]") {
  const auto r = test::runTool(kTool, "synth-city --buildings 100 --max-coarse-buildings 5 --out /tmp/qv-never", true);
  CHECK(r.exitCode == 2);
  CHECK(r.output.find("--max-coarse-buildings") != std::string::npos);
  CHECK_FALSE(fs::exists("/tmp/qv-never"));
}

TEST_CASE("Each city's manifest carries its name: --name, else the folder's, synth-city its size", "[prep][tiling]") {
  const std::string base = (fs::temp_directory_path() / "qv-city-names").string();
  fs::remove_all(base);
  const auto named =
      test::runTool(kTool, "synth-city --buildings 50 --seed 2 --name 'Harbour district' --out '" + base + "/a'");
  REQUIRE(named.exitCode == 0);
  const auto plain = test::runTool(kTool, "synth-city --buildings 50 --seed 2 --out '" + base + "/b/'");
  REQUIRE(plain.exitCode == 0);
  auto nameOf = [](const std::string& dir) {
    std::ifstream in(dir + "/tileset.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto t = parseTileset(json, dir);
    REQUIRE(t.ok());
    return t->name;
  };
  CHECK(nameOf(base + "/a") == "Harbour district");
  CHECK(nameOf(base + "/b") == "Synthetic city, 50 buildings (seed 2)");
  const auto bad = test::runTool(kTool, "synth-city --buildings 50 --seed 2 --name '' --out '" + base + "/c'", true);
  CHECK(bad.exitCode == 2);
  CHECK(bad.output.find("--name must be") != std::string::npos);
  CHECK_FALSE(fs::exists(base + "/c"));
  fs::remove_all(base);
}
