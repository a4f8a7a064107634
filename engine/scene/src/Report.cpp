#include "qv/scene/Report.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string_view>
#include <vector>

#include "ReportParts.h"
#include "qv/core/Text.h"
#include "qv/format/FacilityCategory.h"
#include "qv/scene/Export.h"
#include "qv/scene/Palette.h"
#include "qv/seismic/Loss.h"

namespace qv {
namespace {

using namespace report;

const char* kStateNames[5] = {"None", "Slight", "Moderate", "Extensive", "Complete"};
const char* kTimeLabels[3] = {"2 AM (night)", "2 PM (day)", "5 PM (commute)"};

// The styles, scoped to .qv-report so that a page can embed the report. Print: A4 and Letter alike
// (the content is at most 186 mm wide, what both leave inside 12 mm margins), colours kept.
constexpr std::string_view kStyle = R"CSS(
@page { margin: 12mm; }
.qv-report { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; font-size: 10pt; color: #1a1a1a;
  max-width: 186mm; margin: 0 auto; padding: 8px; line-height: 1.35; background: #fff;
  -webkit-print-color-adjust: exact; print-color-adjust: exact; }
.qv-report h1 { font-size: 17pt; margin: 0 0 4px; }
.qv-report h2 { font-size: 12.5pt; margin: 16px 0 6px; border-bottom: 1.5px solid #555; padding-bottom: 2px;
  break-after: avoid; page-break-after: avoid; }
.qv-report h2.page { break-before: page; page-break-before: always; }
.qv-report h3 { font-size: 10.5pt; margin: 10px 0 4px; break-after: avoid; }
.qv-report p { margin: 4px 0; }
.qv-report .banner { font-weight: bold; font-size: 13pt; color: #fff; padding: 6px 10px; margin: 6px 0;
  border-radius: 3px; }
.qv-report .banner.scenario { background: #b35900; }
.qv-report .banner.actual { background: #b00d00; }
.qv-report .banner.unstated { background: #555; }
.qv-report table { border-collapse: collapse; width: 100%; margin: 4px 0 8px; font-size: 9pt; }
.qv-report th, .qv-report td { border: 1px solid #bbb; padding: 2px 5px; text-align: right; vertical-align: top; }
.qv-report th { background: #eeeae4; }
.qv-report td { white-space: nowrap; }
.qv-report th.k { width: 30%; }
.qv-report svg.swatch { vertical-align: middle; }
.qv-report td.l, .qv-report th.l { text-align: left; white-space: normal; }
.qv-report tr { break-inside: avoid; page-break-inside: avoid; }
.qv-report .small { font-size: 8.5pt; color: #444; }
.qv-report .headline { display: flex; flex-wrap: wrap; gap: 6px; margin: 6px 0; }
.qv-report .figure { flex: 1 1 40mm; border: 1px solid #bbb; padding: 4px 6px; break-inside: avoid; }
.qv-report .figure .v { font-size: 15pt; font-weight: bold; }
.qv-report .level { display: inline-block; padding: 2px 10px; font-weight: bold; border: 1px solid #333; }
.qv-report .level.green { background: #2e9e5b; color: #fff; }
.qv-report .level.yellow { background: #fcdc39; color: #000; }
.qv-report .level.orange { background: #f08c1e; color: #000; }
.qv-report .level.red { background: #c8102e; color: #fff; }
.qv-report .map { break-inside: avoid; page-break-inside: avoid; }
.qv-report .map svg { width: 100%; height: auto; max-height: 200mm; border: 1px solid #999; }
.qv-report .provenance { font-size: 8pt; color: #444; border-top: 1px solid #999; margin-top: 14px; padding-top: 4px; }
.qv-report ul { margin: 4px 0 4px 18px; padding: 0; }
)CSS";

std::string levelBadge(ImpactLevel level) {
  const std::string name(impactLevelName(level));
  std::string label = name;
  label[0] = static_cast<char>(label[0] - 'a' + 'A');
  return "<span class=\"level " + name + "\">" + label + "</span>";
}

void writeEvent(std::string& out, const Tileset& t) {
  const ResponseInfo& r = *t.response;
  const std::string statement = shakingStatement(r);
  const char* kind = r.eventType == "ACTUAL" ? "actual" : r.eventType == "SCENARIO" ? "scenario" : "unstated";
  out += "<div class=\"banner " + std::string(kind) + "\">" + esc(statement) + "</div>\n";
  out += "<table><tbody>\n";
  const auto row = [&out](std::string_view label, const std::string& html) {
    out += "<tr><th class=\"l k\">" + std::string(label) + "</th><td class=\"l\">" + html + "</td></tr>\n";
  };
  if (r.shakemap) {
    const auto& m = *r.shakemap;
    row("Earthquake", esc(m.description.empty() ? "(no description)" : m.description));
    row("Magnitude, depth", fmt("M%.1f", m.magnitude) + fmt(", %.1f km deep", m.depthKm));
    row("Epicentre", fmt("%.4f&deg;, ", m.latitudeDeg) + fmt("%.4f&deg; (latitude, longitude)", m.longitudeDeg));
    row("Time of the earthquake", esc(m.eventTimestamp.empty() ? "not given" : m.eventTimestamp));
    row("ShakeMap", esc(m.eventId) + ", version " + esc(m.version) + (m.source.empty() ? "" : ", by " + esc(m.source)) +
                        ", processed " + esc(m.processTimestamp.empty() ? "(time not given)" : m.processTimestamp));
  } else if (!r.scenario.empty()) {
    row("Scenario", esc(r.scenario));
  } else {
    row("Shaking", "one ground motion for every building: " + esc(r.motion));
  }
  std::string records;
  for (std::size_t i = 0; i < r.records.size() && i < 3; ++i) records += (i ? "; " : "") + esc(r.records[i]);
  if (r.records.size() > 3) records += "; and " + std::to_string(r.records.size() - 3) + " more";
  if (records.empty()) records = esc(r.motion);
  row("Ground-motion records", std::to_string(std::max<std::size_t>(r.records.size(), 1)) + " record" +
                                   (r.records.size() > 1 ? "s: " : ": ") + records);
  row("Scaling", r.scaling == "sa"    ? "each record scaled, per direction, to the shaking's spectral acceleration at "
                                        "the building's first-mode period"
                 : r.scaling == "pga" ? "each record scaled to the peak ground acceleration at the building"
                                      : "records used as given");
  const std::string tod = r.timeOfDay == "night"     ? "night (2 AM)"
                          : r.timeOfDay == "day"     ? "day (2 PM)"
                          : r.timeOfDay == "commute" ? "commute (5 PM)"
                                                     : "not stated";
  row("Occupants assumed at", tod + " (other times of day: the casualty table)");
  row("City",
      esc(t.name.empty() ? "(unnamed)" : t.name) + ", " + grouped(static_cast<double>(t.buildings)) + " buildings");
  out += "</tbody></table>\n";
}

void writeHeadline(std::string& out, const seismic::LossTotals& c) {
  out += "<h2>The impact at a glance</h2>\n<div class=\"headline\">\n";
  const auto figure = [&out](std::string_view label, const std::string& value, const std::string& interval) {
    out += "<div class=\"figure\"><div class=\"small\">" + std::string(label) + "</div><div class=\"v\">" + value +
           "</div><div class=\"small\">90 % interval " + interval + "</div></div>\n";
  };
  figure("Buildings damaged (moderate or worse)", count(c.damaged.expected), range(c.damaged));
  figure("Collapses", count(c.collapsed.expected), range(c.collapsed));
  figure("Red tags (unsafe)", count(c.tags[2].expected), range(c.tags[2]));
  figure("Yellow tags (restricted use)", count(c.tags[1].expected), range(c.tags[1]));
  figure("Deaths", count(c.injuries[3].expected), range(c.injuries[3]));
  figure("Repair cost", money(c.repairCostUsd.expected), range(c.repairCostUsd, true));
  out += "</div>\n";
  const ImpactLevel deaths = fatalityLevel(c.injuries[3].expected);
  const ImpactLevel losses = economicLevel(c.repairCostUsd.expected);
  const ImpactLevel level = std::max(deaths, losses);
  out += "<p><b>Impact level: " + levelBadge(level) + "</b> &nbsp; (deaths " + levelBadge(deaths) +
         ", economic losses " + levelBadge(losses) +
         ")</p>\n<p class=\"small\">An indication for this city on the alert thresholds USGS PAGER publishes "
         "(fatalities: green 0, yellow 1&ndash;99, orange 100&ndash;999, red 1,000 or more; economic losses: green "
         "under $1 million, yellow up to $100 million, orange up to $1 billion, red above), applied to this "
         "city's expected deaths and repair cost. It is not PAGER's alert, which covers the whole region an "
         "earthquake shakes and its own loss models.</p>\n";
  out +=
      "<table><thead><tr><th class=\"l\">Damage state (structural)</th><th>Buildings, expected</th>"
      "<th>90 % interval</th></tr></thead><tbody>\n";
  for (std::size_t k = 0; k < 5; ++k) {
    out += "<tr><td class=\"l\">" + std::string(kStateNames[k]) + "</td><td>" + count(c.damageStates[k].expected) +
           "</td><td>" + range(c.damageStates[k]) + "</td></tr>\n";
  }
  out += "<tr><td class=\"l\"><b>Moderate or worse</b></td><td><b>" + count(c.damaged.expected) + "</b></td><td>" +
         range(c.damaged) + "</td></tr>\n";
  out += "<tr><td class=\"l\">Collapsed (part of complete)</td><td>" + count(c.collapsed.expected) + "</td><td>" +
         range(c.collapsed) + "</td></tr>\n";
  out += "<tr><td class=\"l\">Green tags (inspected)</td><td>" + count(c.tags[0].expected) + "</td><td>" +
         range(c.tags[0]) + "</td></tr>\n";
  out += "</tbody></table>\n";
  out +=
      "<p class=\"small\">Displaced households are not estimated (HAZUS derives them from residential units "
      "and census data the city's files do not hold).</p>\n";
}

void writeCasualties(std::string& out, const seismic::LossTotals& c, const std::string& runTime) {
  out +=
      "<h2>Casualties by time of day</h2>\n<table><thead><tr><th class=\"l\">Earthquake at</th><th>People "
      "present</th><th>Severity 1 (first aid)</th><th>Severity 2 (hospital care)</th><th>Severity 3 "
      "(life-threatening)</th><th>Deaths</th></tr></thead><tbody>\n";
  const char* keys[3] = {"night", "day", "commute"};
  for (std::size_t t = 0; t < 3; ++t) {
    const bool run = runTime == keys[t];
    if (!c.byTime && !run) continue;
    const double people = c.byTime ? (*c.byTime)[t].occupants : c.occupants.expected;
    const auto& injuries = c.byTime ? (*c.byTime)[t].injuries : c.injuries;
    out += "<tr><td class=\"l\">" + std::string(kTimeLabels[t]) + (run ? " &#9664; assumed above" : "") + "</td><td>" +
           count(people) + "</td>";
    for (std::size_t s = 0; s < 4; ++s) {
      out += "<td>" + count(injuries[s].expected) + "<br><span class=\"small\">" + range(injuries[s]) + "</span></td>";
    }
    out += "</tr>\n";
  }
  out +=
      "</tbody></table>\n<p class=\"small\">Expected people with the 90 % interval under each. The same damage at "
      "three times of day (HAZUS's night, day and commute populations): people indoors at each time, by "
      "occupancy class. Outdoor and transport casualties are not modelled.</p>\n";
  if (!c.byTime) out += "<p class=\"small\">Other times of day: not in this response's files (made before them).</p>\n";
}

void writeClasses(std::string& out, const std::vector<seismic::ClassTotals>& rows, bool occupancy) {
  out += occupancy ? "<h3>By occupancy class (HAZUS)</h3>\n" : "<h3>By structural type (HAZUS, as modelled)</h3>\n";
  if (rows.empty()) {
    out += "<p>Not in this response's files (made before the report's tables).</p>\n";
    return;
  }
  out += std::string("<table><thead><tr><th class=\"l\">") + (occupancy ? "Class" : "Type") +
         "</th><th>Buildings</th><th>None</th><th>Slight</th><th>Moderate</th><th>Extensive</th><th>Complete</th>"
         "<th>Moderate or worse</th><th>Repair cost</th></tr></thead><tbody>\n";
  for (const seismic::ClassTotals& r : rows) {
    std::string label = esc(r.key);
    if (occupancy) {
      for (std::size_t k = 0; k < static_cast<std::size_t>(seismic::Occupancy::Count); ++k) {
        const auto o = static_cast<seismic::Occupancy>(k);
        if (seismic::occupancyCode(o) == r.key)
          label += " <span class=\"small\">" + esc(seismic::occupancyDescription(o)) + "</span>";
      }
    } else {
      const StructuralType type = parseStructuralType(r.key);
      if (type != StructuralType::Unknown) {
        label += " <span class=\"small\">" + esc(structuralTypeDescription(type)) + "</span>";
      }
    }
    out += "<tr><td class=\"l\">" + label + "</td><td>" + grouped(static_cast<double>(r.buildings)) + "</td>";
    for (std::size_t k = 0; k < 5; ++k) out += "<td>" + count(r.damageStates[k]) + "</td>";
    out += "<td>" + count(r.damaged) + " (" +
           percent(r.buildings > 0 ? r.damaged / static_cast<double>(r.buildings) : 0.0) + ")</td><td>" +
           money(r.repairCostUsd) + "</td></tr>\n";
  }
  out += "</tbody></table>\n";
}

struct Facility {
  const SearchEntry* entry = nullptr;
  std::array<double, 5> p{};
  double moderate = 0, functional = 0;
};

void writeFacilities(std::string& out, const ReportInputs& in) {
  out += "<h2>Essential facilities</h2>\n";
  std::vector<Facility> facilities;
  std::size_t withoutResult = 0;
  for (std::size_t i = 0; i < in.buildings.size(); ++i) {
    const SearchEntry& e = in.buildings[i];
    if (e.facility != FacilityCategory::Essential && e.facility != FacilityCategory::SchoolShelter) continue;
    const auto p = structuralOf(in.summary, i);
    if (!p) {
      ++withoutResult;
      continue;
    }
    Facility f{&e, *p, (*p)[2] + (*p)[3] + (*p)[4], seismic::functionalProbability(*p, 1.0)};
    facilities.push_back(f);
  }
  if (facilities.empty() && withoutResult == 0) {
    out += "<p>The city's data names no hospitals, fire or police stations, schools or shelters.</p>\n";
    return;
  }
  // Summary by kind, as the Hazus summary report counts them.
  std::map<std::string, std::array<int, 4>> kinds;  // total, moderate > 50 %, complete > 50 %, functional > 50 %
  for (const Facility& f : facilities) {
    std::string kind = f.entry->facilityKind.empty() ? f.entry->use : f.entry->facilityKind;
    std::replace(kind.begin(), kind.end(), '_', ' ');
    auto& k = kinds[kind];
    ++k[0];
    k[1] += f.moderate > 0.5 ? 1 : 0;
    k[2] += f.p[4] > 0.5 ? 1 : 0;
    k[3] += f.functional > 0.5 ? 1 : 0;
  }
  out +=
      "<table><thead><tr><th class=\"l\">Facility</th><th>Total</th><th>At least moderate damage &gt; 50 %</th>"
      "<th>Complete damage &gt; 50 %</th><th>Functional on day one &gt; 50 %</th></tr></thead><tbody>\n";
  for (const auto& [kind, k] : kinds) {
    out += "<tr><td class=\"l\">" + esc(kind) + "</td><td>" + std::to_string(k[0]) + "</td><td>" +
           std::to_string(k[1]) + "</td><td>" + std::to_string(k[2]) + "</td><td>" + std::to_string(k[3]) +
           "</td></tr>\n";
  }
  out += "</tbody></table>\n";
  if (withoutResult > 0) {
    out += "<p class=\"small\">" + std::to_string(withoutResult) +
           " more facilities have no result (not analysed) and are not counted.</p>\n";
  }
  std::stable_sort(facilities.begin(), facilities.end(),
                   [](const Facility& a, const Facility& b) { return a.moderate > b.moderate; });
  constexpr std::size_t kListed = 40;
  out +=
      "<h3>The facilities most likely damaged</h3>\n<table><thead><tr><th class=\"l\">Facility</th><th "
      "class=\"l\">Kind</th><th>P(moderate or worse)</th><th>P(complete)</th><th>P(functional on day "
      "one)</th></tr></thead><tbody>\n";
  for (std::size_t i = 0; i < facilities.size() && i < kListed; ++i) {
    const Facility& f = facilities[i];
    const SearchEntry& e = *f.entry;
    const std::string name = !e.name.empty() ? e.name : !e.address.empty() ? e.address : e.id;
    std::string kind = e.facilityKind.empty() ? e.use : e.facilityKind;
    std::replace(kind.begin(), kind.end(), '_', ' ');
    out += "<tr><td class=\"l\">" + esc(name) + "</td><td class=\"l\">" + esc(kind) + "</td><td>" +
           percent(f.moderate) + "</td><td>" + percent(f.p[4]) + "</td><td>" + percent(f.functional) + "</td></tr>\n";
  }
  out += "</tbody></table>\n";
  if (facilities.size() > kListed) {
    out += "<p class=\"small\">And " + std::to_string(facilities.size() - kListed) +
           " more; the viewer's list (filter: critical facilities) exports them all.</p>\n";
  }
  out +=
      "<p class=\"small\">Functional on day one: HAZUS's functionality, the damage-state probabilities "
      "weighted by the share of facilities restored one day after the earthquake (restoration times: "
      "slight 5 &plusmn; 1, moderate 20 &plusmn; 2, extensive 90 &plusmn; 10, complete 180 &plusmn; 20 "
      "days), so about the probability of no structural damage. Utilities and access are not "
      "modelled.</p>\n";
}

void writeDistricts(std::string& out, const seismic::ConsequenceTotals& c) {
  out += "<h2>Districts</h2>\n";
  if (c.districts.empty()) {
    out +=
        "<p>No districts: the city's input names none, and the response was given no districts file "
        "(<code>quakeview-prep response --districts FILE.geojson</code>).</p>\n";
    return;
  }
  if (!c.districtsSource.empty()) {
    out += "<p>Districts: " + esc(c.districtsSource) +
           (c.districtsInferred ? " <strong>(INFERRED: not official boundaries)</strong>" : "") + ".</p>\n";
  }
  std::vector<const seismic::ConsequenceTotals::District*> rows;
  for (const auto& d : c.districts) rows.push_back(&d);
  std::stable_sort(rows.begin(), rows.end(), [](const auto* a, const auto* b) {
    return a->totals.damaged.expected > b->totals.damaged.expected;
  });
  out +=
      "<table><thead><tr><th class=\"l\">District</th><th>Buildings</th><th>Damaged (moderate or worse)</th>"
      "<th>Red tags</th><th>Injuries (severity 1&ndash;3)</th><th>Deaths</th><th>Repair cost</th></tr></thead>"
      "<tbody>\n";
  for (const auto* d : rows) {
    const seismic::LossTotals& t = d->totals;
    out += "<tr><td class=\"l\">" + esc(d->name) + "</td><td>" + grouped(static_cast<double>(t.buildings)) +
           "</td><td>" + count(t.damaged.expected) + "</td><td>" + count(t.tags[2].expected) + "</td><td>" +
           count(t.injuries[0].expected + t.injuries[1].expected + t.injuries[2].expected) + "</td><td>" +
           count(t.injuries[3].expected) + "</td><td>" + money(t.repairCostUsd.expected) + "</td></tr>\n";
  }
  out +=
      "</tbody></table>\n<p class=\"small\">Expected values; buildings outside every district are in the city's "
      "totals (and in an \"Outside the districts\" row where the districts file names one).</p>\n";
}

void writeBasis(std::string& out, const ReportInputs& in) {
  const ResponseInfo& r = *in.tileset->response;
  out += "<h2>What the numbers rest on, and their limits</h2>\n<ul>\n";
  out +=
      "<li><b>Patterns across a city, not a safety assessment</b> of any building: no building was inspected. "
      "Each was modelled from its footprint, height and the attributes below.</li>\n";
  out += "<li>Model: " + esc(r.method) +
         " for each building's response to its shaking; HAZUS 5.1 fragilities turn the peak drift and floor "
         "acceleration into damage-state probabilities, and HAZUS consequence tables into casualties, "
         "repair cost and inspection tags (ATC-20 placards).</li>\n";
  out +=
      "<li>90 % intervals: 500 Monte Carlo realisations with the buildings' damage drawn independently. One "
      "earthquake shakes neighbours alike, so the real spread is wider: read each interval as a lower "
      "bound of the uncertainty.</li>\n";
  if (in.consequences != nullptr && in.consequences->inferred) {
    const seismic::InferredCounts& i = *in.consequences->inferred;
    const auto share = [&i](std::uint64_t n) {
      return grouped(static_cast<double>(n)) + " of " + grouped(static_cast<double>(i.buildings)) + " (" +
             percent(i.buildings > 0 ? static_cast<double>(n) / static_cast<double>(i.buildings) : 0.0) + ")";
    };
    out += "<li>Inferred, not in the data (docs/attributes.md gives each rule and source):<ul>";
    out += "<li>structural type: " + share(i.structuralType) +
           " buildings, modelled as the mix of HAZUS types usual for their occupancy and height;</li>";
    out += "<li>year of construction (code era): " + share(i.codeEra) + ", spread over design levels;</li>";
    out += "<li>use: " + share(i.use) + ", taken as mixed residential and commercial;</li>";
    out += "<li>occupants: " + share(i.occupants) + ", from floor area and usual densities;</li>";
    out += "<li>replacement value: " + share(i.replacementValue) + ", from floor area and cost per m&sup2;.</li>";
    out += "</ul></li>\n";
  } else {
    out += "<li>How many attributes were inferred is not in this response's files (made before it).</li>\n";
  }
  if (in.consequences != nullptr && in.consequences->population.given()) {
    const auto& p = in.consequences->population;
    const auto& at = in.consequences->city.occupantsAt;
    out += "<li>Occupants against the population given (" + esc(p.source.empty() ? "no source" : p.source) + "): ";
    if (p.night >= 0) out += "night " + grouped(at[0]) + " modelled, " + grouped(p.night) + " given; ";
    if (p.day >= 0) out += "day " + grouped(at[1]) + " modelled, " + grouped(p.day) + " given";
    out += ".</li>\n";
  }
  out +=
      "<li>Not modelled: ground failure (liquefaction, landslides), fire following the earthquake, "
      "aftershocks, utilities and lifelines, outdoor casualties.</li>\n";
  out += "</ul>\n";
}

void writeSources(std::string& out, const Tileset& t) {
  const ResponseInfo& r = *t.response;
  out += "<h2>Data sources and licences</h2>\n<ul>\n";
  const bool osm = fromOpenStreetMap(t);
  std::string files;
  for (const std::string& s : t.sources) {
    const std::size_t slash = s.find_last_of('/');
    files += (files.empty() ? "" : ", ") + esc(slash == std::string::npos ? s : s.substr(slash + 1));
  }
  out += "<li>Buildings: " + (files.empty() ? std::string("not stated") : files) +
         (osm ? ". Map data &copy; OpenStreetMap contributors, Open Database Licence (ODbL) 1.0." : ".") + "</li>\n";
  if (r.shakemap) {
    out += "<li>Shaking: USGS ShakeMap " + esc(r.shakemap->eventId) + " version " + esc(r.shakemap->version) +
           " (U.S. Geological Survey; public domain in the United States).</li>\n";
  } else if (!r.scenario.empty()) {
    out += "<li>Shaking: scenario " + esc(r.scenario) +
           ", medians of the BSSA14 ground-motion model (Boore, Stewart, Seyhan and Atkinson 2014).</li>\n";
  }
  out += "<li>Records: " + std::to_string(std::max<std::size_t>(r.records.size(), 1)) +
         " ground-motion record(s), named in the event table.</li>\n";
  out +=
      "<li>Fragilities, casualty rates, repair costs and times, population by time of day: FEMA Hazus 5.1 "
      "Earthquake Model Technical Manual (2022), as tabulated in NHERI SimCenter's Damage and Loss Model "
      "Library (BSD 3-Clause licence).</li>\n";
  out += "<li>Impact thresholds: USGS PAGER (Wald et al. 2010, USGS Fact Sheet 2010-3036).</li>\n";
  out += "<li>Made by " + esc(t.generator.empty() ? "QuakeView" : t.generator) + ".</li>\n";
  out += "</ul>\n";
}

}  // namespace

ImpactLevel fatalityLevel(double expectedDeaths) {
  const double d = std::round(std::max(expectedDeaths, 0.0));
  return d >= 1000  ? ImpactLevel::Red
         : d >= 100 ? ImpactLevel::Orange
         : d >= 1   ? ImpactLevel::Yellow
                    : ImpactLevel::Green;
}

ImpactLevel economicLevel(double repairCostUsd) {
  return repairCostUsd >= 1e9   ? ImpactLevel::Red
         : repairCostUsd >= 1e8 ? ImpactLevel::Orange
         : repairCostUsd >= 1e6 ? ImpactLevel::Yellow
                                : ImpactLevel::Green;
}

std::string_view impactLevelName(ImpactLevel level) {
  switch (level) {
    case ImpactLevel::Green:
      return "green";
    case ImpactLevel::Yellow:
      return "yellow";
    case ImpactLevel::Orange:
      return "orange";
    case ImpactLevel::Red:
      return "red";
  }
  return "green";
}

std::string situationReportHtml(const ReportInputs& in) {
  std::string out;
  out.reserve(1 << 18);
  const std::string city = in.tileset != nullptr && !in.tileset->name.empty() ? in.tileset->name : "the city";
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>Earthquake situation report: " +
         esc(city) + "</title>\n<style>" + std::string(kStyle) +
         "</style>\n</head>\n<body>\n<div class=\"qv-report\">\n";
  out += "<h1>Earthquake situation report: " + esc(city) + "</h1>\n";
  if (in.tileset == nullptr || !in.tileset->response) {
    out += "<p>No earthquake response has been computed for this city, so there is nothing to report.</p>\n";
  } else {
    const Tileset& t = *in.tileset;
    writeEvent(out, t);
    if (in.consequences == nullptr) {
      out +=
          "<p>This response has no damage probabilities or consequences (it was imported, or made without "
          "them): only the map of the buildings follows.</p>\n";
      writeMap(out, in);
    } else {
      const seismic::LossTotals& c = in.consequences->city;
      writeHeadline(out, c);
      writeMap(out, in);
      writeCasualties(out, c, in.consequences->timeOfDay);
      out += "<h2>Damage by occupancy and by building type</h2>\n";
      writeClasses(out, in.consequences->byOccupancy, true);
      writeClasses(out, in.consequences->byStructure, false);
      writeFacilities(out, in);
      writeDistricts(out, *in.consequences);
    }
    writeBasis(out, in);
    writeSources(out, t);
  }
  if (in.tileset != nullptr) {
    out += "<p class=\"provenance\">" + esc(provenanceText("situation report", exportProvenance(*in.tileset, {}))) +
           "</p>\n";
  }
  out += "</div>\n</body>\n</html>\n";
  return out;
}

}  // namespace qv
