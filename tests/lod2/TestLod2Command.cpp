// Runs the built quakeview-prep: `lod2` puts real CityJSON models (../shared/data/cityjson) into a
// small synthetic city with --place, and `info` then shows them; usage and data errors leave the
// city as it was (native only).
#include <unistd.h>

#include <simdjson.h>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "ToolRun.h"

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;
const std::string kCityJson = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/cityjson/";

using Run = qv::test::ToolRun;

Run run(const std::string& arguments, bool withStderr = false) {
  return qv::test::runTool(kTool, arguments, withStderr);
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The number after `label` at the start of a summary line ("replaced    4 buildings").
long long countAfter(const std::string& output, const std::string& label) {
  const std::size_t at = output.find("\n" + label);
  if (at == std::string::npos) return -1;
  return std::stoll(output.substr(at + 1 + label.size()));
}

struct Json {
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
};

void parse(Json& j, const std::string& text) {
  INFO(text);
  REQUIRE(j.parser.parse(text).get(j.doc) == simdjson::SUCCESS);
}

}  // namespace

TEST_CASE("lod2 puts CityJSON models into a synthetic city and the response goes out of date", "[lod2][cli]") {
  const std::string dir = "/tmp/qv-lod2-cli-" + std::to_string(getpid());
  REQUIRE(run("synth-city --buildings 12 --seed 5 --out '" + dir + "'").exitCode == 0);
  REQUIRE(run("response --city '" + dir + "' --synthetic 1").exitCode == 0);
  const std::string groundBefore = std::string(run("info '" + dir + "' --json").output);

  // Den Haag, about 500 m east of the synthetic buildings: 4 Buildings (8 parts), all new.
  const Run first =
      run("lod2 --city '" + dir + "' --input '" + kCityJson + "DH_01_subs.city.json' --place -73.994,40.71");
  INFO(first.output);
  REQUIRE(first.exitCode == 0);
  CHECK(countAfter(first.output, "imported") == 4);
  CHECK(countAfter(first.output, "replaced") == 0);
  CHECK(countAfter(first.output, "added") == 4);
  CHECK(countAfter(first.output, "skipped") == 0);
  CHECK(first.output.find("(92 vertices before re-meshing") != std::string::npos);

  {
    Json j;
    parse(j, run("info '" + dir + "' --json").output);
    CHECK(j.doc["buildings"].get_uint64().value() == 16);
    CHECK(j.doc["lod2"].get_uint64().value() == 4);
    CHECK(j.doc["buildings_revision"].get_uint64().value() == 2);
    CHECK(j.doc["response_out_of_date"].get_bool().value());
  }
  {
    Json j;
    parse(j, run("info '" + dir + "' --building cj:GUID_8CE54418-E2F7-49A7-9A8D-C3D172BA62C4 --json").output);
    CHECK(j.doc["lod"].get_uint64().value() == 2);
    CHECK(std::string_view(j.doc["lod2"]["source"].get_string().value()) == "cityjson");
    CHECK(j.doc["lod2"]["vertices"].get_uint64().value() > j.doc["lod2"]["vertices_before"].get_uint64().value());
    CHECK(j.doc["response_out_of_date"].get_bool().value());
  }

  // The same file again: every model finds its building by id and replaces it.
  const Run again =
      run("lod2 --city '" + dir + "' --input '" + kCityJson + "DH_01_subs.city.json' --place -73.994,40.71");
  INFO(again.output);
  REQUIRE(again.exitCode == 0);
  CHECK(countAfter(again.output, "replaced") == 4);
  CHECK(countAfter(again.output, "added") == 0);

  // Delft: 160 buildings; roads, vegetation, land use, water and bridges skipped and counted.
  const Run delft = run("lod2 --city '" + dir + "' --input '" + kCityJson + "delft.json' --place -74.0,40.714");
  INFO(delft.output);
  REQUIRE(delft.exitCode == 0);
  CHECK(countAfter(delft.output, "imported") == 160);
  CHECK(countAfter(delft.output, "replaced") + countAfter(delft.output, "added") == 160);
  CHECK(countAfter(delft.output, "skipped") == 410);
  CHECK(delft.output.find("Road                     143") != std::string::npos);
  CHECK(delft.output.find("PlantCover               126") != std::string::npos);
  CHECK(delft.output.find("LandUse                  81") != std::string::npos);
  CHECK(delft.output.find("WaterBody                3") != std::string::npos);
  CHECK(delft.output.find("Bridge                   3") != std::string::npos);

  const Run verify = run("info '" + dir + "' --verify", true);
  INFO(verify.output);
  CHECK(verify.exitCode == 0);  // the ground files too: rewriting the city kept them
  {
    // The map under the city is not in the tiles the city is rewritten from: it is kept as it was.
    Json before, after;
    parse(before, groundBefore);
    parse(after, run("info '" + dir + "' --json").output);
    CHECK(before.doc["ground"]["files"].get_uint64().value() > 0);
    CHECK(simdjson::to_string(after.doc["ground"]) == simdjson::to_string(before.doc["ground"]));
  }

  // `response` brings the response up to date again.
  REQUIRE(run("response --city '" + dir + "' --synthetic 1").exitCode == 0);
  {
    Json j;
    parse(j, run("info '" + dir + "' --json").output);
    CHECK_FALSE(j.doc["response_out_of_date"].get_bool().value());
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("A model over a synthetic building replaces it and keeps its id", "[lod2][cli]") {
  const std::string dir = "/tmp/qv-lod2-cli-replace-" + std::to_string(getpid());
  REQUIRE(run("synth-city --buildings 30 --seed 3 --out '" + dir + "'").exitCode == 0);
  const Run r = run("lod2 --city '" + dir + "' --input '" + kCityJson + "DH_01_subs.city.json' --place -74.0,40.71");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(countAfter(r.output, "replaced") == 1);
  CHECK(countAfter(r.output, "added") == 3);
  int lod2Synthetic = 0;
  for (int i = 1; i <= 30; ++i) {
    Json j;
    parse(j, run("info '" + dir + "' --building s" + std::to_string(i) + " --json").output);
    if (j.doc["lod"].get_uint64().value() != 2) continue;
    ++lod2Synthetic;
    CHECK(std::string_view(j.doc["lod2"]["source"].get_string().value()) == "cityjson");
  }
  CHECK(lod2Synthetic == 1);
  Json j;
  parse(j, run("info '" + dir + "' --json").output);
  CHECK(j.doc["buildings"].get_uint64().value() == 33);
  CHECK(run("info '" + dir + "' --verify").exitCode == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("lod2 places an OBJ model with its unit and rotation", "[lod2][cli]") {
  const std::string dir = "/tmp/qv-lod2-cli-obj-" + std::to_string(getpid());
  REQUIRE(run("synth-city --buildings 10 --seed 1 --out '" + dir + "'").exitCode == 0);
  const std::string obj = std::string(QUAKEVIEW_LOD2_DATA_DIR) + "/box_cm_yup.obj";
  // In metres the box would be 286 storeys tall: refused, and the city stays as it was.
  const Run metres = run("lod2 --city '" + dir + "' --input '" + obj + "' --place -73.995,40.71,30 --obj-centre", true);
  CHECK(metres.exitCode == 1);
  CHECK(metres.output.find("no model could be imported") != std::string::npos);
  const Run r =
      run("lod2 --city '" + dir + "' --input '" + obj + "' --place -73.995,40.71,30 --obj-centre --obj-unit cm");
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(countAfter(r.output, "added") == 1);
  Json j;
  parse(j, run("info '" + dir + "' --building obj:box_cm_yup --json").output);
  CHECK(j.doc["lod"].get_uint64().value() == 2);
  CHECK(std::string_view(j.doc["lod2"]["source"].get_string().value()) == "obj");
  CHECK(j.doc["lod2"]["vertices_before"].get_uint64().value() == 8);
  CHECK(run("info '" + dir + "' --verify").exitCode == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("lod2 usage and data errors leave the city unchanged", "[lod2][cli]") {
  const std::string dir = "/tmp/qv-lod2-cli-errors-" + std::to_string(getpid());
  REQUIRE(run("synth-city --buildings 6 --seed 2 --out '" + dir + "'").exitCode == 0);
  const std::string manifest = readText(dir + "/tileset.json");

  CHECK(run("lod2 --input '" + kCityJson + "DH_01_subs.city.json'").exitCode == 2);
  CHECK(run("lod2 --city '" + dir + "'").exitCode == 2);
  const Run badPlace = run("lod2 --city '" + dir + "' --input x.json --place 1000,1", true);
  CHECK(badPlace.exitCode == 2);
  CHECK(badPlace.output.find("--place must be") != std::string::npos);
  CHECK(run("lod2 --city '" + dir + "' --input x.obj --place 1,2 --obj-unit furlong").exitCode == 2);

  const Run missing = run("lod2 --city '" + dir + "' --input /nonexistent/model.json --place -74,40.71", true);
  CHECK(missing.exitCode == 1);
  CHECK(missing.output.find("/nonexistent/model.json") != std::string::npos);
  // DH_01 has no CRS: without --place it cannot be georeferenced.
  const Run noCrs = run("lod2 --city '" + dir + "' --input '" + kCityJson + "DH_01_subs.city.json'", true);
  CHECK(noCrs.exitCode == 1);
  CHECK(noCrs.output.find("DH_01_subs.city.json") != std::string::npos);
  CHECK(noCrs.output.find("--place") != std::string::npos);
  const Run noCity = run("lod2 --city /nonexistent/city --input x.json --place -74,40.71", true);
  CHECK(noCity.exitCode == 1);
  CHECK(noCity.output.find("/nonexistent/city") != std::string::npos);

  CHECK(readText(dir + "/tileset.json") == manifest);
  CHECK(run("info '" + dir + "' --verify").exitCode == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("city makes OSM buildings with building:parts LOD2 models (the Empire State Building)",
          "[lod2][cli][osm][data]") {
  const std::string dir = "/tmp/qv-lod2-osm-" + std::to_string(getpid());
  const std::string fixture = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/osm/fixture-midtown-empire-state.osm";
  const Run city = run("city --input '" + fixture + "' --out '" + dir + "'");
  INFO(city.output);
  REQUIRE(city.exitCode == 0);
  // 3984 corners: an outline that is itself tagged building:part is one of its own parts (issue 21),
  // 3758 before.
  CHECK(city.output.find("\nlod2        41 of 41 buildings with building:parts are LOD2 models (3984 vertices") !=
        std::string::npos);
  REQUIRE(run("response --city '" + dir + "' --synthetic 1").exitCode == 0);
  {
    Json j;
    parse(j, run("info '" + dir + "' --building w34633854 --json").output);
    CHECK(j.doc["lod"].get_uint64().value() == 2);
    CHECK(std::string_view(j.doc["name"].get_string().value()) == "Empire State Building");
    CHECK(j.doc["height_m"].get_double().value() == Approx(330.0).margin(0.05));  // the roof, not the antenna
    CHECK(j.doc["storeys"].get_uint64().value() == 102);
    CHECK(std::string_view(j.doc["lod2"]["source"].get_string().value()) == "osm-parts");
    CHECK(j.doc["lod2"]["vertices_before"].get_uint64().value() == 354);
    // Cut at every one of its 103 floor levels: far more vertices than the parts' corners.
    CHECK(j.doc["lod2"]["vertices"].get_uint64().value() > 10 * 354);
    // The MDOF model computed its response like any other building's.
    CHECK(j.doc["peak_drift_ratio"].get_array().size() == 102);
  }
  {
    Json j;
    parse(j, run("info '" + dir + "' --json").output);
    CHECK(j.doc["lod2"].get_uint64().value() == 41);
  }

  // --no-lod2 keeps them LOD1 prisms.
  REQUIRE(run("city --no-lod2 --input '" + fixture + "' --out '" + dir + "'").exitCode == 0);
  {
    Json j;
    parse(j, run("info '" + dir + "' --building w34633854 --json").output);
    CHECK(j.doc["lod"].get_uint64().value() == 1);
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("synth-city --detailed-towers makes LOD2 towers, bad values are usage errors", "[lod2][cli][synth]") {
  const std::string dir = "/tmp/qv-lod2-towers-" + std::to_string(getpid());
  const Run made = run("synth-city --buildings 400 --seed 9 --detailed-towers 6 --max-leaf-kib 64 --out '" + dir + "'");
  INFO(made.output);
  REQUIRE(made.exitCode == 0);
  CHECK(made.output.find("\nlod2        6 detailed towers are LOD2 models") != std::string::npos);
  Json j;
  parse(j, run("info '" + dir + "' --json").output);
  CHECK(j.doc["buildings"].get_uint64().value() == 400);
  CHECK(j.doc["lod2"].get_uint64().value() == 6);
  const auto ids = j.doc["lod2_ids"].get_array();
  REQUIRE(ids.size() == 6);
  const std::string first(std::string_view(ids.at(0).get_string().value()));
  Json b;
  parse(b, run("info '" + dir + "' --building " + first + " --json").output);
  CHECK(b.doc["lod"].get_uint64().value() == 2);
  CHECK(std::string_view(b.doc["lod2"]["source"].get_string().value()) == "synthetic");
  CHECK(b.doc["lod2"]["vertices"].get_uint64().value() > b.doc["lod2"]["vertices_before"].get_uint64().value());

  CHECK(run("synth-city --buildings 10 --seed 1 --detailed-towers -1 --out '" + dir + "'").exitCode == 2);
  CHECK(run("synth-city --buildings 10 --seed 1 --max-leaf-kib 4 --out '" + dir + "'").exitCode == 2);
  const Run bad = run("synth-city --buildings 10 --seed 1 --max-leaf-kib x --out '" + dir + "'", true);
  CHECK(bad.exitCode == 2);
  CHECK(bad.output.find("--max-leaf-kib must be from 16 to 16384") != std::string::npos);
  std::filesystem::remove_all(dir);
}
