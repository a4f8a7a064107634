// Runs the built quakeview-prep: `city` and `synth-city` write the map under the city and say so in
// one summary line, --no-ground leaves it out, `info` shows it (text and --json) and --verify
// decodes its files (native only).
#include <unistd.h>

#include <simdjson.h>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "ToolRun.h"

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;
const std::string kMidtown = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/osm/fixture-midtown-empire-state.osm";

qv::test::ToolRun run(const std::string& arguments) {
  return qv::test::runTool(kTool, arguments, true);
}

/// The line of `output` that starts with `label`, or "".
std::string lineOf(const std::string& output, const std::string& label) {
  std::size_t at = output.rfind("\n" + label, std::string::npos);
  if (at == std::string::npos) return output.rfind(label, 0) == 0 ? output.substr(0, output.find('\n')) : "";
  ++at;
  return output.substr(at, output.find('\n', at) - at);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A fresh folder for cities, removed at the end.
struct Folder {
  std::string path = "/tmp/qv-ground-cli-" + std::to_string(getpid());
  Folder() { std::filesystem::create_directories(path); }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

}  // namespace

TEST_CASE("city writes the ground and says so, and --no-ground leaves it out", "[ground][cli]") {
  Folder folder;
  const std::string city = folder.path + "/midtown";
  const auto written = run("city --input '" + kMidtown + "' --out '" + city + "' --no-lod2");
  INFO(written.output);
  REQUIRE(written.exitCode == 0);
  const std::string line = lineOf(written.output, "ground ");
  CHECK(contains(line, " streets, "));
  CHECK(contains(line, " paths, "));
  CHECK(contains(line, " parks and green land, "));
  CHECK(contains(line, " names in "));
  CHECK(contains(line, "tunnel 77"));
  CHECK(std::filesystem::is_directory(city + "/ground"));

  const auto info = run("info '" + city + "'");
  INFO(info.output);
  REQUIRE(info.exitCode == 0);
  CHECK(contains(lineOf(info.output, "ground "), " files in "));
  CHECK(contains(lineOf(info.output, "ground "), " per km2 "));
  CHECK(contains(info.output, "left out: incomplete-boundary 6; tunnel 77;"));

  const auto json = run("info '" + city + "' --json");
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
  REQUIRE(parser.parse(json.output).get(doc) == simdjson::SUCCESS);
  simdjson::dom::element ground;
  REQUIRE(doc["ground"].get(ground) == simdjson::SUCCESS);
  CHECK(ground["files"].get_uint64().value() > 0);
  CHECK(ground["bytes"].get_uint64().value() > 0);
  CHECK(ground["bytes_per_km2"].get_double().value() > 0.0);
  CHECK(ground["features"]["major"].get_uint64().value() > 0);
  CHECK(ground["features"]["path"].get_uint64().value() > 0);
  CHECK(ground["features"]["labels"].get_uint64().value() > 0);
  CHECK(ground["skipped"]["tunnel"].get_uint64().value() == 77);
  CHECK(doc["buildings"].get_uint64().value() > 300);  // the other keys are still there

  const auto verified = run("info --verify '" + city + "'");
  INFO(verified.output);
  CHECK(verified.exitCode == 0);

  const std::string bare = folder.path + "/bare";
  const auto without = run("city --input '" + kMidtown + "' --out '" + bare + "' --no-lod2 --no-ground");
  INFO(without.output);
  REQUIRE(without.exitCode == 0);
  CHECK(lineOf(without.output, "ground ") == "ground      none (--no-ground)");
  CHECK(!std::filesystem::exists(bare + "/ground"));
  const auto bareJson = run("info '" + bare + "' --json");
  simdjson::dom::element bareDoc;
  REQUIRE(parser.parse(bareJson.output).get(bareDoc) == simdjson::SUCCESS);
  CHECK(bareDoc["ground"].is_null());
  CHECK(contains(run("info '" + bare + "'").output, "ground      none (made with --no-ground"));
}

TEST_CASE("A city without streets, water or open land has an empty ground layer", "[ground][cli]") {
  // GeoJSON inputs hold buildings only: the layer is there (the city was made with a ground) with
  // no cells, and the manifest reads back.
  Folder folder;
  const std::string city = folder.path + "/geojson";
  const std::string input = std::string(QUAKEVIEW_SOURCE_DIR) + "/tests/ingest/data/footprints.geojson";
  const auto written = run("city --input '" + input + "' --out '" + city + "'");
  INFO(written.output);
  REQUIRE(written.exitCode == 0);
  CHECK(lineOf(written.output, "ground ") == "ground      the input has no streets, water or open land");
  const auto info = run("info '" + city + "'");
  INFO(info.output);
  REQUIRE(info.exitCode == 0);
  CHECK(contains(info.output, "ground      empty: the input has no streets, water or open land"));
  const auto json = run("info '" + city + "' --json");
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
  REQUIRE(parser.parse(json.output).get(doc) == simdjson::SUCCESS);
  CHECK(doc["ground"]["files"].get_uint64().value() == 0);
  CHECK(run("info --verify '" + city + "'").exitCode == 0);
}

TEST_CASE("synth-city writes its map, --no-ground leaves it out, and --help lists the flag", "[ground][cli]") {
  Folder folder;
  const std::string city = folder.path + "/synth";
  const auto written = run("synth-city --buildings 300 --seed 3 --out '" + city + "'");
  INFO(written.output);
  REQUIRE(written.exitCode == 0);
  const std::string line = lineOf(written.output, "ground ");
  CHECK(contains(line, " streets, "));
  CHECK(contains(line, "1 water, "));
  CHECK(!contains(line, "left out"));
  CHECK(run("info --verify '" + city + "'").exitCode == 0);

  const auto without = run("synth-city --buildings 300 --seed 3 --no-ground --out '" + city + "'");
  REQUIRE(without.exitCode == 0);
  CHECK(lineOf(without.output, "ground ") == "ground      none (--no-ground)");
  CHECK(!std::filesystem::exists(city + "/ground"));

  for (const char* command : {"city", "synth-city"}) {
    INFO(command);
    CHECK(contains(run(std::string(command) + " --help").output, "  --no-ground "));
  }
}

TEST_CASE("Districts by default: city and synth-city make them, response totals by them without --districts",
          "[ground][cli][districts]") {
  Folder folder;
  simdjson::dom::parser parser;
  struct Case {
    std::string label, make, response, line;
    std::uint64_t districts;
  };
  const std::vector<Case> cases{
      {"Midtown (real OSM: nearest neighbourhood names)",
       "city --input '" + kMidtown + "' --no-lod2 --out '" + folder.path + "/midtown'",
       "response --city '" + folder.path + "/midtown' --synthetic 7 --epicentre -73.99,40.74,8 --magnitude 6.6",
       "districts   3 inferred (districts.geojson, 100.0 % of the buildings): each building to its nearest "
       "OpenStreetMap neighbourhood name (place=neighbourhood, quarter, suburb, borough); the input draws no "
       "boundaries that divide the city",
       3},
      {"synth-city (its own neighbourhoods)", "synth-city --buildings 300 --seed 3 --out '" + folder.path + "/synth'",
       "response --city '" + folder.path + "/synth' --synthetic 7", "", 4},
  };
  for (const Case& c : cases) {
    INFO(c.label);
    const std::string city = c.make.substr(c.make.rfind("--out '") + 7, std::string::npos);
    const std::string dir = city.substr(0, city.size() - 1);
    const auto made = run(c.make);
    INFO(made.output);
    REQUIRE(made.exitCode == 0);
    const std::string line = lineOf(made.output, "districts ");
    if (!c.line.empty()) CHECK(line == c.line);
    CHECK(contains(line, std::to_string(c.districts) + " inferred"));
    CHECK(std::filesystem::exists(dir + "/districts.geojson"));
    CHECK(run("info --verify '" + dir + "'").exitCode == 0);

    const auto response = run(c.response);
    INFO(response.output);
    REQUIRE(response.exitCode == 0);
    CHECK(contains(lineOf(response.output, "districts "), "districts   the city's own: each building to its nearest"));

    const auto json = run("info '" + dir + "' --json");
    simdjson::dom::element doc;
    REQUIRE(parser.parse(json.output).get(doc) == simdjson::SUCCESS);
    CHECK(doc["districts"]["count"].get_uint64().value() == c.districts);
    CHECK(doc["districts"]["inferred"].get_bool().value());
    CHECK(doc["districts"]["coverage"].get_double().value() == 1.0);
    // The consequences' rows: one per district, their buildings adding up to the city's.
    const simdjson::dom::element consequences = doc["consequences"];
    const auto rows = consequences["districts"].get_array().value();
    CHECK(rows.size() == c.districts);
    std::uint64_t buildings = 0;
    for (simdjson::dom::element row : rows) {
      CHECK(!std::string(row["name"].get_string().value()).empty());
      buildings += row["buildings"].get_uint64().value();
    }
    CHECK(buildings == consequences["buildings"].get_uint64().value());
    CHECK(consequences["districts_inferred"].get_bool().value());
    CHECK(contains(std::string(consequences["districts_source"].get_string().value()), "nearest"));
  }

  SECTION("--districts still wins, and --no-ground makes none") {
    const std::string dir = folder.path + "/synth";
    const std::string file = folder.path + "/halves.geojson";
    std::FILE* f = std::fopen(file.c_str(), "w");
    REQUIRE(f != nullptr);
    std::fputs(R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"All"},
      "geometry":{"type":"Polygon","coordinates":[[[-75,40],[-73,40],[-73,42],[-75,42],[-75,40]]]}}]})",
               f);
    std::fclose(f);
    const auto given = run("response --city '" + dir + "' --synthetic 7 --districts '" + file + "'");
    REQUIRE(given.exitCode == 0);
    CHECK(lineOf(given.output, "districts ").empty());
    simdjson::dom::element doc;
    const auto json = run("info '" + dir + "' --json");
    REQUIRE(parser.parse(json.output).get(doc) == simdjson::SUCCESS);
    CHECK(doc["consequences"]["districts"].get_array().value().size() == 1);
    CHECK(std::string(doc["consequences"]["districts_source"].get_string().value()) ==
          "a districts file given to the response (--districts)");

    const auto bare = run("synth-city --buildings 300 --seed 3 --no-ground --out '" + folder.path + "/bare'");
    REQUIRE(bare.exitCode == 0);
    CHECK(lineOf(bare.output, "districts ") == "districts   none (--no-ground)");
    CHECK(!std::filesystem::exists(folder.path + "/bare/districts.geojson"));
  }
}
