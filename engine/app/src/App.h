// The browser app: wires the platform layer (context, input, loop), the WebGL2 device, the viewer
// and the ImGui panels together, and serves the `window.quakeview` API through exported C
// functions (see web/quakeview.js for the JavaScript side).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "qv/platform/Browser.h"
#include "qv/platform/BrowserFetcher.h"
#include "qv/platform/BrowserInput.h"
#include "qv/render/GlRenderDevice.h"
#include "qv/scene/Viewer.h"
#include "qv/ui/ControlPanel.h"
#include "qv/ui/TextMirror.h"

namespace qv {

struct AppOptions {
  std::string scene;    ///< "test" for the built-in test scene
  std::string dataUrl;  ///< tileset.json URL
  bool antialias = true;
  double benchSeconds = 0.0;  ///< > 0: run the benchmark flight
  CitySceneOptions city;
};

/// Parses the engine's arguments (set by the shell from the page URL). Unknown arguments are
/// reported in `errors` and ignored.
AppOptions parseAppOptions(const std::vector<std::string>& args, std::vector<std::string>& errors);

class App {
 public:
  /// Creates the context and everything on it; false (after notifying the shell) when fatal.
  bool start(const AppOptions& options, const std::vector<std::string>& startupErrors);
  void frame();

  [[nodiscard]] Viewer& viewer() { return *viewer_; }
  [[nodiscard]] const std::string& uiText() const { return mirror_.text(); }

 private:
  void dispatchInput();

  std::unique_ptr<GlRenderDevice> device_;
  BrowserFetcher fetcher_;
  bool benchSent_ = false;
  std::unique_ptr<Viewer> viewer_;
  std::unique_ptr<BrowserInput> input_;
  std::vector<InputEvent> deferred_;
  TextMirror mirror_;
  ControlPanel panel_;
  double lastFrameSeconds_ = 0.0;
  bool readySent_ = false;
  bool cameraOwnsPointer_ = false;
};

}  // namespace qv
