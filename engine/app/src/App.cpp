#include "App.h"

#include <imgui.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>

#include <algorithm>
#include <array>
#include <cstdlib>

namespace qv {
namespace {

constexpr const char* kCanvas = "#canvas";

// ImGui 1.86 keyboard: our own indices into io.KeysDown for the keys ImGui needs.
struct ImGuiKeyCode {
  const char* code;
  int imguiKey;
};
constexpr std::array<ImGuiKeyCode, 22> kImGuiKeys = {{
    {"Tab", ImGuiKey_Tab},
    {"ArrowLeft", ImGuiKey_LeftArrow},
    {"ArrowRight", ImGuiKey_RightArrow},
    {"ArrowUp", ImGuiKey_UpArrow},
    {"ArrowDown", ImGuiKey_DownArrow},
    {"PageUp", ImGuiKey_PageUp},
    {"PageDown", ImGuiKey_PageDown},
    {"Home", ImGuiKey_Home},
    {"End", ImGuiKey_End},
    {"Insert", ImGuiKey_Insert},
    {"Delete", ImGuiKey_Delete},
    {"Backspace", ImGuiKey_Backspace},
    {"Space", ImGuiKey_Space},
    {"Enter", ImGuiKey_Enter},
    {"Escape", ImGuiKey_Escape},
    {"NumpadEnter", ImGuiKey_KeyPadEnter},
    {"KeyA", ImGuiKey_A},
    {"KeyC", ImGuiKey_C},
    {"KeyV", ImGuiKey_V},
    {"KeyX", ImGuiKey_X},
    {"KeyY", ImGuiKey_Y},
    {"KeyZ", ImGuiKey_Z},
}};

// Whether a point (CSS pixels) lies on a window ImGui drew last frame. Decided per event from the
// windows' rectangles, because ImGui 1.86 updates its own hover state only once a frame.
bool uiCovers(double x, double y) {
  const ImGuiContext* context = ImGui::GetCurrentContext();
  const ImVec2 p(static_cast<float>(x), static_cast<float>(y));
  for (const ImGuiWindow* window : context->Windows) {
    if (window->WasActive && !window->Hidden && window->Rect().Contains(p)) return true;
  }
  return false;
}

int imguiIndexForCode(const std::string& code) {
  for (std::size_t i = 0; i < kImGuiKeys.size(); ++i) {
    if (code == kImGuiKeys[i].code) return static_cast<int>(i) + 1;
  }
  return -1;
}

}  // namespace

AppOptions parseAppOptions(const std::vector<std::string>& args, std::vector<std::string>& errors) {
  AppOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool hasValue = i + 1 < args.size();
    if (a == "--scene" && hasValue) {
      options.scene = args[++i];
      if (options.scene != "test") {
        errors.push_back("Unknown scene '" + options.scene + "' in the URL (known: test); showing the test scene.");
        options.scene = "test";
      }
    } else if (a == "--data" && hasValue) {
      options.dataUrl = args[++i];
    } else if (a == "--no-antialias") {
      options.antialias = false;
    } else if (a == "--bench" && hasValue) {
      const std::string& v = args[++i];
      char* end = nullptr;
      const double seconds = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(seconds >= 1.0 && seconds <= 3600.0)) {
        errors.push_back("bench=" + v + " in the URL is not a number of seconds from 1 to 3600; no benchmark run.");
      } else {
        options.benchSeconds = seconds;
      }
    } else {
      errors.push_back("Ignored unknown engine argument '" + a + "'.");
    }
  }
  if (options.scene == "test") options.dataUrl.clear();
  return options;
}

bool App::start(const AppOptions& options, const std::vector<std::string>& startupErrors) {
  std::string error;
  if (!browser::createWebGl2Context(kCanvas, browser::GlContextOptions{options.antialias}, error)) {
    browser::notifyFatal(error);
    return false;
  }
  device_ = std::make_unique<GlRenderDevice>();
  if (!device_->ok()) {
    browser::notifyFatal("The graphics shaders could not be built on this device: " + device_->error());
    return false;
  }

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in a browser
  io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard;
  io.BackendPlatformName = "quakeview-browser";
  for (std::size_t i = 0; i < kImGuiKeys.size(); ++i) io.KeyMap[kImGuiKeys[i].imguiKey] = static_cast<int>(i) + 1;
  ImGui::StyleColorsLight();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.FrameRounding = 3.0f;
  ImGui_ImplOpenGL3_Init("#version 300 es");

  viewer_ = std::make_unique<Viewer>(*device_);
  for (const std::string& e : startupErrors) viewer_->reportError(e);
  if (!options.dataUrl.empty()) {
    viewer_->openCity(options.dataUrl, fetcher_, options.city);
  } else {
    viewer_->showTestScene();
  }
  if (options.benchSeconds > 0.0) viewer_->startBench(options.benchSeconds);
  input_ = std::make_unique<BrowserInput>(kCanvas);
  lastFrameSeconds_ = browser::nowSeconds();
  return true;
}

void App::dispatchInput() {
  ImGuiIO& io = ImGui::GetIO();
  std::vector<InputEvent> events = std::move(deferred_);
  deferred_.clear();
  for (InputEvent& e : input_->drain()) events.push_back(std::move(e));

  // ImGui 1.86 samples input state once a frame: a press and release in the same frame would be
  // lost, so an event that releases something pressed in this frame waits for the next one.
  std::array<bool, 5> pressedThisFrame{};
  std::vector<std::string> keysPressedThisFrame;
  std::size_t i = 0;
  for (; i < events.size(); ++i) {
    InputEvent& e = events[i];
    const auto button = static_cast<std::size_t>(std::clamp(e.button, 0, 4));
    if (e.type == InputEvent::Type::PointerUp && pressedThisFrame[button]) break;
    if (e.type == InputEvent::Type::KeyUp &&
        std::find(keysPressedThisFrame.begin(), keysPressedThisFrame.end(), e.code) != keysPressedThisFrame.end()) {
      break;
    }
    switch (e.type) {
      case InputEvent::Type::PointerDown: {
        io.MousePos = ImVec2(static_cast<float>(e.x), static_cast<float>(e.y));
        io.MouseDown[button] = true;
        pressedThisFrame[button] = true;
        if (!uiCovers(e.x, e.y)) {
          viewer_->controller().pointerDown(e.button, e.x, e.y, e.shift, e.ctrl);
          cameraOwnsPointer_ = true;
        }
        break;
      }
      case InputEvent::Type::PointerMove:
        io.MousePos = ImVec2(static_cast<float>(e.x), static_cast<float>(e.y));
        if (cameraOwnsPointer_) viewer_->controller().pointerMove(e.x, e.y);
        break;
      case InputEvent::Type::PointerUp:
        io.MouseDown[button] = false;
        if (cameraOwnsPointer_) {
          viewer_->controller().pointerUp(e.button);
          if (!viewer_->controller().dragging()) cameraOwnsPointer_ = false;
        }
        break;
      case InputEvent::Type::Wheel:
        io.MousePos = ImVec2(static_cast<float>(e.x), static_cast<float>(e.y));
        if (uiCovers(e.x, e.y)) {
          io.MouseWheel -= static_cast<float>(e.wheelY / 100.0);
        } else {
          viewer_->controller().wheel(e.x, e.y, e.wheelY);
        }
        break;
      case InputEvent::Type::Touch:
        if (e.touches.size() == 1)
          io.MousePos = ImVec2(static_cast<float>(e.touches[0].x), static_cast<float>(e.touches[0].y));
        if (viewer_->controller().dragging() || e.touches.empty() || !uiCovers(e.touches[0].x, e.touches[0].y)) {
          viewer_->controller().touches(e.touches);
        }
        break;
      case InputEvent::Type::KeyDown:
      case InputEvent::Type::KeyUp: {
        const bool down = e.type == InputEvent::Type::KeyDown;
        io.KeyShift = e.shift;
        io.KeyCtrl = e.ctrl;
        io.KeyAlt = e.alt;
        const int index = imguiIndexForCode(e.code);
        if (index >= 0) io.KeysDown[index] = down;
        if (down) keysPressedThisFrame.push_back(e.code);
        if (!io.WantCaptureKeyboard || !down) {
          if (down && e.code == "Space") {
            if (viewer_->playing())
              viewer_->pause();
            else
              viewer_->play();
          }
          viewer_->controller().key(cameraKeyForCode(e.code), down);
        }
        break;
      }
      case InputEvent::Type::Text:
        if (io.WantCaptureKeyboard) io.AddInputCharactersUTF8(e.code.c_str());
        break;
    }
  }
  deferred_.assign(std::make_move_iterator(events.begin() + static_cast<std::ptrdiff_t>(i)),
                   std::make_move_iterator(events.end()));
}

void App::frame() {
  const double now = browser::nowSeconds();
  const double dt = std::clamp(now - lastFrameSeconds_, 0.0, 0.25);
  lastFrameSeconds_ = now;

  const browser::CanvasSize canvas = browser::syncCanvasSize(kCanvas);
  viewer_->setViewport(canvas.pixelWidth, canvas.pixelHeight, canvas.cssWidth, canvas.cssHeight);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(canvas.cssWidth), static_cast<float>(canvas.cssHeight));
  const auto scale = static_cast<float>(canvas.devicePixelRatio);
  io.DisplayFramebufferScale = ImVec2(scale, scale);
  io.DeltaTime = static_cast<float>(std::max(dt, 1e-4));

  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  dispatchInput();
  input_->setUiWantsKeyboard(io.WantTextInput);

  viewer_->frame(dt);

  const MemoryInfo memory = browser::memoryInfo();
  mirror_.beginFrame();
  ui::Widgets widgets(mirror_);
  panel_.draw(*viewer_, widgets, memory);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  mirror_.endFrame();

  if (!readySent_ && viewer_->settled()) {
    readySent_ = true;
    browser::notifyReady();
  }
  if (!benchSent_ && !viewer_->benchResult().empty()) {
    benchSent_ = true;
    browser::notifyBenchDone(viewer_->benchResult());
  }
}

}  // namespace qv
