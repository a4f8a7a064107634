// The user interface (Dear ImGui): the control panel, the inspection window of the selected
// building, the legend and the orientation overlay (north arrow, scale bar, coordinates).
// Everything it shows is also written to the TextMirror behind `quakeview.uiText()`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "qv/scene/Viewer.h"
#include "qv/ui/Widgets.h"

namespace qv {

/// What the UI needs from the page it runs in.
class UiHost {
 public:
  virtual ~UiHost() = default;
  /// Opens a link in a new browser tab.
  virtual void openUrl(const std::string& url) = 0;
  /// Offers `content` to the user as a downloaded file.
  virtual void download(const std::string& filename, const std::string& mimeType, const std::string& content) = 0;
};

/// Quality presets for weak devices: draw budget, detail and animation radius.
enum class QualityPreset : int { High = 0, Balanced = 1, Low = 2 };

class ControlPanel {
 public:
  /// A canvas narrower than this (CSS px) gets the phone layout: the panel starts collapsed and
  /// never grows wider than the screen, and the inspection window is a bottom sheet.
  static constexpr float kNarrowWidthCss = 600.0f;
  /// The bottom sheet's greatest height, as a fraction of the canvas height.
  static constexpr float kBottomSheetFraction = 0.4f;
  [[nodiscard]] static bool narrowLayout(double cssWidth) { return cssWidth < static_cast<double>(kNarrowWidthCss); }

  /// Draws every window for this frame. Call between ImGui::NewFrame and ImGui::Render.
  void draw(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory, UiHost& host);

  /// The pointer position (CSS pixels) for the coordinates readout; nullopt when off the canvas.
  void setCursor(std::optional<std::pair<double, double>> css) { cursor_ = css; }
  /// Puts the keyboard focus in the search box on the next frame ('/' key).
  void focusSearch() { focusSearch_ = true; }
  /// Exports the filtered list: "csv" or "geojson". Returns the text (also downloaded).
  std::string exportList(Viewer& viewer, const std::string& format, UiHost& host);

  [[nodiscard]] static const char* qualityName(QualityPreset preset);
  static void applyQuality(Viewer& viewer, QualityPreset preset);

 private:
  void drawPanel(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory, UiHost& host);
  /// The selected building's window (ControlPanelInspection.cpp); it starts at the top for each
  /// newly selected building and scrolls when taller than the viewport.
  void drawInspection(Viewer& viewer, ui::Widgets& w, UiHost& host);
  /// Its response: damage, the one peak drift and its source, peaks, plots with axes and the
  /// current time, and the per-storey drifts on a fixed scale with the HAZUS thresholds.
  void drawResponse(Viewer& viewer, const BuildingInfo& info, ui::Widgets& w);
  void drawOverlay(Viewer& viewer, ui::Widgets& w);
  /// The active filters as a strip at the top of the canvas, whatever the panel's state.
  void drawFilterChips(Viewer& viewer, ui::Widgets& w);
  /// SCENARIO or ACTUAL (prominent), the ShakeMap, the earthquake, the record(s) and their scaling.
  static void drawShakingProvenance(const ResponseInfo& response, ui::Widgets& w);
  /// The building's Sa(T1) scaling and its spread across the record suite.
  static void drawShakingOfBuilding(const BuildingInfo& info, ui::Widgets& w);
  /// Damage-state probabilities as bars, tags, and the consequences with their "inferred" marks.
  static void drawBuildingLoss(const BuildingLoss& loss, ui::Widgets& w);
  /// City, view and district totals with their provenance, and their CSV exports.
  void drawConsequences(Viewer& viewer, ui::Widgets& w, UiHost& host);
  std::string lengthText(const Viewer& viewer, double metres) const;

  std::optional<std::pair<double, double>> cursor_;
  bool focusSearch_ = false;
  std::string search_;
  std::string inspected_;  // the building the inspection window showed last frame
  QualityPreset quality_ = QualityPreset::High;
};

}  // namespace qv
