// The browser app: wires the platform layer (context, input, loop), the WebGL2 device, the viewer
// and the ImGui panels together, and serves the `window.quakeview` API through exported C
// functions (see web/quakeview.js for the JavaScript side).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "qv/options/AppOptions.h"
#include "qv/platform/Browser.h"
#include "qv/platform/BrowserFetcher.h"
#include "qv/platform/BrowserInput.h"
#include "qv/quality/FrameGovernor.h"
#include "qv/render/GlRenderDevice.h"
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
};

class App {
 public:
  /// Creates the context and everything on it; false (after notifying the shell) when fatal.
  bool start(const AppOptions& options, const std::vector<std::string>& startupErrors);
  void frame();

  [[nodiscard]] Viewer& viewer() { return *viewer_; }
  [[nodiscard]] const std::string& uiText() const { return mirror_.text(); }
  [[nodiscard]] ControlPanel& panel() { return panel_; }
  [[nodiscard]] UiHost& host() { return host_; }
  /// The viewer's stats() JSON with the device's quality state added: softwareRenderer, renderer,
  /// antialias, maxPixelRatio, quality (the preset's name), governor (on/off) and qualityStep.
  [[nodiscard]] std::string statsJson(const MemoryInfo& memory) const;

 private:
  void dispatchInput();
  void dispatchKey(const InputEvent& e);
  /// Feeds the frame time to the governor and applies the panel's quality requests.
  void adaptQuality(double frameMs);

  std::unique_ptr<GlRenderDevice> device_;
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
  bool readySent_ = false;
  bool cameraOwnsPointer_ = false;
  QualityState quality_;
  FrameGovernor governor_;
  int appliedStep_ = 0;
};

}  // namespace qv
