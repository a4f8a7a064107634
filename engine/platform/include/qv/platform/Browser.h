// Browser services for the app: the WebGL2 context, the canvas size, the main loop, memory
// figures, and the calls back into the page's shell (web/quakeview.js).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "qv/scene/PixelRatio.h"
#include "qv/scene/Viewer.h"

namespace qv::browser {

struct GlContextOptions {
  bool antialias = true;
};

/// Creates a WebGL2 context on the canvas and makes it current. False (with a reason for the
/// user in `error`) when the browser has no WebGL2.
bool createWebGl2Context(const char* canvasSelector, const GlContextOptions& options, std::string& error);

/// Samples per pixel of the current context's drawing buffer (GL_SAMPLES of the default
/// framebuffer: 4 in browsers that antialias with MSAA), 0 without multisampling.
int drawingBufferSamples();

struct CanvasSize {
  double cssWidth = 1.0, cssHeight = 1.0;
  int pixelWidth = 1, pixelHeight = 1;
  /// Drawing-buffer pixels per CSS pixel: the device's ratio as the governor capped it.
  double devicePixelRatio = 1.0;
};

/// Reads the canvas's CSS size and the device's pixel ratio, asks `governor` for the ratio to
/// draw at (given the interval since the last frame, seconds), caps it at `maxPixelRatio` when
/// that is > 0 (fewer pixels on a slow renderer: the weak-device preset), and resizes the
/// canvas's drawing buffer to CSS size × that ratio when it differs.
CanvasSize syncCanvasSize(const char* canvasSelector, PixelRatioGovernor& governor, double frameSeconds,
                          double maxPixelRatio = 0.0);

/// Live heap bytes (malloc'd and not freed) and the size of the WASM memory.
MemoryInfo memoryInfo();

/// Seconds since an arbitrary origin (performance.now()).
double nowSeconds();

/// Runs `frame` once per display refresh (requestAnimationFrame) for the life of the page.
void runMainLoop(std::function<void()> frame);

// Calls into the shell.
/// The initial view has loaded (or failed): resolves `quakeview.ready`.
void notifyReady();
/// The benchmark flight ended: sets `quakeview.benchResult` from this JSON.
void notifyBenchDone(const std::string& json);
/// Opens a link in a new tab (noopener).
void openUrl(const std::string& url);
/// Offers text to the user as a file download (a Blob behind a temporary link).
void downloadText(const std::string& filename, const std::string& mimeType, const std::string& content);
/// Downloads the picture of the view (web/quakeview.js `saveImage`: the canvas and its caption as
/// a PNG) after the frame being drawn completes.
void saveImage();

/// A fatal problem (no WebGL2, shaders failed): shows `message` on the page, rejects `ready`.
void notifyFatal(const std::string& message);

}  // namespace qv::browser
