// Runs the built quakeview-prep: `response` on a small OSM city, then what `info` and the response
// files say about buildings without a result and about the record (native only).
#include <unistd.h>

#include <simdjson.h>
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "ResponseTestCity.h"
#include "ToolRun.h"
#include "qv/core/Crc32.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/StoredFile.h"
#include "qv/format/Tileset.h"

namespace {

using qv::test::readText;
using qv::test::square;
using qv::test::tag;

const std::string kTool = QUAKEVIEW_PREP_EXE;
const std::string kRecords = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/ground-motions/";

qv::test::ToolRun run(const std::string& arguments, bool withStderr = false) {
  return qv::test::runTool(kTool, arguments, withStderr);
}

// A response summary of the city in `cityDir`, decoded (as stored: a Zstandard frame).
qv::ResponseSummaryTile readSummary(const std::string& cityDir, const std::string& file) {
  std::ifstream in(cityDir + "/" + file, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto decoded = qv::decodeResponseSummary(bytes, file);
  REQUIRE(decoded.ok());
  return std::move(decoded).value();
}

}  // namespace

TEST_CASE("response gives rooftop parts no result with a reason, and publishes only the record's name",
          "[response][cli]") {
  const std::string dir = "/tmp/qv-response-test-" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  // Two buildings on the ground and one structure whose base is 51 m up (on another building).
  const std::string osm =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\">\n" +
      square(1, -74.0100, 40.7100, tag("building", "yes") + tag("height", "12")) +
      square(2, -74.0090, 40.7100, tag("building", "office") + tag("height", "30")) +
      square(3, -74.0080, 40.7100, tag("building", "yes") + tag("height", "60") + tag("min_height", "51")) + "</osm>\n";
  std::ofstream(dir + "/in.osm") << osm;
  const auto city = run("city --input '" + dir + "/in.osm' --out '" + dir + "/city'", true);
  INFO(city.output);
  REQUIRE(city.exitCode == 0);
  const auto response = run("response --city '" + dir + "/city' --motion '" + kRecords + "TAK000.AT2'", true);
  INFO(response.output);
  REQUIRE(response.exitCode == 0);
  CHECK(response.output.find("base_above_ground: 1") != std::string::npos);

  SECTION("info --building gives the reason and its details") {
    const auto info = run("info '" + dir + "/city' --building w3 --json");
    REQUIRE(info.exitCode == 0);
    simdjson::dom::parser parser;
    simdjson::dom::element doc;
    REQUIRE(parser.parse(info.output).get(doc) == simdjson::SUCCESS);
    CHECK(std::string(doc["damage_state"].get_string().value()) == "no_result");
    CHECK(std::string(doc["no_result_reason"].get_string().value()) == "base_above_ground");
    CHECK(std::string(doc["no_result_detail"].get_string().value()) == "base 51.0 m above ground");
    CHECK_FALSE(doc["approximate"].get_bool().value());
    const auto text = run("info '" + dir + "/city' --building w3");
    CHECK(text.output.find("rooftop structure resting on another building; not analysed") != std::string::npos);
    // A building on the ground has a result and no reason.
    const auto ground = run("info '" + dir + "/city' --building w1 --json");
    REQUIRE(parser.parse(ground.output).get(doc) == simdjson::SUCCESS);
    CHECK(std::string(doc["damage_state"].get_string().value()) != "no_result");
    CHECK(doc["no_result_reason"].is_null());
  }

  SECTION("info --json counts buildings without a result by reason") {
    const auto info = run("info '" + dir + "/city' --json");
    REQUIRE(info.exitCode == 0);
    simdjson::dom::parser parser;
    simdjson::dom::element doc;
    REQUIRE(parser.parse(info.output).get(doc) == simdjson::SUCCESS);
    CHECK(doc["damage_states"]["no_result"].get_uint64().value() == 1);
    CHECK(doc["no_result_reasons"]["base_above_ground"].get_uint64().value() == 1);
    CHECK(doc["approximate_buildings"].get_uint64().value() == 0);
    CHECK(doc["approximate"].get_array().value().size() == 0);
    // The record by its file name and header title, never the path of the machine that ran it.
    CHECK(std::string(doc["motion"].get_string().value()) == "TAK000.AT2 (KOBE, 01/16/1995, Takatori, 000)");
  }

  SECTION("every tile summary carries its analysed buildings' drift series; the city-wide index does not") {
    CHECK(response.output.find("far series") != std::string::npos);
    const std::string json = readText(dir + "/city/tileset.json");
    const auto tileset = qv::parseTileset(json, "tileset.json");
    REQUIRE(tileset.ok());
    auto summaryOf = [&dir](const std::string& file) { return readSummary(dir + "/city", file); };
    int withSeries = 0;
    for (const qv::TileNode& n : tileset->nodes) {
      REQUIRE(n.response);
      const qv::ResponseSummaryTile s = summaryOf(n.response->summaryFile);
      REQUIRE(s.driftSeries.spans.size() == s.buildings.size());
      CHECK(s.driftSeries.rateHz == qv::kDriftSeriesRateHz);
      for (std::size_t b = 0; b < s.buildings.size(); ++b) {
        const qv::DriftSpan& span = s.driftSeries.spans[b];
        const bool result = s.buildings[b].source != qv::ResponseSource::None;
        CHECK((span.count > 0) == result);  // the rooftop part without a result has none
        if (!result) continue;
        ++withSeries;
        // Its largest window is its peak drift, from the stored history (within the series'
        // quantization and the history's compression: each floor within 1.9 % of the peak roof
        // displacement, so a storey's drift within a few tens of percent).
        std::uint8_t top = 0;
        for (std::uint32_t i = 0; i < span.count; ++i) top = std::max(top, s.driftSeries.codes[span.first + i]);
        CHECK(qv::driftSeriesValue(top, s.driftSeries.fullScale) ==
              Approx(s.buildings[b].peakDriftRatio).epsilon(0.35));
      }
    }
    CHECK(withSeries >= 2);
    REQUIRE(tileset->response->summaryIndex);
    CHECK(summaryOf(tileset->response->summaryIndex->file).driftSeries.empty());
  }

  SECTION("the city and response files are stored as Zstandard frames, as the manifest describes them") {
    CHECK(response.output.find("before compression") != std::string::npos);
    const auto tileset = qv::parseTileset(readText(dir + "/city/tileset.json"), "tileset.json");
    REQUIRE(tileset.ok());
    auto storedAs = [&dir](const std::string& file, std::uint64_t bytes, std::uint32_t crc) {
      INFO(file);
      std::ifstream in(dir + "/city/" + file, std::ios::binary);
      const std::vector<std::uint8_t> stored((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      CHECK(qv::isCompressedFile(stored));
      CHECK(stored.size() == bytes);
      CHECK(qv::crc32(stored) == crc);
      const auto raw = qv::unpackStoredFile(stored, file);
      REQUIRE(raw.ok());
      CHECK(raw->size() > stored.size());
    };
    int files = 0;
    for (const qv::TileNode& n : tileset->nodes) {
      REQUIRE(n.response);
      storedAs(n.response->summaryFile, n.response->summaryBytes, n.response->summaryCrc32);
      ++files;
      if (!n.response->historyFile.empty()) {
        storedAs(n.response->historyFile, n.response->historyBytes, n.response->historyCrc32);
        ++files;
      }
    }
    REQUIRE(tileset->response->summaryIndex);
    const qv::CityFile& index = *tileset->response->summaryIndex;
    storedAs(index.file, index.bytes, index.crc32);
    CHECK(files >= 2);
    // The city's own files, as `city` wrote them.
    for (const qv::TileNode& n : tileset->nodes) storedAs(n.file, n.bytes, n.crc32);
    REQUIRE(tileset->search);
    storedAs(tileset->search->file, tileset->search->bytes, tileset->search->crc32);
  }

  SECTION("tile summaries carry the drawing probabilities; the index the full losses and sites") {
    const auto tileset = qv::parseTileset(readText(dir + "/city/tileset.json"), "tileset.json");
    REQUIRE(tileset.ok());
    auto summaryOf = [&dir](const std::string& file) { return readSummary(dir + "/city", file); };
    REQUIRE(tileset->response->summaryIndex);
    const qv::ResponseSummaryTile index = summaryOf(tileset->response->summaryIndex->file);
    REQUIRE(index.losses.size() == index.buildings.size());
    REQUIRE(index.spread.size() == index.buildings.size());
    REQUIRE_FALSE(index.storeySpread.empty());
    int compared = 0;
    for (const qv::TileNode& n : tileset->nodes) {
      const qv::ResponseSummaryTile s = summaryOf(n.response->summaryFile);
      CHECK(s.losses.empty());
      CHECK(s.sites.empty());
      CHECK(s.spread.empty());
      CHECK(s.storeySpread.empty());
      REQUIRE(s.odds.size() == s.buildings.size());
      CHECK_FALSE(s.scaling.empty());  // the sway periods
      // The same building's probabilities in the index, to 1/65535 (the index is in the search
      // index's order: the buildings are matched by their peak drift).
      for (std::size_t b = 0; b < s.buildings.size(); ++b) {
        if (s.buildings[b].source == qv::ResponseSource::None) continue;
        for (std::size_t i = 0; i < index.buildings.size(); ++i) {
          if (index.buildings[i].peakDriftRatio != s.buildings[b].peakDriftRatio) continue;
          const qv::BuildingDamageOdds full = qv::BuildingDamageOdds::of(index.losses[i]);
          for (int k = 0; k < 4; ++k) CHECK(s.odds[b].atLeast[k] == Approx(full.atLeast[k]).margin(1.0 / 65535.0));
          ++compared;
        }
      }
    }
    CHECK(compared >= 2);
  }

  SECTION("no response file carries the record's directory") {
    CHECK(readText(dir + "/city/tileset.json").find(kRecords) == std::string::npos);
    CHECK(readText(dir + "/city/tileset.json").find("TAK000.AT2") != std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("response writes the same files, intervals included, whatever the number of threads", "[response][cli]") {
  const std::string dir = "/tmp/qv-response-threads-" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  const auto made = run("synth-city --buildings 300 --seed 4 --max-leaf-buildings 25 --out '" + dir + "'", true);
  INFO(made.output);
  REQUIRE(made.exitCode == 0);
  // Each run's response files (a new run replaces the city's response): file name -> bytes.
  std::vector<std::map<std::string, std::vector<std::uint8_t>>> runs;
  for (const char* threads : {"1", "3"}) {
    const auto response = run("response --city '" + dir + "' --synthetic 1 --threads " + std::string(threads), true);
    INFO(response.output);
    REQUIRE(response.exitCode == 0);
    auto& files = runs.emplace_back();
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().filename().string().rfind("response-", 0) != 0) continue;
      for (const auto& file : std::filesystem::directory_iterator(entry.path())) {
        std::ifstream in(file.path(), std::ios::binary);
        files[file.path().filename().string()] =
            std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      }
    }
  }
  const auto& first = runs[0];
  const auto& second = runs[1];
  REQUIRE(first.size() == second.size());
  REQUIRE(first.count("consequences.json") == 1);
  CHECK(first.size() > 10);
  for (const auto& [name, bytes] : first) {
    INFO(name);
    REQUIRE(second.count(name) == 1);
    CHECK(second.at(name) == bytes);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("report writes the situation report of a city's response, and refuses a damaged file whole",
          "[response][cli][report]") {
  const std::string dir = "/tmp/qv-report-" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string city = dir + "/city";
  const auto made = run("synth-city --buildings 400 --seed 2 --out '" + city + "'", true);
  REQUIRE(made.exitCode == 0);
  const auto none = run("report '" + city + "' --out '" + dir + "/r.html'", true);
  CHECK(none.exitCode == 1);
  CHECK_THAT(none.output, Catch::Contains("has no earthquake response"));
  const auto response =
      run("response --city '" + city + "' --synthetic 1 --epicentre -74.0,40.7,10 --magnitude 6.5", true);
  INFO(response.output);
  REQUIRE(response.exitCode == 0);

  const auto written = run("report '" + city + "' --out '" + dir + "/r.html'", true);
  INFO(written.output);
  REQUIRE(written.exitCode == 0);
  CHECK_THAT(written.output, Catch::Contains("wrote " + dir + "/r.html"));
  const std::string html = readText(dir + "/r.html");
  CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK_THAT(html, Catch::Contains("Earthquake situation report: Synthetic city, 400 buildings (seed 2)</h1>"));
  CHECK_THAT(html, Catch::Contains("class=\"banner scenario\">SCENARIO"));
  CHECK_THAT(html, Catch::Contains("2 AM (night)"));
  CHECK_THAT(html, Catch::Contains("5 PM (commute)"));
  CHECK_THAT(html, Catch::Contains("By occupancy class (HAZUS)</h3>\n<table>"));
  CHECK_THAT(html, Catch::Contains("<svg"));
  // Its headline is the consequences file's: damaged buildings (moderate or worse), expected.
  std::string consequencesFile;
  for (const auto& entry : std::filesystem::directory_iterator(city)) {
    if (entry.path().filename().string().rfind("response-", 0) == 0) {
      consequencesFile = entry.path().string() + "/consequences.json";
    }
  }
  simdjson::dom::parser parser;
  const simdjson::padded_string json = simdjson::padded_string::load(consequencesFile).value();
  const double damaged = parser.parse(json)["city"]["moderate_or_worse"]["expected"].get_double().value();
  const simdjson::dom::element root = parser.parse(json).value();
  CHECK(root["by_occupancy"].get_array().size() > 0);
  CHECK(root["inferred"]["buildings"].get_uint64().value() > 0);
  CHECK(root["city"]["casualties_by_time"]["day"]["occupants"].get_double().value() > 0);
  char expected[32];
  if (damaged >= 10) {
    std::snprintf(expected, sizeof expected, "%lld", static_cast<long long>(std::llround(damaged)));
  } else {
    std::snprintf(expected, sizeof expected, "%.1f", damaged);
  }
  INFO("damaged " << damaged);
  CHECK_THAT(html, Catch::Contains("Buildings damaged (moderate or worse)</div><div class=\"v\">" +
                                   std::string(expected) + "</div>"));

  // '-' prints the same document.
  const auto printed = run("report '" + city + "' --out -");
  REQUIRE(printed.exitCode == 0);
  CHECK(printed.output == html);

  // A damaged consequences file is named, and the report already written stays as it was.
  {
    std::fstream f(consequencesFile, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(20);
    f.put('#');
  }
  const auto refused = run("report '" + city + "' --out '" + dir + "/r.html'", true);
  CHECK(refused.exitCode == 1);
  CHECK_THAT(refused.output, Catch::Contains("consequences.json") && Catch::Contains("CRC-32"));
  CHECK(readText(dir + "/r.html") == html);
  std::filesystem::remove_all(dir);
}
