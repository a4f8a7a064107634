// The parts of a sharded response run (prep::response ResponseParts.h): how a city's leaves are
// split, and the part results codec the merge reads.
#include <catch2/catch.hpp>
#include <set>

#include "qv/prep/ResponseCatalogue.h"
#include "qv/prep/ResponseParts.h"

namespace {

// A tileset whose leaves hold the given numbers of buildings under one root.
qv::Tileset leavesOf(const std::vector<std::uint32_t>& buildings) {
  qv::Tileset t;
  t.nodes.emplace_back();
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    qv::TileNode leaf;
    leaf.level = 1;
    leaf.x = static_cast<std::uint32_t>(i);
    leaf.buildings = buildings[i];
    t.nodes[0].children.push_back(static_cast<std::uint32_t>(t.nodes.size()));
    t.nodes.push_back(leaf);
  }
  return t;
}

}  // namespace

TEST_CASE("A shard spec K/N takes part K of N parts, 1-based", "[response][parts]") {
  const auto spec = qv::prep::parseShardSpec("3/4");
  REQUIRE(spec);
  CHECK(spec->part == 3);
  CHECK(spec->parts == 4);
  CHECK(qv::prep::partFolderName(*spec) == "part-3-of-4");
  for (const char* bad : {"0/4", "5/4", "4", "/4", "1/0", "a/b", "1/4x", "-1/4", "1/10001", ""}) {
    INFO(bad);
    CHECK_FALSE(qv::prep::parseShardSpec(bad));
  }
}

TEST_CASE("a city's leaves go whole into parts of about the same number of buildings, the same every time",
          "[response][parts]") {
  const std::vector<std::uint32_t> sizes = {500, 20, 300, 300, 100, 90, 450, 10, 250, 250, 60, 5, 400, 120};
  const qv::Tileset t = leavesOf(sizes);
  const std::uint64_t total = 2855;
  for (const unsigned n : {1u, 2u, 3u, 4u, 14u, 20u}) {
    INFO("parts " << n);
    const auto parts = qv::prep::assignParts(t, n);
    REQUIRE(parts.size() == n);
    std::set<std::uint32_t> seen;
    std::uint64_t largest = 0, sum = 0;
    for (const auto& part : parts) {
      std::uint64_t load = 0;
      for (const std::uint32_t leaf : part) {
        CHECK(seen.insert(leaf).second);  // no leaf in two parts
        CHECK(t.nodes[leaf].children.empty());
        load += t.nodes[leaf].buildings;
      }
      CHECK(std::is_sorted(part.begin(), part.end()));
      largest = std::max(largest, load);
      sum += load;
    }
    CHECK(seen.size() == sizes.size());  // every leaf in a part
    CHECK(sum == total);
    // Largest-first greedy: no part holds more than the even share plus the largest leaf.
    CHECK(largest <= (total + n - 1) / n + 500);
    CHECK(qv::prep::assignParts(t, n) == parts);
  }
  // Four parts of this city: 714 buildings each at best; the greedy split comes within one small leaf.
  const auto four = qv::prep::assignParts(t, 4);
  for (const auto& part : four) {
    std::uint64_t load = 0;
    for (const std::uint32_t leaf : part) load += t.nodes[leaf].buildings;
    CHECK(load >= 690);
    CHECK(load <= 740);
  }
}

TEST_CASE("a part's results file reads back exactly, and a damaged one is refused with its name", "[response][parts]") {
  qv::prep::PartResults r;
  r.leafSummaries.push_back({7, {1, 2, 3, 4, 5}});
  r.leafSummaries.push_back({9, {}});
  qv::prep::PartLoss l;
  l.key = (std::uint64_t{7} << 32) | 3;
  l.district = 2;
  l.lossClass.occupancy = qv::seismic::Occupancy::COM4;
  l.lossClass.type = qv::StructuralType::C2M;
  l.lossClass.typeInferred = true;
  l.loss.structural.p = {0.5, 0.25, 0.125, 0.0625, 0.0625};
  l.loss.collapse = 1.0 / 3.0;
  l.loss.occupantsAt = {10.5, 20.25, 5.125};
  l.loss.valueInferred = true;
  l.loss.injuries = {1e-3, 2e-4, 3e-5, 4e-6};
  l.loss.repairCostUsd = 123456.789;
  l.loss.given.injuriesPerOccupant[5] = {0.4, 0.3, 0.2, 0.1};
  l.loss.given.nsAccelerationCostUsd[4] = 99.5;
  r.losses.push_back(l);
  r.losses.push_back(qv::prep::PartLoss{});
  const auto bytes = qv::prep::encodePartResults(r);
  const auto back = qv::prep::decodePartResults(bytes, "results.qvp");
  REQUIRE(back.ok());
  REQUIRE(back->leafSummaries == r.leafSummaries);
  REQUIRE(back->losses.size() == 2);
  const auto& b = back->losses[0];
  CHECK(b.key == l.key);
  CHECK(b.district == 2);
  CHECK(b.lossClass.occupancy == qv::seismic::Occupancy::COM4);
  CHECK(b.lossClass.type == qv::StructuralType::C2M);
  CHECK(b.lossClass.typeInferred);
  CHECK_FALSE(b.lossClass.eraInferred);
  CHECK(b.loss.structural.p == l.loss.structural.p);
  CHECK(b.loss.collapse == l.loss.collapse);
  CHECK(b.loss.occupantsAt == l.loss.occupantsAt);
  CHECK(b.loss.valueInferred);
  CHECK_FALSE(b.loss.occupantsInferred);
  CHECK(b.loss.injuries == l.loss.injuries);
  CHECK(b.loss.repairCostUsd == l.loss.repairCostUsd);
  CHECK(b.loss.given.injuriesPerOccupant == l.loss.given.injuriesPerOccupant);
  CHECK(b.loss.given.nsAccelerationCostUsd == l.loss.given.nsAccelerationCostUsd);
  CHECK(back->losses[1].district == -1);

  for (std::size_t cut : {std::size_t{0}, std::size_t{3}, std::size_t{20}, bytes.size() - 1}) {
    INFO("cut at " << cut);
    const auto damaged = qv::prep::decodePartResults(std::span(bytes.data(), cut), "part-2-of-4/results.qvp");
    REQUIRE_FALSE(damaged.ok());
    CHECK(damaged.error().find("part-2-of-4/results.qvp") != std::string::npos);
  }
  auto extra = bytes;
  extra.push_back(0);
  CHECK_FALSE(qv::prep::decodePartResults(extra, "x").ok());
  auto badClass = bytes;
  // The first loss's occupancy byte: after the magic, version, leaf table and loss count, key and district.
  const std::size_t occupancyAt = 4 + 4 + 4 + (4 + 8 + 5) + (4 + 8 + 0) + 8 + 8 + 4;
  badClass[occupancyAt] = 200;
  const auto refused = qv::prep::decodePartResults(badClass, "x");
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().find("out of range") != std::string::npos);
  // Flag bits this version never writes (found by fuzz_response_part: they did not survive a
  // write after a read).
  auto badFlags = bytes;
  badFlags[occupancyAt + 2] = 0x80;
  const auto flagsRefused = qv::prep::decodePartResults(badFlags, "x");
  REQUIRE_FALSE(flagsRefused.ok());
  CHECK(flagsRefused.error().find("flags") != std::string::npos);
}

TEST_CASE("a catalogue's scenarios are response options, shared ones overridden, files beside the catalogue",
          "[response][catalogue]") {
  const auto c = qv::prep::parseCatalogue(
      R"({"options": {"synthetic": [1, 2], "time-of-day": "day", "districts": "d.geojson"},
          "scenarios": [
            {"name": "ShakeMap M5.8", "shakemap": "events/grid.xml", "accurate-steps": true},
            {"name": "M6.5 at night", "epicentre": "-74.01,40.70,10", "magnitude": 6.5, "time-of-day": "night",
             "districts": "/abs/d.geojson", "scale-by": "pga", "accurate-steps": false}]})",
      "/data/cat", "catalogue.json");
  REQUIRE(c.ok());
  REQUIRE(c->scenarios.size() == 2);
  CHECK(c->scenarios[0].name == "ShakeMap M5.8");
  // Options in name order, each with its values.
  CHECK(c->scenarios[0].args == std::vector<std::string>{"--accurate-steps", "--districts", "/data/cat/d.geojson",
                                                         "--shakemap", "/data/cat/events/grid.xml", "--synthetic", "1",
                                                         "2", "--time-of-day", "day"});
  CHECK(c->scenarios[1].args == std::vector<std::string>{"--districts", "/abs/d.geojson", "--epicentre",
                                                         "-74.01,40.70,10", "--magnitude", "6.5", "--scale-by", "pga",
                                                         "--synthetic", "1", "2", "--time-of-day", "night"});
  // scenarios.json as the viewer reads it (the one codec of qv/format/ScenarioCatalogue.h).
  const auto listed = qv::parseScenarioCatalogue(qv::prep::scenariosToJson({"A \"quoted\" name", "B"}), "s.json");
  REQUIRE(listed.ok());
  CHECK(listed->warnings.empty());
  CHECK(listed->scenarios ==
        std::vector<qv::ScenarioEntry>{{1, "A \"quoted\" name", "scenario-1.json"}, {2, "B", "scenario-2.json"}});
}

TEST_CASE("a catalogue that cannot be run is refused with its name and the scenario", "[response][catalogue]") {
  const std::vector<std::pair<const char*, const char*>> cases = {
      {"not json", "not valid JSON"},
      {R"({"scenarios": []})", "at least one scenario"},
      {R"({"scenarios": [{"shakemap": "x.xml"}]})", "scenario 1: needs a \"name\""},
      {R"({"scenarios": [{"name": "a"}, {"name": "a"}]})", "scenario 2: another scenario is also named \"a\""},
      {R"({"scenarios": [{"name": "bell\u0007"}]})", "control character"},
      {R"({"scenarios": [{"name": "evil\u202Eexe"}]})", "bidirectional control"},
      {R"({"scenarios": [{"name": "a", "threads": 4}]})", "\"threads\" cannot be set in a catalogue"},
      {R"({"scenarios": [{"name": "a", "--shakemap": "x"}]})", "is not an option name"},
      {R"({"options": {"city": "/x"}, "scenarios": [{"name": "a"}]})", "\"options\": \"city\" cannot be set"},
      {R"({"scenarios": [{"name": "a", "synthetic": [{"seed": 1}]}]})", "not text or a number"},
      {R"({"scenarios": [{"name": "a", "magnitude": null}]})", "not text, a number, true or a list"},
      {R"({"scenarios": [{"name": "a", "time-of-day": "--threads"}]})", "\"--threads\", which reads as an option"},
      {R"({"scenarios": [{"name": "a", "synthetic": [7, "--merge"]}]})", "reads as an option"},
  };
  for (const auto& [json, message] : cases) {
    INFO(json);
    const auto c = qv::prep::parseCatalogue(json, "", "my-catalogue.json");
    REQUIRE_FALSE(c.ok());
    CHECK(c.error().find("my-catalogue.json") != std::string::npos);
    CHECK(c.error().find(message) != std::string::npos);
  }
}
