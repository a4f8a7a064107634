#include "qv/scene/Export.h"

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

}  // namespace

std::string exportCsv(std::span<const BuildingListEntry> buildings, const GeoFrame& geo) {
  std::string out =
      "id,name,address,use,importance,damage_state,peak_drift_ratio,peak_roof_displacement_m,pga_g,height_m,storeys,"
      "lon,lat,x_m,y_m,p_none,p_slight,p_moderate,p_extensive,p_complete,p_collapse,expected_damage_state,"
      "p_tag_green,p_tag_yellow,p_tag_red,occupants,occupants_inferred,injuries_1,injuries_2,injuries_3,deaths,"
      "repair_cost_usd,replacement_value_usd,value_inferred,repair_time_days\r\n";
  for (const BuildingListEntry& b : buildings) {
    const auto ll = geo.reverse({b.x, b.y});
    out += csvField(b.id) + ',' + csvField(b.name) + ',' + csvField(b.address) + ',' + csvField(b.use) + ',';
    out += std::string(importanceName(b.importance)) + ',' + std::string(damageStateName(b.damage)) + ',';
    out += number(b.peakDriftRatio, 6) + ',' + number(b.peakRoofDisplacementM, 4) + ',' + number(b.pgaG, 4) + ',';
    out += number(b.heightM, 1) + ',' + std::to_string(b.storeys) + ',';
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
    out += "\r\n";
  }
  return out;
}

std::string exportGeoJson(std::span<const BuildingListEntry> buildings, const GeoFrame& geo) {
  JsonWriter w;
  w.beginObject().field("type", "FeatureCollection").key("features").beginArray();
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
    w.field("importance", importanceName(b.importance)).field("damage_state", damageStateName(b.damage));
    w.field("peak_drift_ratio", b.peakDriftRatio).field("peak_roof_displacement_m", b.peakRoofDisplacementM);
    w.field("pga_g", b.pgaG).field("height_m", b.heightM).field("storeys", static_cast<unsigned>(b.storeys));
    w.endObject();
    w.endObject();
  }
  w.endArray().endObject();
  std::string out = w.take();
  out += '\n';
  return out;
}

std::string exportConsequencesCsv(const seismic::ConsequenceTotals& totals, const seismic::LossTotals* view) {
  const char* const names[] = {"none",       "slight",     "moderate",   "extensive", "complete",
                               "collapsed",  "tag_green",  "tag_yellow", "tag_red",   "occupants",
                               "injuries_1", "injuries_2", "injuries_3", "deaths",    "repair_cost_usd"};
  std::string out = "area_kind,area,buildings,time_of_day";
  for (const char* n : names) out += std::string(",") + n + "," + n + "_low," + n + "_high";
  out += "\r\n";
  auto row = [&](std::string_view kind, std::string_view area, const seismic::LossTotals& t) {
    const seismic::Estimate* values[] = {&t.damageStates[0], &t.damageStates[1], &t.damageStates[2], &t.damageStates[3],
                                         &t.damageStates[4], &t.collapsed,       &t.tags[0],         &t.tags[1],
                                         &t.tags[2],         &t.occupants,       &t.injuries[0],     &t.injuries[1],
                                         &t.injuries[2],     &t.injuries[3],     &t.repairCostUsd};
    out +=
        std::string(kind) + ',' + csvField(area) + ',' + std::to_string(t.buildings) + ',' + csvField(totals.timeOfDay);
    for (const seismic::Estimate* e : values) {
      out += ',' + number(e->expected, 4) + ',' + number(e->low, 4) + ',' + number(e->high, 4);
    }
    out += "\r\n";
  };
  row("city", "", totals.city);
  if (view != nullptr) row("view", "", *view);
  for (const seismic::ConsequenceTotals::District& d : totals.districts) row("district", d.name, d.totals);
  return out;
}

}  // namespace qv
