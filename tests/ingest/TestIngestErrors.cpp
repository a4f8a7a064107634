// Inputs readCity must refuse, each with a message that names the file and the problem.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "IngestTestData.h"

using namespace qv;
using namespace qv::prep;
using namespace qv::prep::test;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// An OSM file with one square building per {lon, lat}.
std::string osmWithBuildingsAt(const std::vector<std::pair<double, double>>& corners) {
  std::string xml = "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\">\n";
  int node = 1;
  for (const auto& [lon, lat] : corners) {
    const double d = 0.0002;
    const double xs[4] = {lon, lon + d, lon + d, lon};
    const double ys[4] = {lat, lat, lat + d, lat + d};
    for (int k = 0; k < 4; ++k)
      xml += "<node id=\"" + std::to_string(node + k) + "\" lat=\"" + std::to_string(ys[k]) + "\" lon=\"" +
             std::to_string(xs[k]) + "\"/>\n";
    node += 4;
  }
  node = 1;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    xml += "<way id=\"" + std::to_string(i + 1) + "\">";
    for (int k : {0, 1, 2, 3, 0}) xml += "<nd ref=\"" + std::to_string(node + k) + "\"/>";
    xml += "<tag k=\"building\" v=\"yes\"/></way>\n";
    node += 4;
  }
  return xml + "</osm>\n";
}

}  // namespace

TEST_CASE("Missing and unreadable inputs are refused by name", "[ingest][errors]") {
  SECTION("no such file") {
    const auto r = readCity({"/nonexistent/city.osm.pbf"}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(r.error() == "/nonexistent/city.osm.pbf: no such file");
  }
  SECTION("no inputs") {
    CHECK_FALSE(readCity({}, {}).ok());
  }
  SECTION("a folder") {
    TempDir dir;
    const auto r = readCity({dir.path("")}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "is a directory"));
  }
  SECTION("an unknown format") {
    TempDir dir;
    const auto r = readCity({dir.write("city.shp", "not a shapefile")}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "city.shp: unknown input format"));
  }
  SECTION("an unknown height unit") {
    IngestOptions options;
    options.heightUnit = "furlong";
    const auto r = readCity({fixture("small.osm")}, options);
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "furlong"));
  }
}

TEST_CASE("Corrupt OSM input is refused with the position", "[ingest][errors]") {
  SECTION("garbage XML: file, line and column") {
    const auto r = readCity({fixture("garbage.osm")}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "garbage.osm:4:10: not valid OSM XML"));
  }
  SECTION("a truncated PBF: file and byte offset") {
    TempDir dir;
    const std::string whole = readBytes(sharedData("osm/nyc-manhattan-south-buildings.osm.pbf"));
    REQUIRE(whole.size() > 1000000);
    const std::string cut = dir.write("cut.osm.pbf", whole.substr(0, whole.size() / 2));
    const auto r = readCity({cut}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), cut + ": corrupt or truncated PBF (near byte"));
  }
  SECTION("random bytes in a PBF") {
    TempDir dir;
    std::string noise(4096, '\0');
    for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<char>((i * 7919u + 13u) & 0xffu);
    const auto r = readCity({dir.write("noise.osm.pbf", noise)}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "noise.osm.pbf"));
  }
  SECTION("a way referencing missing nodes: how many, and which") {
    const auto r = readCity({fixture("missing-nodes.osm")}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "missing-nodes.osm: 2 node references"));
    CHECK(contains(r.error(), "n3 in w100, n4 in w100"));
  }
}

TEST_CASE("Inputs without buildings, or with absurd coordinates, are refused", "[ingest][errors]") {
  SECTION("no building at all") {
    const auto r = readCity({fixture("no-buildings.osm")}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "no buildings in"));
    CHECK(contains(r.error(), "no-buildings.osm"));
  }
  SECTION("only buildings that cleaning drops") {
    TempDir dir;
    const std::string xml =
        "<osm version=\"0.6\"><node id=\"1\" lat=\"40.75\" lon=\"-73.99\"/><node id=\"2\" lat=\"40.7502\" "
        "lon=\"-73.9898\"/><node id=\"3\" lat=\"40.75\" lon=\"-73.9898\"/><node id=\"4\" lat=\"40.7502\" "
        "lon=\"-73.99\"/><way id=\"1\"><nd ref=\"1\"/><nd ref=\"2\"/><nd ref=\"3\"/><nd ref=\"4\"/><nd "
        "ref=\"1\"/><tag k=\"building\" v=\"yes\"/></way></osm>";
    const auto r = readCity({dir.write("bowtie.osm", xml)}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "no building left"));
    CHECK(contains(r.error(), "self-intersecting 1"));
  }
  SECTION("a building on the other side of the world") {
    TempDir dir;
    const auto r = readCity({dir.write("far.osm", osmWithBuildingsAt({{-73.99, 40.75}, {100.0, 13.7}}))}, {});
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "absurd coordinates"));
    CHECK(contains(r.error(), "w2 (east)"));
  }
  SECTION("an origin far from the data") {
    IngestOptions options;
    options.originLonLat = std::array<double, 2>{2.35, 48.85};
    const auto r = readCity({fixture("small.osm")}, options);
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "more than 10 degrees"));
  }
}

TEST_CASE("Several inputs merge, an object read twice is one building", "[ingest][merge]") {
  const Ingested both = ingest({fixture("small.osm"), sharedData("osm/fixture-midtown-empire-state.osm")});
  REQUIRE(both.model.ok());
  // small.osm's coordinates are in Midtown too: its outline-less part w130 falls inside an
  // underground building of the fixture, which owns no part by containment, so it stays a building
  // of its own with the other 4; the fixture's 2 underground buildings are left out.
  CHECK(both.model->buildings.size() == 5 + 393);
  CHECK(findBuilding(*both.model, "w130") != nullptr);
  CHECK(both.stats.partsAttached == 2 + 237);
  CHECK(both.model->excluded.at("underground") == 2);
  CHECK(both.model->sources.size() == 2);

  const Ingested twice = ingest({fixture("small.osm"), fixture("small.osm")});
  REQUIRE(twice.model.ok());
  CHECK(twice.model->buildings.size() == 5);
  // The 7 kept objects of the second copy (w100, w101, w102, w130, w140, w160, r901).
  CHECK(twice.model->drops.byReason.at("duplicate-id") == 7);
}

TEST_CASE("XML, bzip2-compressed XML and PBF of one city give the same buildings", "[ingest][osm][formats]") {
  if (std::system("command -v osmium > /dev/null 2>&1") != 0) {
    WARN("osmium-tool not installed: format conversion not tested");
    return;
  }
  TempDir dir;
  const std::string source = fixture("small.osm");
  const std::string bz2 = dir.path("small.osm.bz2");
  const std::string pbf = dir.path("small.osm.pbf");
  REQUIRE(std::system(("osmium cat -o '" + bz2 + "' '" + source + "' 2> /dev/null").c_str()) == 0);
  REQUIRE(std::system(("osmium cat -o '" + pbf + "' '" + source + "' 2> /dev/null").c_str()) == 0);
  const auto xml = readCity({source}, {});
  REQUIRE(xml.ok());
  for (const std::string& path : {bz2, pbf}) {
    INFO(path);
    const auto other = readCity({path}, {});
    REQUIRE(other.ok());
    REQUIRE(other->buildings.size() == xml->buildings.size());
    for (std::size_t i = 0; i < xml->buildings.size(); ++i) {
      CHECK(other->buildings[i].attributes.id == xml->buildings[i].attributes.id);
      CHECK(other->buildings[i].attributes.heightM == xml->buildings[i].attributes.heightM);
      CHECK(other->buildings[i].parts.size() == xml->buildings[i].parts.size());
    }
  }
}
