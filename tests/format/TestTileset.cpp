#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>

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

namespace {

GroundNode groundNode(std::uint8_t level, std::uint32_t x, std::uint32_t y, float geometricErrorM) {
  GroundNode n;
  n.level = level;
  n.x = x;
  n.y = y;
  n.geometricErrorM = geometricErrorM;
  n.file = "ground/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvg";
  n.bytes = 1000u + level;
  n.crc32 = 0xabc00000u + x;
  return n;
}

GroundLayer sampleGround() {
  GroundLayer g;
  g.minX = -1234.5;
  g.minY = -987.25;
  g.size = 2468.75;
  g.levels = 3;
  g.nodes = {groundNode(0, 0, 0, 9.6f), groundNode(1, 1, 0, 4.8f), groundNode(2, 3, 1, 0.0f)};
  g.features = {{"street", 120}, {"water", 3}, {"labels", 45}};
  g.skipped = {{"unclosed-coastline", 2}};
  g.bytes = 3006;
  return g;
}

std::string groundErrorOf(const GroundLayer& g) {
  Tileset t = sample();
  t.ground = g;
  const auto r = parseTileset(tilesetToJson(t), "city/tileset.json");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().rfind("city/tileset.json: ", 0) == 0);
  return r.error();
}

}  // namespace

TEST_CASE("The manifest keeps the ground layer, one node per line", "[format][tileset][ground]") {
  Tileset t = sample();
  t.ground = sampleGround();
  const std::string json = tilesetToJson(t);
  CHECK(json.find("\"ground\":{\"minX\":-1234.5,\"minY\":-987.25,\"size\":2468.75,\"levels\":3,\"bytes\":3006,"
                  "\"features\":{\"labels\":45,\"street\":120,\"water\":3},\"skipped\":{\"unclosed-coastline\":2},"
                  "\"nodes\":[\n{\"level\":0,\"x\":0,\"y\":0,\"geometricError\":9.6,\"file\":\"ground/0-0-0.qvg\","
                  "\"bytes\":1000,\"crc32\":\"abc00000\"},\n{\"level\":1,") != std::string::npos);
  const auto parsed = parseTileset(json, "tileset.json");
  INFO((parsed.ok() ? std::string() : parsed.error()));
  REQUIRE(parsed.ok());
  REQUIRE(parsed->ground.has_value());
  const GroundLayer& g = *parsed->ground;
  CHECK(g.minX == -1234.5);
  CHECK(g.minY == -987.25);
  CHECK(g.size == 2468.75);
  CHECK(g.levels == 3);
  CHECK(g.bytes == 3006);
  CHECK(g.features == t.ground->features);
  CHECK(g.skipped == t.ground->skipped);
  REQUIRE(g.nodes.size() == 3);
  CHECK(g.nodes[2].level == 2);
  CHECK(g.nodes[2].x == 3);
  CHECK(g.nodes[2].y == 1);
  CHECK(g.nodes[1].geometricErrorM == 4.8f);
  CHECK(g.nodes[2].file == "ground/2-3-1.qvg");
  CHECK(g.nodes[2].bytes == 1002);
  CHECK(g.nodes[1].crc32 == 0xabc00001u);
  CHECK(tilesetToJson(*parsed) == json);

  SECTION("a layer without features or cells writes neither counts") {
    GroundLayer empty;
    empty.size = 100.0;
    empty.levels = 1;
    t.ground = empty;
    const std::string bare = tilesetToJson(t);
    CHECK(bare.find("\"ground\":{\"minX\":0,\"minY\":0,\"size\":100,\"levels\":1,\"bytes\":0,\"nodes\":[]}") !=
          std::string::npos);
    const auto p = parseTileset(bare, "tileset.json");
    REQUIRE(p.ok());
    REQUIRE(p->ground.has_value());
    CHECK(p->ground->nodes.empty());
    CHECK(p->ground->features.empty());
  }
  SECTION("manifests without the key have no ground layer") {
    const std::string old = tilesetToJson(sample());
    CHECK(old.find("ground") == std::string::npos);
    const auto p = parseTileset(old, "tileset.json");
    REQUIRE(p.ok());
    CHECK_FALSE(p->ground.has_value());
  }
}

TEST_CASE("Ground layers outside their bounds are refused with a message naming the key", "[format][tileset][ground]") {
  struct Case {
    const char* what;
    void (*change)(GroundLayer&);
    const char* message;
  };
  const Case cases[] = {
      {"size 0", [](GroundLayer& g) { g.size = 0.0; }, "ground: \"size\" must be a positive number of metres"},
      {"size negative", [](GroundLayer& g) { g.size = -5.0; }, "ground: \"size\" must be a positive number"},
      {"size NaN", [](GroundLayer& g) { g.size = std::nan(""); }, "ground: \"size\" is not a number"},
      {"size beyond 1e8 m", [](GroundLayer& g) { g.size = 2.0e8; }, "ground: \"size\" must be a positive number"},
      {"minX beyond 1e7 m", [](GroundLayer& g) { g.minX = -3.0e7; }, "ground: \"minX\" and \"minY\" must lie within"},
      {"0 levels", [](GroundLayer& g) { g.levels = 0; }, "ground: \"levels\" must be 1 to 24, not 0"},
      {"25 levels", [](GroundLayer& g) { g.levels = 25; }, "ground: \"levels\" must be 1 to 24, not 25"},
      {"a node as deep as the levels", [](GroundLayer& g) { g.nodes.push_back(groundNode(3, 0, 0, 0.0f)); },
       "ground node 3: \"level\" 3 is not below \"levels\" 3"},
      {"x outside its level", [](GroundLayer& g) { g.nodes[1].x = 2; },
       "ground node 1: \"x\" 2 and \"y\" 0 must be below 2^1 at level 1"},
      {"y outside its level", [](GroundLayer& g) { g.nodes[2].y = 4; }, "ground node 2: \"x\" 3 and \"y\" 4 must be"},
      {"a cell twice", [](GroundLayer& g) { g.nodes.push_back(groundNode(1, 1, 0, 1.0f)); },
       "ground node 3: cell 1/1/0 is listed twice"},
      {"a negative geometric error", [](GroundLayer& g) { g.nodes[0].geometricErrorM = -1.0f; },
       "ground node 0: \"geometricError\" must be 0 to 1e7 m"},
      {"a path out of the city", [](GroundLayer& g) { g.nodes[0].file = "../ground/0-0-0.qvg"; },
       "ground node 0: file \"../ground/0-0-0.qvg\" is not a relative path inside the city directory"},
      {"an absolute path", [](GroundLayer& g) { g.nodes[1].file = "/etc/ground.qvg"; },
       "ground node 1: file \"/etc/ground.qvg\" is not a relative path"},
      {"a backslash", [](GroundLayer& g) { g.nodes[2].file = "ground\\2-3-1.qvg"; }, "is not a relative path"},
      {"a URL", [](GroundLayer& g) { g.nodes[2].file = "https://example.org/g.qvg"; }, "is not a relative path"},
      {"an empty path", [](GroundLayer& g) { g.nodes[2].file.clear(); }, "ground node 2: file \"\" is not a relative"},
      {"a count that is not one", [](GroundLayer& g) { g.features["street"] = 1ull << 60; },
       "ground features: \"street\" is not a count"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    GroundLayer g = sampleGround();
    c.change(g);
    CHECK_THAT(groundErrorOf(g), Catch::Contains(c.message));
  }

  const std::string good = [] {
    Tileset t = sample();
    t.ground = sampleGround();
    return tilesetToJson(t);
  }();
  auto errorOf = [](const std::string& json) {
    const auto r = parseTileset(json, "city/tileset.json");
    REQUIRE_FALSE(r.ok());
    return r.error();
  };
  std::string notObject = good;
  notObject.replace(notObject.find("\"ground\":{"), 10, "\"ground\":[1],\"x\":{");
  CHECK_THAT(errorOf(notObject), Catch::Contains("city/tileset.json: \"ground\" must be an object"));
  std::string noNodes = good;
  noNodes.replace(noNodes.find("\"nodes\""), 7, "\"cells\"");
  CHECK_THAT(errorOf(noNodes), Catch::Contains("ground: \"nodes\" missing or not an array"));
  std::string noLevels = good;
  noLevels.replace(noLevels.find("\"levels\""), 8, "\"depth\"");
  CHECK_THAT(errorOf(noLevels), Catch::Contains("ground: missing \"levels\""));
  std::string badCrc = good;
  badCrc.replace(badCrc.find("\"abc00000\""), 10, "\"-1\"");
  CHECK_THAT(errorOf(badCrc), Catch::Contains("ground node 0: \"crc32\" is not hex"));
  std::string badSkipped = good;
  badSkipped.replace(badSkipped.find("\"skipped\":{"), 11, "\"skipped\":7,\"x\":{");
  CHECK_THAT(errorOf(badSkipped), Catch::Contains("ground: \"skipped\" must be an object of counts"));
  std::string nodeNotObject = good;
  nodeNotObject.replace(nodeNotObject.find("\"nodes\":[\n"), 10, "\"nodes\":[\n5,");
  CHECK_THAT(errorOf(nodeNotObject), Catch::Contains("ground node 0: a ground node must be an object"));
}

TEST_CASE("The manifest keeps the city's own districts, and refuses bad ones by key", "[format][tileset][districts]") {
  Tileset t = sample();
  CHECK(tilesetToJson(t).find("\"districts\"") == std::string::npos);  // absent when none
  t.districts = DistrictsInfo{CityFile{"districts.geojson", 1234, 0xDEADBEEFu}, 3,
                              "each building to its nearest OpenStreetMap neighbourhood name", true, 0.5};
  const std::string json = tilesetToJson(t);
  const auto parsed = parseTileset(json, "tileset.json");
  REQUIRE(parsed.ok());
  REQUIRE(parsed->districts.has_value());
  CHECK(parsed->districts->file.file == "districts.geojson");
  CHECK(parsed->districts->file.bytes == 1234);
  CHECK(parsed->districts->file.crc32 == 0xDEADBEEFu);
  CHECK(parsed->districts->count == 3);
  CHECK(parsed->districts->source == t.districts->source);
  CHECK(parsed->districts->inferred);
  CHECK(parsed->districts->coverage == 0.5);
  CHECK(tilesetToJson(*parsed) == json);

  const std::vector<std::pair<std::string, std::string>> bad{
      {"\"inferred\":true", "\"inferred\":1"},
      {"\"coverage\":0.5", "\"coverage\":1.5"},
      {"\"count\":3", "\"count\":0"},
      {"\"file\":\"districts.geojson\"", "\"file\":\"../districts.geojson\""},
  };
  for (const auto& [from, to] : bad) {
    INFO(to);
    std::string text = json;
    const std::size_t at = text.find(from, text.find("\"districts\""));
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
    const auto refused = parseTileset(text, "tileset.json");
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error().find("tileset.json: districts") == 0);
  }
}
