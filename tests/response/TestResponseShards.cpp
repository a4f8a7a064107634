// Runs the built quakeview-prep's `response --shard K/N` and `response --merge` (native only): the
// merged response is the one-machine run's, byte for byte, and a merge with a part missing, damaged
// or from another run publishes nothing and says which part.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "ToolRun.h"

namespace {

namespace fs = std::filesystem;

const std::string kTool = QUAKEVIEW_PREP_EXE;

qv::test::ToolRun run(const std::string& arguments) {
  return qv::test::runTool(kTool, arguments, true);
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Every file under `dir` (relative path -> bytes).
std::map<std::string, std::string> filesUnder(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = readAll(e.path());
  }
  return out;
}

// Two districts splitting the synthetic city (centred on -74.00, 40.71) into west and east.
void writeDistricts(const std::string& path) {
  std::ofstream(path) << R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{"name":"West"},"geometry":{"type":"Polygon","coordinates":[[[-74.1,40.6],[-74.0,40.6],[-74.0,40.8],[-74.1,40.8],[-74.1,40.6]]]}},
{"type":"Feature","properties":{"name":"East"},"geometry":{"type":"Polygon","coordinates":[[[-74.0,40.6],[-73.9,40.6],[-73.9,40.8],[-74.0,40.8],[-74.0,40.6]]]}}]})";
}

// A short record (8 s of a decaying 2 Hz and 0.7 Hz mix, in g, as "time,acceleration" lines): the
// solver's time under the sanitizers stays small.
void writeRecord(const std::string& path, double phase) {
  std::ofstream out(path);
  for (int i = 0; i <= 800; ++i) {
    const double t = 0.01 * i;
    const double a = 0.3 * std::exp(-0.3 * t) *
                     (std::sin(2 * 3.14159265 * 2.0 * t + phase) + 0.6 * std::sin(2 * 3.14159265 * 0.7 * t));
    out << t << "," << a << "\n";
  }
}

struct Cities {
  std::string root, one, sharded, districts, options;
  std::string quick;  ///< another response: the first record as given
  // `records`: how many of the two short records (two make a suite: pass one and the spread across
  // records).
  Cities(const std::string& name, int buildings, int records) {
    root = "/tmp/qv-shards-" + name + "-" + std::to_string(getpid());
    fs::remove_all(root);
    fs::create_directories(root);
    one = root + "/one";
    sharded = root + "/sharded";
    districts = root + "/districts.geojson";
    writeDistricts(districts);
    writeRecord(root + "/record-1.csv", 0.0);
    writeRecord(root + "/record-2.csv", 1.0);
    quick = "--motion '" + root + "/record-1.csv' --units g";
    const auto made = run("synth-city --buildings " + std::to_string(buildings) +
                          " --seed 4 --max-leaf-buildings 12 --out '" + one + "'");
    INFO(made.output);
    REQUIRE(made.exitCode == 0);
    fs::copy(one, sharded, fs::copy_options::recursive);
    options = "--motion '" + root + "/record-1.csv'" + (records > 1 ? " '" + root + "/record-2.csv'" : "") +
              " --units g --epicentre -74.004,40.708,8 --magnitude 6.6 --time-of-day night --districts '" + districts +
              "'";
  }
  ~Cities() { fs::remove_all(root); }
  [[nodiscard]] qv::test::ToolRun part(const std::string& spec, const std::string& extra = "") const {
    return run("response --city '" + sharded + "' " + options + " --shard " + spec + " " + extra);
  }
  [[nodiscard]] qv::test::ToolRun merge(const std::string& extra = "") const {
    return run("response --city '" + sharded + "' --merge " + extra);
  }
};

}  // namespace

TEST_CASE("a response run in parts and merged is byte-identical to the run on one machine", "[response][cli][parts]") {
  const Cities c("same", 150, 2);
  const auto one = run("response --city '" + c.one + "' " + c.options);
  INFO(one.output);
  REQUIRE(one.exitCode == 0);
  // Parts in any order, on any number of threads.
  for (const char* spec : {"3/3", "1/3", "2/3"}) {
    const auto part = c.part(spec, std::string(spec) == "1/3" ? "--threads 1" : "--threads 2");
    INFO(part.output);
    REQUIRE(part.exitCode == 0);
    CHECK(part.output.find("part " + std::string(1, spec[0]) + " of 3 written") != std::string::npos);
  }
  // Until the merge, the city has no response.
  CHECK(readAll(c.sharded + "/tileset.json").find("\"response\"") == std::string::npos);
  const auto noCores = c.merge("--threads 0");
  CHECK(noCores.exitCode == 2);
  CHECK(noCores.output.find("--threads must be from 1 to 256") != std::string::npos);
  const auto merged = c.merge();
  INFO(merged.output);
  REQUIRE(merged.exitCode == 0);
  CHECK(merged.output.find("response merged from 3 parts") != std::string::npos);
  CHECK_FALSE(fs::exists(c.sharded + "/staging"));

  const auto expected = filesUnder(c.one);
  const auto got = filesUnder(c.sharded);
  REQUIRE(expected.count("tileset.json") == 1);
  REQUIRE(expected.count("response-1/consequences.json") == 1);
  CHECK(expected.at("response-1/consequences.json").find("\"East\"") != std::string::npos);
  CHECK(expected.size() > 30);
  CHECK(got.size() == expected.size());
  for (const auto& [name, bytes] : expected) {
    INFO(name);
    REQUIRE(got.count(name) == 1);
    CHECK(got.at(name) == bytes);
  }
  // Both districts hold buildings: the totals per district went through the merge.
  const std::string consequences = got.at("response-1/consequences.json");
  CHECK(consequences.find("\"West\"") != std::string::npos);
}

TEST_CASE("a merge with a part missing, failed, damaged or from another run publishes nothing and names the part",
          "[response][cli][parts]") {
  const Cities c("refused", 60, 1);
  // The city's current response, which must stay published until a merge succeeds.
  const auto earlier = run("response --city '" + c.sharded + "' " + c.quick);
  REQUIRE(earlier.exitCode == 0);
  const std::string published = readAll(c.sharded + "/tileset.json");
  auto unchanged = [&] {
    CHECK(readAll(c.sharded + "/tileset.json") == published);
    CHECK(fs::exists(c.sharded + "/response-1"));
    CHECK_FALSE(fs::exists(c.sharded + "/response-2"));
  };

  SECTION("usage") {
    CHECK(run("response --city '" + c.sharded + "' --merge --synthetic 7").exitCode == 2);
    for (const char* bad : {"0/3", "4/3", "3", "x/3"}) {
      const auto r = c.part(bad);
      INFO(r.output);
      CHECK(r.exitCode == 2);
      CHECK(r.output.find("--shard must be K/N") != std::string::npos);
    }
    const auto none = c.merge();
    CHECK(none.exitCode == 1);
    CHECK(none.output.find("no parts to merge") != std::string::npos);
    unchanged();
  }

  REQUIRE(c.part("1/3").exitCode == 0);
  REQUIRE(c.part("2/3").exitCode == 0);
  // Part 3 was started on a node that died: its temporary folder is all there is.
  fs::create_directories(c.sharded + "/staging/.part-3-of-3.tmp-99999");
  auto missing = c.merge();
  INFO(missing.output);
  CHECK(missing.exitCode == 1);
  CHECK(missing.output.find("part 3 of 3 (started, but failed or still running) is missing") != std::string::npos);
  CHECK(missing.output.find("--shard 3/3") != std::string::npos);
  unchanged();

  // Part 3 run with other options: another run.
  const auto other = run("response --city '" + c.sharded + "' " + c.quick +
                         " --epicentre -74.004,40.708,8 --magnitude 6.6 --time-of-day day --districts '" + c.districts +
                         "' --shard 3/3");
  REQUIRE(other.exitCode == 0);
  auto mismatched = c.merge();
  INFO(mismatched.output);
  CHECK(mismatched.exitCode == 1);
  CHECK(mismatched.output.find("part 3 of 3 is from another run than part 1: its time-of-day is \"day\", part 1's "
                               "\"night\"") != std::string::npos);
  unchanged();

  // Part 3 again, right this time (it replaces the wrong one); then part 2's history damaged on disk.
  REQUIRE(c.part("3/3").exitCode == 0);
  std::string damagedFile;
  for (const auto& e : fs::directory_iterator(c.sharded + "/staging/part-2-of-3")) {
    if (e.path().extension() == ".qvh") damagedFile = e.path().string();
  }
  REQUIRE_FALSE(damagedFile.empty());
  std::ofstream(damagedFile, std::ios::app) << 'x';
  auto damaged = c.merge("--threads 1");
  INFO(damaged.output);
  CHECK(damaged.exitCode == 1);
  CHECK(damaged.output.find("part 2 of 3") != std::string::npos);
  CHECK(damaged.output.find("is damaged") != std::string::npos);
  CHECK(damaged.output.find(fs::path(damagedFile).filename().string() + " is not the file its part.json names") !=
        std::string::npos);
  unchanged();

  // Re-running the one failed part is enough.
  REQUIRE(c.part("2/3").exitCode == 0);
  const auto merged = c.merge();
  INFO(merged.output);
  REQUIRE(merged.exitCode == 0);
  CHECK(readAll(c.sharded + "/tileset.json") != published);
  CHECK(fs::exists(c.sharded + "/response-2/consequences.json"));
  CHECK_FALSE(fs::exists(c.sharded + "/response-1"));
  CHECK_FALSE(fs::exists(c.sharded + "/staging"));
  // The published response is the one-machine run's.
  REQUIRE(run("response --city '" + c.one + "' " + c.quick).exitCode == 0);
  REQUIRE(run("response --city '" + c.one + "' " + c.options).exitCode == 0);
  const auto expected = filesUnder(c.one);
  const auto got = filesUnder(c.sharded);
  CHECK(got.size() == expected.size());
  for (const auto& [name, bytes] : expected) {
    INFO(name);
    REQUIRE(got.count(name) == 1);
    CHECK(got.at(name) == bytes);
  }

  // A city changed after its parts were made (here: renamed) is not merged; a response published
  // meanwhile does not matter (the parts are of the city, not of its response).
  REQUIRE(c.part("1/1").exitCode == 0);
  REQUIRE(run("response --city '" + c.sharded + "' " + c.quick).exitCode == 0);
  std::string manifest = readAll(c.sharded + "/tileset.json");
  const std::size_t name = manifest.find("\"name\":\"Synthetic city");
  REQUIRE(name != std::string::npos);
  manifest.replace(name, 22, "\"name\":\"Renamed city");
  const std::string before = manifest;
  std::ofstream(c.sharded + "/tileset.json", std::ios::trunc) << manifest;
  const auto changed = c.merge();
  INFO(changed.output);
  CHECK(changed.exitCode == 1);
  CHECK(changed.output.find("the city changed since its parts were made") != std::string::npos);
  CHECK(readAll(c.sharded + "/tileset.json") == before);
}

TEST_CASE("a catalogue's scenarios are published side by side, each as its own response, in parts or not",
          "[response][cli][catalogue]") {
  const Cities c("catalogue", 60, 1);
  const std::string catalogue = c.root + "/catalogue.json";
  std::ofstream(catalogue) << R"({"options": {"motion": "record-1.csv", "units": "g", "time-of-day": "night"},
 "scenarios": [
  {"name": "M6.6 under Lower Manhattan", "epicentre": "-74.004,40.708,8", "magnitude": 6.6, "districts": "districts.geojson"},
  {"name": "M5.0 to the north-east", "epicentre": "-73.99,40.72,8", "magnitude": 5.0, "time-of-day": "day"}]})";
  const auto list = run("response --catalogue '" + catalogue + "' --list");
  CHECK(list.exitCode == 0);
  CHECK(list.output == "1\tM6.6 under Lower Manhattan\n2\tM5.0 to the north-east\n");
  const std::string city = "response --city '" + c.sharded + "' --catalogue '" + catalogue + "'";
  // Usage: a scenario out of range, or options the catalogue gives.
  CHECK(run(city + " --scenario 3").exitCode == 2);
  CHECK(run(city + " --scenario 1 --magnitude 7").exitCode == 2);
  CHECK(run("response --city '" + c.sharded + "' --scenario 1").exitCode == 2);

  // Scenario 2 in two parts, scenario 1 on one machine, in that order.
  REQUIRE(run(city + " --scenario 2 --shard 2/2").exitCode == 0);
  REQUIRE(run(city + " --scenario 2 --shard 1/2").exitCode == 0);
  CHECK(fs::exists(c.sharded + "/staging/scenario-2/part-1-of-2/part.json"));
  const auto plain = c.merge();  // the parts are a scenario's: --scenario is needed
  CHECK(plain.exitCode == 1);
  CHECK(plain.output.find("--merge --scenario I") != std::string::npos);
  const auto merged = run("response --city '" + c.sharded + "' --merge --scenario 2");
  INFO(merged.output);
  REQUIRE(merged.exitCode == 0);
  const auto first = run(city + " --scenario 1");
  INFO(first.output);
  REQUIRE(first.exitCode == 0);
  CHECK(first.output.find("scenario    1 of 2: M6.6 under Lower Manhattan") != std::string::npos);
  CHECK_FALSE(fs::exists(c.sharded + "/staging"));

  const std::string scenarios = readAll(c.sharded + "/scenarios.json");
  CHECK(scenarios.find("{\"index\":1,\"name\":\"M6.6 under Lower Manhattan\",\"manifest\":\"scenario-1.json\"}") !=
        std::string::npos);
  CHECK(scenarios.find("{\"index\":2,\"name\":\"M5.0 to the north-east\",\"manifest\":\"scenario-2.json\"}") !=
        std::string::npos);
  const std::string one = readAll(c.sharded + "/scenario-1.json");
  const std::string two = readAll(c.sharded + "/scenario-2.json");
  CHECK(readAll(c.sharded + "/tileset.json") == one);
  CHECK(one.find("M6.6 at") != std::string::npos);
  CHECK(two.find("M5.0 at") != std::string::npos);
  CHECK(one.find("\"timeOfDay\":\"night\"") != std::string::npos);
  CHECK(two.find("\"timeOfDay\":\"day\"") != std::string::npos);
  // Each scenario's folder, both kept.
  CHECK(two.find("\"response-1/consequences.json\"") != std::string::npos);
  CHECK(one.find("\"response-2/consequences.json\"") != std::string::npos);

  // Scenario 2 again: its own previous folder goes, scenario 1's stays.
  REQUIRE(run(city + " --scenario 2").exitCode == 0);
  CHECK(readAll(c.sharded + "/scenario-2.json").find("\"response-3/consequences.json\"") != std::string::npos);
  CHECK_FALSE(fs::exists(c.sharded + "/response-1"));
  CHECK(fs::exists(c.sharded + "/response-2"));
  CHECK(fs::exists(c.sharded + "/response-3"));
  // A plain run replaces tileset.json and keeps the scenarios' folders.
  REQUIRE(run("response --city '" + c.sharded + "' " + c.quick).exitCode == 0);
  CHECK(fs::exists(c.sharded + "/response-2"));
  CHECK(fs::exists(c.sharded + "/response-3"));
  CHECK(fs::exists(c.sharded + "/response-4"));
  CHECK(readAll(c.sharded + "/tileset.json").find("\"response-4/consequences.json\"") != std::string::npos);
}
