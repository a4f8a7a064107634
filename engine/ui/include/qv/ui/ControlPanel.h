// The user interface (Dear ImGui): the control panel, the inspection window of the selected
// building, the legend and the orientation overlay (north arrow, scale bar, coordinates).
// Everything it shows is also written to the TextMirror behind `quakeview.uiText()`.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "qv/format/GroundTile.h"
#include "qv/quality/FrameGovernor.h"
#include "qv/quality/QualityPreset.h"
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
  /// Offers the picture of the view (the canvas with its caption: the event, the city, the
  /// attribution) as a downloaded PNG, once the frame being drawn is complete.
  virtual void saveImage() = 0;
};

/// How the viewer adapts to the device, shared by the app (which decides) and the Performance
/// panel (which shows it and lets the user override it). Owned by the app.
struct QualityState {
  std::string renderer;           ///< the WebGL renderer's name; empty when unknown
  bool softwareRenderer = false;  ///< isSoftwareRenderer(renderer)
  bool weakStart = false;         ///< started in the Low preset because of the software renderer
  bool antialias = true;          ///< of the context (fixed for the page's life)
  double maxPixelRatio = 0.0;     ///< cap on the device pixel ratio; 0: none
  bool governorOn = true;         ///< the frame-time governor adapts the detail step
  int governorStep = 0;           ///< steps below the preset (0 .. FrameGovernorOptions::maxStep)
  int governorMaxStep = 3;
  GovernorReason governorReason = GovernorReason::Steady;
  double governorChangeMedianMs = 0.0;  ///< the median frame time behind the last change
  double governorMedianMs = 0.0;        ///< the median frame time of the current window
  double slowFrameMs = 50.0, fastFrameMs = 25.0;
  // The drawing buffer of the current frame, set by the app every frame: on a software renderer
  // the frame time is the triangles and these samples.
  int pixelWidth = 0, pixelHeight = 0;  ///< device pixels
  int msaaSamples = 0;                  ///< samples per pixel (GL_SAMPLES); 0 or 1: no multisampling
  /// Pixels of the drawing buffer: pixelWidth x pixelHeight (0 while either is not positive).
  [[nodiscard]] std::uint64_t pixels() const {
    if (pixelWidth <= 0 || pixelHeight <= 0) return 0;
    return static_cast<std::uint64_t>(pixelWidth) * static_cast<std::uint64_t>(pixelHeight);
  }
  /// Samples filled per frame: pixels() x msaaSamples with multisampling, else pixels().
  [[nodiscard]] std::uint64_t samples() const {
    return msaaSamples > 1 ? pixels() * static_cast<std::uint64_t>(msaaSamples) : pixels();
  }
  // Requests from the panel, cleared by the app once handled.
  bool fullQualityRequested = false;  ///< "Use full quality": High preset, no pixel ratio cap, governor off
  bool presetChosen = false;          ///< the user picked a preset: the governor starts again from step 0
  bool governorToggled = false;       ///< the governor checkbox changed
};

class ControlPanel {
 public:
  /// A canvas narrower than this (CSS px) gets the phone layout: the panel starts collapsed and
  /// never grows wider than the screen, and the inspection window is a bottom sheet.
  static constexpr float kNarrowWidthCss = 600.0f;
  /// The bottom sheet's greatest height, as a fraction of the canvas height.
  static constexpr float kBottomSheetFraction = 0.4f;
  [[nodiscard]] static bool narrowLayout(double cssWidth) { return cssWidth < static_cast<double>(kNarrowWidthCss); }
  /// The right edge of the widest the main panel may be drawn on a canvas `cssWidth` wide (CSS px;
  /// 0 in the narrow layout, where it folds over the bottom): Viewer::setFramingInsetCss's widestLeft.
  [[nodiscard]] static float widestPanelRightCss(float cssWidth);

  /// Draws every window for this frame. Call between ImGui::NewFrame and ImGui::Render.
  void draw(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory, UiHost& host);

  /// The pointer position (CSS pixels) for the coordinates readout; nullopt when off the canvas.
  void setCursor(std::optional<std::pair<double, double>> css) { cursor_ = css; }
  /// Puts the keyboard focus in the search box on the next frame ('/' key).
  void focusSearch() { focusSearch_ = true; }
  /// Withdraws a `focusSearch()` not yet acted on (Escape pressed right after '/').
  void cancelFocusSearch() { focusSearch_ = false; }
  /// Exports the filtered list: "csv" or "geojson". Returns the text (also downloaded).
  std::string exportList(Viewer& viewer, const std::string& format, UiHost& host);

  /// Sets the city's detail from the preset, lowered by `governorStep` steps (qualitySettings).
  static void applyQuality(Viewer& viewer, QualityPreset preset, int governorStep = 0);
  [[nodiscard]] QualityPreset quality() const { return quality_; }
  /// The right edge of the panel at its usual width (CSS px), 0 when it is folded or on a narrow
  /// screen: the framing inset (Viewer::setFramingInsetCss). Not the width as drawn, which follows
  /// the content (errors, sections, results arriving): the same link opens the same view however
  /// its content arrived.
  [[nodiscard]] float framingRightCss() const { return framingRight_; }
  /// Opens the panel's section `label` ("Damage and colours", "Performance", ...) at the next draw.
  void openSection(const std::string& label);
  void setQuality(QualityPreset preset) { quality_ = preset; }
  /// The app's quality state shown in the Performance panel (nullptr: none); not owned.
  void setQualityState(QualityState* state) { qualityState_ = state; }

  /// A name drawn on the map in the last frame (CSS pixels), for `window.quakeview.map()`.
  struct ShownMapLabel {
    std::string text;
    GroundLabelKind kind = GroundLabelKind::Street;
    float x = 0.0f, y = 0.0f;           ///< its centre
    float width = 0.0f, height = 0.0f;  ///< its text's box before turning
    float angleDeg = 0.0f;              ///< clockwise on screen
    bool facility = false;              ///< a highlighted building's name
  };
  [[nodiscard]] const std::vector<ShownMapLabel>& shownMapLabels() const { return shownMapLabels_; }

 private:
  void drawPanel(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory, UiHost& host);
  /// The selected building's window (ControlPanelInspection.cpp); it starts at the top for each
  /// newly selected building and scrolls when taller than the viewport.
  void drawInspection(Viewer& viewer, ui::Widgets& w, UiHost& host);
  /// Its response: damage, the one peak drift and its source, peaks, plots with axes and the
  /// current time, and the per-storey drifts on a fixed scale with the HAZUS thresholds.
  void drawResponse(Viewer& viewer, const BuildingInfo& info, ui::Widgets& w);
  /// The "Damage and colours" section: the shown colour mode's key, what follows the response
  /// (and how), the damage thresholds (ControlPanelLegend.cpp, with the overlay and its key).
  void drawDamageAndColours(Viewer& viewer, ui::Widgets& w, const StatsSummary& stats);
  void drawOverlay(Viewer& viewer, ui::Widgets& w);
  /// The active filters as a strip at the top of the canvas, whatever the panel's state.
  void drawFilterChips(Viewer& viewer, ui::Widgets& w);
  /// The colour mode's key in the map overlay: its five stops (three tags) with their values.
  void drawColourKey(Viewer& viewer, ui::Widgets& w);
  /// A section header of the panel (closed until opened unless `defaultOpen`), opened now when
  /// openSection asked for it.
  bool section(ui::Widgets& w, const char* label, bool defaultOpen);
  /// The name of the map marker under the pointer, and of the selected building, beside its marker.
  void drawMarkerLabels(Viewer& viewer, ui::Widgets& w);
  /// The map's names (streets, water, parks, places) under the panels (ControlPanelMap.cpp),
  /// placed by qv::placeMapLabels clear of every window, mirrored as "Map labels: ...".
  void drawMapLabels(Viewer& viewer, ui::Widgets& w);
  /// The district shown from the consequences' table (Viewer::showDistrict) outlined on the
  /// ground, under the map's names; mirrored as "Outlined district: <name>".
  void drawDistrictOutline(const Viewer& viewer, ui::Widgets& w);
  /// One line on the map under the city: what it shows, or why there is none.
  void drawMapLine(const Tileset& tileset, ui::Widgets& w);
  /// The "Names on the map" switch (General section), when the city has a map.
  void drawMapNamesSwitch(Viewer& viewer, ui::Widgets& w);
  /// The city's scenarios (ControlPanelScenarios.cpp): the one shown, and a section listing them
  /// all with their event types, a click showing another; nothing without a catalogue.
  void drawScenarios(Viewer& viewer, ui::Widgets& w);
  /// SCENARIO or ACTUAL (prominent), the ShakeMap, the earthquake, the record(s) and their scaling.
  static void drawShakingProvenance(const ResponseInfo& response, ui::Widgets& w);
  /// The building's Sa(T1) scaling and its spread across the record suite.
  static void drawShakingOfBuilding(const BuildingInfo& info, ui::Widgets& w);
  /// "Shaking at the site (ShakeMap <id> version <v>)": the field's own values at the building.
  static void drawSiteShaking(const BuildingInfo& info, const Tileset* tileset, ui::Widgets& w);
  /// Damage-state probabilities as bars, tags, and the consequences with their "inferred" marks.
  static void drawBuildingLoss(const BuildingLoss& loss, ui::Widgets& w);
  /// City, view and district totals with their provenance, and their CSV exports.
  void drawConsequences(Viewer& viewer, ui::Widgets& w, UiHost& host);
  std::string lengthText(const Viewer& viewer, double metres) const;

  bool showMapNames_ = true;
  std::vector<ShownMapLabel> shownMapLabels_;
  std::optional<std::pair<double, double>> cursor_;
  bool focusSearch_ = false;
  std::string search_;
  std::string inspected_;     // the building the inspection window showed last frame
  float overlayTop_ = -1.0f;  // its top edge last frame (px); -1 before it was drawn
  /// Room the panels leave at the bottom for the map overlay (px): its height and margin.
  [[nodiscard]] float overlayRoom() const;
  float overlayLeft_ = -1.0f;  // the map overlay's left edge last frame (px); -1 before it was drawn
  QualityPreset quality_ = QualityPreset::High;
  float framingRight_ = 0.0f;
  std::set<std::string> openRequests_;  // openSection's, until drawn
  QualityState* qualityState_ = nullptr;
};

}  // namespace qv
