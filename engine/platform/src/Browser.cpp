#include "qv/platform/Browser.h"

#include <GLES3/gl3.h>
#include <emscripten.h>
#include <emscripten/heap.h>
#include <emscripten/html5.h>
#include <malloc.h>

#include <algorithm>
#include <cmath>

namespace qv::browser {
namespace {

std::function<void()>* gFrame = nullptr;

void frameTrampoline() {
  if (gFrame != nullptr) (*gFrame)();
}

}  // namespace

EM_JS(void, qv_js_notify_ready, (), {
  if (Module["qvHooks"] && Module["qvHooks"].ready) Module["qvHooks"].ready();
});

EM_JS(void, qv_js_notify_fatal, (const char* message), {
  var text = UTF8ToString(message);
  if (Module["qvHooks"] && Module["qvHooks"].fatal) Module["qvHooks"].fatal(text);
});

EM_JS(void, qv_js_notify_bench, (const char* json), {
  var text = UTF8ToString(json);
  if (Module["qvHooks"] && Module["qvHooks"].benchDone) Module["qvHooks"].benchDone(text);
});

EM_JS(void, qv_js_open_url, (const char* url), {
  var text = UTF8ToString(url);
  if (text.indexOf("https:") == 0 || text.indexOf("http:") == 0) window.open(text, "_blank", "noopener");
});

EM_JS(void, qv_js_download, (const char* name, const char* type, const char* data, int length), {
  var bytes = HEAPU8.slice(data, data + length);
  var blob = new Blob([bytes], {
    type:
      UTF8ToString(type)
  });
  var link = document.createElement("a");
  link.href = URL.createObjectURL(blob);
  link.download = UTF8ToString(name);
  document.body.appendChild(link);
  link.click();
  setTimeout(
      function() {
        URL.revokeObjectURL(link.href);
        link.remove();
      },
      1000);
});

// After the current frame's task (the drawing buffer then holds the whole frame, panels included).
EM_JS(void, qv_js_save_image, (), {
  setTimeout(
      function() {
        if (window.quakeview && window.quakeview.saveImage) window.quakeview.saveImage();
      },
      0);
});

bool createWebGl2Context(const char* canvasSelector, const GlContextOptions& options, std::string& error) {
  EmscriptenWebGLContextAttributes attributes;
  emscripten_webgl_init_context_attributes(&attributes);
  attributes.majorVersion = 2;
  attributes.minorVersion = 0;
  attributes.alpha = EM_FALSE;
  attributes.depth = EM_TRUE;
  attributes.stencil = EM_FALSE;
  attributes.antialias = options.antialias ? EM_TRUE : EM_FALSE;
  attributes.premultipliedAlpha = EM_FALSE;
  // Not kept between frames: keeping it costs a copy a frame, measured at one FPS step (20 -> 15)
  // of the NYC flight on SwiftShader. quakeview.screenshot() draws a frame and reads it in the
  // same task instead.
  attributes.preserveDrawingBuffer = EM_FALSE;
  attributes.powerPreference = EM_WEBGL_POWER_PREFERENCE_HIGH_PERFORMANCE;
  const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = emscripten_webgl_create_context(canvasSelector, &attributes);
  if (context <= 0) {
    error =
        "WebGL2 is not available in this browser or on this device, so the city cannot be drawn. "
        "Use a current Chrome, Edge, Firefox or Safari with hardware acceleration enabled.";
    return false;
  }
  if (emscripten_webgl_make_context_current(context) != EMSCRIPTEN_RESULT_SUCCESS) {
    error = "The WebGL2 context could not be made current.";
    return false;
  }
  return true;
}

int drawingBufferSamples() {
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  return samples;
}

CanvasSize syncCanvasSize(const char* canvasSelector, PixelRatioGovernor& governor, double frameSeconds,
                          double maxPixelRatio) {
  CanvasSize size;
  emscripten_get_element_css_size(canvasSelector, &size.cssWidth, &size.cssHeight);
  double deviceRatio = emscripten_get_device_pixel_ratio();
  if (!(deviceRatio > 0.0)) deviceRatio = 1.0;
  size.devicePixelRatio = governor.update(deviceRatio, size.cssWidth, frameSeconds);
  if (maxPixelRatio > 0.0) size.devicePixelRatio = std::min(size.devicePixelRatio, maxPixelRatio);
  size.pixelWidth = std::max(1, static_cast<int>(std::lround(size.cssWidth * size.devicePixelRatio)));
  size.pixelHeight = std::max(1, static_cast<int>(std::lround(size.cssHeight * size.devicePixelRatio)));
  int currentWidth = 0, currentHeight = 0;
  emscripten_get_canvas_element_size(canvasSelector, &currentWidth, &currentHeight);
  if (currentWidth != size.pixelWidth || currentHeight != size.pixelHeight) {
    emscripten_set_canvas_element_size(canvasSelector, size.pixelWidth, size.pixelHeight);
  }
  return size;
}

MemoryInfo memoryInfo() {
  const struct mallinfo info = mallinfo();
  MemoryInfo m;
  m.heapBytes = static_cast<std::uint64_t>(static_cast<unsigned>(info.uordblks));
  m.heapReservedBytes = static_cast<std::uint64_t>(emscripten_get_heap_size());
  return m;
}

double nowSeconds() {
  return emscripten_get_now() / 1000.0;
}

void runMainLoop(std::function<void()> frame) {
  delete gFrame;
  gFrame = new std::function<void()>(std::move(frame));
  emscripten_set_main_loop(frameTrampoline, 0, 0);
}

void notifyReady() {
  qv_js_notify_ready();
}

void notifyFatal(const std::string& message) {
  qv_js_notify_fatal(message.c_str());
}

void notifyBenchDone(const std::string& json) {
  qv_js_notify_bench(json.c_str());
}

void openUrl(const std::string& url) {
  qv_js_open_url(url.c_str());
}

void saveImage() {
  qv_js_save_image();
}

void downloadText(const std::string& filename, const std::string& mimeType, const std::string& content) {
  qv_js_download(filename.c_str(), mimeType.c_str(), content.data(), static_cast<int>(content.size()));
}

}  // namespace qv::browser
