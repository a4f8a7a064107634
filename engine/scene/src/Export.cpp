#include "qv/scene/Export.h"

#include <cctype>
#include <cmath>
#include <cstdio>

#include "qv/core/JsonWriter.h"
#include "qv/core/Text.h"

namespace qv {
namespace {

// An RFC 4180 field of text from outside (names, addresses, ids). A field that a spreadsheet would
// take for a formula (it begins with =, +, -, @, a tab or a carriage return: OWASP's list against
// CSV injection, CWE-1236) gets a leading apostrophe inside a quoted field, which spreadsheets show
// as text. Invalid UTF-8 becomes U+FFFD. Numbers never pass through here: they stay numbers.
std::string csvField(std::string_view raw) {
  std::string repaired;
  if (!isValidUtf8(raw)) repaired = toValidUtf8(raw);
  const std::string_view text = repaired.empty() ? raw : std::string_view(repaired);
  const bool formula = !text.empty() && std::string_view("=+-@\t\r").find(text.front()) != std::string_view::npos;
  if (!formula && text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = formula ? "\"'" : "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

std::string number(double v, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// A provenance value inside the comment line: one line, no commas (a spreadsheet would split the
// cell there) and no double quotes.
std::string commentValue(std::string_view raw) {
  std::string out = isValidUtf8(raw) ? std::string(raw) : toValidUtf8(raw);
  for (char& c : out) {
    if (c == ',' || c == '\r' || c == '\n' || c == '\t') c = ' ';
    if (c == '"') c = '\'';
  }
  return out;
}

std::string commentLine(std::string_view title, const ExportProvenance& p) {
  return "# " + provenanceText(title, p) + "\r\n";
}

}  // namespace

std::string provenanceText(std::string_view title, const ExportProvenance& p) {
  std::string line = "QuakeView " + std::string(title);
  auto part = [&line](std::string_view label, const std::string& value) {
    if (!value.empty()) line += " | " + std::string(label) + ": " + commentValue(value);
  };
  part("City", p.city);
  part("Shaking", p.shaking);
  part("Earthquake", p.earthquake);
  part("Records", p.records);
  part("Method", p.method);
  part("Time of day", p.timeOfDay);
  part("Filter", p.filter);
  return line;
}

namespace {

std::string preamble(std::string_view title, const ExportProvenance* provenance) {
  std::string out(kByteOrderMark);
  if (provenance != nullptr) out += commentLine(title, *provenance);
  return out;
}

}  // namespace

std::string shakingStatement(const ResponseInfo& r) {
  const bool imported = r.method.rfind("imported", 0) == 0;
  if (r.eventType == "ACTUAL") return "ACTUAL EVENT (ShakeMap of a recorded earthquake)";
  if (r.eventType == "SCENARIO" || (r.eventType.empty() && !imported && r.shakingField != "shakemap")) {
    return r.shakingField == "shakemap" ? "SCENARIO (a ShakeMap scenario, not a recorded event)"
                                        : "SCENARIO (computed, not a recorded event)";
  }
  if (imported) return "IMPORTED RESULTS (not stated whether a scenario or an actual event)";
  return "NOT STATED whether a scenario or an actual event";
}

namespace {

// The importance column: "critical" for essential facilities, schools and shelters only (never
// for height or parts, which older search indexes still stored as critical).
std::string_view criticalName(FacilityCategory facility) {
  return importanceName((facilityCategoryBit(facility) & kCriticalCategories) != 0 ? Importance::Critical
                                                                                   : Importance::General);
}

// "hospital+school" -> "hospital or school".
std::string joinedWith(std::string_view plusJoined, std::string_view separator) {
  std::string out;
  for (const char c : plusJoined) {
    if (c == '+')
      out += separator;
    else
      out += c;
  }
  return out;
}

// The names (or labels) of the categories set in `mask`, in category order.
std::string categoryNames(unsigned mask, std::string_view separator, bool names) {
  std::string out;
  for (auto i = 1u; i < static_cast<unsigned>(FacilityCategory::Count); ++i) {
    const auto category = static_cast<FacilityCategory>(i);
    if ((mask & facilityCategoryBit(category)) == 0) continue;
    if (!out.empty()) out += separator;
    out += names ? facilityCategoryName(category) : facilityCategoryLabel(category);
  }
  return out;
}

}  // namespace

std::string describeFilters(const BuildingFilters& f) {
  std::string text;
  auto add = [&text](const std::string& phrase) { text += (text.empty() ? "" : " | ") + phrase; };
  if (f.minDamage >= 0 && f.minDamage <= 4) {
    add("damage at least " + std::string(damageStateName(static_cast<DamageState>(f.minDamage))));
  }
  if (f.probabilityActive()) {
    add("P(damage at least " + std::string(damageStateName(static_cast<DamageState>(f.probabilityState))) +
        ") at least " + std::to_string(f.minProbabilityPercent) + " %");
  }
  if (!f.use.empty()) add("use: " + joinedWith(f.use, " or "));
  if (f.criticalOnly) add("critical facilities only (essential or school/shelter)");
  if (f.categories != 0) add("facility: " + categoryNames(f.categories, " or ", false));
  return text.empty() ? "none" : text;
}

namespace {

// Lower-case ASCII letters and digits; everything else becomes one '-' (none at either end).
std::string slug(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    const bool upper = c >= 'A' && c <= 'Z';
    if (keep || upper) {
      out += upper ? static_cast<char>(c - 'A' + 'a') : c;
    } else if (!out.empty() && out.back() != '-') {
      out += '-';
    }
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

}  // namespace

std::string exportFileName(const Tileset& tileset, const BuildingFilters& filters, std::string_view what,
                           std::string_view extension) {
  std::string name = "quakeview";
  auto add = [&name](std::string_view part) {
    const std::string s = slug(part);
    if (!s.empty()) name += "-" + s;
  };
  add(tileset.name);
  if (!tileset.response) {
    add("no-response");
  } else {
    const ResponseInfo& r = *tileset.response;
    const std::string statement = shakingStatement(r);
    add(statement.substr(0, statement.find(' ')) == "NOT" ? "unstated" : statement.substr(0, statement.find(' ')));
    if (r.shakemap) add(r.shakemap->eventId);
  }
  add(what);
  if (filters.minDamage >= 0 && filters.minDamage <= 4) {
    add("damage-" + std::string(damageStateName(static_cast<DamageState>(filters.minDamage))));
  }
  if (filters.probabilityActive()) {
    add("p-" + std::string(damageStateName(static_cast<DamageState>(filters.probabilityState))) + "-" +
        std::to_string(filters.minProbabilityPercent) + "pct");
  }
  if (!filters.use.empty()) add("use-" + filters.use);  // "use-hospital-school": slug turns '+' into '-'
  if (filters.criticalOnly) add("critical");
  if (filters.categories != 0) add("facility-" + categoryNames(filters.categories, "-", true));
  if (name.size() > 150) name.resize(150);
  while (name.back() == '-') name.pop_back();
  return name + "." + std::string(extension);
}

ExportProvenance exportProvenance(const Tileset& tileset, const BuildingFilters& filters) {
  ExportProvenance p;
  p.city = tileset.name;
  p.filter = describeFilters(filters);
  if (!tileset.response) {
    p.shaking = "no response computed";
    return p;
  }
  const ResponseInfo& r = *tileset.response;
  p.shaking = shakingStatement(r);
  if (r.shakemap) {
    p.earthquake = "ShakeMap " + r.shakemap->eventId + " version " + r.shakemap->version +
                   (r.shakemap->description.empty() ? "" : " (" + r.shakemap->description + ")");
  } else {
    p.earthquake = r.scenario.empty() ? "one record for every building" : r.scenario;
  }
  for (const std::string& record : r.records) p.records += (p.records.empty() ? "" : "; ") + record;
  if (p.records.empty()) p.records = r.motion;
  p.method = r.method;
  p.timeOfDay = r.timeOfDay;
  return p;
}

bool fromOpenStreetMap(const Tileset& tileset) {
  for (const std::string& s : tileset.sources) {
    std::string lower(s);
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (lower.ends_with(".osm") || lower.ends_with(".pbf") || lower.ends_with(".osm.bz2") ||
        lower.find("openstreetmap") != std::string::npos) {
      return true;
    }
  }
  return false;
}

ImageCaption imageCaption(const Tileset& tileset, const BuildingFilters& filters, double timeSeconds,
                          double durationSeconds) {
  const ExportProvenance p = exportProvenance(tileset, filters);
  ImageCaption c;
  c.actual = tileset.response && tileset.response->eventType == "ACTUAL";
  c.lines.push_back("Shaking: " + p.shaking + (p.earthquake.empty() ? "" : " | Earthquake: " + p.earthquake));
  char time[96];
  std::snprintf(time, sizeof time, " | Time: %.1f s of %.1f s", timeSeconds, durationSeconds);
  c.lines.push_back("City: " + (p.city.empty() ? std::string("(unnamed)") : p.city) + time + " | Filter: " + p.filter);
  const bool osm = fromOpenStreetMap(tileset);
  c.lines.push_back("QuakeView" + (p.method.empty() ? std::string() : " (" + p.method + ")") +
                    ": patterns across a city, not a safety assessment" +
                    (osm ? " | Map data © OpenStreetMap contributors (ODbL)" : ""));
  c.fileName = exportFileName(tileset, filters, "view", "png");
  return c;
}

std::string exportCsv(std::span<const BuildingListEntry> buildings, const GeoFrame& geo,
                      const ExportProvenance* provenance) {
  std::string out = preamble("building list", provenance);
  out +=
      "id,name,address,use,importance,damage_state,peak_drift_ratio,peak_roof_displacement_m,pga_g,height_m,storeys,"
      "lon,lat,x_m,y_m,p_none,p_slight,p_moderate,p_extensive,p_complete,p_collapse,expected_damage_state,"
      "p_tag_green,p_tag_yellow,p_tag_red,occupants,occupants_inferred,injuries_1,injuries_2,injuries_3,deaths,"
      "repair_cost_usd,replacement_value_usd,value_inferred,repair_time_days,"
      "site_source,site_pga_g,site_pgv_cms,site_psa03_g,site_psa10_g,site_psa30_g,site_mmi\r\n";
  for (const BuildingListEntry& b : buildings) {
    const auto ll = geo.reverse({b.x, b.y});
    out += csvField(b.id) + ',' + csvField(b.name) + ',' + csvField(b.address) + ',' + csvField(b.use) + ',';
    out += std::string(criticalName(b.facility)) + ',' + std::string(damageStateName(b.damage)) + ',';
    // Peaks exist only for a building with a result: blank otherwise (a zero would read as "no motion").
    if (b.damage != DamageState::NoResult) {
      out += number(b.peakDriftRatio, 6) + ',' + number(b.peakRoofDisplacementM, 4) + ',' + number(b.pgaG, 4) + ',';
    } else {
      out += ",,,";
    }
    out += number(b.heightM, 1) + ',' + (b.storeys > 0 ? std::to_string(b.storeys) : std::string()) + ',';
    out += (ll ? number(ll->lon, 7) : std::string()) + ',' + (ll ? number(ll->lat, 7) : std::string()) + ',';
    out += number(b.x, 2) + ',' + number(b.y, 2);
    // HAZUS columns: left blank (not zero) for a building without probabilities.
    if (b.loss) {
      const BuildingLoss& l = *b.loss;
      for (const float p : l.structural) out += ',' + number(p, 5);
      out += ',' + number(l.collapse, 6) + ',' + number(l.expectedState(), 4);
      for (const float p : l.tag) out += ',' + number(p, 5);
      out += ',' + number(l.occupants, 2) + ',' + ((l.flags & kLossOccupantsInferred) != 0 ? "1" : "0");
      for (const float v : l.injuries) out += ',' + number(v, 5);
      out += ',' + number(l.repairCostUsd, 0) + ',' + number(l.replacementValueUsd, 0) + ',' +
             ((l.flags & kLossValueInferred) != 0 ? "1" : "0") + ',' + number(l.repairTimeDays, 1);
    } else {
      out += std::string(20, ',');
    }
    // The field's own shaking at the site (pga_g above is the scaled record's): blank where not given.
    auto site = [](float v, int decimals) { return std::isnan(v) ? std::string() : number(v, decimals); };
    out += ',' + std::string(b.site.given() ? siteSourceName(b.site.source) : std::string_view()) + ',';
    out += site(b.site.pgaG, 4) + ',' + site(b.site.pgvCmS, 2) + ',' + site(b.site.psa03G, 4) + ',' +
           site(b.site.psa10G, 4) + ',' + site(b.site.psa30G, 4) + ',' + site(b.site.mmi, 2);
    out += "\r\n";
  }
  return out;
}

std::string exportGeoJson(std::span<const BuildingListEntry> buildings, const GeoFrame& geo,
                          const ExportProvenance* provenance) {
  JsonWriter w;
  w.beginObject().field("type", "FeatureCollection");
  if (provenance != nullptr) {
    const ExportProvenance& p = *provenance;
    w.key("quakeview").beginObject().field("city", p.city).field("shaking", p.shaking);
    w.field("earthquake", p.earthquake).field("records", p.records).field("method", p.method);
    w.field("filter", p.filter).field("time_of_day", p.timeOfDay).endObject();
  }
  w.key("features").beginArray();
  for (const BuildingListEntry& b : buildings) {
    const auto ll = geo.reverse({b.x, b.y});
    if (!ll) continue;
    w.breakLine();
    w.beginObject().field("type", "Feature");
    w.key("geometry").beginObject().field("type", "Point");
    w.key("coordinates").beginArray().value(ll->lon).value(ll->lat).endArray();
    w.endObject();
    w.key("properties").beginObject();
    w.field("id", b.id).field("name", b.name).field("address", b.address).field("use", b.use);
    w.field("importance", criticalName(b.facility))
        .field("facility", facilityCategoryName(b.facility))
        .field("damage_state", damageStateName(b.damage));
    if (b.damage != DamageState::NoResult) {
      w.field("peak_drift_ratio", b.peakDriftRatio).field("peak_roof_displacement_m", b.peakRoofDisplacementM);
      w.field("pga_g", b.pgaG);
    } else {
      w.key("peak_drift_ratio").null().key("peak_roof_displacement_m").null().key("pga_g").null();
    }
    if (b.site.given()) {
      w.key("site_shaking").beginObject().field("source", siteSourceName(b.site.source));
      w.field("pga_g", b.site.pgaG).field("pgv_cms", b.site.pgvCmS).field("psa03_g", b.site.psa03G);
      w.field("psa10_g", b.site.psa10G).field("psa30_g", b.site.psa30G).field("mmi", b.site.mmi).endObject();
    } else {
      w.key("site_shaking").null();
    }
    w.field("height_m", b.heightM);
    if (b.storeys > 0) {
      w.field("storeys", static_cast<unsigned>(b.storeys));
    } else {
      w.key("storeys").null();
    }
    w.endObject();
    w.endObject();
  }
  w.endArray().endObject();
  std::string out = w.take();
  out += '\n';
  return out;
}

std::string exportConsequencesCsv(const seismic::ConsequenceTotals& totals, const seismic::LossTotals* view,
                                  const ExportProvenance* provenance, const ViewArea* viewArea) {
  const char* const names[] = {"none",       "slight",     "moderate",   "extensive", "complete",
                               "collapsed",  "tag_green",  "tag_yellow", "tag_red",   "occupants",
                               "injuries_1", "injuries_2", "injuries_3", "deaths",    "repair_cost_usd"};
  std::string out = preamble("consequences", provenance) + "area_kind,area,buildings,time_of_day";
  for (const char* n : names) out += std::string(",") + n + "," + n + "_low," + n + "_high";
  out += ",west,south,east,north\r\n";
  auto row = [&](std::string_view kind, std::string_view area, const seismic::LossTotals& t,
                 const ViewArea* bounds = nullptr) {
    const seismic::Estimate* values[] = {&t.damageStates[0], &t.damageStates[1], &t.damageStates[2], &t.damageStates[3],
                                         &t.damageStates[4], &t.collapsed,       &t.tags[0],         &t.tags[1],
                                         &t.tags[2],         &t.occupants,       &t.injuries[0],     &t.injuries[1],
                                         &t.injuries[2],     &t.injuries[3],     &t.repairCostUsd};
    out +=
        std::string(kind) + ',' + csvField(area) + ',' + std::to_string(t.buildings) + ',' + csvField(totals.timeOfDay);
    for (const seismic::Estimate* e : values) {
      out += ',' + number(e->expected, 4) + ',' + number(e->low, 4) + ',' + number(e->high, 4);
    }
    if (bounds != nullptr) {
      out += ',' + number(bounds->west, 6) + ',' + number(bounds->south, 6) + ',' + number(bounds->east, 6) + ',' +
             number(bounds->north, 6);
    } else {
      out += ",,,,";
    }
    out += "\r\n";
  };
  row("city", "", totals.city);
  if (view != nullptr) row("view", viewArea != nullptr ? viewAreaText(*viewArea) : std::string(), *view, viewArea);
  for (const seismic::ConsequenceTotals::District& d : totals.districts) row("district", d.name, d.totals);
  return out;
}

}  // namespace qv
