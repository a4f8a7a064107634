// The map under the city in the panel: its names on the canvas and its one line of provenance.
#include <imgui.h>
#include <imgui_internal.h>  // ImGuiContext::Windows: the panels the names keep clear of

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "qv/scene/MapLabels.h"
#include "qv/scene/Viewer.h"
#include "qv/ui/ControlPanel.h"
#include "qv/ui/Widgets.h"

namespace qv {
namespace {

float labelScale(GroundLabelKind kind) {
  switch (kind) {
    case GroundLabelKind::Settlement:
      return 1.35f;
    case GroundLabelKind::Neighbourhood:
      return 1.15f;
    case GroundLabelKind::Water:
    case GroundLabelKind::Park:
      return 1.0f;
    case GroundLabelKind::Street:
    case GroundLabelKind::Count:
      break;
  }
  return 0.92f;
}

ImU32 labelColour(GroundLabelKind kind) {
  switch (kind) {
    case GroundLabelKind::Water:
      return IM_COL32(24, 64, 140, 255);
    case GroundLabelKind::Park:
      return IM_COL32(30, 90, 30, 255);
    case GroundLabelKind::Neighbourhood:
      return IM_COL32(70, 40, 90, 255);
    case GroundLabelKind::Settlement:
      return IM_COL32(10, 10, 10, 255);
    case GroundLabelKind::Street:
    case GroundLabelKind::Count:
      break;
  }
  return IM_COL32(40, 40, 40, 255);
}

// Turns the vertices [first, end) of the draw list by `angle` around `centre`.
void rotateVertices(ImDrawList& list, int first, ImVec2 centre, float angle) {
  const float c = std::cos(angle);
  const float s = std::sin(angle);
  for (int i = first; i < list.VtxBuffer.Size; ++i) {
    ImVec2& p = list.VtxBuffer[i].pos;
    const float x = p.x - centre.x;
    const float y = p.y - centre.y;
    p = ImVec2(centre.x + x * c - y * s, centre.y + x * s + y * c);
  }
}

}  // namespace

void ControlPanel::drawDistrictOutline(const Viewer& viewer, ui::Widgets& w) {
  const std::vector<std::vector<glm::dvec2>>& rings = viewer.shownDistrictOutline();
  if (rings.empty()) return;
  // On the ground under the map's names: a white halo, then the navy of the report map's district
  // lines (#1d3557). A segment with an end behind the eye is left out.
  ImDrawList& list = *ImGui::GetBackgroundDrawList();
  for (const auto& [colour, width] :
       {std::pair{IM_COL32(255, 255, 255, 200), 6.0f}, {IM_COL32(29, 53, 87, 255), 3.0f}}) {
    for (const std::vector<glm::dvec2>& ring : rings) {
      std::optional<glm::dvec2> previous = viewer.worldToScreen(ring.back().x, ring.back().y, 0.0);
      for (const glm::dvec2& p : ring) {
        const std::optional<glm::dvec2> at = viewer.worldToScreen(p.x, p.y, 0.0);
        if (at && previous) {
          list.AddLine(ImVec2(static_cast<float>(previous->x), static_cast<float>(previous->y)),
                       ImVec2(static_cast<float>(at->x), static_cast<float>(at->y)), colour, width);
        }
        previous = at;
      }
    }
  }
  w.mirror().line("Outlined district: " + viewer.shownDistrict());
}

void ControlPanel::drawMapLabels(Viewer& viewer, ui::Widgets& w) {
  shownMapLabels_.clear();
  CityScene* city = viewer.city();
  if (city == nullptr || !showMapNames_) return;
  // The highlighted facilities carry their names first (above their markers, at their roofs),
  // then the map's names in their rank order.
  std::vector<std::string> facilityNames;
  const std::vector<BuildingListEntry>& marked = city->markedBuildings();
  const std::size_t facilities = std::min<std::size_t>(marked.size(), 200);
  facilityNames.reserve(facilities);
  std::vector<MapLabel> labels;
  for (std::size_t i = 0; i < facilities; ++i) {
    const BuildingListEntry& e = marked[i];
    facilityNames.push_back(!e.name.empty() ? e.name : !e.address.empty() ? e.address : e.id);
  }
  for (std::size_t i = 0; i < facilities; ++i) {
    MapLabel l;
    l.kind = GroundLabelKind::Park;  // not drawn as a park: `facility` picks the style
    l.rank = 0;
    l.position = {marked[i].x, marked[i].y};
    l.z = marked[i].heightM;
    l.text = &facilityNames[i];
    l.facility = true;
    l.liftPx = 8.0f;
    labels.push_back(l);
  }
  if (city->ground() != nullptr) {
    const std::vector<MapLabel>& map = city->ground()->labels();
    labels.insert(labels.end(), map.begin(), map.end());
  }
  if (labels.empty()) return;
  ImFont* font = ImGui::GetFont();
  const float base = ImGui::GetFontSize();
  const auto measure = [font, base](std::string_view text, GroundLabelKind kind) {
    const ImVec2 size =
        font->CalcTextSizeA(base * labelScale(kind), FLT_MAX, 0.0f, text.data(), text.data() + text.size());
    return glm::vec2(size.x, size.y);
  };
  // The windows of the last frame (the panel, the inspection, errors, chips) are kept clear.
  std::vector<Rect> windows;
  for (const ImGuiWindow* window : ImGui::GetCurrentContext()->Windows) {
    if (!window->WasActive || window->Hidden || (window->Flags & ImGuiWindowFlags_ChildWindow) != 0) continue;
    windows.push_back(
        Rect{window->Pos.x, window->Pos.y, window->Pos.x + window->Size.x, window->Pos.y + window->Size.y});
  }
  const glm::dvec2 css = viewer.cssSize();
  const std::vector<PlacedLabel> placed =
      placeMapLabels(labels, viewer.viewProjection(), glm::vec2(css), measure, windows);
  ImDrawList& list = *ImGui::GetBackgroundDrawList();
  std::string mirrored;
  for (const PlacedLabel& p : placed) {
    const float size = p.facility ? base : base * labelScale(p.kind);
    const ImVec2 topLeft(p.center.x - 0.5f * p.size.x, p.center.y - 0.5f * p.size.y);
    const char* begin = p.text.data();
    const char* end = begin + p.text.size();
    const int first = list.VtxBuffer.Size;
    // A light halo keeps the name readable over streets, water and buildings' shadows.
    for (const ImVec2 d : {ImVec2(-1, -1), ImVec2(1, 1)}) {
      list.AddText(font, size, ImVec2(topLeft.x + d.x, topLeft.y + d.y), IM_COL32(255, 255, 255, 200), begin, end);
    }
    list.AddText(font, size, topLeft, p.facility ? IM_COL32(120, 20, 10, 255) : labelColour(p.kind), begin, end);
    if (p.angleRad != 0.0f) rotateVertices(list, first, ImVec2(p.center.x, p.center.y), p.angleRad);
    shownMapLabels_.push_back(ShownMapLabel{std::string(p.text), p.kind, p.center.x, p.center.y, p.size.x, p.size.y,
                                            p.angleRad * 57.29578f, p.facility});
    if (!mirrored.empty()) mirrored += "; ";
    mirrored += p.text;
  }
  // What the canvas shows in text, for screen readers' mirror and the tests.
  if (!placed.empty()) w.mirror().line("Map labels: " + mirrored);
}

void ControlPanel::drawMapLine(const Tileset& tileset, ui::Widgets& w) {
  // One short line: the panel must leave the city most of the canvas.
  if (!tileset.ground) {
    w.text("Map: none (made with --no-ground or an older tool)");
    return;
  }
  const GroundLayer& g = *tileset.ground;
  if (g.nodes.empty()) {
    w.text("Map: none in the input (no streets, water or parks)");
    return;
  }
  auto count = [&g](const char* key) {
    const auto it = g.features.find(key);
    return it == g.features.end() ? 0ull : static_cast<unsigned long long>(it->second);
  };
  const unsigned long long streets = count("street") + count("major") + count("motorway") + count("path");
  const unsigned long long water = count("water");
  const unsigned long long open = count("park") + count("green") + count("forest");
  w.text(ui::format("Map from the input: %llu streets, %llu water, %llu parks", streets, water, open));
}

void ControlPanel::drawMapNamesSwitch(Viewer& viewer, ui::Widgets& w) {
  const CityScene* city = viewer.city();
  if (city == nullptr || city->ground() == nullptr) return;
  bool names = showMapNames_;
  if (w.checkbox("Names on the map", &names)) showMapNames_ = names;
}

}  // namespace qv
