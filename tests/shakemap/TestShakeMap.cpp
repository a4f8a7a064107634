// prep::shakemap: the real NYC scenario ShakeMap (3.5) read back against its own text, ShakeMap 4
// and 3.5 fixtures cut from it giving the same grid, bilinear sampling, and every refusal naming
// the file and the line.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../fuzz/RegressionInputs.h"
#include "qv/prep/ShakeMap.h"

using namespace qv;
using namespace qv::prep;

namespace {

const std::string kRealGrid = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/shakemap/nyc-m5.8-scenario-grid.xml";
const std::string kDataDir = QUAKEVIEW_SHAKEMAP_DATA_DIR;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// 1-based number of the first line of `text` that contains `part`.
std::size_t lineOf(const std::string& text, const std::string& part) {
  const auto at = text.find(part);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::vector<double> numbers(const std::string& row) {
  std::istringstream in(row);
  std::vector<double> values;
  for (std::string token; in >> token;) values.push_back(std::stod(token));
  return values;
}

/// The real grid's data row for the node printed as "<lon> <lat>" (e.g. "-74.0050 40.6995"), found
/// in the file's text. Columns (ShakeMap 3.5): LON LAT PGA(pctg) PGV(cms) MMI PSA03 PSA10 PSA30 SVEL.
std::vector<double> realRow(const std::string& text, const std::string& lonLat) {
  const auto at = text.find("\n" + lonLat + " ");
  REQUIRE(at != std::string::npos);
  const auto end = text.find('\n', at + 1);
  return numbers(text.substr(at + 1, end - at - 1));
}

/// Column and row (0 at lat_max) of a node of the real grid from its printed coordinates.
std::size_t realIndex(double lon, double lat) {
  const auto column = static_cast<std::size_t>(std::lround((lon + 76.03) / 0.025));
  const auto row = static_cast<std::size_t>(std::lround((42.07 - lat) / ((42.07 - 39.03) / 122.0)));
  return row * 161 + column;
}

void requireNodeEquals(const ShakeMapGrid& grid, std::size_t i, const std::vector<double>& row) {
  REQUIRE(row.size() == 9);
  CHECK(grid.pga[i] == static_cast<float>(row[2] / 100.0));
  CHECK(grid.pgv[i] == static_cast<float>(row[3]));
  CHECK(grid.mmi[i] == static_cast<float>(row[4]));
  CHECK(grid.psa03[i] == static_cast<float>(row[5] / 100.0));
  CHECK(grid.psa10[i] == static_cast<float>(row[6] / 100.0));
  CHECK(grid.psa30[i] == static_cast<float>(row[7] / 100.0));
  CHECK(grid.vs30[i] == static_cast<float>(row[8]));
}

ShakeMapGrid parsed(const std::string& text, const std::string& name) {
  auto grid = parseShakeMapGrid(text, name);
  INFO(name << ": " << (grid.ok() ? std::string() : grid.error()));
  REQUIRE(grid.ok());
  return std::move(grid).value();
}

}  // namespace

TEST_CASE("The real NYC scenario ShakeMap: event metadata and extent", "[shakemap]") {
  const auto grid = readShakeMapGrid(kRealGrid);
  INFO((grid.ok() ? std::string() : grid.error()));
  REQUIRE(grid.ok());
  const ShakeMapEvent& e = grid->event;
  CHECK(e.eventId == "NYC_M5.8_se");
  CHECK(e.type == ShakeMapEventType::Scenario);
  CHECK(shakeMapEventTypeName(e.type) == "SCENARIO");
  CHECK(e.shakemapVersion == "3");
  CHECK(e.codeVersion == "3.5.1586");
  CHECK(e.processTimestamp == "2017-10-20T16:51:52Z");
  CHECK(e.originator == "us");
  CHECK(e.mapStatus == "RELEASED");
  CHECK(e.magnitude == 5.8);
  CHECK(e.depthKm == 5.0);
  CHECK(e.latitudeDeg == 40.55);
  CHECK(e.longitudeDeg == -74.03);
  CHECK(e.eventTimestamp == "2017-03-31T00:00:00UTC");
  CHECK(e.network == "us");
  CHECK(e.description == "Manhattan, New M5.8 Scenario");

  CHECK(grid->lonCount == 161);
  CHECK(grid->latCount == 123);
  CHECK(grid->lonMin == -76.03);
  CHECK(grid->lonMax == -72.03);
  CHECK(grid->latMin == 39.03);
  CHECK(grid->latMax == 42.07);
  CHECK(grid->lonSpacing == Approx(0.025).margin(1e-12));
  CHECK(grid->latSpacing == Approx(0.024918).margin(1e-6));
  CHECK(grid->describeExtent() == "lon -76.03..-72.03, lat 39.03..42.07 (161 x 123 nodes)");
  CHECK(grid->hasSpectra());
  for (const auto* field : {&grid->pga, &grid->pgv, &grid->mmi, &grid->psa03, &grid->psa10, &grid->psa30, &grid->vs30})
    CHECK(field->size() == 161u * 123u);
}

TEST_CASE("The real ShakeMap's node values read back exactly, in g, cm/s and m/s", "[shakemap]") {
  const std::string text = readText(kRealGrid);
  const auto grid = readShakeMapGrid(kRealGrid);
  REQUIRE(grid.ok());
  // The first and last rows of the file, and Lower Manhattan nodes (PGA 33-39 % g there).
  for (const std::string node : {"-76.0300 42.0700", "-72.0300 39.0300", "-74.0300 40.7244", "-74.0050 40.6995",
                                 "-73.9550 40.6746", "-76.0300 39.0300", "-72.0300 42.0700"}) {
    INFO(node);
    const auto row = realRow(text, node);
    const std::size_t i = realIndex(row[0], row[1]);
    requireNodeEquals(*grid, i, row);
  }
  // By hand from the file (grep "^-74.0050 40.6995"): PGA 36.1 % g, PGV 7.46 cm/s, MMI 6.5, SVEL 600.931.
  const std::size_t i = realIndex(-74.005, 40.6995);
  CHECK(grid->pga[i] == 0.361f);
  CHECK(grid->pgv[i] == 7.46f);
  CHECK(grid->mmi[i] == 6.5f);
  CHECK(grid->vs30[i] == 600.931f);
}

TEST_CASE("Sampling the real ShakeMap: bilinear between the 4 nodes around, exact at nodes, none outside",
          "[shakemap]") {
  const std::string text = readText(kRealGrid);
  const auto grid = readShakeMapGrid(kRealGrid);
  REQUIRE(grid.ok());
  const double dLon = 0.025, dLat = (42.07 - 39.03) / 122.0;

  SECTION("a point in Lower Manhattan, between nodes") {
    // The cell with corners lon -74.03 / -74.005 and lat 40.7244 / 40.6995 (column 80, row 54).
    const auto v00 = realRow(text, "-74.0300 40.7244"), v01 = realRow(text, "-74.0050 40.7244");
    const auto v10 = realRow(text, "-74.0300 40.6995"), v11 = realRow(text, "-74.0050 40.6995");
    const double tx = 0.3, ty = 0.6;
    const double lon = -76.03 + (80 + tx) * dLon;
    const double lat = 42.07 - (54 + ty) * dLat;
    const auto s = sampleShakeMap(*grid, lon, lat);
    REQUIRE(s);
    auto bilinear = [&](std::size_t column, double divisor) {
      // Node values as stored (floats of the file's values), weighted by hand.
      auto v = [&](const std::vector<double>& row) {
        return static_cast<double>(static_cast<float>(row[column] / divisor));
      };
      return 0.7 * 0.4 * v(v00) + 0.3 * 0.4 * v(v01) + 0.7 * 0.6 * v(v10) + 0.3 * 0.6 * v(v11);
    };
    CHECK(s->pgaG == Approx(bilinear(2, 100.0)).epsilon(1e-9));
    CHECK(s->pgvCmS == Approx(bilinear(3, 1.0)).epsilon(1e-9));
    CHECK(s->mmi == Approx(bilinear(4, 1.0)).epsilon(1e-9));
    CHECK(s->psa03G == Approx(bilinear(5, 100.0)).epsilon(1e-9));
    CHECK(s->psa10G == Approx(bilinear(6, 100.0)).epsilon(1e-9));
    CHECK(s->psa30G == Approx(bilinear(7, 100.0)).epsilon(1e-9));
    CHECK(s->vs30Mps == Approx(bilinear(8, 1.0)).epsilon(1e-9));
    // Lower Manhattan shakes at about a third of g (the data README: 29-38 % g).
    CHECK(s->pgaG > 0.29);
    CHECK(s->pgaG < 0.38);
  }

  SECTION("at a node and on the boundary the node's own values") {
    const auto row = realRow(text, "-74.0050 40.6995");
    const auto s = sampleShakeMap(*grid, -76.03 + 81 * dLon, 42.07 - 55 * dLat);
    REQUIRE(s);
    CHECK(s->pgaG == Approx(row[2] / 100.0).epsilon(1e-6));
    CHECK(s->vs30Mps == Approx(row[8]).epsilon(1e-6));
    for (const std::string corner : {"-76.0300 42.0700", "-72.0300 39.0300", "-76.0300 39.0300", "-72.0300 42.0700"}) {
      INFO(corner);
      const auto c = realRow(text, corner);
      const auto atCorner = sampleShakeMap(*grid, c[0], c[1]);
      REQUIRE(atCorner);
      CHECK(atCorner->pgaG == Approx(c[2] / 100.0).epsilon(1e-6));
      CHECK(atCorner->mmi == Approx(c[4]).epsilon(1e-6));
    }
    // On an edge, halfway between two nodes of the last row.
    const auto a = realRow(text, "-74.0300 39.0300"), b = realRow(text, "-74.0050 39.0300");
    const auto edge = sampleShakeMap(*grid, -74.0175, 39.03);
    REQUIRE(edge);
    CHECK(edge->pgaG == Approx((a[2] + b[2]) / 200.0).epsilon(1e-6));
  }

  SECTION("outside the extent, or not a coordinate: nothing") {
    CHECK_FALSE(sampleShakeMap(*grid, -76.031, 40.7));
    CHECK_FALSE(sampleShakeMap(*grid, -72.029, 40.7));
    CHECK_FALSE(sampleShakeMap(*grid, -74.0, 39.029));
    CHECK_FALSE(sampleShakeMap(*grid, -74.0, 42.071));
    CHECK_FALSE(sampleShakeMap(*grid, std::nan(""), 40.7));
    CHECK_FALSE(sampleShakeMap(*grid, -74.0, std::nan("")));
  }
}

TEST_CASE("ShakeMap 4 and 3.5 layouts, extra fields and empty units all give the same grid", "[shakemap]") {
  const auto real = readShakeMapGrid(kRealGrid);
  REQUIRE(real.ok());
  const auto sm4 = readShakeMapGrid(kDataDir + "/sm4-4x3.xml");
  INFO((sm4.ok() ? std::string() : sm4.error()));
  REQUIRE(sm4.ok());
  CHECK(sm4->event.codeVersion == "4.0.1");
  CHECK(sm4->event.type == ShakeMapEventType::Scenario);
  CHECK(sm4->describeExtent() == "lon -74.03..-73.955, lat 40.6746..40.7244 (4 x 3 nodes)");
  REQUIRE(sm4->hasSpectra());
  // Each fixture node is the real grid's node at column 80 + c, row 54 + r, values copied as printed.
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 4; ++c) {
      const std::size_t i = r * 4 + c, j = (54 + r) * 161 + 80 + c;
      INFO("row " << r << " column " << c);
      CHECK(sm4->pga[i] == real->pga[j]);
      CHECK(sm4->pgv[i] == real->pgv[j]);
      CHECK(sm4->mmi[i] == real->mmi[j]);
      CHECK(sm4->psa03[i] == real->psa03[j]);
      CHECK(sm4->psa10[i] == real->psa10[j]);
      CHECK(sm4->psa30[i] == real->psa30[j]);
      CHECK(sm4->vs30[i] == real->vs30[j]);
    }

  const auto file = GENERATE(as<std::string>{}, "sm4-4x3-extra-fields.xml", "sm4-4x3-empty-units.xml", "sm35-4x3.xml");
  INFO(file);
  const auto other = readShakeMapGrid(kDataDir + "/" + file);
  INFO((other.ok() ? std::string() : other.error()));
  REQUIRE(other.ok());
  CHECK(other->lonCount == 4);
  CHECK(other->latCount == 3);
  CHECK(other->pga == sm4->pga);
  CHECK(other->pgv == sm4->pgv);
  CHECK(other->mmi == sm4->mmi);
  CHECK(other->psa03 == sm4->psa03);
  CHECK(other->psa10 == sm4->psa10);
  CHECK(other->psa30 == sm4->psa30);
  CHECK(other->vs30 == sm4->vs30);
  for (const auto& [lon, lat] : std::vector<std::pair<double, double>>{
           {-74.01, 40.71}, {-73.96, 40.68}, {-74.03, 40.6746}, {-73.955, 40.7244}, {-73.99, 40.70}}) {
    INFO(lon << ", " << lat);
    const auto a = sampleShakeMap(*sm4, lon, lat), b = sampleShakeMap(*other, lon, lat);
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->pgaG == b->pgaG);
    CHECK(a->pgvCmS == b->pgvCmS);
    CHECK(a->mmi == b->mmi);
    CHECK(a->psa03G == b->psa03G);
    CHECK(a->psa10G == b->psa10G);
    CHECK(a->psa30G == b->psa30G);
    CHECK(a->vs30Mps == b->vs30Mps);
  }
}

TEST_CASE("Accepted variations of the text: CRLF lines, namespace prefixes, exponents, blank lines", "[shakemap]") {
  const std::string good = readText(kDataDir + "/sm4-4x3.xml");
  const ShakeMapGrid reference = parsed(good, "sm4-4x3.xml");
  std::string crlf;
  for (const char c : good) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  std::string prefixed = good;
  for (const std::string element : {"shakemap_grid", "event", "grid_specification", "grid_field", "grid_data"}) {
    for (std::size_t at = 0; (at = prefixed.find("<" + element, at)) != std::string::npos; at += 4)
      prefixed.replace(at, 1, "<sm:");
    for (std::size_t at = 0; (at = prefixed.find("</" + element, at)) != std::string::npos; at += 5)
      prefixed.replace(at, 2, "</sm:");
  }
  prefixed = replaced(prefixed, "<sm:shakemap_grid ",
                      "<sm:shakemap_grid xmlns:sm=\"http://earthquake.usgs.gov/eqcenter/shakemap\" ");
  const std::string numbers =
      replaced(replaced(replaced(good, " 6.5 36.1 ", " 6.5e0 3.61E+1 "), " 425.365\n", " +425.365\n\n  \n"),
               "-74.0300 40.6746 ", "\t-74.03 40.67460000000000000000001 ");
  for (const auto& [what, text] : std::vector<std::pair<std::string, std::string>>{
           {"CRLF", crlf}, {"prefixed", prefixed}, {"number spellings", numbers}}) {
    INFO(what);
    const ShakeMapGrid grid = parsed(text, what + ".xml");
    CHECK(grid.pga == reference.pga);
    CHECK(grid.mmi == reference.mmi);
    CHECK(grid.vs30 == reference.vs30);
    CHECK(grid.psa30 == reference.psa30);
  }
}

TEST_CASE("A ShakeMap with PGA only: no spectra, absent fields sample as NaN, PGA in g", "[shakemap]") {
  const std::string xml = R"(<?xml version="1.0"?>
<shakemap_grid event_id="us7000abcd" shakemap_event_type="ACTUAL" code_version="4.1.3">
<event magnitude="6.1" depth="10" lat="34.2" lon="-118.5" event_description="Somewhere" />
<grid_specification lon_min="-118.6" lat_min="34.1" lon_max="-118.5" lat_max="34.2" nlon="2" nlat="2" />
<grid_field index="1" name="LON" units="dd" />
<grid_field index="2" name="LAT" units="dd" />
<grid_field index="3" name="PGA" units="g" />
<grid_data>
-118.6 34.2 0.1
-118.5 34.2 0.2
-118.6 34.1 0.3
-118.5 34.1 0.5
</grid_data>
</shakemap_grid>
)";
  const ShakeMapGrid grid = parsed(xml, "pga-only.xml");
  CHECK(grid.event.type == ShakeMapEventType::Actual);
  CHECK(shakeMapEventTypeName(grid.event.type) == "ACTUAL");
  CHECK(grid.event.eventId == "us7000abcd");
  CHECK(grid.event.magnitude == 6.1);
  CHECK(grid.event.depthKm == 10.0);
  CHECK_FALSE(grid.hasSpectra());
  CHECK(grid.pgv.empty());
  CHECK(grid.vs30.empty());
  const auto centre = sampleShakeMap(grid, -118.55, 34.15);
  REQUIRE(centre);
  CHECK(centre->pgaG == Approx((0.1 + 0.2 + 0.3 + 0.5) / 4).epsilon(1e-6));
  CHECK(std::isnan(centre->pgvCmS));
  CHECK(std::isnan(centre->psa10G));
  CHECK(std::isnan(centre->vs30Mps));
  CHECK(shakeMapEventTypeName(ShakeMapEventType::Unknown) == "UNKNOWN");
}

TEST_CASE("Bad ShakeMaps are refused with the file and the line", "[shakemap]") {
  const std::string good = readText(kDataDir + "/sm4-4x3.xml");
  REQUIRE(parseShakeMapGrid(good, "good.xml").ok());
  const std::size_t gridDataLine = lineOf(good, "<grid_data>");
  const std::size_t firstRow = gridDataLine + 1;
  const std::size_t specLine = lineOf(good, "<grid_specification");

  const auto lines = splitLines(good);
  const std::string swappedRows = replaced(
      replaced(replaced(good, lines[firstRow - 1], "@@"), lines[firstRow], lines[firstRow - 1]), "@@", lines[firstRow]);

  struct Case {
    const char* what;
    std::string xml;
    std::size_t line;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases = {
      {"a row with a value missing", replaced(good, " 425.365\n", "\n"), firstRow, {"8 values, expected 9"}},
      {"a row with a value too many",
       replaced(good, " 425.365\n", " 425.365 1\n"),
       firstRow,
       {"10 values, expected 9"}},
      {"a row off the lattice",
       replaced(good, "-74.0050 40.6995", "-74.0060 40.6995"),
       lineOf(good, "-74.0050 40.6995"),
       {"off the grid", "-74.005"}},
      {"rows out of order", swappedRows, firstRow, {"off the grid", "lon -74.03, lat 40.7244"}},
      {"a nan value", replaced(good, "6.5 36.1", "6.5 nan"), lineOf(good, "6.5 36.1"), {"PGA", "not a finite number"}},
      {"an inf value", replaced(good, "600.931", "inf"), lineOf(good, "600.931"), {"SVEL", "not a finite number"}},
      {"a value beyond float range",
       replaced(good, "600.931", "1e300"),
       lineOf(good, "600.931"),
       {"SVEL", "out of range"}},
      {"a garbage value",
       replaced(good, "6.5 36.1", "6.5 3x6.1"),
       lineOf(good, "6.5 36.1"),
       {"\"3x6.1\"", "column 4 (PGA)", "not a number"}},
      {"a missing PGA field",
       replaced(good, "name=\"PGA\"", "name=\"PGAX\""),
       gridDataLine,
       {"PGA", "LON, LAT and PGA"}},
      {"a missing LAT field", replaced(good, "name=\"LAT\"", "name=\"LATITUDE\""), gridDataLine, {"LAT"}},
      {"an unknown unit",
       replaced(good, "units=\"cm/s\"", "units=\"furlong/s\""),
       lineOf(good, "units=\"cm/s\""),
       {"PGV", "furlong/s"}},
      {"PGA in m/s/s",
       replaced(good, "name=\"PGA\" units=\"%g\"", "name=\"PGA\" units=\"m/s/s\""),
       lineOf(good, "name=\"PGA\""),
       {"PGA", "m/s/s"}},
      {"a row too many",
       replaced(good, "</grid_data>", "-73.9550 40.6746 6.9 45.3 10.24 39.51 12.07 2.31 403.541\n</grid_data>"),
       lineOf(good, "</grid_data>"),
       {"more than nlon x nlat", "12"}},
      {"no grid_specification",
       replaced(good, splitLines(good)[specLine - 1] + "\n", ""),
       gridDataLine - 1,
       {"grid_specification"}},
      {"nlon below 2", replaced(good, "nlon=\"4\"", "nlon=\"1\""), specLine, {"nlon", "at least 2"}},
      {"nlat not a number", replaced(good, "nlat=\"3\"", "nlat=\"three\""), specLine, {"nlat", "three"}},
      {"spacing that does not fit the extent",
       replaced(good, "nominal_lon_spacing=\"0.0250\"", "nominal_lon_spacing=\"0.0300\""),
       specLine,
       {"nominal_lon_spacing", "does not fit"}},
      {"an extent upside down", replaced(good, "lat_min=\"40.6746\"", "lat_min=\"40.8\""), specLine, {"lat_min"}},
      {"an oversized declared grid",
       replaced(replaced(good, "nlon=\"4\"", "nlon=\"200000\""), "nlat=\"3\"", "nlat=\"300000\""),
       specLine,
       {"200000 x 300000", "larger than the limit"}},
      {"a duplicate field index",
       replaced(good, "index=\"9\"", "index=\"8\""),
       lineOf(good, "index=\"9\""),
       {"index 8"}},
      {"a missing field index", replaced(good, "index=\"9\"", "index=\"10\""), gridDataLine, {"index 9"}},
      {"an element inside grid_data",
       replaced(good, "<grid_data>\n", "<grid_data>\n<row/>\n"),
       firstRow,
       {"\"<row", "only numbers"}},
      {"another root element", "<?xml version=\"1.0\"?>\n<gpx version=\"1.1\"/>\n", 2, {"<gpx>", "not a ShakeMap"}},
      {"a grid cut off inside grid_data",
       good.substr(0, good.find("-73.9800 40.6746")),
       lineOf(good, "-73.9800 40.6746"),
       {"ends inside <grid_data>", "10 of 12", "truncated"}},
      {"not XML", "lon,lat,pga\n-74.03,40.72,0.36\n", 1, {"not XML"}},
      {"a comment inside grid_data",
       replaced(good, "</grid_data>", "<!-- end --></grid_data>"),
       lineOf(good, "</grid_data>"),
       {"only numbers", "<!--"}},
      {"an empty grid_data element",
       replaced(good, "<grid_data>", "<grid_data/><grid_data_rest>"),
       gridDataLine,
       {"0 rows", "4 x 3 = 12"}},
      {"junk after the grid",
       replaced(good, "</shakemap_grid>", "</shakemap_grid><more/>"),
       lineOf(good, "</shakemap_grid>"),
       {"XML error"}},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    const auto result = parseShakeMapGrid(c.xml, "bad.xml");
    REQUIRE_FALSE(result.ok());
    INFO(result.error());
    CHECK(contains(result.error(), "bad.xml:" + std::to_string(c.line) + ": "));
    for (const std::string& part : c.says) CHECK(contains(result.error(), part));
  }
}

TEST_CASE("Bad ShakeMap files: truncated grid, not XML, empty", "[shakemap]") {
  SECTION("fewer rows than nlon x nlat: how many found and expected, at </grid_data>") {
    const std::string path = kDataDir + "/sm4-4x3-truncated.xml";
    const auto result = readShakeMapGrid(path);
    REQUIRE_FALSE(result.ok());
    INFO(result.error());
    CHECK(contains(result.error(), path + ":" + std::to_string(lineOf(readText(path), "</grid_data>")) + ": "));
    CHECK(contains(result.error(), "11 rows"));
    CHECK(contains(result.error(), "4 x 3 = 12"));
  }
  SECTION("not XML at all") {
    const std::string path = kDataDir + "/not-xml.csv";
    const auto result = readShakeMapGrid(path);
    REQUIRE_FALSE(result.ok());
    INFO(result.error());
    CHECK(contains(result.error(), path + ":1: not XML"));
  }
  SECTION("an empty file") {
    const std::string path = kDataDir + "/empty.xml";
    const auto result = readShakeMapGrid(path);
    REQUIRE_FALSE(result.ok());
    CHECK(result.error() == path + ": empty file, not a ShakeMap grid.xml");
  }
  SECTION("a file that is not there") {
    const auto result = readShakeMapGrid(kDataDir + "/no-such-grid.xml");
    REQUIRE_FALSE(result.ok());
    CHECK(contains(result.error(), "no-such-grid.xml"));
  }
  SECTION("a file larger than limits.maxBytes") {
    ShakeMapLimits limits;
    limits.maxBytes = 1000;
    const auto result = readShakeMapGrid(kDataDir + "/sm4-4x3.xml", limits);
    REQUIRE_FALSE(result.ok());
    CHECK(contains(result.error(), "sm4-4x3.xml"));
  }
}

TEST_CASE("Limits: values counted from the declared grid and fields, nesting depth", "[shakemap]") {
  const std::string good = readText(kDataDir + "/sm4-4x3.xml");
  ShakeMapLimits limits;
  limits.maxValues = 4 * 3 * 9;  // exactly this grid
  CHECK(parseShakeMapGrid(good, "sm4.xml", limits).ok());
  limits.maxValues = 4 * 3 * 9 - 1;
  const auto refused = parseShakeMapGrid(good, "sm4.xml", limits);
  REQUIRE_FALSE(refused.ok());
  INFO(refused.error());
  CHECK(contains(refused.error(), "sm4.xml:" + std::to_string(lineOf(good, "<grid_data>")) + ": "));
  CHECK(contains(refused.error(), "4 x 3 x 9 values is larger than the limit of 107"));

  std::string deep = "<?xml version=\"1.0\"?>\n<shakemap_grid>\n";
  for (int i = 0; i < 100; ++i) deep += "<a>";
  const auto tooDeep = parseShakeMapGrid(deep, "deep.xml");
  REQUIRE_FALSE(tooDeep.ok());
  CHECK(contains(tooDeep.error(), "deep.xml:3: elements nested deeper than 16 levels"));
}

TEST_CASE("Entity attacks are refused at the DOCTYPE, fast, and nothing external is read", "[shakemap]") {
  const auto file = GENERATE(as<std::string>{}, "billion-laughs.xml", "external-entity.xml");
  const std::string path = kDataDir + "/" + file;
  const auto started = std::chrono::steady_clock::now();
  const auto result = readShakeMapGrid(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  REQUIRE_FALSE(result.ok());
  INFO(result.error());
  CHECK(contains(result.error(), path + ":2: a DOCTYPE is not allowed"));
  CHECK_FALSE(contains(result.error(), "root:"));  // /etc/passwd's first line never shows up
  CHECK(seconds < 0.5);
}

TEST_CASE("A large generated grid parses whole, every node on its lattice", "[shakemap]") {
  // 400 x 300 nodes in ShakeMap 4 order; PGA encodes the node index so the order is checked too.
  const std::size_t nlon = 400, nlat = 300;
  std::string xml =
      "<?xml version=\"1.0\"?>\n<shakemap_grid event_id=\"big\" shakemap_event_type=\"SCENARIO\">\n"
      "<grid_specification lon_min=\"-120.0000\" lat_min=\"35.0000\" lon_max=\"-110.0250\" lat_max=\"42.4750\" "
      "nominal_lon_spacing=\"0.025\" nominal_lat_spacing=\"0.025\" nlon=\"400\" nlat=\"300\" />\n";
  const char* names[] = {"LON", "LAT", "MMI", "PGA", "PGV", "PSA03", "PSA10", "PSA30", "SVEL"};
  for (int i = 0; i < 9; ++i)
    xml += "<grid_field index=\"" + std::to_string(i + 1) + "\" name=\"" + names[i] + "\" units=\"\" />\n";
  xml += "<grid_data>\n";
  char line[256];
  for (std::size_t r = 0; r < nlat; ++r)
    for (std::size_t c = 0; c < nlon; ++c) {
      const std::size_t k = r * nlon + c;
      std::snprintf(line, sizeof line, "%.4f %.4f 5.5 %zu 3 4 5 6 760\n", -120.0 + 0.025 * static_cast<double>(c),
                    42.475 - 0.025 * static_cast<double>(r), k % 1000);
      xml += line;
    }
  xml += "</grid_data>\n</shakemap_grid>\n";
  const ShakeMapGrid grid = parsed(xml, "big.xml");
  REQUIRE(grid.pga.size() == nlon * nlat);
  for (std::size_t k : {std::size_t{0}, std::size_t{399}, std::size_t{400}, std::size_t{12345}, nlon * nlat - 1})
    CHECK(grid.pga[k] == static_cast<float>(static_cast<double>(k % 1000) / 100.0));
  CHECK(grid.vs30.back() == 760.0f);
}

TEST_CASE("Fuzzer-found ShakeMaps are read or refused cleanly", "[shakemap][fuzz]") {
  // tests/fuzz/regressions/shakemap: float-overflow.xml holds a finite value (1e300 range) that
  // would have become an infinite float.
  const auto inputs = qv::fuzz::savedInputs(QUAKEVIEW_SOURCE_DIR, "shakemap");
  REQUIRE(!inputs.empty());
  for (const auto& input : inputs) {
    INFO(input.path);
    const auto grid = readShakeMapGrid(input.path);
    if (!grid.ok()) {
      CHECK(contains(grid.error(), input.path + ":"));
      continue;
    }
    for (const auto* field :
         {&grid->pga, &grid->pgv, &grid->mmi, &grid->psa03, &grid->psa10, &grid->psa30, &grid->vs30})
      for (const float v : *field) CHECK(std::isfinite(v));
  }
}
