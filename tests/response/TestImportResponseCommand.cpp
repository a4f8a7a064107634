// Runs the built quakeview-prep: import-response from JSON and CSV into a small synthetic city, what
// `info` then shows, and the errors a user gets for bad files (native only).
#include <unistd.h>

#include <simdjson.h>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "ToolRun.h"

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;

using Run = qv::test::ToolRun;

Run run(const std::string& arguments, bool withStderr = false) {
  return qv::test::runTool(kTool, arguments, withStderr);
}

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A displacement history of `storeys` floors, linear profile, roof amplitude `roof` (file units).
std::string floorsJson(int storeys, int samples, double roof, double periodSteps) {
  std::string s = "[";
  for (int i = 1; i <= storeys; ++i) {
    s += i > 1 ? ",[" : "[";
    for (int k = 0; k < samples; ++k) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%s%.6g", k > 0 ? "," : "",
                    roof * i / storeys * std::sin(6.283185307 * k / periodSteps));
      s += buffer;
    }
    s += "]";
  }
  return s + "]";
}

struct City {
  std::string dir;
  int storeys1 = 0, storeys2 = 0;
};

int storeysOf(const std::string& dir, const std::string& id) {
  const Run r = run("info '" + dir + "' --building " + id + " --json");
  REQUIRE(r.exitCode == 0);
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
  REQUIRE(parser.parse(r.output).get(doc) == simdjson::SUCCESS);
  std::int64_t storeys = 0;
  REQUIRE(doc["storeys"].get(storeys) == simdjson::SUCCESS);
  return static_cast<int>(storeys);
}

City makeCity(const std::string& name) {
  City c;
  c.dir = "/tmp/qv-import-test-" + std::to_string(getpid()) + "-" + name;
  run("synth-city --buildings 12 --seed 5 --out '" + c.dir + "'");
  c.storeys1 = storeysOf(c.dir, "s1");
  c.storeys2 = storeysOf(c.dir, "s2");
  return c;
}

std::string goodJson(const City& c, const std::string& units = "cm") {
  return "{\"format\": \"quakeview-response-import\", \"version\": 1, \"units\": \"" + units +
         "\", \"time_step_s\": 0.02, \"motion\": \"OpenSees, Kobe TAK000\",\n \"buildings\": [{\"id\": \"s1\", "
         "\"pga_g\": 0.61, \"start_s\": 1.5, \"x\": " +
         floorsJson(c.storeys1, 500, 12.0, 40) + ", \"y\": " + floorsJson(c.storeys1, 500, 5.0, 44) + "}]}";
}

std::string goodCsv(const City& c, double dt = 0.02) {
  std::string s = "# units: mm\nbuilding,time_s,floor,x,y\n";
  for (int k = 0; k < 300; ++k) {
    for (int i = 1; i <= c.storeys2; ++i) {
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, "s2,%.4f,%d,%.4f,0\n", k * dt, i,
                    30.0 * i / c.storeys2 * std::sin(6.283185307 * k / 25.0));
      s += buffer;
    }
  }
  return s;
}

simdjson::dom::element parse(simdjson::dom::parser& parser, const std::string& text) {
  simdjson::dom::element doc;
  REQUIRE(parser.parse(text).get(doc) == simdjson::SUCCESS);
  return doc;
}

}  // namespace

TEST_CASE("import-response writes response tiles that info shows", "[response][cli]") {
  const City c = makeCity("ok");
  write(c.dir + "/a.json", goodJson(c));
  write(c.dir + "/b.csv", goodCsv(c));
  const Run r =
      run("import-response --city '" + c.dir + "' --input '" + c.dir + "/a.json' '" + c.dir + "/b.csv'", true);
  INFO(r.output);
  REQUIRE(r.exitCode == 0);
  CHECK(r.output.find("no result   10 buildings stay static") != std::string::npos);

  simdjson::dom::parser parser;
  const Run info = run("info '" + c.dir + "' --json");
  REQUIRE(info.exitCode == 0);
  const auto doc = parse(parser, info.output);
  std::uint64_t buildings = 0, sum = 0, noResult = 0;
  REQUIRE(doc["buildings"].get(buildings) == simdjson::SUCCESS);
  for (const char* k : {"none", "slight", "moderate", "extensive", "complete", "no_result"}) {
    std::uint64_t v = 0;
    REQUIRE(doc["damage_states"][k].get(v) == simdjson::SUCCESS);
    sum += v;
  }
  REQUIRE(doc["damage_states"]["no_result"].get(noResult) == simdjson::SUCCESS);
  CHECK(sum == buildings);
  CHECK(noResult == buildings - 2);
  std::string_view motion;
  REQUIRE(doc["motion"].get(motion) == simdjson::SUCCESS);
  CHECK(motion.find("OpenSees, Kobe TAK000") != std::string_view::npos);
  bool outOfDate = true;
  REQUIRE(doc["response_out_of_date"].get(outOfDate) == simdjson::SUCCESS);
  CHECK(!outOfDate);

  // One imported building: 12 cm roof in X (5 cm in Y) → a peak roof displacement of ~0.12 m.
  simdjson::dom::parser parser1;
  const Run one = run("info '" + c.dir + "' --building s1 --json");
  REQUIRE(one.exitCode == 0);
  const auto b = parse(parser1, one.output);
  std::string_view damage;
  REQUIRE(b["damage_state"].get(damage) == simdjson::SUCCESS);
  CHECK(damage != "no_result");
  simdjson::dom::array drifts;
  REQUIRE(b["peak_drift_ratio"].get(drifts) == simdjson::SUCCESS);
  CHECK(drifts.size() == static_cast<std::size_t>(c.storeys1));
  double roof = 0.0, pga = 0.0;
  REQUIRE(b["peak_roof_displacement_m"].get(roof) == simdjson::SUCCESS);
  REQUIRE(b["pga_g"].get(pga) == simdjson::SUCCESS);
  CHECK(roof >= 0.12 * 0.99);  // |(x, y)|: 12 cm in X with up to 5 cm in Y
  CHECK(roof <= 0.13);
  CHECK(pga == Approx(0.61).epsilon(1e-5));

  // A building without results stays static and says so.
  simdjson::dom::parser parser2;
  const auto none = parse(parser2, run("info '" + c.dir + "' --building s3 --json").output);
  REQUIRE(none["damage_state"].get(damage) == simdjson::SUCCESS);
  CHECK(damage == "no_result");

  // The text form shows the counts and the motion.
  const Run text = run("info '" + c.dir + "'");
  CHECK(text.output.find("damage      none:") != std::string::npos);
  CHECK(text.output.find("OpenSees, Kobe TAK000") != std::string::npos);

  // A response older than the buildings is reported.
  {
    std::ifstream in(c.dir + "/tileset.json");
    std::string manifest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string key = "\"buildingsRevision\":";
    const std::size_t at = manifest.find(key);
    REQUIRE(at != std::string::npos);
    manifest.replace(at, key.size() + 1, key + "9");
    write(c.dir + "/tileset.json", manifest);
  }
  CHECK(run("info '" + c.dir + "'").output.find("the response is out of date") != std::string::npos);
  simdjson::dom::parser parser3;
  const auto stale = parse(parser3, run("info '" + c.dir + "' --json").output);
  REQUIRE(stale["response_out_of_date"].get(outOfDate) == simdjson::SUCCESS);
  CHECK(outOfDate);
  std::system(("rm -rf '" + c.dir + "'").c_str());
}

TEST_CASE("import-response errors name the file and the place, and leave the city unchanged", "[response][cli]") {
  const City c = makeCity("errors");
  const std::string json = c.dir + "/r.json", csv = c.dir + "/r.csv";
  auto import = [&](const std::string& inputs) {
    return run("import-response --city '" + c.dir + "' --input " + inputs, true);
  };
  struct Case {
    const char* what;
    std::string file, text, inputs;
    std::vector<std::string> expected;
  };
  std::string unknownId = goodJson(c);
  unknownId.replace(unknownId.find("\"s1\""), 4, "\"w999\"");
  std::string badUnits = goodJson(c, "furlong");
  const std::string wrongFloors = "{\"units\": \"m\", \"time_step_s\": 0.02, \"buildings\": [{\"id\": \"s1\", \"x\": " +
                                  floorsJson(c.storeys1 + 1, 50, 0.1, 20) + "}]}";
  std::string nonUniform = goodCsv(c);
  for (std::size_t at = nonUniform.find("s2,0.1000,"); at != std::string::npos; at = nonUniform.find("s2,0.1000,")) {
    nonUniform.replace(at, 10, "s2,0.1100,");
  }
  const Case cases[] = {
      {"unknown id", json, unknownId, "'" + json + "'", {"r.json: buildings[0]", "w999", "not in the city"}},
      {"unknown unit", json, badUnits, "'" + json + "'", {"r.json: units", "furlong"}},
      {"storey count",
       json,
       wrongFloors,
       "'" + json + "'",
       {"r.json: buildings[0] (s1)", std::to_string(c.storeys1 + 1) + " floors",
        std::to_string(c.storeys1) + " storeys"}},
      {"non-uniform time", csv, nonUniform, "'" + csv + "'", {"r.csv:", "non-uniform time step"}},
      {"no units", csv, goodCsv(c).substr(12), "'" + csv + "'", {"r.csv", "--units"}},
  };
  for (const Case& k : cases) {
    INFO(k.what);
    write(k.file, k.text);
    const Run r = import(k.inputs);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    for (const std::string& e : k.expected) CHECK(r.output.find(e) != std::string::npos);
  }
  // Mismatched time bases between files.
  write(json, goodJson(c));
  write(csv, goodCsv(c, 0.01));
  const Run mismatch = import("'" + json + "' '" + csv + "'");
  INFO(mismatch.output);
  CHECK(mismatch.exitCode == 1);
  CHECK(mismatch.output.find("differs from 0.02 s") != std::string::npos);
  // Nothing was written: no response in the manifest, no response folder left behind.
  simdjson::dom::parser parser;
  const auto doc = parse(parser, run("info '" + c.dir + "' --json").output);
  CHECK(doc["response"].is_null());
  CHECK(std::system(("test -z \"$(ls -d '" + c.dir + "'/response-* 2>/dev/null)\"").c_str()) == 0);
  CHECK(run("import-response --city '" + c.dir + "'", true).exitCode == 2);
  const Run help = run("import-response --help");
  CHECK(help.exitCode == 0);
  CHECK(help.output.find("--units") != std::string::npos);
  std::system(("rm -rf '" + c.dir + "'").c_str());
}
