#include "qv/scene/ViewConsequences.h"

#include <algorithm>
#include <cmath>

#include "qv/core/JsonWriter.h"

namespace qv {
namespace {

// z of the 95th percentile of the standard normal: a two-sided 90 % interval.
constexpr double kZ90 = 1.6448536269514722;

seismic::Estimate estimate(double mean, double variance, double upper) {
  const double half = kZ90 * std::sqrt(std::max(variance, 0.0));
  return {mean, std::max(0.0, mean - half), std::min(upper, mean + half)};
}

}  // namespace

void ConsequenceSums::add(const BuildingLoss& loss) {
  ++buildings_;
  auto bernoulli = [](double p) { return p * (1.0 - p); };
  for (std::size_t k = 0; k < 5; ++k) {
    const double p = loss.structural[k];
    states_[k].add(p, bernoulli(p));
  }
  const double damaged = loss.structural[2] + loss.structural[3] + loss.structural[4];
  damaged_.add(damaged, bernoulli(damaged));
  collapsed_.add(loss.collapse, bernoulli(loss.collapse));
  for (std::size_t k = 0; k < 3; ++k) tags_[k].add(loss.tag[k], bernoulli(loss.tag[k]));
  cost_.add(loss.repairCostUsd, static_cast<double>(loss.repairCostStdUsd) * loss.repairCostStdUsd);
  for (std::size_t k = 0; k < 4; ++k) {
    injuries_[k].add(loss.injuries[k], static_cast<double>(loss.injuriesStd[k]) * loss.injuriesStd[k]);
  }
  occupants_ += loss.occupants;
}

seismic::LossTotals ConsequenceSums::totals() const {
  seismic::LossTotals t;
  t.buildings = buildings_;
  const auto n = static_cast<double>(buildings_);
  for (std::size_t k = 0; k < 5; ++k) t.damageStates[k] = estimate(states_[k].mean, states_[k].variance, n);
  t.damaged = estimate(damaged_.mean, damaged_.variance, n);
  t.collapsed = estimate(collapsed_.mean, collapsed_.variance, n);
  for (std::size_t k = 0; k < 3; ++k) t.tags[k] = estimate(tags_[k].mean, tags_[k].variance, n);
  t.repairCostUsd = estimate(cost_.mean, cost_.variance, HUGE_VAL);
  for (std::size_t k = 0; k < 4; ++k) t.injuries[k] = estimate(injuries_[k].mean, injuries_[k].variance, HUGE_VAL);
  t.occupants = {occupants_, occupants_, occupants_};
  return t;
}

namespace {

void writeEstimate(JsonWriter& w, std::string_view key, const seismic::Estimate& e) {
  w.key(key).beginObject().field("expected", e.expected).field("low", e.low).field("high", e.high).endObject();
}

void writeTotals(JsonWriter& w, const seismic::LossTotals& t) {
  static const char* const states[5] = {"none", "slight", "moderate", "extensive", "complete"};
  static const char* const tags[3] = {"green", "yellow", "red"};
  static const char* const severities[4] = {"severity1", "severity2", "severity3", "severity4"};
  w.field("buildings", t.buildings);
  w.key("damageStates").beginObject();
  for (std::size_t k = 0; k < 5; ++k) writeEstimate(w, states[k], t.damageStates[k]);
  w.endObject();
  writeEstimate(w, "moderateOrWorse", t.damaged);
  writeEstimate(w, "collapsed", t.collapsed);
  writeEstimate(w, "occupants", t.occupants);
  w.key("injuries").beginObject();
  for (std::size_t k = 0; k < 4; ++k) writeEstimate(w, severities[k], t.injuries[k]);
  w.endObject();
  writeEstimate(w, "deaths", t.injuries[3]);
  writeEstimate(w, "repairCostUsd", t.repairCostUsd);
  w.key("tags").beginObject();
  for (std::size_t k = 0; k < 3; ++k) writeEstimate(w, tags[k], t.tags[k]);
  w.endObject();
}

}  // namespace

std::string viewAreaText(const ViewArea& a) {
  char text[96];
  std::snprintf(text, sizeof text, "lon %.5f..%.5f, lat %.5f..%.5f", a.west, a.east, a.south, a.north);
  return text;
}

std::string consequencesJson(const ResponseInfo* response, const seismic::ConsequenceTotals* file,
                             const seismic::LossTotals* view, const ViewArea* viewArea) {
  if (response == nullptr) return "null";
  JsonWriter w;
  w.beginObject();
  if (response->eventType.empty()) {
    w.key("eventType").null();
  } else {
    w.field("eventType", response->eventType);
  }
  w.field("shakingField", response->shakingField);
  if (response->shakemap) {
    const ResponseInfo::ShakeMap& m = *response->shakemap;
    w.key("shakemap").beginObject().field("eventId", m.eventId).field("version", m.version);
    w.field("processTimestamp", m.processTimestamp).field("eventTimestamp", m.eventTimestamp);
    w.field("description", m.description).endObject();
  } else {
    w.key("shakemap").null();
  }
  w.field("timeOfDay", file != nullptr ? file->timeOfDay : response->timeOfDay);
  if (file != nullptr) {
    w.key("city").beginObject();
    writeTotals(w, file->city);
    w.endObject();
  } else {
    w.key("city").null();
  }
  if (view != nullptr && file != nullptr) {
    w.key("view").beginObject();
    writeTotals(w, *view);
    if (viewArea != nullptr) {
      w.key("bounds").beginObject().field("west", viewArea->west).field("south", viewArea->south);
      w.field("east", viewArea->east).field("north", viewArea->north).endObject();
    } else {
      w.key("bounds").null();
    }
    w.endObject();
  } else {
    w.key("view").null();
  }
  w.key("districts").beginArray();
  if (file != nullptr) {
    for (const seismic::ConsequenceTotals::District& d : file->districts) {
      w.beginObject().field("name", d.name);
      writeTotals(w, d.totals);
      w.endObject();
    }
  }
  w.endArray();
  // What the districts are, and whether they are inferred (nearest place names, no drawn boundary).
  if (file != nullptr && !file->districtsSource.empty()) {
    w.field("districtsSource", file->districtsSource).field("districtsInferred", file->districtsInferred);
  } else {
    w.key("districtsSource").null();
    w.field("districtsInferred", false);
  }
  w.endObject();
  return w.take();
}

}  // namespace qv
