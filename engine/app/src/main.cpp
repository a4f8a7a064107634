// Entry point of the browser app (quakeview-engine.js/.wasm) and the C functions behind the
// `window.quakeview` API. The shell (web/quakeview.js) passes the page's URL options as
// arguments and wraps these functions; strings returned stay valid until the next call.
#include <emscripten.h>

#include <string>
#include <vector>

#include "App.h"
#include "qv/core/JsonWriter.h"

namespace {
qv::App* gApp = nullptr;
std::string gReturned;  // backing store of the last string handed to JavaScript

const char* hand(std::string text) {
  gReturned = std::move(text);
  return gReturned.c_str();
}
}  // namespace

extern "C" {

EMSCRIPTEN_KEEPALIVE const char* qv_stats_json() {
  if (gApp == nullptr) return hand("null");
  return hand(gApp->viewer().statsJson(qv::browser::memoryInfo()));
}

EMSCRIPTEN_KEEPALIVE const char* qv_errors_json() {
  if (gApp == nullptr) return hand("[]");
  qv::JsonWriter w;
  w.beginArray();
  for (const std::string& e : gApp->viewer().errors()) w.value(e);
  w.endArray();
  return hand(w.take());
}

EMSCRIPTEN_KEEPALIVE const char* qv_ui_text() {
  if (gApp == nullptr) return hand("");
  return hand(gApp->uiText());
}

/// [x, y] in CSS pixels of a city-frame point, or null when it is behind the eye.
EMSCRIPTEN_KEEPALIVE const char* qv_world_to_screen(double x, double y, double z) {
  if (gApp == nullptr) return hand("null");
  const auto p = gApp->viewer().worldToScreen(x, y, z);
  if (!p) return hand("null");
  qv::JsonWriter w;
  w.beginArray().value(p->x).value(p->y).endArray();
  return hand(w.take());
}

EMSCRIPTEN_KEEPALIVE const char* qv_get_camera_json() {
  if (gApp == nullptr) return hand("null");
  return hand(gApp->viewer().cameraJson());
}

/// Sets the camera; the shell fills fields the caller left out with the current values.
/// Returns 1 when every value was valid, 0 when some were replaced (non-finite or out of range).
EMSCRIPTEN_KEEPALIVE int qv_set_camera(double x, double y, double distance, double headingDeg, double pitchDeg,
                                       double fovDeg) {
  if (gApp == nullptr) return 0;
  return gApp->viewer().setCamera(qv::CameraState{x, y, distance, headingDeg, pitchDeg, fovDeg}) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE int qv_set_time(double seconds) {
  return gApp != nullptr && gApp->viewer().setTime(seconds) ? 1 : 0;
}

EMSCRIPTEN_KEEPALIVE double qv_time() {
  return gApp == nullptr ? 0.0 : gApp->viewer().time();
}

EMSCRIPTEN_KEEPALIVE double qv_duration() {
  return gApp == nullptr ? 0.0 : gApp->viewer().duration();
}

EMSCRIPTEN_KEEPALIVE void qv_play() {
  if (gApp != nullptr) gApp->viewer().play();
}

EMSCRIPTEN_KEEPALIVE void qv_pause() {
  if (gApp != nullptr) gApp->viewer().pause();
}

EMSCRIPTEN_KEEPALIVE int qv_playing() {
  return gApp != nullptr && gApp->viewer().playing() ? 1 : 0;
}

}  // extern "C"

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::vector<std::string> errors;
  const qv::AppOptions options = qv::parseAppOptions(args, errors);
  static qv::App app;
  if (!app.start(options, errors)) return 0;
  gApp = &app;
  qv::browser::runMainLoop([] { gApp->frame(); });
  return 0;
}
