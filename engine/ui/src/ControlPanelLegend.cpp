// The control panel's legend: the "Damage and colours" section (the colour mode's full key, what
// follows the response and how, the damage thresholds) and the map overlay in the corner (north
// arrow, scale bar, cursor position and the colour key always in view).
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "PanelText.h"
#include "qv/scene/Palette.h"
#include "qv/seismic/Damage.h"
#include "qv/ui/ControlPanel.h"

namespace qv {
namespace {

using panel::kDamageLabels;
using panel::kFeetPerMetre;
using panel::percent;

// A round number of metres (1, 2 or 5 × 10^k) not larger than `limit`.
double roundLength(double limit) {
  const double p = std::pow(10.0, std::floor(std::log10(std::max(limit, 1e-3))));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * p <= limit) return m * p;
  }
  return p;
}

std::string degrees(double value, char positive, char negative) {
  return ui::format("%.5f° %c", std::abs(value), value >= 0.0 ? positive : negative);
}

}  // namespace

void ControlPanel::drawDamageAndColours(Viewer& viewer, ui::Widgets& w, const StatsSummary& s) {
  CityScene* city = viewer.city();
  const Tileset* tileset = city != nullptr ? city->tileset() : nullptr;
  const ColorMode mode = viewer.shownColorMode();
  if (viewer.showingDamageAfterShaking()) {
    w.textWrapped(
        "The shaking is over: each building shows its probability of moderate damage or worse "
        "(Play shows the shaking again).");
  }
  bool after = viewer.damageAfterShaking();
  if (w.checkbox("After the shaking, show the damage probabilities", &after)) viewer.setDamageAfterShaking(after);
  const bool byDamage = mode == ColorMode::DamageState;
  const bool probabilistic =
      mode == ColorMode::ModerateOrWorse || mode == ColorMode::ExpectedDamage || mode == ColorMode::InspectionTag;
  const std::array<std::uint64_t, 6>* inView = city != nullptr ? &city->damageInView() : nullptr;
  if (mode == ColorMode::ModerateOrWorse) {
    w.text("Probability of moderate damage or worse (HAZUS 5.1 fragility):");
  } else if (mode == ColorMode::ExpectedDamage) {
    w.text("Expected damage state (probability-weighted, HAZUS 5.1):");
  } else if (mode == ColorMode::InspectionTag) {
    w.text("Most likely inspection tag (ATC-20 placard from the damage probabilities):");
    const char* tags[3] = {"Green: inspected, no restriction (none or slight damage)",
                           "Yellow: restricted use (moderate damage)", "Red: unsafe (extensive or complete damage)"};
    for (std::size_t k = 0; k < 3; ++k) w.swatch(kTagPalette[k].r, kTagPalette[k].g, kTagPalette[k].b, tags[k]);
  } else if (byDamage || tileset == nullptr) {
    w.text("Damage state (HAZUS, from peak inter-storey drift):");
  } else if (mode == ColorMode::PeakDrift) {
    w.text("Inter-storey drift (peak):");
  } else if (city != nullptr && city->hasDriftSeries()) {
    w.textWrapped("Inter-storey drift (now), every building: its largest storey (close by, each storey):");
  } else {
    w.text("Inter-storey drift (now), animated buildings:");
  }
  for (int k = 0; k < 5 && mode != ColorMode::InspectionTag; ++k) {
    const Rgb c = kDamagePalette[static_cast<std::size_t>(k)];
    std::string label;
    if (mode == ColorMode::ModerateOrWorse) {
      label = ui::format("%d %%", 25 * k);
    } else if (mode == ColorMode::ExpectedDamage) {
      label = ui::format("%d: %s", k, kDamageLabels[k]);
    } else if (byDamage) {
      label = kDamageLabels[k];
      if (tileset != nullptr && tileset->response) {
        label += ui::format(": %llu in the city", static_cast<unsigned long long>(tileset->response->damageStates[k]));
      }
      if (inView != nullptr)
        label += ui::format(", %llu in view", static_cast<unsigned long long>((*inView)[static_cast<std::size_t>(k)]));
    } else {
      const double drift = 100.0 * static_cast<double>(kDriftStops[static_cast<std::size_t>(k)]);
      label = k < 4 ? ui::format("%g %% drift", drift) : ui::format("%g %% drift or more", drift);
    }
    w.swatch(c.r, c.g, c.b, label);
  }
  if (mode == ColorMode::CurrentDrift && city != nullptr && tileset != nullptr && city->hasDriftSeries()) {
    // Every building with a response follows its drift series (far blocks: their worst member).
    const CitySceneOptions& o = city->options();
    w.textWrapped(
        ui::format("%u buildings in view follow their response now; within %s of the camera "
                   "(at most %u) each storey moves by its own displacement where the sway (times the "
                   "amplitude) reaches a pixel on screen: %u now. The others sway as their drift series "
                   "gives: the roof by the building's drift now times its peak roof displacement over its "
                   "peak drift, at its first-mode periods (estimated as 0.1 s a storey where the response "
                   "has none), evenly in X and Y (an approximation of the history, not its record).",
                   s.latest.buildingsAnimated, lengthText(viewer, static_cast<double>(o.animationRadiusM)).c_str(),
                   o.maxAnimatedBuildings,
                   s.latest.buildingsAnimated - std::min(s.latest.buildingsAnimated, s.latest.buildingsSeriesOnly)));
  } else if (mode == ColorMode::CurrentDrift && city != nullptr && tileset != nullptr) {
    // Only animated buildings have a drift now; the others show their peak, in greys that no one
    // can take for damage that has already happened (qv/scene/Palette.h).
    w.textWrapped("Not animated (beyond the animation radius): peak drift over the whole record");
    for (std::size_t k = 0; k < kNotAnimatedPalette.size(); ++k) {
      const Rgb c = kNotAnimatedPalette[k];
      const double drift = 100.0 * static_cast<double>(kDriftStops[k]);
      w.swatch(c.r, c.g, c.b,
               k + 1 < kNotAnimatedPalette.size() ? ui::format("%g %% peak drift", drift)
                                                  : ui::format("%g %% peak drift or more", drift));
    }
    const CitySceneOptions& o = city->options();
    if (o.animationRadiusM > 0.0f && o.maxAnimatedBuildings > 0) {
      w.textWrapped(
          ui::format("Animated: the buildings within %s of the camera whose sway (times the amplitude) "
                     "reaches a pixel on screen, at most %u (Performance panel), %u now; the others and the "
                     "far-view tiles are grey.",
                     lengthText(viewer, static_cast<double>(o.animationRadiusM)).c_str(), o.maxAnimatedBuildings,
                     s.latest.buildingsAnimated));
    } else {
      w.textWrapped("Animation is off (General panel): every building shows its peak drift in grey.");
    }
  }
  std::string noResult = probabilistic ? "No result or no probabilities (hatched)" : "No result (hatched)";
  if (tileset != nullptr && tileset->response) {
    noResult += ui::format(": %llu in the city", static_cast<unsigned long long>(tileset->response->damageStates[5]));
  }
  w.swatch(kNoResultColor.r, kNoResultColor.g, kNoResultColor.b, noResult, true);
  // The thresholds behind the damage states, for the most common type of the general stock.
  const auto thresholds = seismic::hazusDriftThresholds(StructuralType::C2M, CodeEra::ModerateCode, 5);
  w.textWrapped(
      ui::format("Damage states use HAZUS drift thresholds per structural type and code era, e.g. "
                 "concrete shear wall, mid-rise, moderate code: slight %s, moderate %s, extensive %s, "
                 "complete %s. The inspection window shows each building's own.",
                 percent(thresholds[0]).c_str(), percent(thresholds[1]).c_str(), percent(thresholds[2]).c_str(),
                 percent(thresholds[3]).c_str()));
}

void ControlPanel::drawOverlay(Viewer& viewer, ui::Widgets& w) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  // In the bottom-right corner; on a phone with a building selected, just above the bottom sheet.
  const float bottom = narrowLayout(display.x) && !viewer.selection().empty()
                           ? display.y * (1.0f - kBottomSheetFraction) - 10.0f
                           : display.y - 10.0f;
  ImGui::SetNextWindowPos(ImVec2(display.x - 10.0f, bottom), ImGuiCond_Always, ImVec2(1.0f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.75f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  if (w.begin("Map", nullptr, flags)) {
    overlayLeft_ = ImGui::GetWindowPos().x;
    overlayTop_ = ImGui::GetWindowPos().y;
    // North arrow: north points up when the heading is 0 and turns against the view.
    // The "N" goes round the circle at radius + 9 px (its glyph about 7 px across): the arrow's
    // square leaves that much room on every side, so no heading puts it outside the window.
    const float radius = 16.0f;
    const float room = radius + 14.0f;
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const ImVec2 centre(p.x + room, p.y + room);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const auto angle = static_cast<float>(-viewer.camera().headingDeg * 3.14159265358979 / 180.0);
    auto rotate = [&](float x, float y) {
      return ImVec2(centre.x + x * std::cos(angle) - y * std::sin(angle),
                    centre.y + x * std::sin(angle) + y * std::cos(angle));
    };
    draw->AddCircle(centre, radius, IM_COL32(60, 60, 60, 255), 24, 1.5f);
    draw->AddTriangleFilled(rotate(0.0f, -radius + 2.0f), rotate(-5.0f, 4.0f), rotate(5.0f, 4.0f),
                            IM_COL32(200, 30, 30, 255));
    draw->AddTriangleFilled(rotate(0.0f, radius - 2.0f), rotate(-5.0f, 4.0f), rotate(5.0f, 4.0f),
                            IM_COL32(90, 90, 90, 255));
    const ImVec2 n = rotate(0.0f, -radius - 9.0f);
    draw->AddText(ImVec2(n.x - 4.0f, n.y - 7.0f), IM_COL32(30, 30, 30, 255), "N");
    ImGui::Dummy(ImVec2(2.0f * room, 2.0f * room));
    w.mirror().line(ui::format("North arrow: view heading %.0f°", viewer.camera().headingDeg));
    ImGui::SameLine();
    ImGui::BeginGroup();
    // Scale bar: a round length about 120 px long at the looked-at point.
    const double metresPerPixel = viewer.metresPerCssPixel();
    if (std::isfinite(metresPerPixel) && metresPerPixel > 0.0) {
      const double unit = viewer.showFeet() ? 1.0 / kFeetPerMetre : 1.0;  // metres per displayed unit
      const double length = roundLength(120.0 * metresPerPixel / unit) * unit;
      const auto pixels = static_cast<float>(length / metresPerPixel);
      const ImVec2 q = ImGui::GetCursorScreenPos();
      draw->AddLine(ImVec2(q.x, q.y + 10.0f), ImVec2(q.x + pixels, q.y + 10.0f), IM_COL32(30, 30, 30, 255), 2.0f);
      draw->AddLine(ImVec2(q.x, q.y + 4.0f), ImVec2(q.x, q.y + 14.0f), IM_COL32(30, 30, 30, 255), 2.0f);
      draw->AddLine(ImVec2(q.x + pixels, q.y + 4.0f), ImVec2(q.x + pixels, q.y + 14.0f), IM_COL32(30, 30, 30, 255),
                    2.0f);
      ImGui::Dummy(ImVec2(std::max(pixels, 60.0f), 16.0f));
      w.text("Scale: " + lengthText(viewer, length) + " (at the view centre)");
    }
    if (cursor_ && viewer.geo().valid()) {
      const auto ground = viewer.groundAt(cursor_->first, cursor_->second);
      const auto ll = ground ? viewer.geo().reverse(*ground) : std::nullopt;
      if (ll) {
        w.text("Cursor: " + degrees(ll->lat, 'N', 'S') + ", " + degrees(ll->lon, 'E', 'W'));
      } else {
        w.text("Cursor: (sky)");
      }
    }
    ImGui::EndGroup();
    drawColourKey(viewer, w);
  }
  w.end();
}

void ControlPanel::drawColourKey(Viewer& viewer, ui::Widgets& w) {
  // The colours' key, always in view (the panel's "Damage and colours" has the whole legend).
  const ColorMode mode = viewer.shownColorMode();
  if (mode == ColorMode::Neutral) return;
  std::string title;
  std::array<std::string, 5> labels;
  std::vector<Rgb> colours(kDamagePalette.begin(), kDamagePalette.end());
  switch (mode) {
    case ColorMode::CurrentDrift:
    case ColorMode::PeakDrift:
      title = mode == ColorMode::CurrentDrift ? "Colour: storey drift now" : "Colour: peak storey drift";
      for (std::size_t k = 0; k < labels.size(); ++k) {
        labels[k] =
            ui::format("%g", 100.0 * static_cast<double>(kDriftStops[k])) + (k + 1 == labels.size() ? " %" : "");
      }
      break;
    case ColorMode::ModerateOrWorse:
      title = viewer.showingDamageAfterShaking() ? "Colour: P(moderate damage or worse), after the shaking"
                                                 : "Colour: P(moderate damage or worse)";
      labels = {"0", "25", "50", "75", "100 %"};
      break;
    case ColorMode::InspectionTag:
      title = "Colour: most likely inspection tag";
      colours.assign(kTagPalette.begin(), kTagPalette.end());
      labels = {"green", "yellow", "red", "", ""};
      break;
    default:
      title = mode == ColorMode::ExpectedDamage ? "Colour: expected damage state" : "Colour: damage state";
      labels = {"none", "slight", "mod.", "ext.", "compl."};
      break;
  }
  w.text(title);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const float cell = 52.0f;
  const ImVec2 p = ImGui::GetCursorScreenPos();
  std::string mirrored = title + ":";
  for (std::size_t k = 0; k < colours.size(); ++k) {
    const Rgb c = colours[k];
    const ImVec2 a(p.x + cell * static_cast<float>(k), p.y);
    draw->AddRectFilled(a, ImVec2(a.x + cell - 4.0f, a.y + 10.0f),
                        ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
    draw->AddRect(a, ImVec2(a.x + cell - 4.0f, a.y + 10.0f), IM_COL32(90, 90, 90, 255));
    draw->AddText(ImVec2(a.x, a.y + 12.0f), IM_COL32(30, 30, 30, 255), labels[k].c_str());
    mirrored += " " + labels[k];
  }
  ImGui::Dummy(ImVec2(cell * static_cast<float>(colours.size()), 28.0f));
  w.mirror().line(mirrored);
}

}  // namespace qv
