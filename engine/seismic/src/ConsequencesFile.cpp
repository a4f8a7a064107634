#include "qv/seismic/ConsequencesFile.h"

#include <simdjson.h>

#include <cmath>
#include <string>

namespace qv::seismic {
namespace {

constexpr const char* kStateKeys[5] = {"none", "slight", "moderate", "extensive", "complete"};
constexpr const char* kTagKeys[3] = {"green", "yellow", "red"};
constexpr const char* kTimeKeys[3] = {"night", "day", "commute"};
constexpr const char* kSeverityKeys[4] = {"severity_1", "severity_2", "severity_3", "severity_4"};

using simdjson::dom::array;
using simdjson::dom::element;
using simdjson::dom::object;

void writeEstimate(JsonWriter& w, std::string_view key, const Estimate& e) {
  w.key(key).beginObject().field("expected", e.expected).field("low", e.low).field("high", e.high).endObject();
}
Result<Estimate> readEstimate(object parent, const char* key, const std::string& where) {
  object o;
  if (parent[key].get(o) != simdjson::SUCCESS) return Error{where + ": missing \"" + key + "\""};
  Estimate e;
  if (o["expected"].get_double().get(e.expected) || o["low"].get_double().get(e.low) ||
      o["high"].get_double().get(e.high)) {
    return Error{where + ": \"" + key + "\" needs numbers expected, low and high"};
  }
  return e;
}
Result<LossTotals> readTotals(object o, const std::string& where) {
  LossTotals t;
  std::uint64_t buildings = 0;
  if (o["buildings"].get_uint64().get(buildings)) return Error{where + ": missing \"buildings\""};
  t.buildings = buildings;
  object states, injuries, tags;
  if (o["damage_states"].get(states) || o["injuries"].get(injuries) || o["tags"].get(tags)) {
    return Error{where + ": missing damage_states, injuries or tags"};
  }
  for (int k = 0; k < 5; ++k) {
    auto e = readEstimate(states, kStateKeys[k], where + " damage_states");
    if (!e.ok()) return Error{e.error()};
    t.damageStates[static_cast<std::size_t>(k)] = *e;
  }
  for (int k = 0; k < 4; ++k) {
    auto e = readEstimate(injuries, kSeverityKeys[k], where + " injuries");
    if (!e.ok()) return Error{e.error()};
    t.injuries[static_cast<std::size_t>(k)] = *e;
  }
  for (int k = 0; k < 3; ++k) {
    auto e = readEstimate(tags, kTagKeys[k], where + " tags");
    if (!e.ok()) return Error{e.error()};
    t.tags[static_cast<std::size_t>(k)] = *e;
  }
  // Written since the panel's headline shows it; older files lack it: the expected value is the
  // states' sum, its interval unknown (NaN).
  if (o["moderate_or_worse"].error() == simdjson::SUCCESS) {
    auto damaged = readEstimate(o, "moderate_or_worse", where);
    if (!damaged.ok()) return Error{damaged.error()};
    t.damaged = *damaged;
  } else {
    t.damaged = {t.damageStates[2].expected + t.damageStates[3].expected + t.damageStates[4].expected, std::nan(""),
                 std::nan("")};
  }
  auto collapsed = readEstimate(o, "collapsed", where);
  auto occupants = readEstimate(o, "occupants", where);
  auto cost = readEstimate(o, "repair_cost_usd", where);
  if (!collapsed.ok()) return Error{collapsed.error()};
  if (!occupants.ok()) return Error{occupants.error()};
  if (!cost.ok()) return Error{cost.error()};
  t.collapsed = *collapsed;
  t.occupants = *occupants;
  t.occupantsAt = {std::nan(""), std::nan(""), std::nan("")};
  object byTime;
  if (o["occupants_by_time"].get(byTime) == simdjson::SUCCESS) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (byTime[kTimeKeys[k]].get_double().get(t.occupantsAt[k])) {
        return Error{where + ": \"occupants_by_time\" needs numbers night, day and commute"};
      }
    }
  }
  t.repairCostUsd = *cost;
  object casualties;
  if (o["casualties_by_time"].get(casualties) == simdjson::SUCCESS) {
    std::array<CasualtiesAtTime, 3> at;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::string here = where + " casualties_by_time " + kTimeKeys[k];
      object time, severities;
      if (casualties[kTimeKeys[k]].get(time) || time["occupants"].get_double().get(at[k].occupants) ||
          time["injuries"].get(severities)) {
        return Error{here + ": needs \"occupants\" and \"injuries\""};
      }
      for (std::size_t s = 0; s < 4; ++s) {
        auto e = readEstimate(severities, kSeverityKeys[s], here + " injuries");
        if (!e.ok()) return Error{e.error()};
        at[k].injuries[s] = *e;
      }
    }
    t.byTime = at;
  }
  return t;
}

void writeClassTotals(JsonWriter& w, const ClassTotals& c) {
  w.field("buildings", c.buildings);
  w.key("damage_states").beginObject();
  for (std::size_t k = 0; k < 5; ++k) w.field(kStateKeys[k], c.damageStates[k]);
  w.endObject();
  w.field("moderate_or_worse", c.damaged).field("collapsed", c.collapsed).field("repair_cost_usd", c.repairCostUsd);
  w.field("occupants", c.occupants);
  w.key("injuries").beginObject();
  for (std::size_t k = 0; k < 4; ++k) w.field(kSeverityKeys[k], c.injuries[k]);
  w.endObject();
}

Result<std::vector<ClassTotals>> readClasses(element root, const char* member, const char* keyName,
                                             const std::string& name) {
  std::vector<ClassTotals> out;
  array rows;
  if (root[member].get(rows) != simdjson::SUCCESS) return out;
  if (rows.size() > 1000) return Error{name + ": more than 1,000 rows in \"" + member + "\""};
  for (element e : rows) {
    const std::string where = name + " " + member + " row " + std::to_string(out.size() + 1);
    object o, states, injuries;
    std::string_view key;
    ClassTotals c;
    if (e.get(o) || o[keyName].get(key) || o["buildings"].get_uint64().get(c.buildings) ||
        o["damage_states"].get(states) || o["injuries"].get(injuries) ||
        o["moderate_or_worse"].get_double().get(c.damaged) || o["collapsed"].get_double().get(c.collapsed) ||
        o["repair_cost_usd"].get_double().get(c.repairCostUsd) || o["occupants"].get_double().get(c.occupants)) {
      return Error{
          where + ": needs \"" + keyName +
          "\", buildings, damage_states, moderate_or_worse, collapsed, repair_cost_usd, occupants and injuries"};
    }
    for (std::size_t k = 0; k < 5; ++k) {
      if (states[kStateKeys[k]].get_double().get(c.damageStates[k]))
        return Error{where + ": damage_states needs numbers"};
    }
    for (std::size_t k = 0; k < 4; ++k) {
      if (injuries[kSeverityKeys[k]].get_double().get(c.injuries[k])) return Error{where + ": injuries needs numbers"};
    }
    c.key = std::string(key);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

void writeLossTotals(JsonWriter& w, const LossTotals& t) {
  w.field("buildings", t.buildings);
  w.key("damage_states").beginObject();
  for (int k = 0; k < 5; ++k) writeEstimate(w, kStateKeys[k], t.damageStates[static_cast<std::size_t>(k)]);
  w.endObject();
  // Read from a file written before it (NaN bounds): left out again, so that it reads back the same.
  if (std::isfinite(t.damaged.low) && std::isfinite(t.damaged.high)) writeEstimate(w, "moderate_or_worse", t.damaged);
  writeEstimate(w, "collapsed", t.collapsed);
  writeEstimate(w, "occupants", t.occupants);
  if (std::isfinite(t.occupantsAt[0])) {
    w.key("occupants_by_time").beginObject();
    for (std::size_t k = 0; k < 3; ++k) w.field(kTimeKeys[k], t.occupantsAt[k]);
    w.endObject();
  }
  w.key("injuries").beginObject();
  for (int k = 0; k < 4; ++k) writeEstimate(w, kSeverityKeys[k], t.injuries[static_cast<std::size_t>(k)]);
  w.endObject();
  writeEstimate(w, "deaths", t.injuries[3]);
  writeEstimate(w, "repair_cost_usd", t.repairCostUsd);
  w.key("tags").beginObject();
  for (int k = 0; k < 3; ++k) writeEstimate(w, kTagKeys[k], t.tags[static_cast<std::size_t>(k)]);
  w.endObject();
  if (t.byTime) {
    w.key("casualties_by_time").beginObject();
    for (std::size_t k = 0; k < 3; ++k) {
      const CasualtiesAtTime& c = (*t.byTime)[k];
      w.key(kTimeKeys[k]).beginObject().field("occupants", c.occupants);
      w.key("injuries").beginObject();
      for (std::size_t s = 0; s < 4; ++s) writeEstimate(w, kSeverityKeys[s], c.injuries[s]);
      w.endObject().endObject();
    }
    w.endObject();
  }
}
std::string consequencesToJson(const ConsequenceTotals& totals) {
  JsonWriter w;
  w.beginObject();
  w.field("format", "quakeview-consequences").field("version", 1);
  w.field("timeOfDay", totals.timeOfDay);
  w.field("interval", "90 % (5th to 95th percentile)");
  if (totals.population.given()) {
    w.key("population").beginObject();
    if (totals.population.night >= 0) w.field("night", totals.population.night);
    if (totals.population.day >= 0) w.field("day", totals.population.day);
    if (!totals.population.source.empty()) w.field("source", totals.population.source);
    w.endObject();
  }
  w.key("city").beginObject();
  writeLossTotals(w, totals.city);
  w.endObject();
  w.key("districts").beginArray();
  for (const ConsequenceTotals::District& d : totals.districts) {
    w.beginObject().field("name", d.name);
    writeLossTotals(w, d.totals);
    if (!d.outline.empty()) {
      // Degrees to 1e-6 (about 0.1 m): the outline is for maps.
      const auto round6 = [](double v) { return std::round(v * 1e6) / 1e6; };
      w.key("outline").beginArray();
      for (const auto& ring : d.outline) {
        w.beginArray();
        for (const auto& point : ring) w.beginArray().value(round6(point[0])).value(round6(point[1])).endArray();
        w.endArray();
      }
      w.endArray();
    }
    w.endObject();
  }
  w.endArray();
  if (!totals.districtsSource.empty()) {
    w.field("districts_source", totals.districtsSource).field("districts_inferred", totals.districtsInferred);
  }
  const auto writeClasses = [&w](const char* member, const char* keyName, const std::vector<ClassTotals>& rows) {
    if (rows.empty()) return;
    w.key(member).beginArray();
    for (const ClassTotals& c : rows) {
      w.beginObject().field(keyName, c.key);
      writeClassTotals(w, c);
      w.endObject();
    }
    w.endArray();
  };
  writeClasses("by_occupancy", "class", totals.byOccupancy);
  writeClasses("by_structure", "type", totals.byStructure);
  if (totals.inferred) {
    const InferredCounts& i = *totals.inferred;
    w.key("inferred").beginObject().field("buildings", i.buildings).field("structural_type", i.structuralType);
    w.field("code_era", i.codeEra).field("use", i.use).field("occupants", i.occupants);
    w.field("replacement_value", i.replacementValue).endObject();
  }
  w.endObject();
  return w.take();
}
Result<ConsequenceTotals> parseConsequences(std::string_view json, const std::string& name) {
  simdjson::dom::parser parser;
  element root;
  if (auto error = parser.parse(json.data(), json.size()).get(root)) {
    return Error{name + ": not valid JSON (" + simdjson::error_message(error) + ")"};
  }
  ConsequenceTotals out;
  std::string_view timeOfDay;
  object city;
  array districts;
  if (root["timeOfDay"].get(timeOfDay) || root["city"].get(city) || root["districts"].get(districts)) {
    return Error{name + ": missing timeOfDay, city or districts"};
  }
  out.timeOfDay = std::string(timeOfDay);
  object population;
  if (root["population"].get(population) == simdjson::SUCCESS) {
    for (const char* key : {"night", "day"}) {
      double v = 0;
      if (population[key].get_double().get(v) != simdjson::SUCCESS) continue;
      if (!(v >= 0 && v < 1e10)) return Error{name + ": population \"" + key + "\" must be a count of people"};
      (key[0] == 'n' ? out.population.night : out.population.day) = v;
    }
    std::string_view source;
    if (population["source"].get(source) == simdjson::SUCCESS) out.population.source = std::string(source);
  }
  auto c = readTotals(city, name + " city");
  if (!c.ok()) return Error{c.error()};
  out.city = *c;
  if (districts.size() > 10000) return Error{name + ": more than 10,000 districts"};
  for (element e : districts) {
    object d;
    std::string_view districtName;
    if (e.get(d) || d["name"].get(districtName)) return Error{name + ": a district without a name"};
    const std::string where = name + " district " + std::string(districtName);
    auto t = readTotals(d, where);
    if (!t.ok()) return Error{t.error()};
    ConsequenceTotals::District district{std::string(districtName), *t, {}};
    array rings;
    if (d["outline"].get(rings) == simdjson::SUCCESS) {
      std::size_t points = 0;
      if (rings.size() > 1000) return Error{where + ": \"outline\" has more than 1,000 rings"};
      for (element ringElement : rings) {
        array ring;
        if (ringElement.get(ring) || ring.size() < 3) {
          return Error{where + ": each ring of \"outline\" is a list of at least 3 [lon, lat] points"};
        }
        points += ring.size();
        if (points > 20000) return Error{where + ": \"outline\" has more than 20,000 points"};
        auto& kept = district.outline.emplace_back();
        for (element pointElement : ring) {
          array point;
          double lon = 0, lat = 0;
          if (pointElement.get(point) || point.size() != 2 || point.at(0).get_double().get(lon) ||
              point.at(1).get_double().get(lat) || !(std::abs(lon) <= 180.0) || !(std::abs(lat) <= 90.0)) {
            return Error{where + ": an \"outline\" point is not [lon, lat] in degrees"};
          }
          kept.push_back({lon, lat});
        }
      }
    }
    out.districts.push_back(std::move(district));
  }
  // Optional (files before them have neither).
  std::string_view districtsSource;
  if (root["districts_source"].get(districtsSource) == simdjson::SUCCESS) {
    if (districtsSource.size() > 1000) return Error{name + ": \"districts_source\" is longer than 1,000 bytes"};
    out.districtsSource = std::string(districtsSource);
  }
  element districtsInferred;
  if (root["districts_inferred"].get(districtsInferred) == simdjson::SUCCESS &&
      districtsInferred.get(out.districtsInferred) != simdjson::SUCCESS) {
    return Error{name + ": \"districts_inferred\" must be true or false"};
  }
  auto byOccupancy = readClasses(root, "by_occupancy", "class", name);
  if (!byOccupancy.ok()) return Error{byOccupancy.error()};
  out.byOccupancy = std::move(byOccupancy).value();
  auto byStructure = readClasses(root, "by_structure", "type", name);
  if (!byStructure.ok()) return Error{byStructure.error()};
  out.byStructure = std::move(byStructure).value();
  object inferred;
  if (root["inferred"].get(inferred) == simdjson::SUCCESS) {
    InferredCounts i;
    if (inferred["buildings"].get_uint64().get(i.buildings) ||
        inferred["structural_type"].get_uint64().get(i.structuralType) ||
        inferred["code_era"].get_uint64().get(i.codeEra) || inferred["use"].get_uint64().get(i.use) ||
        inferred["occupants"].get_uint64().get(i.occupants) ||
        inferred["replacement_value"].get_uint64().get(i.replacementValue)) {
      return Error{name +
                   ": \"inferred\" needs counts buildings, structural_type, code_era, use, occupants and "
                   "replacement_value"};
    }
    out.inferred = i;
  }
  return out;
}

}  // namespace qv::seismic
