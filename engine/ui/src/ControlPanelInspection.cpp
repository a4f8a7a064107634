// The inspection window of the selected building: what it is, its response with one peak drift
// from a stated source, plots with axes, units and the current time, and the per-storey peak drifts
// on a fixed scale with the building's HAZUS thresholds. Values and scales come from the pure
// qv/scene/InspectionValues.h; this file only draws them (Dear ImGui) and mirrors them as text.
#include <imgui.h>
#include <imgui_internal.h>  // BringWindowToDisplayFront: the inspection window appears in front, unfocused

#include <algorithm>
#include <cmath>

#include "qv/format/FacilityCategory.h"
#include "qv/scene/InspectionValues.h"
#include "qv/scene/Palette.h"
#include "qv/seismic/Damage.h"
#include "qv/seismic/TypeMixture.h"
#include "qv/ui/ControlPanel.h"

namespace qv {
namespace {

constexpr float kInspectionWidth = 370.0f;
constexpr float kMarginPx = 10.0f;
// Room left under the window for the map overlay (north arrow, scale bar, cursor) at the bottom right.
constexpr float kOverlayRoomPx = 78.0f;

ImU32 colourOf(const Rgb& c, float alpha = 1.0f) {
  return ImGui::GetColorU32(ImVec4(c.r, c.g, c.b, alpha));
}

const char* const kStateNames[4] = {"slight", "moderate", "extensive", "complete"};

// A value axis: tick values and labels for [0, top] (or [-top, top]) in the axis's display unit.
struct Axis {
  double low = 0.0, high = 1.0;  // in display units
  std::vector<double> ticks;
  double step = 1.0;
};

Axis makeAxis(double low, double high, int maxTicks) {
  Axis a;
  a.low = low;
  a.high = high > low ? high : low + 1.0;
  a.ticks = axisTicks(a.low, a.high, maxTicks);
  a.step = a.ticks.size() > 1 ? a.ticks[1] - a.ticks[0] : a.high - a.low;
  return a;
}

// Frame of a plot: the area for the curve inside room for the value labels (left) and the time
// labels (below). Returns the curve's rectangle.
struct PlotFrame {
  ImVec2 min, max;
};

PlotFrame beginPlotFrame(float height, const Axis& y, const char* yUnit) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  const float labelWidth = ImGui::CalcTextSize("0000.0").x;
  const float line = ImGui::GetTextLineHeight();
  PlotFrame f;
  f.min = ImVec2(origin.x + labelWidth + 4.0f, origin.y + line * 0.5f);
  f.max = ImVec2(origin.x + width - 4.0f, origin.y + height);
  draw->AddRectFilled(f.min, f.max, IM_COL32(25, 28, 34, 255));
  const auto yOf = [&](double v) {
    return f.max.y - static_cast<float>((v - y.low) / (y.high - y.low)) * (f.max.y - f.min.y);
  };
  for (double t : y.ticks) {
    const float py = yOf(t);
    draw->AddLine(ImVec2(f.min.x, py), ImVec2(f.max.x, py), IM_COL32(90, 95, 105, 140));
    const std::string label = tickLabel(t, y.step);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    draw->AddText(ImVec2(f.min.x - w - 3.0f, py - line * 0.5f), ImGui::GetColorU32(ImGuiCol_Text), label.c_str());
  }
  draw->AddText(ImVec2(origin.x, origin.y - line * 0.55f), ImGui::GetColorU32(ImGuiCol_Text), yUnit);
  draw->AddRect(f.min, f.max, IM_COL32(120, 125, 135, 255));
  return f;
}

// The time axis under a plot: ticks in seconds and the current time as a vertical line.
void drawTimeAxis(const PlotFrame& f, double durationSeconds, double nowSeconds) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float line = ImGui::GetTextLineHeight();
  const Axis x = makeAxis(0.0, std::max(durationSeconds, 1e-3), 6);
  const auto xOf = [&](double t) { return f.min.x + static_cast<float>(t / (x.high - x.low)) * (f.max.x - f.min.x); };
  for (double t : x.ticks) {
    const float px = xOf(t);
    draw->AddLine(ImVec2(px, f.max.y), ImVec2(px, f.max.y + 3.0f), ImGui::GetColorU32(ImGuiCol_Text));
    const std::string label = tickLabel(t, x.step);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    draw->AddText(ImVec2(std::min(px - w * 0.5f, f.max.x - w), f.max.y + 3.0f), ImGui::GetColorU32(ImGuiCol_Text),
                  label.c_str());
  }
  draw->AddText(ImVec2(f.min.x - ImGui::CalcTextSize("s ").x - 2.0f, f.max.y + 3.0f), ImGui::GetColorU32(ImGuiCol_Text),
                "s");
  if (nowSeconds >= 0.0 && nowSeconds <= durationSeconds + 1e-9) {
    const float px = xOf(nowSeconds);
    draw->AddLine(ImVec2(px, f.min.y), ImVec2(px, f.max.y), IM_COL32(60, 160, 255, 255), 2.0f);
  }
  ImGui::Dummy(ImVec2(f.max.x - ImGui::GetCursorScreenPos().x, f.max.y - ImGui::GetCursorScreenPos().y + line + 4.0f));
}

// A time series over [0, duration] as a line in display units (values × scale) with axes.
void drawSeries(const std::vector<float>& values, double scale, const Axis& y, const char* yUnit,
                double durationSeconds, double nowSeconds, float height,
                const std::array<double, 4>* thresholds = nullptr) {
  const PlotFrame f = beginPlotFrame(height, y, yUnit);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const auto yOf = [&](double v) {
    const double c = std::clamp(v, y.low, y.high);
    return f.max.y - static_cast<float>((c - y.low) / (y.high - y.low)) * (f.max.y - f.min.y);
  };
  if (thresholds != nullptr) {
    for (std::size_t k = 0; k < 4; ++k) {
      const double v = (*thresholds)[k] * scale;
      if (v > y.high) continue;
      draw->AddLine(ImVec2(f.min.x, yOf(v)), ImVec2(f.max.x, yOf(v)), colourOf(kDamagePalette[k + 1]), 1.5f);
    }
  }
  const std::size_t n = values.size();
  if (n >= 2) {
    std::vector<ImVec2> points(n);
    for (std::size_t i = 0; i < n; ++i) {
      points[i] = ImVec2(f.min.x + (f.max.x - f.min.x) * static_cast<float>(i) / static_cast<float>(n - 1),
                         yOf(static_cast<double>(values[i]) * scale));
    }
    draw->AddPolyline(points.data(), static_cast<int>(n), IM_COL32(235, 235, 240, 255), 0, 1.5f);
  }
  drawTimeAxis(f, durationSeconds, nowSeconds);
}

// Peak drift per storey, ground storey on the left, on the fixed scale [0, scaleMax] (a ratio),
// each bar in the colour of the damage state its drift reaches, the thresholds as lines.
void drawStoreyBars(const std::vector<float>& drifts, const std::array<double, 4>& thresholds, double scaleMax,
                    float height) {
  const Axis y = makeAxis(0.0, scaleMax * 100.0, 5);
  const PlotFrame f = beginPlotFrame(height, y, "%");
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const auto yOf = [&](double ratio) {
    const double c = std::clamp(ratio / scaleMax, 0.0, 1.0);
    return f.max.y - static_cast<float>(c) * (f.max.y - f.min.y);
  };
  const std::size_t n = drifts.size();
  const float slot = (f.max.x - f.min.x) / static_cast<float>(std::max<std::size_t>(n, 1));
  const float gap = slot > 4.0f ? std::max(1.0f, slot * 0.15f) : 0.0f;
  for (std::size_t s = 0; s < n; ++s) {
    const double d = static_cast<double>(drifts[s]);
    const auto state = static_cast<std::size_t>(seismic::classifyDamage(d, thresholds));
    const float x0 = f.min.x + slot * static_cast<float>(s) + gap * 0.5f;
    const float top = yOf(d);
    draw->AddRectFilled(ImVec2(x0, std::min(top, f.max.y - 1.0f)), ImVec2(x0 + std::max(slot - gap, 1.0f), f.max.y),
                        colourOf(kDamagePalette[state]));
    if (d > scaleMax) {  // beyond the scale: an arrow on top says so
      draw->AddTriangleFilled(ImVec2(x0, f.min.y + 5.0f), ImVec2(x0 + std::max(slot - gap, 4.0f), f.min.y + 5.0f),
                              ImVec2(x0 + std::max(slot - gap, 4.0f) * 0.5f, f.min.y), IM_COL32(255, 255, 255, 255));
    }
  }
  const float line = ImGui::GetTextLineHeight();
  // The lines' names sit above them at the right; a name that would overlap the one before (close
  // thresholds) moves left of it.
  float lastY = 1e9f, lastLeft = f.max.x;
  for (std::size_t k = 0; k < 4; ++k) {
    if (thresholds[k] > scaleMax || !(thresholds[k] > 0.0)) continue;
    const float py = yOf(thresholds[k]);
    draw->AddLine(ImVec2(f.min.x, py), ImVec2(f.max.x, py), colourOf(kDamagePalette[k + 1]), 1.5f);
    const char* name = kStateNames[k];
    const float w = ImGui::CalcTextSize(name).x;
    const float right = std::abs(lastY - py) < line ? lastLeft - 6.0f : f.max.x - 2.0f;
    draw->AddText(ImVec2(right - w, py - line), colourOf(kDamagePalette[k + 1]), name);
    lastY = py;
    lastLeft = right - w;
  }
  // Storey numbers under the bars: the first, the last and a few between.
  const std::size_t every = std::max<std::size_t>(1, (n + 5) / 6);
  for (std::size_t s = 0; s < n; s += every) {
    const std::string label = std::to_string(s + 1);
    const float px = f.min.x + slot * (static_cast<float>(s) + 0.5f) - ImGui::CalcTextSize(label.c_str()).x * 0.5f;
    draw->AddText(ImVec2(px, f.max.y + 2.0f), ImGui::GetColorU32(ImGuiCol_Text), label.c_str());
  }
  ImGui::Dummy(ImVec2(f.max.x - ImGui::GetCursorScreenPos().x, f.max.y - ImGui::GetCursorScreenPos().y + line + 4.0f));
}

}  // namespace

void ControlPanel::drawInspection(Viewer& viewer, ui::Widgets& w, UiHost& host) {
  const std::string id = viewer.selection();
  if (id.empty()) {
    inspected_.clear();
    return;
  }
  const auto info = viewer.building(id);
  if (!info) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  // The window fits the screen: as tall as its content up to the viewport less the margins and
  // the map overlay's room; beyond that it scrolls (wheel, scrollbar, keyboard).
  if (narrowLayout(display.x)) {
    // A phone: a bottom sheet across the screen, at most its lower part, so that the building
    // stays in view above it (the app brings it there).
    ImGui::SetNextWindowPos(ImVec2(0.0f, display.y), ImGuiCond_Always, ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(display.x, 0.0f), ImVec2(display.x, display.y * kBottomSheetFraction));
  } else {
    const float maxHeight = std::max(160.0f, display.y - 2.0f * kMarginPx - std::max(kOverlayRoomPx, overlayRoom()));
    ImGui::SetNextWindowPos(ImVec2(display.x - kInspectionWidth - kMarginPx, kMarginPx), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(kInspectionWidth, 0.0f), ImVec2(kInspectionWidth, maxHeight));
  }
  ImGui::SetNextWindowBgAlpha(0.92f);
  bool open = true;
  const std::string title = "Building " + id + "###inspection";
  const bool newBuilding = id != inspected_;
  inspected_ = id;
  // A selection does not take the keyboard: a search just asked for ('/') keeps its field, and a
  // control showing the focus keeps it. The window still comes to the front.
  if (w.begin(title.c_str(), &open, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoFocusOnAppearing)) {
    if (ImGui::IsWindowAppearing()) ImGui::BringWindowToDisplayFront(ImGui::GetCurrentWindow());
    // Each newly selected building starts at the top (its name), not where the last one was scrolled to.
    if (newBuilding) ImGui::SetScrollY(0.0f);
    const BuildingAttributes& a = info->attributes;
    w.text(a.name.empty() ? std::string("(no name)") : a.name);
    w.field("Use", a.use.empty() ? std::string("unknown") : a.use);
    if (!a.address.empty()) w.field("Address", a.address);
    if (!info->detailed) w.text("(loading the full record of this building)");
    w.field("Height", lengthText(viewer, a.heightM) + (a.heightSource == ValueSource::Tagged
                                                           ? std::string(" (tagged)")
                                                           : std::string(" (inferred from storeys and use)")));
    w.field("Storeys", ui::format("%u", a.storeys) + (a.storeysSource == ValueSource::Tagged
                                                          ? std::string(" (tagged)")
                                                          : std::string(" (inferred from height and use)")));
    if (a.minHeightM > 0.0f) w.field("Base", lengthText(viewer, a.minHeightM));
    if (const seismic::TypeMixtureInfo m = seismic::buildingTypeMixture(a); !m.shares.empty()) {
      // The type is a guess from use and height: the damage spreads over the Hazus types.
      w.field("Structure", "not in the data; modelled as " + std::string(structuralTypeCode(a.structuralType)) + " (" +
                               std::string(structuralTypeDescription(a.structuralType)) + ", a guess)");
      std::string shares;
      for (const seismic::TypeShare& t : m.shares) {
        shares += (shares.empty() ? "" : ", ") + std::string(t.code) + ui::format(" %.0f %%", 100 * t.share);
      }
      w.textWrapped(ui::format("Damage is the mixture over the Hazus types of a %s %s building: ",
                               std::string(seismic::occupancyCode(m.occupancy)).c_str(),
                               std::string(m.heightClass).c_str()) +
                    shares + " (" + std::string(seismic::kTypeMixtureSource) +
                    (m.substituted ? "; none published for this class and height, the nearest class's" : "") + ")");
    } else {
      w.field("Structure", std::string(structuralTypeCode(a.structuralType)) + ", " +
                               std::string(structuralTypeDescription(a.structuralType)) +
                               (a.structure.empty() && a.material.empty() ? " (inferred)" : " (from its tags)"));
    }
    w.field("Code era",
            a.codeEra == CodeEra::Unknown
                ? ui::format("year unknown: damage judged %.0f %% pre-code, %.0f %% low code (Hazus's New "
                             "York default; wood frame at low code)",
                             100 * seismic::kUnknownEraPreCodeShare, 100 * (1 - seismic::kUnknownEraPreCodeShare))
                : std::string(codeEraName(a.codeEra)) +
                      (a.startYear > 0 ? ui::format(" (built %d)", a.startYear) : std::string()));
    // The facility category (FacilityCategory.h), never height or parts.
    const FacilityClass facility = classifyFacility(a);
    if (facility.category == FacilityCategory::None) {
      w.field("Facility", "general (not a critical, high-occupancy or hazardous facility)");
    } else {
      w.field("Facility",
              std::string(facilityCategoryLabel(facility.category)) + " (" + std::string(facility.kind) + ")");
      w.textWrapped("Source: " + std::string(facilityCategorySource(facility.category)));
    }
    // Why values were inferred or changed (docs/attributes.md, "Plausibility rules").
    for (unsigned bit = 1; bit < 256; bit <<= 1) {
      if ((a.notes & bit) != 0) w.textWrapped("Inferred: " + std::string(attributeNoteText(bit)));
    }
    if (a.lod == 2 && !info->modelSource.empty()) {
      const std::string_view source = info->modelSource == "cityjson"    ? "CityJSON"
                                      : info->modelSource == "obj"       ? "OBJ"
                                      : info->modelSource == "osm-parts" ? "OpenStreetMap building parts"
                                      : info->modelSource == "synthetic" ? "the synthetic city's tower generator"
                                                                         : "other source";
      w.field("Model",
              ui::format("LOD2 detailed model from %s, %u triangles%s", std::string(source).c_str(),
                         info->modelTriangles, info->detailed ? "" : "; drawn as its extruded parts at this distance"));
    } else {
      w.field("Model", a.lod == 2 ? "LOD2 detailed model" : "LOD1 extruded footprint");
    }
    if (a.id.size() > 1 && (a.id[0] == 'w' || a.id[0] == 'r') &&
        a.id.find_first_not_of("0123456789", 1) == std::string::npos) {
      const std::string path = (a.id[0] == 'w' ? "way/" : "relation/") + a.id.substr(1);
      const std::string url = "https://www.openstreetmap.org/" + path;
      if (w.button(("View on openstreetmap.org/" + path).c_str())) host.openUrl(url);
    }
    w.separator();
    if (info->hasResponse && info->response.source != ResponseSource::None) {
      drawResponse(viewer, *info, w);
    } else {
      w.swatch(kNoResultColor.r, kNoResultColor.g, kNoResultColor.b, "No earthquake result for this building", true);
      if (info->hasResponse) {
        w.textWrapped("Reason: " + std::string(noResultReasonDescription(info->response.noResultReason)));
      }
      drawSiteShaking(*info, viewer.city() != nullptr ? viewer.city()->tileset() : nullptr, w);
    }
    if (w.button("Fly to (F)")) viewer.flyToSelection();
    w.sameLine();
    if (w.button("Close (Esc)")) open = false;
  }
  w.end();
  if (!open) viewer.select("");
}

void ControlPanel::drawResponse(Viewer& viewer, const BuildingInfo& info, ui::Widgets& w) {
  const BuildingAttributes& a = info.attributes;
  const BuildingResponse& r = info.response;
  const bool feet = viewer.showFeet();
  const Rgb c = r.damage == DamageState::NoResult ? kNoResultColor : kDamagePalette[static_cast<std::size_t>(r.damage)];
  w.swatch(c.r, c.g, c.b, "Damage state: " + std::string(damageStateName(r.damage)));
  const auto t = seismic::hazusDriftThresholds(a.structuralType, a.codeEra, a.storeys);
  w.textWrapped(ui::format("HAZUS thresholds for %s, %s: slight %s, moderate %s, extensive %s, complete %s",
                           std::string(structuralTypeCode(a.structuralType)).c_str(),
                           std::string(codeEraName(a.codeEra)).c_str(), driftPercentText(t[0]).c_str(),
                           driftPercentText(t[1]).c_str(), driftPercentText(t[2]).c_str(),
                           driftPercentText(t[3]).c_str()));
  // The one peak drift of the window, with its source; the plots below say how they relate to it.
  std::string where;
  if (!info.storeyPeakDrift.empty()) {
    const auto worst = static_cast<std::size_t>(
        std::max_element(info.storeyPeakDrift.begin(), info.storeyPeakDrift.end()) - info.storeyPeakDrift.begin());
    where = ui::format(" in storey %zu", worst + 1);
  }
  w.field("Peak inter-storey drift", driftPercentText(r.peakDriftRatio) + where +
                                         (r.source == ResponseSource::Imported ? " (peak of the imported analysis)"
                                                                               : " (exact peak from the solver)"));
  w.field("Peak roof displacement", displacementText(r.peakRoofDisplacementM, feet));
  // The site's own shaking first; the record's PGA is what the scaled record peaks at (its scale
  // follows Sa(T1), so it differs from the site's PGA).
  drawSiteShaking(info, viewer.city() != nullptr ? viewer.city()->tileset() : nullptr, w);
  w.field("Record's PGA (scaled)", ui::format("%.3f g", static_cast<double>(r.pgaG)));
  w.field("Residual drift", driftPercentText(r.residualDriftRatio));
  w.field("Results from",
          r.source == ResponseSource::Imported ? "imported analysis" : "MDOF shear-building model (simplified)");
  if (r.approximate) {
    w.textColored(0.6f, 0.35f, 0.0f,
                  ui::format("Approximate (solver did not converge at %u steps, residual %.2g of the forces)",
                             r.unconvergedSteps, static_cast<double>(r.worstResidualRatio)));
  }
  drawShakingOfBuilding(info, w);
  if (info.loss) drawBuildingLoss(*info.loss, w);

  if (!info.storeyPeakDrift.empty()) {
    w.separator();
    const double scaleMax = storeyDriftScaleMax(t);
    std::string lines;
    for (std::size_t k = 0; k < 4; ++k) {
      if (t[k] <= scaleMax) lines += (lines.empty() ? "" : ", ") + std::string(kStateNames[k]);
    }
    w.textWrapped(
        ui::format("Peak drift per storey (storey 1 = ground, left), fixed scale 0 to %s; lines: %s "
                   "thresholds; bars coloured by the state they reach",
                   driftPercentText(scaleMax).c_str(), lines.c_str()));
    drawStoreyBars(info.storeyPeakDrift, t, scaleMax, 96.0f);
    std::array<std::size_t, 5> reached{};
    for (float d : info.storeyPeakDrift) ++reached[static_cast<std::size_t>(seismic::classifyDamage(d, t))];
    std::string counts;
    const char* const names[5] = {"none", "slight", "moderate", "extensive", "complete"};
    for (std::size_t k = 0; k < 5; ++k) {
      if (reached[k] > 0) counts += (counts.empty() ? "" : ", ") + ui::format("%zu %s", reached[k], names[k]);
    }
    w.mirror().line("Storeys by the state their drift reaches: " + counts);
  }

  CityScene* city = viewer.city();
  if (city == nullptr) return;
  const auto series = city->selectionSeries(240);
  if (!series) {
    w.text("(loading this building's motion)");
    return;
  }
  const std::size_t n = series->roofDisplacementM.size();
  const double now = viewer.time();
  const auto at = std::min<std::size_t>(
      n - 1,
      static_cast<std::size_t>(
          std::clamp(now / std::max(series->durationSeconds, 1e-3), 0.0, 1.0) * static_cast<double>(n - 1) + 0.5));
  w.separator();
  // Drift over time: the stored (compressed) history, which the peak above need not match exactly.
  const double bound = historyDriftErrorBound(r.peakRoofDisplacementM, std::max(a.storeyHeightM(), 0.1f));
  const float driftTop = *std::max_element(series->maxDriftRatio.begin(), series->maxDriftRatio.end());
  const double driftAxisTop = std::max(static_cast<double>(std::max(driftTop, r.peakDriftRatio)) * 100.0 * 1.05, 0.01);
  w.textWrapped("Largest inter-storey drift over time (%), now " + driftPercentText(series->maxDriftRatio[at]));
  const Axis driftAxis = makeAxis(0.0, driftAxisTop, 4);
  drawSeries(series->maxDriftRatio, 100.0, driftAxis, "%", series->durationSeconds, now, 70.0f, &t);
  w.textWrapped(
      ui::format("Plotted from the stored history (%zu samples): each floor within %.1f %% of the peak "
                 "roof displacement, so drift within ±%s of the solver's; the peak above is the "
                 "solver's exact value.",
                 n, kHistoryRelativeErrorBound * 100.0, driftPercentText(bound).c_str()));
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "The viewer stores each building's motion compressed (a few shape vectors x quantized time\n"
        "series, docs/formats.md). Its highest point can differ from the solver's peak by up to the\n"
        "bound, and the plot's samples can fall between the solver's steps.");
  }
  // Roof displacement over time, in the unit its peak reads best in.
  const float roofTop = std::max(*std::max_element(series->roofDisplacementM.begin(), series->roofDisplacementM.end()),
                                 r.peakRoofDisplacementM);
  const DisplayUnit unit = displacementUnit(roofTop, feet);
  w.textWrapped(std::string("Roof displacement over time (") + unit.name + "), now " +
                displacementText(series->roofDisplacementM[at], feet));
  const Axis roofAxis = makeAxis(0.0, std::max(static_cast<double>(roofTop) / unit.metresPerUnit * 1.05, 0.1), 4);
  drawSeries(series->roofDisplacementM, 1.0 / unit.metresPerUnit, roofAxis, unit.name, series->durationSeconds, now,
             70.0f);
  w.mirror().line(
      ui::format("Plot axes: time 0 to %.1f s, the current time %.1f s marked", series->durationSeconds, now));
}

namespace {

// What a map marker's label says: the building's name (or address, or id), its facility kind and
// how likely it is damaged.
std::string markerLabel(const BuildingListEntry& e) {
  std::string label(listName(e));
  if (e.facility != FacilityCategory::None) {
    const std::string kind = facilityKindLabel(e.facilityKind);
    label += " (" + std::string(facilityCategoryLabel(e.facility)) + (kind.empty() ? "" : ": " + kind) + ")";
  }
  if (e.loss) {
    label += ui::format(": P(moderate or worse) %.0f %%", static_cast<double>(e.loss->structuralAtLeast(2)) * 100.0);
  } else if (e.damage != DamageState::NoResult) {
    label += ": " + std::string(damageStateName(e.damage));
  }
  return label;
}

// `rightLimit`: where the free part of the canvas ends (the inspection window's left edge, or the
// canvas's): a label that would reach beyond it goes to the marker's left instead.
void labelAt(ui::Widgets& w, const char* id, glm::dvec2 at, const std::string& text, float rightLimit) {
  const float width = ImGui::CalcTextSize(text.c_str()).x + 2.0f * ImGui::GetStyle().WindowPadding.x;
  const bool left = static_cast<float>(at.x) + 12.0f + width > rightLimit;
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(at.x) + (left ? -12.0f : 12.0f), static_cast<float>(at.y) - 12.0f),
                          ImGuiCond_Always, ImVec2(left ? 1.0f : 0.0f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoNav;
  if (w.begin(id, nullptr, flags)) w.text(text);
  w.end();
}

}  // namespace

void ControlPanel::drawMarkerLabels(Viewer& viewer, ui::Widgets& w) {
  CityScene* city = viewer.city();
  if (city == nullptr) return;
  // The marked building under the pointer (within its 7 px disc, a little more), unless a window is.
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const BuildingListEntry* hovered = nullptr;
  glm::dvec2 hoveredAt{};
  double nearest = 10.0 * 10.0;
  if (!ImGui::IsWindowHovered(ImGuiHoveredFlags_AnyWindow) && mouse.x > -1e6f) {
    for (const BuildingListEntry& e : city->markedBuildings()) {
      const auto p = viewer.worldToScreen(e.x, e.y, e.heightM);
      if (!p) continue;
      const double d2 = (p->x - mouse.x) * (p->x - mouse.x) + (p->y - mouse.y) * (p->y - mouse.y);
      if (d2 < nearest) {
        nearest = d2;
        hovered = &e;
        hoveredAt = *p;
      }
    }
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float rightLimit = !viewer.selection().empty() && !narrowLayout(display.x)
                               ? display.x - kInspectionWidth - 2.0f * kMarginPx
                               : display.x - kMarginPx;
  if (hovered != nullptr) {
    labelAt(w, "Building under the pointer##markerHover", hoveredAt, markerLabel(*hovered), rightLimit);
  }
  // The selected building carries its name on the map.
  if (const auto selected = city->selectedListEntry()) {
    if (hovered == nullptr || hovered->id != selected->id) {
      if (const auto p = viewer.worldToScreen(selected->x, selected->y, selected->heightM)) {
        labelAt(w, "Selected building on the map##markerSelected", *p, markerLabel(*selected), rightLimit);
      }
    }
  }
}

}  // namespace qv
