// Inputs the OSM and GeoJSON fuzzers found (tests/fuzz/regressions/osm, .../geojson) read through
// readCity as the fuzz targets read them: the result is either a clean error naming the file or a
// city of sane buildings, never a crash.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "../fuzz/RegressionInputs.h"
#include "IngestTestData.h"

using namespace qv;
using namespace qv::prep;
using namespace qv::prep::test;

namespace {

void replay(const std::string& path) {
  IngestOptions options;
  options.threads = 1;
  const Result<CityModel> city = readCity({path}, options);
  if (!city.ok()) {
    INFO(city.error());
    CHECK(city.error().find(path) != std::string::npos);
    return;
  }
  for (const Building& b : city->buildings) {
    CHECK(std::isfinite(b.attributes.heightM));
    CHECK(b.attributes.storeys >= 1);
    for (const BuildingPart& p : b.parts) {
      for (const auto& point : p.points) CHECK((std::isfinite(point.x) && std::isfinite(point.y)));
    }
  }
}

}  // namespace

TEST_CASE("Fuzzer-found OSM inputs are read or rejected cleanly", "[ingest][osm][fuzz]") {
  const TempDir dir;
  std::string missing;
  const auto inputs = fuzz::requiredInputs(QUAKEVIEW_SOURCE_DIR, "osm", missing);
  INFO(missing);
  REQUIRE(missing.empty());
  for (const fuzz::SavedInput& input : inputs) {
    SECTION(input.path) {
      // As fuzz_osm: text starting with '<' is OSM XML, anything else PBF.
      const std::string bytes(input.bytes.begin(), input.bytes.end());
      const std::size_t first = bytes.find_first_not_of(" \t\r\n");
      const bool xml = first != std::string::npos && bytes[first] == '<';
      replay(dir.write(xml ? "input.osm" : "input.osm.pbf", bytes));
    }
  }
}

TEST_CASE("An OSM coordinate with a huge exponent is refused, not read as a wrong place", "[ingest][osm][fuzz]") {
  // libosmium 2.18 scales "40.750e705" by multiplying an int64 705 times (signed overflow, which
  // OsmReader.cpp compiles with -fwrapv to make defined): the latitude wraps to 0. The building
  // then spans 40 degrees, which the city's extent check refuses, naming the building.
  const TempDir dir;
  std::string text;
  std::string missing;
  const auto inputs = fuzz::requiredInputs(QUAKEVIEW_SOURCE_DIR, "osm", missing);
  INFO(missing);
  REQUIRE(missing.empty());
  for (const fuzz::SavedInput& input : inputs) {
    if (input.path.ends_with("coordinate-with-huge-exponent.osm")) text.assign(input.bytes.begin(), input.bytes.end());
  }
  REQUIRE(text.find("lat=\"40.750e705\"") != std::string::npos);
  const std::string path = dir.write("exponent.osm", text);
  IngestOptions options;
  options.threads = 1;
  const auto city = readCity({path}, options);
  REQUIRE_FALSE(city.ok());
  CHECK(city.error().find(path) != std::string::npos);
  CHECK(city.error().find("absurd coordinates") != std::string::npos);
  CHECK(city.error().find("w10") != std::string::npos);
}

TEST_CASE("Fuzzer-found GeoJSON inputs are read or rejected cleanly", "[ingest][geojson][fuzz]") {
  const TempDir dir;
  std::string missing;
  const auto inputs = fuzz::requiredInputs(QUAKEVIEW_SOURCE_DIR, "geojson", missing);
  INFO(missing);
  REQUIRE(missing.empty());
  for (const fuzz::SavedInput& input : inputs) {
    SECTION(input.path) {
      replay(dir.write("input.geojson", std::string(input.bytes.begin(), input.bytes.end())));
    }
  }
}

TEST_CASE("GeoJSON that simdjson refuses before iterating is reported with its position", "[ingest][geojson][fuzz]") {
  // A UTF-8-encoded surrogate (ED A0 80) in a name: well formed to a lenient UTF-8 check, refused
  // by simdjson's. The message must give the byte's line and column.
  const TempDir dir;
  const std::string path = dir.write("surrogate.geojson",
                                     "{\"type\": \"FeatureCollection\", \"features\": [\n"
                                     "  {\"name\": \"Tower \xED\xA0\x80\"}\n]}\n");
  IngestOptions options;
  options.threads = 1;
  const auto city = readCity({path}, options);
  REQUIRE_FALSE(city.ok());
  CHECK(city.error() == path + ":2:19: malformed JSON: invalid UTF-8");
}
