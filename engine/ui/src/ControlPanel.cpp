#include "qv/ui/ControlPanel.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "PanelText.h"
#include "qv/format/FacilityCategory.h"
#include "qv/scene/Export.h"
#include "qv/scene/Palette.h"
#include "qv/seismic/Damage.h"

namespace qv {
namespace {

using panel::kDamageLabels;
using panel::kFeetPerMetre;

constexpr float kPanelWidth = 350.0f;
// The map overlay's height in the bottom corner (north arrow, scale bar), with its margin.
constexpr float kOverlayRoomPx = 90.0f;
// Its width before it was first drawn (the arrow, a scale bar and its text).
constexpr float kOverlayWidthGuessPx = 330.0f;

// The record as the panel shows it: file names only. Responses written before the files stored
// only the name carried the path of the machine that ran `response`; its directories are dropped
// (each " + "-separated component, before any " (header title)", which may contain slashes).
// "$1.25 M", "$830 k", "$920".
std::string usd(double v) {
  if (v >= 1e9) return ui::format("$%.2f bn", v / 1e9);
  if (v >= 1e6) return ui::format("$%.2f M", v / 1e6);
  if (v >= 1e3) return ui::format("$%.0f k", v / 1e3);
  return ui::format("$%.0f", v);
}

std::string recordText(const std::string& motion) {
  std::string out;
  std::size_t at = 0;
  while (at <= motion.size()) {
    std::size_t end = motion.find(" + ", at);
    if (end == std::string::npos) end = motion.size();
    std::string part = motion.substr(at, end - at);
    const std::size_t title = part.find(" (");
    const std::size_t slash = part.rfind('/', title == std::string::npos ? std::string::npos : title);
    if (slash != std::string::npos && (title == std::string::npos || slash < title)) part.erase(0, slash + 1);
    out += (at > 0 ? " + " : "") + part;
    at = end + 3;
  }
  return out;
}

const char* const kColorModes[] = {
    "Current inter-storey drift", "Peak inter-storey drift", "Damage state (median drift)", "Neutral",
    "P(damage >= moderate)",      "Expected damage state",   "Inspection tag (most likely)"};
static_assert(sizeof(kColorModes) / sizeof(kColorModes[0]) == kColorModeCount);

std::string megabytes(std::uint64_t bytes) {
  return ui::format("%.1f MB", static_cast<double>(bytes) / (1024.0 * 1024.0));
}

// The device's quality state in the Performance panel: the software renderer and the way back to
// full quality, antialiasing and the pixel ratio, and the frame-time governor's step and why.
void drawQualityState(QualityState& q, ui::Widgets& w) {
  const std::string renderer = q.renderer.empty() ? std::string("unknown") : q.renderer;
  if (q.softwareRenderer && q.weakStart) {
    w.textWrapped("Software rendering detected (" + renderer + "): weak-device preset.");
    if (w.button("Use full quality")) q.fullQualityRequested = true;
  } else if (q.softwareRenderer) {
    w.textWrapped("Software rendering detected (" + renderer + "): full quality as chosen.");
  } else {
    w.textWrapped("Renderer: " + renderer);
  }
  w.text(ui::format("antialiasing %s, pixel ratio %s", q.antialias ? "on" : "off",
                    q.maxPixelRatio > 0.0 ? ui::format("capped at %.1f", q.maxPixelRatio).c_str() : "not capped"));
  if (!q.antialias && q.softwareRenderer) w.textWrapped("Antialiasing needs a reload: add ?aa=1 to the address.");
  bool on = q.governorOn;
  if (w.checkbox("Adapt detail to the frame time", &on)) {
    q.governorOn = on;
    q.governorToggled = true;
  }
  if (!q.governorOn) {
    w.text("detail step 0 (governor off)");
    return;
  }
  std::string why;
  switch (q.governorReason) {
    case GovernorReason::TooSlow:
      why = ui::format("lowered: median frame %.0f ms > %.0f ms", q.governorChangeMedianMs, q.slowFrameMs);
      break;
    case GovernorReason::Headroom:
      why = ui::format("raised: median frame %.0f ms < %.0f ms", q.governorChangeMedianMs, q.fastFrameMs);
      break;
    case GovernorReason::Steady:
      why = ui::format("steady: frames within %.0f ms", q.slowFrameMs);
      break;
  }
  w.text(ui::format("detail step %d of %d below the preset (%s)", q.governorStep, q.governorMaxStep, why.c_str()));
}

// "Occupants: 1.78 million by day, 529800 at night, ... (inferred ...); population: ..." — the city's
// people against its published population where the run was given it.
std::string occupantsLine(const seismic::ConsequenceTotals& file) {
  auto people = [](double n) {
    return n >= 1e6 ? ui::format("%.2f million", n / 1e6) : ui::format("%.0f", std::round(n / 100) * 100);
  };
  const auto& at = file.city.occupantsAt;
  std::string line = std::isfinite(at[0])
                         ? "Occupants: " + people(at[1]) + " by day, " + people(at[0]) + " at night, " + people(at[2]) +
                               " at commute time (inferred from floor area and use unless the data gives them)"
                         : "Occupants: " + people(file.city.occupants.expected) + " at " + file.timeOfDay;
  const seismic::PopulationFigures& p = file.population;
  if (p.given()) {
    line += "; population: ";
    if (p.night >= 0) line += people(p.night) + " residents";
    if (p.night >= 0 && p.day >= 0) line += ", ";
    if (p.day >= 0) line += people(p.day) + " by day";
    line += " (" + (p.source.empty() ? std::string("source not given") : p.source) + ")";
    if (std::isfinite(at[0]) && p.night > 0 && p.day > 0) {
      line += ui::format(": the city holds %.0f %% of them at night, %.0f %% by day", 100 * at[0] / p.night,
                         100 * at[1] / p.day);
    }
  }
  return line;
}

}  // namespace

void ControlPanel::applyQuality(Viewer& viewer, QualityPreset preset, int governorStep) {
  CityScene* city = viewer.city();
  if (city == nullptr) return;
  const QualitySettings q = qualitySettings(preset, governorStep);
  CitySceneOptions& o = city->mutableOptions();
  o.maxScreenSpaceError = q.maxScreenSpaceError;
  o.blockPixels = q.blockPixels;
  o.maxDrawTiles = q.maxDrawTiles;
  o.animationRadiusM = q.animationRadiusM;
  o.maxAnimatedBuildings = q.maxAnimatedBuildings;
}

std::string ControlPanel::lengthText(const Viewer& viewer, double metres) const {
  if (viewer.showFeet()) {
    const double feet = metres * kFeetPerMetre;
    return feet >= 5280.0 ? ui::format("%.2f mi", feet / 5280.0) : ui::format("%.0f ft", feet);
  }
  return metres >= 1000.0 ? ui::format("%.2f km", metres / 1000.0) : ui::format("%.1f m", metres);
}

std::string ControlPanel::exportList(Viewer& viewer, const std::string& format, UiHost& host) {
  CityScene* city = viewer.city();
  if (city == nullptr) return {};
  const std::vector<BuildingListEntry> list = city->filteredList(1000000);
  const Tileset none;
  const Tileset& tileset = city->tileset() != nullptr ? *city->tileset() : none;
  const ExportProvenance provenance = exportProvenance(tileset, city->filters());
  if (format == "geojson") {
    std::string text = exportGeoJson(list, viewer.geo(), &provenance);
    host.download(exportFileName(tileset, city->filters(), "buildings", "geojson"), "application/geo+json", text);
    return text;
  }
  std::string text = exportCsv(list, viewer.geo(), &provenance);
  host.download(exportFileName(tileset, city->filters(), "buildings", "csv"), "text/csv", text);
  return text;
}

void ControlPanel::draw(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory, UiHost& host) {
  drawDistrictOutline(viewer, w);
  drawMapLabels(viewer, w);
  drawPanel(viewer, w, memory, host);
  drawInspection(viewer, w, host);
  drawOverlay(viewer, w);
  drawFilterChips(viewer, w);
  drawMarkerLabels(viewer, w);

  if (!viewer.errors().empty()) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    // Beside the panel; on a phone across the screen, above the bottom sheet when it is there.
    const bool narrow = narrowLayout(display.x);
    const float left = narrow ? 10.0f : kPanelWidth + 20.0f;
    const float bottom =
        narrow && !viewer.selection().empty() ? display.y * (1.0f - kBottomSheetFraction) - 10.0f : display.y - 10.0f;
    ImGui::SetNextWindowPos(ImVec2(left, bottom), ImGuiCond_Always, ImVec2(0.0f, 1.0f));
    const float maxWidth = narrow ? display.x - 20.0f : std::max(200.0f, display.x - kPanelWidth - 40.0f);
    ImGui::SetNextWindowSizeConstraints(ImVec2(200.0f, 0.0f), ImVec2(maxWidth, display.y * 0.3f));
    ImGui::SetNextWindowBgAlpha(0.92f);
    // A new message does not take the keyboard from the search or the focused control.
    if (w.begin("Errors", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoFocusOnAppearing)) {
      // Long messages (what to do about a refused address) wrap at the widest the window may be.
      ImGui::PushTextWrapPos(maxWidth - 2.0f * ImGui::GetStyle().WindowPadding.x);
      const auto& errors = viewer.errors();
      const std::size_t first = errors.size() > 6 ? errors.size() - 6 : 0;
      if (first > 0) w.text(ui::format("(%zu earlier messages not shown)", first));
      for (std::size_t i = first; i < errors.size(); ++i) w.textColored(0.75f, 0.1f, 0.05f, errors[i]);
      ImGui::PopTextWrapPos();
    }
    w.end();
  }
}

void ControlPanel::drawShakingProvenance(const ResponseInfo& r, ui::Widgets& w) {
  // Whether the shaking is a scenario or an actual event, always in view: confusing the two is the
  // worst error this product can make.
  const bool actual = r.eventType == "ACTUAL";
  w.textColored(actual ? 0.80f : 0.55f, actual ? 0.05f : 0.25f, 0.0f, "Shaking: " + shakingStatement(r));
  if (r.shakemap) {
    w.textWrapped("ShakeMap: " + r.shakemap->eventId + " version " + r.shakemap->version + ", processed " +
                  r.shakemap->processTimestamp +
                  (r.shakemap->description.empty() ? "" : "; " + r.shakemap->description));
  }
  w.textWrapped("Earthquake: " + (r.scenario.empty() ? std::string("one record for every building") : r.scenario));
  if (r.records.size() > 1) {
    w.textWrapped(ui::format("Records: a suite of %zu (medians shown; each building animates the record nearest its "
                             "median): ",
                             r.records.size()) +
                  recordText(r.records.front()) + ", ...");
  } else {
    w.textWrapped("Record: " + recordText(r.motion));
  }
  if (r.scaling == "sa") {
    w.textWrapped("Scaling: each record to the target Sa at the building's own first-mode period");
  } else if (r.scaling == "pga") {
    w.textWrapped("Scaling: each record to the target PGA at the building");
  }
}

void ControlPanel::drawSiteShaking(const BuildingInfo& info, const Tileset* tileset, ui::Widgets& w) {
  if (!info.site) return;
  std::string label = "Shaking at the site (" + std::string(siteSourceLabel(info.site->source));
  if (info.site->source == SiteSource::ShakeMap && tileset != nullptr && tileset->response &&
      tileset->response->shakemap) {
    label += " " + tileset->response->shakemap->eventId + " version " + tileset->response->shakemap->version;
  }
  w.field(label + ")", siteShakingText(*info.site));
}

void ControlPanel::drawShakingOfBuilding(const BuildingInfo& info, ui::Widgets& w) {
  if (info.scaling && info.scaling->periodS[0] > 0.0f) {
    const BuildingScaling& s = *info.scaling;
    for (int d = 0; d < 2; ++d) {
      if (!(s.scale[d] > 0.0f)) continue;
      w.field(d == 0 ? "Shaking, X" : "Shaking, Y",
              ui::format("T1 %.2f s; target Sa(T1) %.3f g, the record's own %.3f g, scaled by %.3f",
                         static_cast<double>(s.periodS[d]), static_cast<double>(s.targetSaG[d]),
                         static_cast<double>(s.recordSaG[d]), static_cast<double>(s.scale[d])));
    }
  }
  if (info.spread && info.spread->records > 1) {
    w.textWrapped(
        ui::format("Across %u records: peak drift and floor acceleration are medians (log standard "
                   "deviation %.2f and %.2f); the motion shown is record %u, the nearest the median",
                   info.spread->records, static_cast<double>(info.spread->driftBeta),
                   static_cast<double>(info.spread->accelerationBeta), info.spread->shownRecord + 1u));
  }
}

void ControlPanel::drawBuildingLoss(const BuildingLoss& l, ui::Widgets& w) {
  w.separator();
  w.text("Damage probabilities (HAZUS 5.1 fragility):");
  for (std::size_t k = 0; k < 5; ++k) {
    const Rgb c = kDamagePalette[k];
    w.meter(kDamageLabels[k], l.structural[k], ui::format("%.1f %%", 100.0 * static_cast<double>(l.structural[k])), c.r,
            c.g, c.b);
  }
  const float moderate = l.structural[2] + l.structural[3] + l.structural[4];
  w.field("Moderate or worse", ui::format("%.1f %%; expected state %.2f (0 none .. 4 complete); collapse %.2f %%",
                                          100.0 * static_cast<double>(moderate), static_cast<double>(l.expectedState()),
                                          100.0 * static_cast<double>(l.collapse)));
  const char* tags[3] = {"Tag green", "Tag yellow", "Tag red"};
  for (std::size_t k = 0; k < 3; ++k) {
    w.meter(tags[k], l.tag[k], ui::format("%.1f %%", 100.0 * static_cast<double>(l.tag[k])), kTagPalette[k].r,
            kTagPalette[k].g, kTagPalette[k].b);
  }
  const bool occupantsInferred = (l.flags & kLossOccupantsInferred) != 0;
  const bool valueInferred = (l.flags & kLossValueInferred) != 0;
  w.field("Occupants present", ui::format("%.1f%s", static_cast<double>(l.occupants),
                                          occupantsInferred ? " (inferred from floor area and use)" : ""));
  w.field("Expected injuries", ui::format("%.2f minor, %.2f hospital, %.3f life-threatening; deaths %.3f%s",
                                          static_cast<double>(l.injuries[0]), static_cast<double>(l.injuries[1]),
                                          static_cast<double>(l.injuries[2]), static_cast<double>(l.injuries[3]),
                                          occupantsInferred ? " (from inferred occupants)" : ""));
  w.field("Expected repair cost", ui::format("%s of %s%s; repair time %.0f days", usd(l.repairCostUsd).c_str(),
                                             usd(l.replacementValueUsd).c_str(),
                                             valueInferred ? " (value inferred from floor area and use)" : "",
                                             static_cast<double>(l.repairTimeDays)));
}

float ControlPanel::overlayRoom() const {
  // The overlay's height and margin as last drawn, never less than before it had a colour key.
  const float display = ImGui::GetIO().DisplaySize.y;
  return overlayTop_ >= 0.0f ? std::max(kOverlayRoomPx, display - overlayTop_ + 10.0f) : kOverlayRoomPx + 45.0f;
}

bool ControlPanel::section(ui::Widgets& w, const char* label, bool defaultOpen) {
  if (openRequests_.erase(label) > 0) ImGui::SetNextItemOpen(true);
  return w.collapsingHeader(label, defaultOpen);
}

void ControlPanel::openSection(const std::string& label) {
  openRequests_.insert(label);
}

void ControlPanel::drawConsequences(Viewer& viewer, ui::Widgets& w, UiHost& host) {
  CityScene* city = viewer.city();
  const Tileset* tileset = city != nullptr ? city->tileset() : nullptr;
  if (tileset == nullptr || !tileset->response || !section(w, "Consequences", true)) return;
  const ResponseInfo& r = *tileset->response;
  const seismic::ConsequenceTotals* file = city->consequences();
  if (file == nullptr) {
    w.textWrapped(r.consequences ? (city->consequencesFailed() ? "The consequences file could not be loaded."
                                                               : "Loading the consequences...")
                                 : "These results carry no damage probabilities or consequences (computed before "
                                   "they existed, or imported): run quakeview-prep response again.");
    return;
  }
  auto cell = [](const seismic::Estimate& e, int decimals) {
    // Whole numbers from a thousand up, so the city's and the view's columns fit the panel.
    if (e.high >= 1000.0 || e.expected >= 1000.0) decimals = 0;
    if (std::isnan(e.low) || std::isnan(e.high)) return ui::format("%.*f (interval unknown)", decimals, e.expected);
    return ui::format("%.*f (%.*f-%.*f)", decimals, e.expected, decimals, e.low, decimals, e.high);
  };
  auto money = [](const seismic::Estimate& e) {
    // One unit for the three numbers, from the expected value: "$1.86 M (0.87-3.36)".
    const double m = std::max({e.expected, e.high, 1.0});
    const double unit = m >= 1e9 ? 1e9 : m >= 1e6 ? 1e6 : m >= 1e3 ? 1e3 : 1.0;
    const char* name = m >= 1e9 ? " bn" : m >= 1e6 ? " M" : m >= 1e3 ? " k" : "";
    return ui::format("$%.2f%s (%.2f-%.2f)", e.expected / unit, name, e.low / unit, e.high / unit);
  };
  const seismic::LossTotals& c = file->city;
  // The headline: what an emergency manager acts on first, for the whole city, with its 90 %
  // interval (the shaking they assume is stated right above the section).
  {
    std::vector<std::vector<std::string>> headline;
    headline.push_back({"Damaged: moderate or worse", cell(c.damaged, 1)});
    headline.push_back({"Red tags (unsafe)", cell(c.tags[2], 1)});
    headline.push_back({"Yellow tags (restricted use)", cell(c.tags[1], 1)});
    headline.push_back({"Injuries: minor", cell(c.injuries[0], 1)});
    headline.push_back({"Injuries: hospital care", cell(c.injuries[1], 1)});
    headline.push_back({"Deaths", cell(c.injuries[3], 2)});
    headline.push_back({"Repair cost", money(c.repairCostUsd)});
    w.table("##headline", {ui::format("HAZUS 5.1, occupants at %s", file->timeOfDay.c_str()), "City (90 % interval)"},
            headline);
  }
  ImGui::Indent();
  const bool full = section(w, "All consequences: city, view, districts", false);
  if (!full) {
    ImGui::Unindent();
    return;
  }
  const seismic::LossTotals view = city->consequencesInView();
  if (r.records.size() > 1) {
    const std::optional<float> spread = city->suiteDriftSpread();
    w.textWrapped(spread ? ui::format("Record-to-record spread: peak drifts vary by a log standard deviation of %.2f "
                                      "(median over the buildings; each building's own in its inspection); the "
                                      "probabilities include it",
                                      static_cast<double>(*spread))
                         : ui::format("Record-to-record spread: loading (%zu records)", r.records.size()));
  }
  w.textWrapped(
      ui::format("HAZUS 5.1, occupants at %s; expected value (90 %% interval). Occupants and values "
                 "are inferred from floor area and use unless the data gives them.",
                 file->timeOfDay.c_str()));
  w.textWrapped(occupantsLine(*file));
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"Buildings (with a result)", ui::format("%llu", static_cast<unsigned long long>(c.buildings)),
                  ui::format("%llu", static_cast<unsigned long long>(view.buildings))});
  for (std::size_t k = 0; k < 5; ++k) {
    rows.push_back({std::string(kDamageLabels[k]), cell(c.damageStates[k], 1), cell(view.damageStates[k], 1)});
  }
  rows.push_back({"Collapsed", cell(c.collapsed, 2), cell(view.collapsed, 2)});
  const char* tags[3] = {"Tag green", "Tag yellow", "Tag red"};
  for (std::size_t k = 0; k < 3; ++k) rows.push_back({tags[k], cell(c.tags[k], 1), cell(view.tags[k], 1)});
  rows.push_back(
      {"Occupants (inferred)", ui::format("%.0f", c.occupants.expected), ui::format("%.0f", view.occupants.expected)});
  const char* injuries[4] = {"Minor injuries", "Hospitalised", "Life-threatening", "Deaths"};
  for (std::size_t k = 0; k < 4; ++k) rows.push_back({injuries[k], cell(c.injuries[k], 2), cell(view.injuries[k], 2)});
  rows.push_back({"Repair cost", money(c.repairCostUsd), money(view.repairCostUsd)});
  if (!city->consequencesInViewComplete()) {
    // The view's losses come with the city index: no zeros meanwhile.
    for (std::vector<std::string>& row : rows) row.back() = "loading";
  }
  w.table("##consequences", {"", "City", "In view"}, rows);
  if (!file->districts.empty()) {
    // Where the districts come from (a city's own are made from its input; nearest place names are
    // inferred, and say so), then the table: sorted by a click on a header, a row flies there.
    w.textWrapped(
        ui::format("Districts (%zu): %s%s", file->districts.size(),
                   file->districtsSource.empty() ? "from the response's districts file" : file->districtsSource.c_str(),
                   file->districtsInferred ? " (INFERRED: not official boundaries)" : ""));
    w.textWrapped(
        "Expected values (their intervals: Export totals); Damaged: moderate or worse. Click a district to fly "
        "there and outline it; click a header to sort.");
    std::vector<std::vector<std::string>> districtRows;
    std::vector<std::vector<double>> keys;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const seismic::ConsequenceTotals::District& d : file->districts) {
      const seismic::LossTotals& t = d.totals;
      const double moderate = t.damageStates[2].expected + t.damageStates[3].expected + t.damageStates[4].expected;
      double hurt = 0.0;
      for (std::size_t k = 0; k < 3; ++k) hurt += t.injuries[k].expected;
      // Expected values only, so that seven columns fit the panel.
      const double cost = t.repairCostUsd.expected;
      districtRows.push_back({d.name, ui::format("%llu", static_cast<unsigned long long>(t.buildings)),
                              ui::format("%.1f", moderate), ui::format("%.1f", t.tags[2].expected),
                              ui::format("%.2f", hurt), ui::format("%.3f", t.injuries[3].expected),
                              cost >= 1e9   ? ui::format("$%.2f bn", cost / 1e9)
                              : cost >= 1e6 ? ui::format("$%.2f M", cost / 1e6)
                                            : ui::format("$%.0f k", cost / 1e3)});
      keys.push_back(
          {nan, static_cast<double>(t.buildings), moderate, t.tags[2].expected, hurt, t.injuries[3].expected, cost});
    }
    const int clicked =
        w.sortableTable("##districts", {"District", "Buildings", "Damaged", "Red tags", "Injured", "Deaths", "Repair"},
                        districtRows, keys, 2);
    if (clicked >= 0) viewer.showDistrict(file->districts[static_cast<std::size_t>(clicked)].name);
    if (!viewer.shownDistrict().empty()) {
      w.text("Outlined: " + viewer.shownDistrict());
      ImGui::SameLine();
      if (w.button("Clear outline")) viewer.showDistrict("");
    }
  }
  if (w.button("Export totals (CSV)")) {
    // The totals are the whole city's (and the view's): the list filters do not apply to them.
    const ExportProvenance provenance = exportProvenance(*tileset, BuildingFilters{});
    const std::optional<ViewArea> area = viewer.viewArea();
    host.download(exportFileName(*tileset, BuildingFilters{}, "consequences", "csv"), "text/csv",
                  exportConsequencesCsv(*file, city->consequencesInViewComplete() ? &view : nullptr, &provenance,
                                        area ? &*area : nullptr));
  }
  w.sameLine();
  // The view as a PNG, with the event, the city and the attribution under it (quakeview.screenshot()).
  if (w.button("Save image (PNG)")) host.saveImage();
  // The situation report (quakeview.report(), `quakeview-prep report`): a print-ready HTML page.
  w.sameLine();
  if (city->situationReportReady()) {
    if (w.button("Report (HTML)")) {
      if (const auto html = city->situationReport()) {
        host.download(exportFileName(*tileset, BuildingFilters{}, "report", "html"), "text/html", *html);
      }
    }
  } else {
    w.text("Report: loading the city's index...");
  }
  ImGui::Unindent();
}

float ControlPanel::widestPanelRightCss(float cssWidth) {
  return 10.0f + std::max(200.0f, std::min(520.0f, cssWidth - 20.0f));
}

void ControlPanel::drawPanel(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory, UiHost& host) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, 0.0f), ImGuiCond_FirstUseEver);
  // A phone starts with the panel folded to its title bar (tap it to open), the city in view; the
  // panel never grows wider than the screen and scrolls when taller.
  // Its bottom stays clear of the map overlay in the corner wherever the panel at its widest would
  // reach the overlay's left edge (last frame's; before the first, a guess): on a phone, and on a
  // tablet in portrait.
  const bool narrow = narrowLayout(display.x);
  if (narrow) ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
  const float maxWidth = widestPanelRightCss(display.x) - 10.0f;
  const float overlayLeft = overlayLeft_ >= 0.0f ? overlayLeft_ : display.x - kOverlayWidthGuessPx;
  const bool clearOverlay = narrow || 10.0f + maxWidth + 10.0f > overlayLeft;
  const float maxHeight = std::max(200.0f, display.y - 20.0f - (clearOverlay ? overlayRoom() : 0.0f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(260.0f, maxWidth), 0.0f), ImVec2(maxWidth, maxHeight));
  ImGui::SetNextWindowBgAlpha(0.90f);
  if (focusSearch_) ImGui::SetNextWindowCollapsed(false);  // '/' opens the panel, whatever its state
  if (!w.begin("QuakeView", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    framingRight_ = 0.0f;
    w.end();
    return;
  }
  framingRight_ = narrow ? 0.0f : ImGui::GetWindowPos().x + std::min(kPanelWidth, maxWidth);
  const StatsSummary s = viewer.stats();
  CityScene* city = viewer.city();
  const Tileset* tileset = city != nullptr ? city->tileset() : nullptr;
  w.text(ui::format("FPS: %.1f   frame: %.2f ms   draw calls %.0f", s.fps, s.frameMs.total, s.drawCalls));
  if (tileset != nullptr) {
    const TileCounts tiles = city->tileCounts();
    w.text(ui::format("City: %llu buildings, %u of %zu tiles loaded%s",
                      static_cast<unsigned long long>(tileset->buildings), tiles.loaded, tileset->nodes.size(),
                      tiles.pending > 0 ? ", loading..." : ""));
    // Provenance: which city this is and where its files (tiles and results alike: a manifest
    // names only files beside it) came from, so a link to someone else's data cannot pass as ours.
    w.textWrapped("Data: " + (tileset->name.empty() ? std::string("(unnamed city)") : "\"" + tileset->name + "\"") +
                  " from " + (viewer.dataSource().empty() ? std::string("this site") : viewer.dataSource()));
    drawMapLine(*tileset, w);
    if (tileset->response) {
      drawShakingProvenance(*tileset->response, w);
      if (tileset->responseOutOfDate()) {
        w.textColored(0.75f, 0.1f, 0.05f, "Results are older than the buildings: run quakeview-prep response again.");
      }
    } else {
      w.textColored(0.6f, 0.35f, 0.0f, "No earthquake results for this city (quakeview-prep response).");
    }
  }
  drawScenarios(viewer, w);

  // On a software renderer, one line says why the picture is coarser (details under Performance).
  if (qualityState_ != nullptr && qualityState_->weakStart && !qualityState_->presetChosen) {
    w.textWrapped("Software rendering: the weak-device preset is on (Performance).");
  }

  // The decision numbers right under the shaking they assume.
  drawConsequences(viewer, w, host);

  // The transport, always in view: play or pause and the time.
  if (w.button(viewer.playing() ? "Pause (Space)##transport" : "Play (Space)##transport")) {
    if (viewer.playing())
      viewer.pause();
    else
      viewer.play();
  }
  w.sameLine();
  double t = viewer.time();
  if (w.sliderDouble("Time (s)", &t, 0.0, std::max(viewer.duration(), 0.01), "%.2f")) viewer.setTime(t);

  if (section(w, "Animation", false)) {
    if (w.button("Reset view (R)")) viewer.controller().reset();
    float speed = static_cast<float>(viewer.speed());
    if (w.sliderFloat("Speed", &speed, 0.1f, 4.0f, "%.2fx")) viewer.setSpeed(speed);
    float amplitude = viewer.amplitude();
    if (w.sliderFloat("Amplitude", &amplitude, 1.0f, 200.0f, "%.0fx", true)) viewer.setAmplitude(amplitude);
    int mode = static_cast<int>(viewer.colorMode());
    if (w.combo("Colour", &mode, kColorModes, kColorModeCount)) viewer.setColorMode(static_cast<ColorMode>(mode));
    if (tileset != nullptr && tileset->response && !tileset->response->motionPreviewG.empty()) {
      const auto& g = tileset->response->motionPreviewG;
      float peak = 0.0f;
      std::size_t at = 0;
      for (std::size_t i = 0; i < g.size(); ++i) {
        if (std::abs(g[i]) > peak) {
          peak = std::abs(g[i]);
          at = i;
        }
      }
      const double rate = tileset->response->motionPreviewRateHz;
      const double recordSeconds = static_cast<double>(g.size()) / rate;
      const float cursor = static_cast<float>(viewer.time() / std::max(recordSeconds, 1e-3));
      const float seek = w.plot(
          "##motion", g.data(), static_cast<int>(g.size()), -peak, peak, 50.0f, cursor,
          ui::format("Ground motion (input record, X): peak %.2f g at %.1f s; time cursor at %.1f s (click or drag "
                     "the plot to move the time)",
                     static_cast<double>(peak), static_cast<double>(at) / rate, viewer.time()));
      if (seek >= 0.0f) viewer.setTime(static_cast<double>(seek) * recordSeconds);
      // Why the slider runs past the record: the shaking reaches distant buildings later.
      const double delays = viewer.duration() - recordSeconds;
      if (delays > 0.05) {
        w.textWrapped(
            ui::format("Time runs to %.1f s: the record lasts %.1f s and reaches each building after its "
                       "S-wave travel time from the hypocentre, up to %.1f s.",
                       viewer.duration(), recordSeconds, delays));
      }
    }
  }

  if (section(w, "Damage and colours", false)) drawDamageAndColours(viewer, w, s);

  // '/' opens this section (however it was left) and puts the keyboard in the search; Enter there
  // takes the first result, as a click on it does.
  if (focusSearch_) ImGui::SetNextItemOpen(true);
  if (city != nullptr && section(w, "Find and filter", false)) {
    const bool focus = focusSearch_;
    focusSearch_ = false;
    bool entered = false;
    w.inputText("Search (/)", search_, focus, &entered);
    if (!search_.empty()) {
      const auto hits = city->search(search_, 8);
      if (entered && !hits.empty()) {
        const BuildingListEntry& first = hits.front();
        if (!viewer.select(first.id) || !viewer.flyToSelection())
          viewer.flyTo(first.x, first.y, std::max(200.0, static_cast<double>(first.heightM) * 3.0));
      }
      if (!city->searchIndexLoaded()) {
        // Left out for memory: the notice under the filters says why.
        if (city->cityIndexNotice().empty())
          w.text(city->searchIndexSettled() ? "The search index could not be loaded." : "Loading the search index...");
      } else if (hits.empty()) {
        w.text("No building matches.");
      }
      for (const BuildingListEntry& hit : hits) {
        const std::string label = (hit.name.empty() ? hit.id : hit.name + " (" + hit.id + ")") +
                                  (hit.address.empty() ? "" : ", " + hit.address) + "##search" + hit.id;
        if (w.selectable(label.c_str(), hit.id == viewer.selection())) {
          // Framed from a side where it is seen (FlyToPose.h), like the window's Fly to.
          if (!viewer.select(hit.id) || !viewer.flyToSelection())
            viewer.flyTo(hit.x, hit.y, std::max(200.0, static_cast<double>(hit.heightM) * 3.0));
        }
      }
    }
    BuildingFilters f = city->filters();
    static const char* const damageItems[] = {"any", "slight or worse", "moderate or worse", "extensive or worse",
                                              "complete"};
    int damage = std::clamp(f.minDamage, 0, 4);
    if (f.minDamage < 0) damage = 0;
    if (w.combo("Damage", &damage, damageItems, 5)) f.minDamage = damage == 0 ? -1 : damage;
    // The probabilistic filter (HAZUS fragility): the choices people ask for, plus the one in use
    // when a link or the API set another.
    struct ProbabilityChoice {
      int state, percent;
    };
    static constexpr ProbabilityChoice kProbabilityChoices[] = {{-1, 0}, {1, 10}, {1, 25}, {2, 5},
                                                                {2, 10}, {2, 25}, {3, 5},  {4, 1}};
    std::vector<std::string> probabilityLabels;
    std::vector<ProbabilityChoice> probabilityValues;
    int probability = 0;
    for (const ProbabilityChoice& c : kProbabilityChoices) {
      if (c.state == f.probabilityState && c.percent == f.minProbabilityPercent) {
        probability = static_cast<int>(probabilityValues.size());
      }
      probabilityValues.push_back(c);
    }
    if (f.probabilityActive() && probability == 0) {
      probability = static_cast<int>(probabilityValues.size());
      probabilityValues.push_back({f.probabilityState, f.minProbabilityPercent});
    }
    for (const ProbabilityChoice& c : probabilityValues) {
      probabilityLabels.push_back(
          c.state < 1 ? std::string("any")
                      : ui::format("P(%s or worse) at least %d %%",
                                   std::string(damageStateName(static_cast<DamageState>(c.state))).c_str(), c.percent));
    }
    std::vector<const char*> probabilityItems;
    for (const std::string& label : probabilityLabels) probabilityItems.push_back(label.c_str());
    if (w.combo("Likely damage", &probability, probabilityItems.data(), static_cast<int>(probabilityItems.size()))) {
      f.probabilityState = probabilityValues[static_cast<std::size_t>(probability)].state;
      f.minProbabilityPercent = probabilityValues[static_cast<std::size_t>(probability)].percent;
    }
    // Facility categories (FacilityCategory.h: Hazus essential facilities, FEMA community lifelines).
    w.checkbox("Critical facilities only (essential, schools and shelters)", &f.criticalOnly);
    w.text("Facility categories (any checked):");
    for (auto i = 1u; i < static_cast<unsigned>(FacilityCategory::Count); ++i) {
      const auto category = static_cast<FacilityCategory>(i);
      bool on = (f.categories & facilityCategoryBit(category)) != 0;
      const std::string label = std::string(facilityCategoryLabel(category)) + "##category";
      if (w.checkbox(label.c_str(), &on)) f.categories ^= facilityCategoryBit(category);
    }
    // Uses: several at once, those present in the city with their counts.
    std::vector<std::string_view> chosen;
    for (std::string_view rest = f.use; !rest.empty();) {
      const std::size_t plus = rest.find('+');
      chosen.push_back(rest.substr(0, plus));
      rest = plus == std::string_view::npos ? std::string_view() : rest.substr(plus + 1);
    }
    w.text(chosen.empty() ? "Uses (any checked; none checked: every use):" : "Uses (any checked):");
    std::string uses = f.use;
    for (const auto& [use, count] : city->useCounts()) {
      bool on = std::find(chosen.begin(), chosen.end(), use) != chosen.end();
      const std::string label = ui::format("%s (%zu)##use", use.c_str(), count);
      if (w.checkbox(label.c_str(), &on)) {
        uses.clear();
        for (const std::string_view c : chosen) {
          if (c != use) uses += (uses.empty() ? "" : "+") + std::string(c);
        }
        if (on) uses += (uses.empty() ? "" : "+") + use;
      }
    }
    f.use = uses;
    city->setFilters(f);
    std::size_t total = 0;
    const auto list = city->filteredList(12, &total);
    if (!city->searchIndexLoaded() && !city->searchIndexSettled()) w.text("Loading the city's building list...");
    if (const std::string& notice = city->cityIndexNotice(); !notice.empty()) {
      w.textWrapped(notice + " A larger budget (?memory=MB in the address) loads it where the device has the memory.");
    }
    w.text(ui::format("Filtered: %zu of %llu buildings%s", total,
                      static_cast<unsigned long long>(tileset != nullptr ? tileset->buildings : 0),
                      f.active() ? " (the rest is dimmed)" : ""));
    // Each row: name or address, damage, use and category, distance from the camera's target.
    const CameraState& camera = viewer.camera();
    for (const BuildingListEntry& e : list) {
      const std::string label = listRowText(e, camera.x, camera.y, listProbabilityState(f)) + "##list" + e.id;
      if (w.selectable(label.c_str(), e.id == viewer.selection())) {
        if (!viewer.select(e.id) || !viewer.flyToSelection())
          viewer.flyTo(e.x, e.y, std::max(200.0, static_cast<double>(e.heightM) * 3.0));
      }
    }
    if (w.button("Export CSV")) exportList(viewer, "csv", host);
    w.sameLine();
    if (w.button("Export GeoJSON")) exportList(viewer, "geojson", host);
  }

  focusSearch_ = false;  // also without a city (nothing to search)

  if (section(w, "General", false)) {
    if (city != nullptr) {
      CitySceneOptions& o = city->mutableOptions();
      bool animate = o.animationRadiusM > 0.0f;
      if (w.checkbox("Animate buildings near the camera (off: static, grey peak colours)", &animate)) {
        o.animationRadiusM = animate ? 1000.0f : 0.0f;
      }
      bool lod1 = city->showLod1();
      bool lod2 = city->showLod2();
      const bool a = w.checkbox("Show LOD1 buildings (extruded footprints)", &lod1);
      const bool b = w.checkbox("Show LOD2 buildings (detailed models)", &lod2);
      if (a || b) city->setLodVisibility(lod1, lod2);
    }
    drawMapNamesSwitch(viewer, w);
    bool feet = viewer.showFeet();
    if (w.radio("Metres##units", !feet)) viewer.setShowFeet(false);
    w.sameLine();
    if (w.radio("Feet##units", feet)) viewer.setShowFeet(true);
  }

  // Open from the start when the device made the viewer start in the weak-device preset, so the
  // person sees why and how to get full quality back.
  if (section(w, "Performance", false)) {
    int quality = static_cast<int>(quality_);
    static const char* const qualities[] = {qualityName(QualityPreset::High), qualityName(QualityPreset::Balanced),
                                            qualityName(QualityPreset::Low)};
    if (w.combo("Quality", &quality, qualities, 3)) {
      quality_ = static_cast<QualityPreset>(quality);
      applyQuality(viewer, quality_);
      if (qualityState_ != nullptr) qualityState_->presetChosen = true;
    }
    if (qualityState_ != nullptr) drawQualityState(*qualityState_, w);
    if (city != nullptr) {
      CitySceneOptions& o = city->mutableOptions();
      w.sliderFloat("Animation radius (m)", &o.animationRadiusM, 0.0f, 5000.0f, "%.0f");
      int animated = static_cast<int>(o.maxAnimatedBuildings);
      if (w.sliderInt("Max animated", &animated, 0, 100000))
        o.maxAnimatedBuildings = static_cast<std::uint32_t>(animated);
      int tiles = static_cast<int>(o.maxDrawTiles);
      if (w.sliderInt("Max tiles drawn", &tiles, 1, 250)) o.maxDrawTiles = static_cast<std::uint32_t>(tiles);
      w.sliderFloat("Detail (pixels of error)", &o.maxScreenSpaceError, 2.0f, 100.0f, "%.0f");
      w.sliderFloat("Far blocks (pixels, 0 off)", &o.blockPixels, 0.0f, 32.0f, "%.0f");
    }
    w.text(ui::format("cull %.2f  lod %.2f  animate %.2f ms", s.frameMs.cull, s.frameMs.lod, s.frameMs.animate));
    w.text(ui::format("upload %.2f  render %.2f  total %.2f ms", s.frameMs.upload, s.frameMs.render, s.frameMs.total));
    // What a software renderer's frame time is made of, in one line: triangles and pixels.
    std::string pixels = "pixels unknown";
    if (qualityState_ != nullptr && qualityState_->pixels() > 0) {
      const QualityState& q = *qualityState_;
      const std::string msaa = q.msaaSamples > 1 ? ui::format("×%d MSAA", q.msaaSamples) : std::string("no MSAA");
      pixels = ui::format("pixels %d×%d (%s)", q.pixelWidth, q.pixelHeight, msaa.c_str());
    }
    w.text(ui::format("triangles %.0f · ", s.triangles) + pixels);
    w.text(ui::format("buildings: %u loaded, %u visible, %u animated", s.latest.buildingsLoaded,
                      s.latest.buildingsVisible, s.latest.buildingsAnimated));
    w.text(ui::format("upload %.1f KB/frame", s.uploadBytes / 1024.0));
    w.text("memory: " + megabytes(memory.heapBytes) + " live, " + megabytes(memory.heapReservedBytes) + " reserved");
  }

  if (section(w, "About these results", false)) {
    w.textWrapped(
        "Responses come from simplified models: every building is a shear building (one mass per floor, "
        "storey springs with Bouc-Wen hysteresis) sized from its footprint, height and a structural type "
        "inferred from its tags; damage states from HAZUS drift thresholds. They show patterns across a "
        "city, not a safety assessment of any one building.");
    if (tileset != nullptr && tileset->response) w.textWrapped("Method: " + tileset->response->method);
    w.textWrapped(
        "Colours: in the current-drift mode every building shows its drift at the current time, from light "
        "grey through yellow to dark red: its largest storey's from its drift series (four values a second) "
        "and, within the animation radius of the camera, each storey's own as it moves. A building without a "
        "drift series (results prepared before them) shows its peak drift over the whole record in grey levels "
        "(light to dark slate), never in the colours of damage, because that peak may not have happened yet: "
        "paused before the shaking arrives, no building is yellow, orange or red. The peak-drift and damage "
        "modes show every building's peak over the whole record in colour.");
    w.textWrapped("Map data © OpenStreetMap contributors (ODbL) where the city comes from OpenStreetMap.");
    w.textWrapped(
        "Keys: Space play/pause, , and . step time, arrows/WASD pan, Q/E turn, PageUp/PageDown tilt, +/- zoom, "
        "R reset, F fly to the selection, Esc clear it, / search (Enter takes the first result); Tab and "
        "Shift+Tab move through every control, Space or Enter presses it, Esc returns to the view.");
  }
  w.end();
}

void ControlPanel::drawFilterChips(Viewer& viewer, ui::Widgets& w) {
  CityScene* city = viewer.city();
  if (city == nullptr || !city->filters().active()) return;
  const BuildingFilters& f = city->filters();
  const std::string chips = describeFilters(f);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, 10.0f), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoSavedSettings;
  if (w.begin("Active filters", nullptr, flags)) {
    w.text("Filtered (the rest is dimmed): " + chips);
    w.sameLine();
    if (w.button("Clear##filterchips")) city->setFilters(BuildingFilters{});
  }
  w.end();
}

}  // namespace qv
