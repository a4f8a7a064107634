// Entry point of the browser app (quakeview-engine.js/.wasm) and the C functions behind the
// `window.quakeview` API. The shell (web/quakeview.js) passes the page's URL options as
// arguments and wraps these functions; strings returned stay valid until the next call.
#include <emscripten.h>

#include <string>
#include <vector>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "App.h"
#include "qv/core/JsonWriter.h"
#include "qv/scene/Export.h"

namespace {
qv::App* gApp = nullptr;
std::string gReturned;  // backing store of the last string handed to JavaScript

const char* hand(std::string text) {
  gReturned = std::move(text);
  return gReturned.c_str();
}
}  // namespace

extern "C" {

EMSCRIPTEN_KEEPALIVE const char* qv_stats_json() {
  if (gApp == nullptr) return hand("null");
  return hand(gApp->statsJson(qv::browser::memoryInfo()));
}

EMSCRIPTEN_KEEPALIVE const char* qv_errors_json() {
  if (gApp == nullptr) return hand("[]");
  qv::JsonWriter w;
  w.beginArray();
  for (const std::string& e : gApp->viewer().errors()) w.value(e);
  w.endArray();
  return hand(w.take());
}

EMSCRIPTEN_KEEPALIVE const char* qv_ui_text() {
  if (gApp == nullptr) return hand("");
  return hand(gApp->uiText());
}

/// The panels' accessible outline, {"revision": n, "sections": [{heading, lines}]} (TextMirror.h).
EMSCRIPTEN_KEEPALIVE const char* qv_ui_outline_json() {
  if (gApp == nullptr) return hand("null");
  return hand(gApp->uiOutlineJson().empty() ? std::string("null") : gApp->uiOutlineJson());
}

/// The outline's revision: grows when its content changes (cheap to poll).
EMSCRIPTEN_KEEPALIVE double qv_ui_outline_revision() {
  return gApp == nullptr ? 0.0 : static_cast<double>(gApp->uiOutlineRevision());
}

/// The control showing the keyboard focus ("Export CSV, button"), or "".
EMSCRIPTEN_KEEPALIVE const char* qv_ui_focus() {
  if (gApp == nullptr) return hand("");
  return hand(gApp->focusedControl());
}

/// Where the windows and their buttons, headers and checkboxes are (TextMirror::layoutJson).
EMSCRIPTEN_KEEPALIVE const char* qv_ui_layout() {
  if (gApp == nullptr) return hand("null");
  return hand(gApp->uiLayoutJson());
}

/// [x, y] in CSS pixels of a city-frame point, or null when it is behind the eye.
EMSCRIPTEN_KEEPALIVE const char* qv_world_to_screen(double x, double y, double z) {
  if (gApp == nullptr) return hand("null");
  const auto p = gApp->viewer().worldToScreen(x, y, z);
  if (!p) return hand("null");
  qv::JsonWriter w;
  w.beginArray().value(p->x).value(p->y).endArray();
  return hand(w.take());
}

EMSCRIPTEN_KEEPALIVE const char* qv_get_camera_json() {
  if (gApp == nullptr) return hand("null");
  return hand(gApp->viewer().cameraJson());
}

/// Sets the camera; the shell fills fields the caller left out with the current values.
/// Returns 1 when every value was valid, 0 when some were replaced (non-finite or out of range).
EMSCRIPTEN_KEEPALIVE int qv_set_camera(double x, double y, double distance, double headingDeg, double pitchDeg,
                                       double fovDeg) {
  if (gApp == nullptr) return 0;
  return gApp->viewer().setCamera(qv::CameraState{x, y, distance, headingDeg, pitchDeg, fovDeg}) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE int qv_set_time(double seconds) {
  return gApp != nullptr && gApp->viewer().setTime(seconds) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE double qv_time() {
  return gApp == nullptr ? 0.0 : gApp->viewer().time();
}

EMSCRIPTEN_KEEPALIVE double qv_duration() {
  return gApp == nullptr ? 0.0 : gApp->viewer().duration();
}

EMSCRIPTEN_KEEPALIVE void qv_play() {
  if (gApp != nullptr) gApp->viewer().play();
}

EMSCRIPTEN_KEEPALIVE void qv_pause() {
  if (gApp != nullptr) gApp->viewer().pause();
}

EMSCRIPTEN_KEEPALIVE int qv_playing() {
  return gApp != nullptr && gApp->viewer().playing() ? 1 : 0;
}

/// The building under a canvas point (CSS pixels), as JSON, or null.
EMSCRIPTEN_KEEPALIVE const char* qv_pick(double x, double y) {
  if (gApp == nullptr) return hand("null");
  const auto info = gApp->viewer().pick(x, y);
  return hand(info ? qv::buildingInfoJson(*info) : std::string("null"));
}

EMSCRIPTEN_KEEPALIVE const char* qv_building(const char* id) {
  if (gApp == nullptr || id == nullptr) return hand("null");
  const auto info = gApp->viewer().building(id);
  return hand(info ? qv::buildingInfoJson(*info) : std::string("null"));
}

/// Draws a frame now (quakeview.screenshot() then reads the canvas in the same task).
/// The 2D city without WebGL2 (App::map2d, qv/scene/Map2d.h): qv_map2d() makes this frame's shapes
/// and returns where their floats start in the heap, qv_map2d_floats() how many there are.
EMSCRIPTEN_KEEPALIVE int qv_map2d_mode() {
  return gApp != nullptr && gApp->map2dMode() ? 1 : 0;
}
EMSCRIPTEN_KEEPALIVE const float* qv_map2d() {
  if (gApp == nullptr) return nullptr;
  return gApp->map2d().data.data();
}
EMSCRIPTEN_KEEPALIVE int qv_map2d_floats() {
  if (gApp == nullptr) return 0;
  return static_cast<int>(gApp->lastMap2d().data.size());  // of the last qv_map2d()
}

/// The palette for the 2D city's legend (qv/scene/Palette.h): {"ramp": [5 stops], "tags": [green,
/// yellow, red], "noResult", "dimmed", "selected"}, each "#rrggbb".
EMSCRIPTEN_KEEPALIVE const char* qv_palette_json() {
  const auto hex = [](qv::Rgb c) {
    char buffer[8];
    std::snprintf(buffer, sizeof buffer, "#%06x", qv::packRgb(c));
    return std::string(buffer);
  };
  qv::JsonWriter w;
  w.beginObject().key("ramp").beginArray();
  for (const qv::Rgb& c : qv::kDamagePalette) w.value(hex(c));
  w.endArray().key("tags").beginArray();
  for (const qv::Rgb& c : qv::kTagPalette) w.value(hex(c));
  w.endArray().field("noResult", hex(qv::kNoResultColor)).field("dimmed", hex(qv::kDimmedColor));
  w.field("selected", hex(qv::kSelectedColor)).endObject();
  return hand(w.take());
}

EMSCRIPTEN_KEEPALIVE void qv_draw_now() {
  if (gApp != nullptr) gApp->frame(true);
}

/// The caption of a picture of the view (quakeview.screenshot()): {"actual", "lines", "fileName"}
/// (qv::imageCaption); "null" before a city is loaded.
EMSCRIPTEN_KEEPALIVE const char* qv_image_caption() {
  if (gApp == nullptr) return hand("null");
  qv::CityScene* city = gApp->viewer().city();
  const qv::Tileset* tileset = city != nullptr ? city->tileset() : nullptr;
  if (tileset == nullptr) return hand("null");
  const qv::ImageCaption c =
      qv::imageCaption(*tileset, city->filters(), gApp->viewer().time(), gApp->viewer().duration());
  qv::JsonWriter w;
  w.beginObject().field("actual", c.actual).key("lines").beginArray();
  for (const std::string& line : c.lines) w.value(line);
  w.endArray().field("fileName", c.fileName).endObject();
  return hand(w.take());
}

/// `quakeview.report()`: the situation report's HTML (qv::situationReportHtml, the same document as
/// `quakeview-prep report`); "" while the city's index and totals are loading, or without a city.
EMSCRIPTEN_KEEPALIVE const char* qv_report() {
  if (gApp == nullptr) return hand("");
  const qv::CityScene* city = gApp->viewer().city();
  if (city == nullptr) return hand("");
  return hand(city->situationReport().value_or(""));
}

/// `quakeview.consequences()`: the totals of the city (consequences.json), of the view and of each
/// district, with the shaking's provenance (qv/scene/ViewConsequences.h); "null" without a response.
EMSCRIPTEN_KEEPALIVE const char* qv_consequences() {
  if (gApp == nullptr) return hand("null");
  qv::CityScene* city = gApp->viewer().city();
  const qv::Tileset* tileset = city != nullptr ? city->tileset() : nullptr;
  if (tileset == nullptr || !tileset->response) return hand("null");
  const qv::seismic::LossTotals view = city->consequencesInView();
  const std::optional<qv::ViewArea> area = gApp->viewer().viewArea();
  // While the view's losses are still loading (from the city index), the view is null, not zeros.
  return hand(qv::consequencesJson(&*tileset->response, city->consequences(),
                                   city->consequencesInViewComplete() ? &view : nullptr, area ? &*area : nullptr));
}

namespace {
const char* switchStateName(qv::ScenarioSwitch::State state) {
  switch (state) {
    case qv::ScenarioSwitch::State::Checking:
      return "checking";
    case qv::ScenarioSwitch::State::Loading:
      return "loading";
    case qv::ScenarioSwitch::State::Loaded:
      return "loaded";
    case qv::ScenarioSwitch::State::Failed:
      return "failed";
    default:
      return "none";
  }
}
}  // namespace

/// `quakeview.map()`: the map under the city: {"layer": "none" (no ground layer: --no-ground or an
/// older tool) | "empty" (the input had no streets, water or open land) | "present", "cells": files
/// in the pyramid, "cellsDrawn", "cellsLoaded", "cellsFailed", "triangles": the map's triangles in
/// the last frame, "bytes": all ground files, "features": {class: count}, "skipped": {reason:
/// count}, "labels": [{text, kind, x, y, width, height, angleDeg, facility}] the names drawn in the last frame
/// (CSS pixels)}; null without a city manifest.
EMSCRIPTEN_KEEPALIVE const char* qv_map_json() {
  if (gApp == nullptr) return hand("null");
  const qv::CityScene* city = gApp->viewer().city();
  const qv::Tileset* tileset = city != nullptr ? city->tileset() : nullptr;
  if (tileset == nullptr) return hand("null");
  qv::JsonWriter w;
  w.beginObject();
  w.field("layer", !tileset->ground ? "none" : tileset->ground->nodes.empty() ? "empty" : "present");
  const qv::GroundScene* ground = city->ground();
  w.field("cells", static_cast<double>(tileset->ground ? tileset->ground->nodes.size() : 0));
  w.field("cellsDrawn", static_cast<double>(ground != nullptr ? ground->cellsDrawn() : 0));
  w.field("cellsLoaded", static_cast<double>(ground != nullptr ? ground->cellsLoaded() : 0));
  w.field("cellsFailed", static_cast<double>(ground != nullptr ? ground->cellsFailed() : 0));
  w.field("triangles", static_cast<double>(ground != nullptr ? ground->trianglesDrawn() : 0));
  w.field("bytes", static_cast<double>(tileset->ground ? tileset->ground->bytes : 0));
  w.key("features").beginObject();
  if (tileset->ground) {
    for (const auto& [name, n] : tileset->ground->features) w.field(name.c_str(), static_cast<double>(n));
  }
  w.endObject();
  w.key("skipped").beginObject();
  if (tileset->ground) {
    for (const auto& [name, n] : tileset->ground->skipped) w.field(name.c_str(), static_cast<double>(n));
  }
  w.endObject();
  w.key("labels").beginArray();
  for (const qv::ControlPanel::ShownMapLabel& l : gApp->panel().shownMapLabels()) {
    w.beginObject();
    w.field("text", l.text).field("kind", std::string(qv::groundLabelKindName(l.kind)));
    w.field("x", static_cast<double>(l.x)).field("y", static_cast<double>(l.y));
    w.field("width", static_cast<double>(l.width)).field("height", static_cast<double>(l.height));
    w.field("angleDeg", static_cast<double>(l.angleDeg)).field("facility", l.facility);
    w.endObject();
  }
  w.endArray();
  w.endObject();
  return hand(w.take());
}

/// `quakeview.scenarios()`: the city folder's scenario catalogue as the viewer knows it
/// (qv::CityScenarios): {"catalogue": "loading" | "none" (no catalogue, no city, or its manifest
/// failed) | "loaded" | "failed", "manifestUrl": the manifest shown, "scenarios":
/// [{index, name, manifest, current, state, eventType, earthquake, sameResultsAsOpen}], "switch":
/// {serial, index, state: "none" | "checking" | "loading" | "loaded" | "failed", problem}}.
EMSCRIPTEN_KEEPALIVE const char* qv_scenarios_json() {
  if (gApp == nullptr) return hand("null");
  const qv::Viewer& viewer = gApp->viewer();
  const qv::CityScenarios* scenarios = viewer.scenarios();
  qv::JsonWriter w;
  w.beginObject().key("catalogue");
  if (scenarios != nullptr) {
    using State = qv::CityScenarios::CatalogueState;
    const State s = scenarios->state();
    w.value(s == State::Loading ? "loading" : s == State::Absent ? "none" : s == State::Loaded ? "loaded" : "failed");
  } else {
    // Requested once the city's manifest has loaded; none without a city or when it failed.
    const qv::CityScene* city = viewer.city();
    w.value(city == nullptr || city->manifestFailed() ? "none" : "loading");
  }
  w.field("manifestUrl", viewer.manifestUrl());
  w.key("scenarios").beginArray();
  if (scenarios != nullptr) {
    const qv::ScenarioStatus* current = scenarios->current();
    for (const qv::ScenarioStatus& s : scenarios->scenarios()) {
      w.beginObject().field("index", s.entry.index).field("name", s.entry.name).field("manifest", s.entry.manifest);
      w.field("current", &s == current).field("state", qv::scenarioStateName(s.state));
      // SCENARIO or ACTUAL once its manifest has been read; null before, or when it does not say.
      if (s.state == qv::ScenarioState::Ready && !s.eventType.empty())
        w.field("eventType", s.eventType);
      else
        w.key("eventType").null();
      w.field("earthquake", s.earthquake).field("sameResultsAsOpen", s.sameResultsAsOpen);
      if (!s.problem.empty()) w.field("problem", s.problem);
      w.endObject();
    }
  }
  w.endArray();
  const qv::ScenarioSwitch& sw = viewer.scenarioSwitch();
  w.key("switch").beginObject().field("serial", sw.serial).field("index", sw.index);
  w.field("state", switchStateName(sw.state)).field("problem", sw.problem).endObject();
  w.endObject();
  return hand(w.take());
}

/// The address of the manifest shown (the page's ?data= follows it).
EMSCRIPTEN_KEEPALIVE const char* qv_manifest_url() {
  if (gApp == nullptr) return hand("");
  return hand(gApp->viewer().manifestUrl());
}

/// Starts showing scenario `index` (qv::Viewer::selectScenario): {"serial": n} to follow in
/// qv_scenarios_json's "switch", or {"problem": "..."} when the catalogue has no such scenario.
EMSCRIPTEN_KEEPALIVE const char* qv_select_scenario(double index) {
  if (gApp == nullptr) return hand("{\"problem\":\"the viewer has not started\"}");
  std::string problem;
  const bool valid =
      std::isfinite(index) && index >= 1.0 && index <= qv::kMaxScenarioIndex && std::floor(index) == index;
  const std::uint64_t serial = valid ? gApp->viewer().selectScenario(static_cast<std::uint32_t>(index), &problem) : 0;
  if (!valid) problem = "a scenario's index is a whole number from 1";
  qv::JsonWriter w;
  w.beginObject();
  if (serial > 0)
    w.field("serial", serial);
  else
    w.field("problem", problem);
  w.endObject();
  return hand(w.take());
}

EMSCRIPTEN_KEEPALIVE int qv_select(const char* id) {
  return gApp != nullptr && id != nullptr && gApp->viewer().select(id) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE const char* qv_selection() {
  if (gApp == nullptr) return hand("");
  return hand(gApp->viewer().selection());
}

EMSCRIPTEN_KEEPALIVE int qv_fly_to_selection() {
  return gApp != nullptr && gApp->viewer().flyToSelection() ? 1 : 0;
}

/// Flies to the consequences' district `name` and outlines it ("" clears); 0 when unknown.
EMSCRIPTEN_KEEPALIVE int qv_show_district(const char* name) {
  return gApp != nullptr && name != nullptr && gApp->viewer().showDistrict(name) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE const char* qv_shown_district() {
  if (gApp == nullptr) return hand("");
  return hand(gApp->viewer().shownDistrict());
}

/// Amplitude exaggeration of displayed displacements, 1 … 200 as the panel's slider; 0 when out of
/// range (nothing changes).
EMSCRIPTEN_KEEPALIVE int qv_set_amplitude(double amplitude) {
  if (gApp == nullptr || !std::isfinite(amplitude) || amplitude < 1.0 || amplitude > 200.0) return 0;
  gApp->viewer().setAmplitude(static_cast<float>(amplitude));
  return 1;
}

EMSCRIPTEN_KEEPALIVE double qv_amplitude() {
  return gApp != nullptr ? static_cast<double>(gApp->viewer().amplitude()) : 0.0;
}

/// Colour mode: 0 current drift, 1 peak drift, 2 damage state, 3 neutral, 4 P(>= moderate), 5 expected
/// damage state, 6 inspection tag (qv::ColorMode); 0 when out of range.
EMSCRIPTEN_KEEPALIVE int qv_set_color_mode(int mode) {
  if (gApp == nullptr || mode < 0 || mode >= qv::kColorModeCount) return 0;
  gApp->viewer().setColorMode(static_cast<qv::ColorMode>(mode));
  return 1;
}

EMSCRIPTEN_KEEPALIVE int qv_color_mode() {
  return gApp != nullptr ? static_cast<int>(gApp->viewer().colorMode()) : -1;
}

/// The mode the city is drawn in now (qv::Viewer::shownColorMode).
EMSCRIPTEN_KEEPALIVE int qv_shown_color_mode() {
  return gApp != nullptr ? static_cast<int>(gApp->viewer().shownColorMode()) : -1;
}

/// LOD1 and LOD2 buildings shown (1) or hidden (0), as the General panel's switches. Returns 0
/// when there is no city.
EMSCRIPTEN_KEEPALIVE int qv_set_lod_visibility(int lod1, int lod2) {
  if (gApp == nullptr || gApp->viewer().city() == nullptr) return 0;
  gApp->viewer().city()->setLodVisibility(lod1 != 0, lod2 != 0);
  return 1;
}

EMSCRIPTEN_KEEPALIVE const char* qv_lod_visibility_json() {
  if (gApp == nullptr || gApp->viewer().city() == nullptr) return hand("null");
  qv::JsonWriter w;
  w.beginObject().field("lod1", gApp->viewer().city()->showLod1()).field("lod2", gApp->viewer().city()->showLod2());
  w.endObject();
  return hand(w.take());
}

/// Filters: minDamage -1..4, use ("" any; several joined by '+'), critical 0/1, categories
/// (FacilityCategory names joined by '+', "" none; unknown names are ignored), the probability
/// filter: P(structural damage >= probabilityState) at least minPercent % (state 1..4 and percent
/// 1..100, else off). Returns 0 when there is no city.
EMSCRIPTEN_KEEPALIVE int qv_set_filters(int minDamage, const char* use, int critical, const char* categories,
                                        int probabilityState, int minPercent) {
  if (gApp == nullptr || gApp->viewer().city() == nullptr || use == nullptr || categories == nullptr) return 0;
  qv::BuildingFilters f;
  f.minDamage = minDamage < 0 || minDamage > 4 ? -1 : minDamage;
  if (probabilityState >= 1 && probabilityState <= 4 && minPercent >= 1 && minPercent <= 100) {
    f.probabilityState = probabilityState;
    f.minProbabilityPercent = minPercent;
  }
  f.use = use;
  f.criticalOnly = critical != 0;
  for (std::string_view rest = categories; !rest.empty();) {
    const std::size_t plus = rest.find('+');
    if (const auto c = qv::parseFacilityCategory(rest.substr(0, plus))) f.categories |= qv::facilityCategoryBit(*c);
    rest = plus == std::string_view::npos ? std::string_view() : rest.substr(plus + 1);
  }
  gApp->viewer().city()->setFilters(f);
  return 1;
}

EMSCRIPTEN_KEEPALIVE const char* qv_filters_json() {
  if (gApp == nullptr || gApp->viewer().city() == nullptr) return hand("null");
  const qv::BuildingFilters& f = gApp->viewer().city()->filters();
  qv::JsonWriter w;
  w.beginObject();
  if (f.minDamage >= 0)
    w.field("minDamage", qv::damageStateName(static_cast<qv::DamageState>(f.minDamage)));
  else
    w.key("minDamage").null();
  if (f.probabilityActive()) {
    w.key("minProbability").beginObject();
    w.field("state", qv::damageStateName(static_cast<qv::DamageState>(f.probabilityState)));
    w.field("percent", f.minProbabilityPercent);
    w.endObject();
  } else {
    w.key("minProbability").null();
  }
  w.field("use", f.use).field("criticalOnly", f.criticalOnly);
  w.key("categories").beginArray();
  for (auto i = 1u; i < static_cast<unsigned>(qv::FacilityCategory::Count); ++i) {
    const auto c = static_cast<qv::FacilityCategory>(i);
    if ((f.categories & qv::facilityCategoryBit(c)) != 0) w.value(qv::facilityCategoryName(c));
  }
  w.endArray().endObject();
  return hand(w.take());
}

namespace {
void writeEntries(qv::JsonWriter& w, const std::vector<qv::BuildingListEntry>& list) {
  w.beginArray();
  for (const auto& e : list) {
    w.beginObject().field("id", e.id).field("name", e.name).field("address", e.address).field("use", e.use);
    w.field("facility", qv::facilityCategoryName(e.facility)).field("facilityKind", e.facilityKind);
    w.field("label", qv::listName(e));
    w.field("damageState", qv::damageStateName(e.damage)).field("peakDriftRatio", e.peakDriftRatio);
    // P(structural damage >= slight, moderate, extensive, complete); null without probabilities.
    if (e.loss) {
      w.key("probabilityAtLeast").beginObject();
      for (int k = 1; k <= 4; ++k) {
        w.field(qv::damageStateName(static_cast<qv::DamageState>(k)),
                static_cast<double>(e.loss->structuralAtLeast(k)));
      }
      w.endObject();
    } else {
      w.key("probabilityAtLeast").null();
    }
    w.field("x", e.x).field("y", e.y).endObject();
  }
  w.endArray();
}
}  // namespace

/// Buildings matching a query (id, name, address), as JSON (at most `limit`).
EMSCRIPTEN_KEEPALIVE const char* qv_search(const char* query, int limit) {
  if (gApp == nullptr || gApp->viewer().city() == nullptr || query == nullptr) return hand("[]");
  qv::JsonWriter w;
  writeEntries(w, gApp->viewer().city()->search(query, static_cast<std::size_t>(std::clamp(limit, 1, 10000))));
  return hand(w.take());
}

/// The filtered list, most damaged first: {total, buildings: [...]} (at most `limit`).
EMSCRIPTEN_KEEPALIVE const char* qv_filtered_json(int limit) {
  if (gApp == nullptr || gApp->viewer().city() == nullptr) return hand("null");
  std::size_t total = 0;
  const auto list =
      gApp->viewer().city()->filteredList(static_cast<std::size_t>(std::clamp(limit, 0, 1000000)), &total);
  qv::JsonWriter w;
  w.beginObject().field("total", static_cast<std::uint64_t>(total)).key("buildings");
  writeEntries(w, list);
  w.endObject();
  return hand(w.take());
}

/// Exports the filtered list ("csv" or "geojson"): downloads it and returns the text.
EMSCRIPTEN_KEEPALIVE const char* qv_export(const char* format) {
  if (gApp == nullptr || format == nullptr) return hand("");
  return hand(gApp->panel().exportList(gApp->viewer(), format, gApp->host()));
}

EMSCRIPTEN_KEEPALIVE int qv_search_ready() {
  qv::CityScene* city = gApp != nullptr ? gApp->viewer().city() : nullptr;
  return city != nullptr && city->searchIndexLoaded() && city->searchIndexSettled() ? 1 : 0;
}

}  // extern "C"

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> errors;
  const qv::AppOptions options = qv::parseAppOptions(args, errors);
  static qv::App app;
  if (!app.start(options, errors)) return 0;
  gApp = &app;
  qv::browser::runMainLoop([] { gApp->frame(); });
  return 0;
}
