#include <catch2/catch.hpp>

#include <map>

#include "qv/format/Tileset.h"

using namespace qv;

namespace {

Tileset sample() {
  Tileset t;
  t.generator = "test";
  t.name = "Lower \"Manhattan\"";
  t.originLon = -74.0;
  t.originLat = 40.71;
  t.bounds = Rect{-500, -400, 500, 400};
  t.maxHeightM = 443.2f;
  t.buildings = 3;
  t.sources = {"a.osm"};
  TileNode root;
  root.bounds = t.bounds;
  root.coarse = true;
  root.geometricErrorM = 4.0f;
  root.buildings = 3;
  root.subtreeBuildings = 3;
  root.file = "tiles/0-0-0.qvt";
  root.bytes = 1000;
  root.crc32 = 0xdeadbeef;
  root.children = {1};
  TileNode leaf;
  leaf.level = 1;
  leaf.x = 1;
  leaf.y = 0;
  leaf.bounds = Rect{0, -400, 500, 0};
  leaf.maxHeightM = 443.2f;
  leaf.buildings = 3;
  leaf.subtreeBuildings = 3;
  leaf.file = "tiles/1-1-0.qvt";
  leaf.bytes = 5000;
  leaf.crc32 = 7;
  leaf.response = TileResponseFiles{"response/1-1-0.qvs", 10, 1, "response/1-1-0.qvh", 20, 2};
  t.nodes = {root, leaf};
  ResponseInfo r;
  r.motion = "TAK000.AT2";
  r.method = "MDOF shear building, Bouc-Wen";
  r.durationSeconds = 40.96;
  r.sampleRateHz = 25;
  r.buildingsRevision = 1;
  r.damageStates[0] = 1;
  r.damageStates[3] = 2;
  t.response = r;
  return t;
}

}  // namespace

TEST_CASE("The manifest round-trips through JSON", "[format][tileset]") {
  const Tileset t = sample();
  const std::string json = tilesetToJson(t);
  CHECK(json.find("\"format\":\"quakeview-tileset\",\"version\":1") != std::string::npos);
  CHECK(json.find("\"origin\":[-74,40.71]") != std::string::npos);
  CHECK(json.find("\"crc32\":\"deadbeef\"") != std::string::npos);
  const auto parsed = parseTileset(json, "tileset.json");
  REQUIRE(parsed.ok());
  const Tileset& p = *parsed;
  CHECK(p.originLon == -74.0);
  CHECK(p.originLat == 40.71);
  CHECK(p.name == "Lower \"Manhattan\"");
  CHECK(p.buildings == 3);
  CHECK(p.maxHeightM == 443.2f);
  REQUIRE(p.nodes.size() == 2);
  CHECK(p.nodes[0].children == std::vector<std::uint32_t>{1});
  CHECK(p.nodes[0].coarse);
  CHECK(p.nodes[0].crc32 == 0xdeadbeefu);
  CHECK(p.nodes[1].key() == "1/1/0");
  REQUIRE(p.nodes[1].response.has_value());
  CHECK(p.nodes[1].response->historyFile == "response/1-1-0.qvh");
  REQUIRE(p.response.has_value());
  CHECK(p.response->damageStates[3] == 2);
  CHECK_FALSE(p.responseOutOfDate());
  CHECK(tilesetToJson(p) == json);
}

TEST_CASE("Buildings left out of the city are counted in the manifest by reason", "[format][tileset]") {
  Tileset t = sample();
  CHECK(tilesetToJson(t).find("excluded") == std::string::npos);  // absent when none
  t.excluded["underground"] = 2;
  const std::string json = tilesetToJson(t);
  CHECK(json.find("\"excluded\":{\"underground\":2}") != std::string::npos);
  const auto parsed = parseTileset(json, "tileset.json");
  REQUIRE(parsed.ok());
  CHECK(parsed->excluded == std::map<std::string, std::uint64_t>{{"underground", 2}});
  std::string bad = json;
  bad.replace(bad.find("\"underground\":2"), 15, "\"underground\":-1");
  const auto refused = parseTileset(bad, "tileset.json");
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error() == "tileset.json: excluded: \"underground\" is not a count");
}

TEST_CASE("A response computed for older buildings is reported out of date", "[format][tileset]") {
  Tileset t = sample();
  t.buildingsRevision = 2;
  CHECK(t.responseOutOfDate());
}

TEST_CASE("Malformed manifests are rejected with a specific message", "[format][tileset]") {
  auto errorOf = [](const std::string& json) {
    const auto r = parseTileset(json, "city/tileset.json");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("city/tileset.json: ", 0) == 0);
    return r.error();
  };
  const std::string good = tilesetToJson(sample());
  CHECK(errorOf("{not json").find("not valid JSON") != std::string::npos);
  CHECK(errorOf("[1,2]").find("must be a JSON object") != std::string::npos);
  std::string other = good;
  other.replace(other.find("quakeview-tileset"), 17, "something-else-xx");
  CHECK(errorOf(other).find("not a QuakeView tileset") != std::string::npos);
  std::string v2 = good;
  v2.replace(v2.find("\"version\":1"), 11, "\"version\":2");
  CHECK(errorOf(v2).find("unsupported tileset version 2") != std::string::npos);
  std::string escape = good;
  escape.replace(escape.find("tiles/1-1-0.qvt"), 15, "../../etc/passw");
  CHECK(errorOf(escape).find("is not a relative path inside the city directory") != std::string::npos);
  std::string badChild = good;
  badChild.replace(badChild.find("\"level\":1"), 9, "\"level\":2");
  CHECK(errorOf(badChild).find("is not a quadtree child") != std::string::npos);
  std::string badOrigin = good;
  badOrigin.replace(badOrigin.find("[-74,40.71]"), 11, "[-74,140.7]");
  CHECK(errorOf(badOrigin).find("\"origin\" must hold") != std::string::npos);
}

TEST_CASE("Checksums are hex digits only and file sizes fit the formats' 32-bit size", "[format][tileset]") {
  auto errorOf = [](const std::string& json) {
    const auto r = parseTileset(json, "city/tileset.json");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("city/tileset.json: ", 0) == 0);
    return r.error();
  };
  const std::string good = tilesetToJson(sample());
  for (const char* crc : {"\"-1\"", "\"+1\"", "\" 1\"", "\"0x1\"", "\"\""}) {
    std::string bad = good;
    bad.replace(bad.find("\"deadbeef\""), 10, crc);
    CHECK(errorOf(bad).find("\"crc32\" is not hex") != std::string::npos);
  }
  std::string huge = good;
  const std::size_t at = huge.find("\"bytes\":") + 8;
  huge.replace(at, huge.find(',', at) - at, "4294967296");
  CHECK(errorOf(huge).find("\"bytes\" is larger than a QuakeView file can be") != std::string::npos);
}

TEST_CASE("The city's name is optional in a manifest and must be text when present", "[format][tileset]") {
  Tileset t = sample();
  t.name.clear();
  const std::string unnamed = tilesetToJson(t);
  CHECK(unnamed.find("\"name\"") == std::string::npos);  // as manifests written before names existed
  const auto parsed = parseTileset(unnamed, "old/tileset.json");
  REQUIRE(parsed.ok());
  CHECK(parsed->name.empty());
  std::string numeric = unnamed;
  numeric.replace(numeric.find("\"generator\""), 0, "\"name\":42,");
  const auto refused = parseTileset(numeric, "bad/tileset.json");
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error().find("\"name\"") != std::string::npos);
  CHECK(refused.error().find("bad/tileset.json") != std::string::npos);
}

TEST_CASE("The manifest keeps the shaking's provenance: event type, ShakeMap, records, consequences",
          "[format][tileset]") {
  Tileset t = sample();
  ResponseInfo& r = *t.response;
  r.eventType = "ACTUAL";
  r.shakingField = "shakemap";
  r.scaling = "sa";
  r.shakemap = ResponseInfo::ShakeMap{
      "us7000abcd", "3",   "2026-11-25T10:00:00Z", "2026-11-25T09:41:07Z", "10 km SE of Somewhere", "us", 5.8, 5.0,
      40.55,        -74.03};
  r.records = {"elCentro.AT2", "TAK000.AT2 (KOBE 01/16/95 2046, TAKATORI, 000)"};
  r.timeOfDay = "day";
  r.consequences = CityFile{"response-1/consequences.json", 1234, 0x01020304u};
  const std::string json = tilesetToJson(t);
  const auto parsed = parseTileset(json, "tileset.json");
  REQUIRE(parsed.ok());
  const ResponseInfo& p = *parsed->response;
  CHECK(p.eventType == "ACTUAL");
  CHECK(p.shakingField == "shakemap");
  CHECK(p.scaling == "sa");
  REQUIRE(p.shakemap.has_value());
  CHECK(*p.shakemap == *r.shakemap);
  CHECK(p.records == r.records);
  CHECK(p.timeOfDay == "day");
  REQUIRE(p.consequences.has_value());
  CHECK(p.consequences->file == "response-1/consequences.json");
  CHECK(tilesetToJson(*parsed) == json);

  SECTION("an event type other than SCENARIO or ACTUAL is refused") {
    std::string bad = json;
    bad.replace(bad.find("\"ACTUAL\""), 8, "\"MAYBE\"");
    const auto refused = parseTileset(bad, "tileset.json");
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error(), Catch::Contains("eventType"));
  }
}
