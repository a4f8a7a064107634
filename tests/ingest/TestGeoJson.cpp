// GeoJSON ingest: ids, feet, winding, multipolygons and holes, missing properties, and the errors
// a person gets for a broken file.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "IngestTestData.h"
#include "qv/prep/Cleaning.h"

using namespace qv;
using namespace qv::prep;
using namespace qv::prep::test;

namespace {

/// NYC's building footprints: height in feet under "heightroof", the year under "cnstrct_yr".
IngestOptions nycOptions() {
  IngestOptions options;
  options.idProperty = "bin";
  options.heightProperty = "heightroof";
  options.heightUnit = "ft";
  options.yearProperty = "cnstrct_yr";
  return options;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("GeoJSON footprints: ids, feet, winding, holes and missing properties", "[ingest][geojson]") {
  const Ingested in = ingest({fixture("footprints.geojson")}, nycOptions());
  REQUIRE(in.model.ok());
  const CityModel& model = *in.model;
  CHECK(in.stats.geojsonFeatures == 5);
  std::vector<std::string> ids;
  for (const Building& b : model.buildings) ids.push_back(b.attributes.id);
  // The id property, then the feature's id, then its index.
  CHECK(ids == std::vector<std::string>{"g:1001", "g:42", "g:2", "g:1005"});
  CHECK(model.drops.byReason.at("not-a-polygon") == 1);  // feature 3 is a Point

  SECTION("a polygon given clockwise, height in feet") {
    const Building& b = *findBuilding(model, "g:1001");
    CHECK(b.attributes.name == "Foot Tower");
    CHECK(b.attributes.heightM == Approx(30.48f));
    CHECK(b.attributes.heightSource == ValueSource::Tagged);
    CHECK(b.attributes.storeys == 9);  // round(30.48 / 3.5)
    CHECK(b.attributes.storeysSource == ValueSource::Inferred);
    CHECK(b.attributes.startYear == 1931);
    CHECK(b.attributes.codeEra == CodeEra::PreCode);
    REQUIRE(b.parts.size() == 1);
    CHECK(b.parts[0].ringEnds == std::vector<std::uint32_t>{4});
    CHECK(signedRingArea(b.parts[0].points.data(), 4) > 0.0);  // made counter-clockwise
  }
  SECTION("a multipolygon with a hole; a height given as a string") {
    const Building& b = *findBuilding(model, "g:42");
    CHECK(b.attributes.heightM == Approx(15.3924f));
    REQUIRE(b.parts.size() == 2);
    REQUIRE(b.parts[0].ringCount() == 2);
    const BuildingPart& p = b.parts[0];
    CHECK(signedRingArea(p.points.data(), p.ringEnds[0]) > 0.0);
    CHECK(signedRingArea(p.points.data() + p.ringEnds[0], p.ringEnds[1] - p.ringEnds[0]) < 0.0);
    CHECK(b.parts[1].ringCount() == 1);
    CHECK(b.attributes.footprintAreaM2 == Approx(polygonArea(b.parts[0].points, b.parts[0].ringEnds) +
                                                 polygonArea(b.parts[1].points, b.parts[1].ringEnds)));
  }
  SECTION("no properties at all: defaults") {
    const Building& b = *findBuilding(model, "g:2");
    CHECK(b.attributes.use == "unknown");
    CHECK(b.attributes.heightM == Approx(7.0f));
    CHECK(b.attributes.storeys == 2);
    CHECK(b.attributes.heightSource == ValueSource::Inferred);
  }
  SECTION("a zero height is warned under its property name and inferred") {
    const Building& b = *findBuilding(model, "g:1005");
    CHECK(b.attributes.heightSource == ValueSource::Inferred);
    CHECK(std::any_of(model.warnings.begin(), model.warnings.end(),
                      [](const std::string& w) { return contains(w, "g:1005: heightroof=0"); }));
  }
}

TEST_CASE("Merged GeoJSON files keep distinct ids", "[ingest][geojson]") {
  const Ingested in = ingest({fixture("footprints.geojson"), fixture("footprints.geojson")}, nycOptions());
  REQUIRE(in.model.ok());
  // The second copy's explicit ids repeat the first's (kept once); its index id is file-qualified.
  CHECK(in.model->buildings.size() == 5);
  CHECK(findBuilding(*in.model, "g:1.2") != nullptr);
  CHECK(in.model->drops.byReason.at("duplicate-id") == 3);
}

TEST_CASE("Broken GeoJSON is refused with the file and position", "[ingest][geojson]") {
  SECTION("malformed JSON") {
    const auto r = readCity({fixture("malformed.geojson")}, nycOptions());
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "malformed.geojson:3:46: malformed JSON"));
    CHECK(contains(r.error(), "expected ',' or '}'"));
  }
  SECTION("not a FeatureCollection") {
    const auto r = readCity({fixture("not-a-collection.geojson")}, nycOptions());
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "not-a-collection.geojson:1:10:"));
    CHECK(contains(r.error(), "\"Feature\""));
    CHECK(contains(r.error(), "FeatureCollection"));
  }
  SECTION("projected coordinates") {
    const auto r = readCity({fixture("projected.geojson")}, nycOptions());
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "projected.geojson:3:"));
    CHECK(contains(r.error(), "[987654.3, 212345.6] is not WGS84"));
  }
  SECTION("a top-level array") {
    TempDir dir;
    const auto r = readCity({dir.write("array.geojson", "\n  [1, 2]\n")}, nycOptions());
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "array.geojson:2:3: expected a GeoJSON FeatureCollection (an object), found an array"));
  }
  SECTION("a truncated file") {
    TempDir dir;
    const auto r = readCity({dir.write("cut.geojson", "{\"type\": \"FeatureCollection\", \"features\": [{\"type\": ")},
                            nycOptions());
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error(), "cut.geojson:1:53: malformed JSON: unexpected end of file"));
  }
}
