// The situation report (qv/scene/Report.h): what a mayor's office reads from it.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "../fuzz/RegressionInputs.h"
#include "qv/core/Text.h"
#include "qv/scene/Report.h"

using namespace qv;

namespace {

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

struct ReportCity {
  Tileset tileset;
  seismic::ConsequenceTotals totals;
  std::vector<SearchEntry> entries;
  ResponseSummaryTile summary;

  ReportCity() {
    tileset.name = "Testville";
    tileset.buildings = 4;
    tileset.sources = {"/data/testville.osm.pbf"};
    ResponseInfo r;
    r.eventType = "ACTUAL";
    r.method = "MDOF shear building";
    r.timeOfDay = "day";
    r.scaling = "sa";
    r.records = {"RSN1 Northridge", "RSN2 Kobe"};
    ResponseInfo::ShakeMap m;
    m.eventId = "us7000test";
    m.version = "4";
    m.magnitude = 6.7;
    m.depthKm = 12;
    m.description = "Testville fault";
    m.processTimestamp = "2026-11-27T10:00:00Z";
    m.eventTimestamp = "2026-11-27T09:41:00Z";
    r.shakemap = m;
    tileset.response = r;

    totals.timeOfDay = "day";
    totals.city.buildings = 4;
    totals.city.damaged = {2.5, 1.0, 4.0};
    totals.city.injuries[3] = {140.2, 90.0, 200.0};     // PAGER orange on deaths
    totals.city.repairCostUsd = {2.5e8, 1.0e8, 4.0e8};  // orange on losses
    totals.city.tags[2] = {1.25, 0.0, 3.0};
    std::array<seismic::CasualtiesAtTime, 3> at;
    at[0].occupants = 11;
    at[1].occupants = 222;
    at[2].occupants = 33;
    at[1].injuries[0] = {17.5, 10.0, 25.0};
    totals.city.byTime = at;
    seismic::ClassTotals c;
    c.key = "COM6";
    c.buildings = 1;
    totals.byOccupancy.push_back(c);
    c.key = "URML";
    totals.byStructure.push_back(c);
    totals.inferred = seismic::InferredCounts{4, 3, 2, 1, 4, 4};
    totals.districts.push_back({"Old <Town>", totals.city, {{{0.0, 0.0}, {0.003, 0.0}, {0.003, 0.002}, {0.0, 0.002}}}});

    const char* names[4] = {"General Hospital", "<script>alert(1)</script> Fire Hall", "Flat block", "School No. 5"};
    const char* kinds[4] = {"hospital", "fire_station", "", "school"};
    const FacilityCategory categories[4] = {FacilityCategory::Essential, FacilityCategory::Essential,
                                            FacilityCategory::None, FacilityCategory::SchoolShelter};
    for (int i = 0; i < 4; ++i) {
      SearchEntry e;
      e.id = "w" + std::to_string(i);
      e.name = names[i];
      e.facility = categories[i];
      e.facilityKind = kinds[i];
      e.x = 100.0f * static_cast<float>(i);
      e.y = 50.0f * static_cast<float>(i);
      entries.push_back(e);
      BuildingResponse b;
      b.damage = DamageState::Moderate;
      summary.buildings.push_back(b);
      BuildingLoss l;
      // The hospital: 80 % moderate or worse; the fire hall: no damage; the school: complete.
      const float p[4][5] = {{0.1f, 0.1f, 0.5f, 0.2f, 0.1f}, {1, 0, 0, 0, 0}, {0.5f, 0.5f, 0, 0, 0}, {0, 0, 0, 0, 1}};
      for (int k = 0; k < 5; ++k) l.structural[k] = p[i][k];
      summary.losses.push_back(l);
    }
  }

  [[nodiscard]] std::string html() const {
    ReportInputs in;
    in.tileset = &tileset;
    in.consequences = &totals;
    in.buildings = entries;
    in.summary = &summary;
    return situationReportHtml(in);
  }
};

}  // namespace

TEST_CASE("PAGER's thresholds give the impact level on deaths and on losses", "[report]") {
  CHECK(fatalityLevel(0.4) == ImpactLevel::Green);
  CHECK(fatalityLevel(0.6) == ImpactLevel::Yellow);
  CHECK(fatalityLevel(99.4) == ImpactLevel::Yellow);
  CHECK(fatalityLevel(100) == ImpactLevel::Orange);
  CHECK(fatalityLevel(1000) == ImpactLevel::Red);
  CHECK(economicLevel(999e3) == ImpactLevel::Green);
  CHECK(economicLevel(1e6) == ImpactLevel::Yellow);
  CHECK(economicLevel(1e8) == ImpactLevel::Orange);
  CHECK(economicLevel(2e9) == ImpactLevel::Red);
  CHECK(impactLevelName(ImpactLevel::Orange) == "orange");
}

TEST_CASE("The situation report says what happened, how sure it is and where it came from", "[report]") {
  const ReportCity city;
  const std::string html = city.html();
  CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK(html.find("<script") == std::string::npos);  // a building's name is text, never markup
  CHECK(html.find("&lt;script&gt;alert(1)&lt;/script&gt; Fire Hall") != std::string::npos);
  CHECK(html.find("Old &lt;Town&gt;") != std::string::npos);
  // The event: ACTUAL in red, with the ShakeMap's id, version and times.
  CHECK(html.find("class=\"banner actual\">ACTUAL EVENT") != std::string::npos);
  CHECK(html.find("us7000test, version 4") != std::string::npos);
  CHECK(html.find("processed 2026-11-27T10:00:00Z") != std::string::npos);
  CHECK(html.find("M6.7, 12.0 km deep") != std::string::npos);
  CHECK(html.find("2 records: RSN1 Northridge; RSN2 Kobe") != std::string::npos);
  // Headline numbers with their intervals, and the impact level.
  CHECK(html.find("<div class=\"v\">140</div><div class=\"small\">90 % interval 90 &ndash; 200</div>") !=
        std::string::npos);
  CHECK(html.find("$250.0 M") != std::string::npos);
  CHECK(html.find("Impact level: <span class=\"level orange\">Orange</span>") != std::string::npos);
  CHECK(html.find("not PAGER's alert") != std::string::npos);
  // Casualties at the three times, the run's marked.
  CHECK(html.find("2 AM (night)</td><td>11</td>") != std::string::npos);
  CHECK(html.find("2 PM (day) &#9664; assumed above</td><td>222</td><td>18<br><span class=\"small\">10 &ndash; "
                  "25</span>") != std::string::npos);
  CHECK(html.find("5 PM (commute)</td><td>33</td>") != std::string::npos);
  // Tables by class with the Technical Manual's names.
  CHECK(html.find("COM6 <span class=\"small\">hospital</span>") != std::string::npos);
  CHECK(html.find("URML <span") != std::string::npos);
  // Facilities: the hospital likely damaged and not functional; the fire hall functional.
  CHECK(html.find("<tr><td class=\"l\">hospital</td><td>1</td><td>1</td><td>0</td><td>0</td></tr>") !=
        std::string::npos);
  CHECK(html.find("<tr><td class=\"l\">fire station</td><td>1</td><td>0</td><td>0</td><td>1</td></tr>") !=
        std::string::npos);
  CHECK(html.find("<tr><td class=\"l\">school</td><td>1</td><td>1</td><td>1</td><td>0</td></tr>") != std::string::npos);
  // The most damaged facility first: the school (100 %), then the hospital (80 %).
  CHECK(html.find("School No. 5") < html.find("General Hospital</td>"));
  // The map: a picture with the essential facilities marked, a scale bar and a north arrow.
  CHECK(html.find("<svg") != std::string::npos);
  CHECK(occurrences(html, "<circle") == 2);
  CHECK(html.find(">N</text>") != std::string::npos);
  // The district's outline and name on the map, clipped to it.
  CHECK(html.find("clip-path=\"url(#qv-report-map-clip)\" fill=\"none\" stroke=\"#1d3557\"") != std::string::npos);
  CHECK(html.find(">Old &lt;Town&gt;</text>") != std::string::npos);
  CHECK(html.find("Blue lines: the districts of the table below.") != std::string::npos);
  // Inferred values counted, limits and sources stated, the provenance line at the end.
  CHECK(html.find("structural type: 3 of 4 (75 %)") != std::string::npos);
  CHECK(html.find("Patterns across a city, not a safety assessment") != std::string::npos);
  CHECK(html.find("OpenStreetMap contributors") != std::string::npos);
  CHECK(html.find("USGS ShakeMap us7000test version 4") != std::string::npos);
  CHECK(html.find("<p class=\"provenance\">QuakeView situation report | City: Testville | Shaking: ACTUAL EVENT") !=
        std::string::npos);
  // Deterministic.
  CHECK(city.html() == html);
}

TEST_CASE("A report without some of its files says what is missing instead of inventing numbers", "[report]") {
  ReportCity city;
  ReportInputs in;
  in.tileset = &city.tileset;
  const std::string noTotals = situationReportHtml(in);
  CHECK(noTotals.find("no damage probabilities or consequences") != std::string::npos);
  CHECK(noTotals.find("No map: the city has no search index") != std::string::npos);
  CHECK(noTotals.find("Impact level") == std::string::npos);

  city.totals.city.byTime.reset();
  city.totals.byOccupancy.clear();
  city.totals.inferred.reset();
  city.tileset.response->eventType = "SCENARIO";
  const std::string older = city.html();
  CHECK(older.find("class=\"banner scenario\">SCENARIO") != std::string::npos);
  CHECK(older.find("Other times of day: not in this response's files") != std::string::npos);
  CHECK(older.find("2 AM (night)") == std::string::npos);
  CHECK(older.find("Not in this response's files (made before the report's tables)") != std::string::npos);

  city.tileset.response.reset();
  in.tileset = &city.tileset;
  CHECK(situationReportHtml(in).find("No earthquake response has been computed") != std::string::npos);
}

TEST_CASE("Fuzzer-found consequence files read back the same and make a whole report", "[report][fuzz]") {
  std::string missing;
  const auto inputs = fuzz::requiredInputs(QUAKEVIEW_SOURCE_DIR, "consequences", missing);
  INFO(missing);
  REQUIRE(missing.empty());
  for (const fuzz::SavedInput& input : inputs) {
    SECTION(input.path) {
      const std::string_view json(reinterpret_cast<const char*>(input.bytes.data()), input.bytes.size());
      const auto parsed = seismic::parseConsequences(json, input.path);
      if (!parsed.ok()) {
        CHECK(parsed.error().rfind(input.path, 0) == 0);
        continue;
      }
      const auto again = seismic::parseConsequences(seismic::consequencesToJson(*parsed), input.path);
      INFO((again.ok() ? std::string() : again.error()));
      REQUIRE(again.ok());
      CHECK(again->districts.size() == parsed->districts.size());
      ReportCity city;
      city.totals = *parsed;
      const std::string html = city.html();
      CHECK(html.find("</html>") != std::string::npos);
      CHECK(isValidUtf8(html));
    }
  }
}
