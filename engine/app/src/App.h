// The browser app: wires the platform layer (context, input, loop), the WebGL2 device, the viewer
// and the ImGui panels together, and serves the `window.quakeview` API through exported C
// functions (see web/quakeview.js for the JavaScript side).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "qv/options/AppOptions.h"
#include "qv/platform/Browser.h"
#include "qv/platform/BrowserFetcher.h"
#include "qv/platform/BrowserInput.h"
#include "qv/quality/FrameGovernor.h"
#include "qv/quality/PanelCache.h"
#include "qv/render/GlImGuiRenderer.h"
#include "qv/render/GlRenderDevice.h"
#include "qv/scene/Map2d.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/scene/PixelRatio.h"
#include "qv/scene/TouchGesture.h"
#include "qv/scene/Viewer.h"
#include "qv/ui/ControlPanel.h"
#include "qv/ui/TextMirror.h"

namespace qv {

/// The UI's host services in the browser.
class BrowserUiHost final : public UiHost {
 public:
  void openUrl(const std::string& url) override { browser::openUrl(url); }
  void download(const std::string& filename, const std::string& mimeType, const std::string& content) override {
    browser::downloadText(filename, mimeType, content);
  }
  void saveImage() override { browser::saveImage(); }
};

class App {
 public:
  /// Creates the context and everything on it; false (after notifying the shell) when fatal.
  bool start(const AppOptions& options, const std::vector<std::string>& startupErrors);
  /// One frame; `forced` draws it even while the first view is paced (quakeview.screenshot() draws
  /// a frame and reads the canvas in the same task: the drawing buffer is not kept between frames).
  void frame(bool forced = false);

  [[nodiscard]] Viewer& viewer() { return *viewer_; }
  /// Without WebGL2 (--map2d): no 3D view, no panels drawn on the canvas; the page draws the 2D
  /// city from map2d() and the panels as HTML, and owns the pointer and the keys.
  [[nodiscard]] bool map2dMode() const { return map2d_; }
  /// This frame's 2D map (qv/scene/Map2d.h), remade on each call.
  const Map2dFrame& map2d() {
    viewer_->map2d(map2dFrame_);
    return map2dFrame_;
  }
  [[nodiscard]] const Map2dFrame& lastMap2d() const { return map2dFrame_; }
  [[nodiscard]] const std::string& uiText() const { return mirror_.text(); }
  /// The panels' accessible outline as JSON, and its revision (TextMirror::outlineJson).
  [[nodiscard]] const std::string& uiOutlineJson() const { return mirror_.outlineJson(); }
  [[nodiscard]] std::uint64_t uiOutlineRevision() const { return mirror_.outlineRevision(); }
  /// What control shows the keyboard focus ("Export CSV, button"), or "".
  [[nodiscard]] const std::string& focusedControl() const { return focusedControl_; }
  [[nodiscard]] std::string uiLayoutJson() const { return mirror_.layoutJson(); }
  [[nodiscard]] ControlPanel& panel() { return panel_; }
  [[nodiscard]] UiHost& host() { return host_; }
  /// The viewer's stats() JSON with the device's quality state added: softwareRenderer, renderer,
  /// antialias, maxPixelRatio, quality (the preset's name), governor (on/off) and qualityStep;
  /// pixels and samples of this frame's drawing buffer (QualityState::pixels, ::samples); and
  /// lastFrame {triangles, drawCalls} of this frame (the viewer's fields are medians), and
  /// lastFrame.ui, the panels' share (GlImGuiRenderer::FrameStats, PanelRefresh's counts).
  [[nodiscard]] std::string statsJson(const MemoryInfo& memory) const;

 private:
  void dispatchInput();
  void dispatchKey(const InputEvent& e);
  /// One touch event, decided by touchGesture_. Returns true when the events after it must wait
  /// for the next frame: a tap on the UI became a click there, fed over the next frames.
  bool dispatchTouch(std::vector<InputEvent>& events, std::size_t at);
  /// A click or tap on the canvas (not on the UI): selects the building under it, or clears.
  void selectAt(double x, double y);
  /// On a narrow screen, a newly selected building hidden by the bottom sheet (or off screen) is
  /// brought into the part of the view above it.
  void keepSelectionAboveSheet(double cssWidth, double cssHeight);
  /// Draws the panels through their cached picture (redrawn when PanelRefresh says so).
  void drawPanels(double nowSeconds);
  /// Applies the panel's quality requests and, when `judgeFrame`, feeds the frame time to the governor.
  void adaptQuality(double frameMs, bool judgeFrame);
  /// True when this animation frame is skipped: the first view is loading (see the definition).
  [[nodiscard]] bool pacedForFirstView(double now) const;

  std::unique_ptr<RenderDevice> device_;  // a GlRenderDevice, or a NullRenderDevice without WebGL2
  bool map2d_ = false;
  Map2dFrame map2dFrame_;
  std::unique_ptr<GlImGuiRenderer> uiRenderer_;
  BrowserFetcher fetcher_;
  bool benchSent_ = false;
  std::unique_ptr<Viewer> viewer_;
  std::unique_ptr<BrowserInput> input_;
  std::vector<InputEvent> deferred_;
  TextMirror mirror_;
  ControlPanel panel_;
  BrowserUiHost host_;
  std::optional<double> pendingTime_;
  std::string pendingSelect_;
  std::optional<std::pair<double, double>> cursor_;
  double lastFrameSeconds_ = 0.0;
  double startSeconds_ = 0.0;  // the app's start (browser::nowSeconds)
  bool readySent_ = false;
  bool cameraOwnsPointer_ = false;
  // Frames the keys after '/' still wait for the search field (dispatchInput).
  static constexpr int kSearchPendingFrames = 30;
  int searchPendingFrames_ = 0;
  bool swallowSlashText_ = false;
  std::string focusedControl_;
  TouchGestureClassifier touchGesture_;
  bool touchOnUi_ = false;   ///< the current touch gesture began on a window of the UI
  double touchLastY_ = 0.0;  ///< the dragging finger's last height (CSS px), to scroll the UI
  PixelRatioGovernor pixelRatio_;
  std::string revealedSelection_;  ///< the selection keepSelectionAboveSheet last looked at
  QualityState quality_;
  // The panels' cached picture (qv/quality/PanelCache.h): when it is redrawn, and the disjoint
  // rectangles of the windows it was drawn with. uiInput_: this frame's input acted on the panels
  // (any click, wheel, key or touch, and pointer moves over a window or off one).
  PanelRefresh panelRefresh_;
  std::vector<PixelRect> panelCover_;
  bool uiInput_ = false;
  bool pointerOverUi_ = false;
  FrameGovernor governor_;
  int appliedStep_ = 0;
};

}  // namespace qv
