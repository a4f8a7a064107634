#include <catch2/catch.hpp>

#include <string>

#include "qv/format/ScenarioCatalogue.h"

using namespace qv;

namespace {

// The catalogue as the contract shows it.
constexpr const char* kContract = R"({"format":"quakeview-scenarios","version":1,"scenarios":[)"
                                  R"({"index":1,"name":"M6.6 scenario, Lower Manhattan","manifest":"scenario-1.json"},)"
                                  R"({"index":2,"name":"USGS ShakeMap NYC M5.8","manifest":"scenario-2.json"}]})";

std::string withEntry(const std::string& entry) {
  return R"({"format":"quakeview-scenarios","version":1,"scenarios":[)"
         R"({"index":1,"name":"Good","manifest":"scenario-1.json"},)" +
         entry + "]}";
}

}  // namespace

TEST_CASE("The contract's catalogue parses, in the file's order", "[format][scenarios]") {
  const auto c = parseScenarioCatalogue(kContract, "city/scenarios.json");
  REQUIRE(c.ok());
  REQUIRE(c->scenarios.size() == 2);
  CHECK(c->scenarios[0] == ScenarioEntry{1, "M6.6 scenario, Lower Manhattan", "scenario-1.json"});
  CHECK(c->scenarios[1] == ScenarioEntry{2, "USGS ShakeMap NYC M5.8", "scenario-2.json"});
  CHECK(c->warnings.empty());
}

TEST_CASE("A catalogue round-trips through JSON, byte for byte", "[format][scenarios]") {
  ScenarioCatalogue c;
  c.scenarios = {{1, "M6.6 scenario, Lower Manhattan", "scenario-1.json"},
                 {7, "\"Quoted\" name, ünïcödé", "scenario-7.json"},
                 {2, "USGS ShakeMap NYC M5.8", "tileset.json"}};
  const std::string json = scenarioCatalogueToJson(c);
  // Golden text: what the tool writes and the viewer reads.
  CHECK(json ==
        "{\"format\":\"quakeview-scenarios\",\"version\":1,\"scenarios\":[\n"
        "{\"index\":1,\"name\":\"M6.6 scenario, Lower Manhattan\",\"manifest\":\"scenario-1.json\"},\n"
        "{\"index\":7,\"name\":\"\\\"Quoted\\\" name, ünïcödé\",\"manifest\":\"scenario-7.json\"},\n"
        "{\"index\":2,\"name\":\"USGS ShakeMap NYC M5.8\",\"manifest\":\"tileset.json\"}]}\n");
  const auto back = parseScenarioCatalogue(json, "x");
  REQUIRE(back.ok());
  CHECK(back->scenarios == c.scenarios);
  CHECK(back->warnings.empty());
}

TEST_CASE("Keys a reader does not know are ignored", "[format][scenarios]") {
  const auto c =
      parseScenarioCatalogue(R"({"format":"quakeview-scenarios","version":1,"generator":"later tool","scenarios":[)"
                             R"({"index":3,"name":"A","manifest":"a.json","magnitude":6.6,"extra":{"x":[1,2]}}]})",
                             "s");
  REQUIRE(c.ok());
  REQUIRE(c->scenarios.size() == 1);
  CHECK(c->scenarios[0].index == 3);
  CHECK(c->warnings.empty());
}

TEST_CASE("A file that is no catalogue is refused whole, with a message naming it", "[format][scenarios]") {
  struct Case {
    std::string json;
    const char* expected;
  };
  const Case cases[] = {
      {"", "city/scenarios.json: not valid JSON"},
      {"{\"format\":", "not valid JSON"},
      {"<html>404</html>", "not valid JSON"},
      {"[1,2,3]", "must be a JSON object"},
      {"\"scenarios\"", "must be a JSON object"},
      {R"({"version":1,"scenarios":[]})", "not a QuakeView scenario catalogue"},
      {R"({"format":"quakeview-tileset","version":1,"scenarios":[]})", "not a QuakeView scenario catalogue"},
      {R"({"format":"quakeview-scenarios","scenarios":[]})", "\"version\" missing or not a number"},
      {R"({"format":"quakeview-scenarios","version":"1","scenarios":[]})", "\"version\" missing or not a number"},
      {R"({"format":"quakeview-scenarios","version":2,"scenarios":[]})",
       "unsupported scenario catalogue version 2 (this build reads version 1)"},
      {R"({"format":"quakeview-scenarios","version":1e300,"scenarios":[]})", "unsupported scenario catalogue version"},
      {R"({"format":"quakeview-scenarios","version":1})", "\"scenarios\" missing or not a list"},
      {R"({"format":"quakeview-scenarios","version":1,"scenarios":{"index":1}})",
       "\"scenarios\" missing or not a list"},
      // Invalid UTF-8 in a name: the whole text is not JSON.
      {std::string(R"({"format":"quakeview-scenarios","version":1,"scenarios":[{"index":1,"name":"a)") + "\xff\xfe" +
           R"(","manifest":"a.json"}]})",
       "not valid JSON"},
      // Nesting deeper than the parser goes.
      {std::string(R"({"format":"quakeview-scenarios","version":1,"scenarios":[)") + std::string(5000, '[') +
           std::string(5000, ']') + "]}",
       "not valid JSON"},
  };
  for (const Case& c : cases) {
    INFO(c.json.substr(0, 200));
    const auto r = parseScenarioCatalogue(c.json, "city/scenarios.json");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("city/scenarios.json: ", 0) == 0);
    CHECK(r.error().find(c.expected) != std::string::npos);
  }
  // Larger than a list of scenarios can be: refused before parsing.
  const std::string huge =
      withEntry(R"({"index":2,"name":")" + std::string(2u << 20, 'x') + R"(","manifest":"b.json"})");
  const auto r = parseScenarioCatalogue(huge, "big.json");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error() == "big.json: larger than 1024 KiB; a scenario catalogue is a short list");
}

TEST_CASE("A manifest that is a path, an address or no JSON file name leaves its entry out", "[format][scenarios]") {
  const char* const hostile[] = {
      "../other-city/tileset.json",
      "..json",
      "a..b.json",
      "response-1/tileset.json",
      "/etc/passwd.json",
      "C:\\\\city\\\\x.json",
      "https://evil.example/x.json",
      "//evil.example/x.json",
      "javascript:alert(1).json",
      "data:x.json",
      "%2e%2e%2fx.json",
      "x.json?y=1",
      "x.json#y",
      ".hidden.json",
      ".json",
      "tileset.qvt",
      "scenario-1",
      "scenario 1.json",
      "sc\\u00e9nario.json",
      "a\\u0000.json",
      "",
  };
  for (const char* manifest : hostile) {
    INFO(manifest);
    const auto c = parseScenarioCatalogue(
        withEntry(std::string(R"({"index":2,"name":"Hostile","manifest":")") + manifest + "\"}"), "s.json");
    REQUIRE(c.ok());
    REQUIRE(c->scenarios.size() == 1);  // the good entry stays
    CHECK(c->scenarios[0].manifest == "scenario-1.json");
    REQUIRE(c->warnings.size() == 1);
    CHECK(c->warnings[0].rfind("s.json: entry 2 of \"scenarios\" (scenario 2) has the manifest \"", 0) == 0);
    CHECK(c->warnings[0].find("it is left out") != std::string::npos);
  }
  const auto path =
      parseScenarioCatalogue(withEntry(R"({"index":2,"name":"H","manifest":"../x/tileset.json"})"), "s.json");
  REQUIRE(path.ok());
  CHECK(path->warnings.at(0) ==
        "s.json: entry 2 of \"scenarios\" (scenario 2) has the manifest \"../x/tileset.json\", which is a path; a "
        "scenario's manifest must be a file name beside scenarios.json; it is left out");
  const std::string longName(kMaxScenarioManifestBytes, 'a');
  CHECK_FALSE(scenarioManifestProblem(longName.substr(0, kMaxScenarioManifestBytes - 5) + ".json").size() > 0);
  CHECK(scenarioManifestProblem(longName + ".json") == "is longer than 128 bytes");
  for (const char* good : {"scenario-1.json", "tileset.json", "M5.8_shakemap-v4.json", "a.b.json"}) {
    INFO(good);
    CHECK(scenarioManifestProblem(good).empty());
  }
}

TEST_CASE("Names with control characters, line breaks or bidirectional controls leave their entry out",
          "[format][scenarios]") {
  const char* const hostile[] = {
      "",
      "a\\u0000b",
      "line\\nbreak",
      "tab\\there",
      "\\u001b[31mred",
      "\\u007f",
      "\\u0085next line",
      "\\u202Eevil.exe",
      "isolate\\u2066x\\u2069",
      "mark\\u200F",
      "para\\u2029graph",
  };
  for (const char* name : hostile) {
    INFO(name);
    const auto c = parseScenarioCatalogue(
        withEntry(std::string(R"({"index":2,"name":")") + name + R"(","manifest":"b.json"})"), "s.json");
    REQUIRE(c.ok());
    CHECK(c->scenarios.size() == 1);
    REQUIRE(c->warnings.size() == 1);
    CHECK(c->warnings[0].find("(scenario 2) has the name \"") != std::string::npos);
    // The message itself is one clean line: what it quotes is made safe to show.
    CHECK(c->warnings[0].find('\n') == std::string::npos);
    CHECK(c->warnings[0].find('\x1b') == std::string::npos);
    CHECK(c->warnings[0].find("\xE2\x80\xAE") == std::string::npos);  // U+202E
  }
  const std::string longest(kMaxScenarioNameBytes, 'n');
  auto c = parseScenarioCatalogue(withEntry(R"({"index":2,"name":")" + longest + R"(","manifest":"b.json"})"), "s");
  REQUIRE(c.ok());
  CHECK(c->scenarios.size() == 2);
  c = parseScenarioCatalogue(withEntry(R"({"index":2,"name":")" + longest + R"(n","manifest":"b.json"})"), "s");
  REQUIRE(c.ok());
  CHECK(c->scenarios.size() == 1);
  REQUIRE(c->warnings.size() == 1);
  CHECK(c->warnings[0].find("is longer than 200 bytes") != std::string::npos);
  CHECK(c->warnings[0].find("nnn...\"") != std::string::npos);  // quoted, cut short
  // Other scripts are names like any other.
  c = parseScenarioCatalogue(withEntry(R"({"index":2,"name":"東京 M7.3 シナリオ","manifest":"b.json"})"), "s");
  REQUIRE(c.ok());
  CHECK(c->scenarios.size() == 2);
}

TEST_CASE("Bad indices, missing fields and repeats leave their entry out", "[format][scenarios]") {
  struct Case {
    const char* entry;
    const char* expected;
  };
  const Case cases[] = {
      {"42", "entry 2 of \"scenarios\" is not an object; it is left out"},
      {"null", "is not an object"},
      {R"({"name":"A","manifest":"a.json"})", "has no number \"index\""},
      {R"({"index":"2","name":"A","manifest":"a.json"})", "has no number \"index\""},
      {R"({"index":0,"name":"A","manifest":"a.json"})", "has \"index\" 0, not a whole number from 1 to 1000000"},
      {R"({"index":-3,"name":"A","manifest":"a.json"})", "has \"index\" -3"},
      {R"({"index":1.5,"name":"A","manifest":"a.json"})", "has \"index\" 1.5"},
      {R"({"index":1e300,"name":"A","manifest":"a.json"})", "not a whole number"},
      {R"({"index":1000001,"name":"A","manifest":"a.json"})", "not a whole number"},
      {R"({"index":2,"manifest":"a.json"})", "(scenario 2) has no string \"name\""},
      {R"({"index":2,"name":["A"],"manifest":"a.json"})", "(scenario 2) has no string \"name\""},
      {R"({"index":2,"name":"A"})", "(scenario 2) has no string \"manifest\""},
      {R"({"index":2,"name":"A","manifest":7})", "(scenario 2) has no string \"manifest\""},
      {R"({"index":1,"name":"Again","manifest":"a.json"})", "repeats scenario index 1"},
      {R"({"index":2,"name":"Same file","manifest":"scenario-1.json"})",
       "(scenario 2) repeats the manifest \"scenario-1.json\""},
  };
  for (const Case& k : cases) {
    INFO(k.entry);
    const auto c = parseScenarioCatalogue(withEntry(k.entry), "s.json");
    REQUIRE(c.ok());
    CHECK(c->scenarios.size() == 1);
    REQUIRE(c->warnings.size() == 1);
    CHECK(c->warnings[0].find(k.expected) != std::string::npos);
  }
  // An empty list is a catalogue with nothing in it.
  const auto empty = parseScenarioCatalogue(R"({"format":"quakeview-scenarios","version":1,"scenarios":[]})", "s");
  REQUIRE(empty.ok());
  CHECK(empty->scenarios.empty());
}

TEST_CASE("Thousands of entries: the first kMaxScenarios are read, the rest left out in one message",
          "[format][scenarios]") {
  std::string json = R"({"format":"quakeview-scenarios","version":1,"scenarios":[)";
  constexpr int kEntries = 5000;
  for (int i = 1; i <= kEntries; ++i) {
    if (i > 1) json += ',';
    json += R"({"index":)" + std::to_string(i) + R"(,"name":"Scenario )" + std::to_string(i) +
            R"(","manifest":"scenario-)" + std::to_string(i) + R"(.json"})";
  }
  json += "]}";
  const auto c = parseScenarioCatalogue(json, "s.json");
  REQUIRE(c.ok());
  REQUIRE(c->scenarios.size() == kMaxScenarios);
  CHECK(c->scenarios.back().index == kMaxScenarios);
  REQUIRE(c->warnings.size() == 1);
  CHECK(c->warnings[0] == "s.json: lists 5000 scenarios; the first 1000 are read, the other 4000 left out");

  // Thousands of bad entries: a message for each of the first ten, then one for the rest.
  std::string bad = R"({"format":"quakeview-scenarios","version":1,"scenarios":[)";
  for (int i = 1; i <= 3000; ++i) bad += std::string(i > 1 ? "," : "") + R"({"index":1,"name":"x","manifest":"../a"})";
  bad += "]}";
  const auto b = parseScenarioCatalogue(bad, "s.json");
  REQUIRE(b.ok());
  CHECK(b->scenarios.empty());
  REQUIRE(b->warnings.size() == 11);
  CHECK(b->warnings[1].rfind("s.json: entry 2 of \"scenarios\" (scenario 1) has the manifest \"../a\"", 0) == 0);
  CHECK(b->warnings.back() == "s.json: 2990 more bad entries are left out");
}

TEST_CASE("The file name of a manifest's address", "[format][scenarios]") {
  CHECK(urlFileName("data/city/scenario-2.json") == "scenario-2.json");
  CHECK(urlFileName("https://x.example/a/b/tileset.json?v=3#top") == "tileset.json");
  CHECK(urlFileName("tileset.json") == "tileset.json");
  CHECK(urlFileName("/a/b/") == "");
  CHECK(urlFileName("") == "");
}
