#include "App.h"

#include <imgui.h>
#include <imgui_impl_opengl3.h>
#include <imgui_internal.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
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

std::optional<BuildingFilters> parseFilters(const std::string& text) {
  if (text.size() > 100) return std::nullopt;
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (parts.size() != 3) return std::nullopt;
  BuildingFilters f;
  if (!parts[0].empty()) {
    if (parts[0].size() != 1 || parts[0][0] < '0' || parts[0][0] > '4') return std::nullopt;
    f.minDamage = parts[0][0] - '0';
  }
  for (char c : parts[1]) {
    if (!(std::islower(static_cast<unsigned char>(c)) || c == '_')) return std::nullopt;
  }
  f.use = parts[1];
  if (!parts[2].empty() && parts[2] != "0" && parts[2] != "1") return std::nullopt;
  f.criticalOnly = parts[2] == "1";
  return f;
}

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
    } else if (a == "--page-origin" && hasValue) {
      options.city.origin.pageOrigin = args[++i];
    } else if (a == "--data-origin" && hasValue) {
      options.city.origin.urlOrigin = args[++i];
    } else if (a == "--allow-origin" && hasValue) {
      options.city.origin.allowedOrigins.push_back(args[++i]);
    } else if (a == "--shell-error" && hasValue) {
      errors.push_back(args[++i]);  // a message of the page shell (a broken config.json)
    } else if (a == "--no-antialias") {
      options.antialias = false;
    } else if (a == "--camera" && hasValue) {
      // x,y,distance,headingDeg,pitchDeg[,fovDeg] from the URL hash.
      const std::string& text = args[++i];
      std::vector<double> v;
      bool valid = true;
      std::size_t start = 0;
      while (valid && v.size() < 7) {
        const auto comma = text.find(',', start);
        const std::string piece = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        char* end = nullptr;
        const double number = std::strtod(piece.c_str(), &end);
        valid = !piece.empty() && end == piece.c_str() + piece.size() && std::isfinite(number);
        v.push_back(number);
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      valid = valid && (v.size() == 5 || v.size() == 6);
      CameraState c;
      if (valid) c = CameraState{v[0], v[1], v[2], v[3], v[4], v.size() == 6 ? v[5] : 45.0};
      CameraState checked = c;
      if (!valid || !sanitizeCamera(checked, c)) {
        errors.push_back("The camera in the link (" + text + ") is not valid; showing the default view.");
      } else {
        options.camera = checked;
      }
    } else if (a == "--time" && hasValue) {
      const std::string& v = args[++i];
      char* end = nullptr;
      const double t = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !std::isfinite(t) || t < 0.0) {
        errors.push_back("The time in the link (" + v + ") is not a number of seconds; starting at 0 s.");
      } else {
        options.timeSeconds = t;
      }
    } else if (a == "--playing" && hasValue) {
      const std::string& v = args[++i];
      if (v == "0" || v == "1") {
        options.playing = v == "1";
      } else {
        errors.push_back("The play state in the link (" + v.substr(0, 40) + ") is not 0 or 1; playing.");
      }
    } else if (a == "--select" && hasValue) {
      const std::string& v = args[++i];
      if (v.empty() || v.size() > 200 || v.find_first_of("\n\r\t") != std::string::npos) {
        errors.push_back("The selected building in the link is not a valid id; nothing is selected.");
      } else {
        options.select = v;
      }
    } else if (a == "--filters" && hasValue) {
      const std::string& v = args[++i];
      options.filters = parseFilters(v);
      if (!options.filters)
        errors.push_back("The filters in the link (" + v + ") are not valid; showing every building.");
    } else if (a == "--memory-mb" && hasValue) {
      const std::string& v = args[++i];
      char* end = nullptr;
      const double mb = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || !(mb >= 16.0 && mb <= 4096.0)) {
        errors.push_back("memory=" + v + " in the URL is not a number of megabytes from 16 to 4096; using " +
                         std::to_string(options.city.memoryBudgetBytes >> 20) + " MB.");
      } else {
        options.city.memoryBudgetBytes = static_cast<std::uint64_t>(mb * 1048576.0);
      }
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
  io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard | ImGuiConfigFlags_NavNoCaptureKeyboard;
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
  if (options.camera) viewer_->setCamera(*options.camera);
  pendingTime_ = options.timeSeconds;
  if (!options.playing) viewer_->pause();
  pendingSelect_ = options.select;
  if (options.filters && viewer_->city() != nullptr) viewer_->city()->setFilters(*options.filters);
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
        cursor_ = std::make_pair(e.x, e.y);
        if (cameraOwnsPointer_) viewer_->controller().pointerMove(e.x, e.y);
        break;
      case InputEvent::Type::PointerUp:
        io.MouseDown[button] = false;
        if (cameraOwnsPointer_) {
          const bool click = viewer_->controller().isClick() && e.button == 0;
          viewer_->controller().pointerUp(e.button);
          if (!viewer_->controller().dragging()) cameraOwnsPointer_ = false;
          // A click (no drag) selects the building under the pointer, or clears the selection.
          if (click) {
            const auto hit = viewer_->pick(e.x, e.y);
            viewer_->select(hit ? hit->attributes.id : std::string());
          }
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
        // Shortcuts reach the viewer unless a text field is being edited.
        if (!io.WantTextInput || !down) {
          if (down && e.code == "Space") {
            if (viewer_->playing())
              viewer_->pause();
            else
              viewer_->play();
          }
          if (down && (e.code == "Comma" || e.code == "Period")) {
            viewer_->pause();
            viewer_->setTime(viewer_->time() + (e.code == "Comma" ? -1.0 : 1.0));
          }
          if (down && e.code == "KeyF") viewer_->flyToSelection();
          if (down && e.code == "Escape") viewer_->select("");
          if (down && e.code == "Slash") panel_.focusSearch();
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

  // The shareable view's time and selection, once the city is there to apply them to.
  if ((pendingTime_ || !pendingSelect_.empty()) && viewer_->settled()) {
    if (pendingTime_) {
      if (*pendingTime_ > viewer_->duration()) {
        viewer_->reportError("The time in the link is beyond the end of the record; showing its end.");
      }
      viewer_->setTime(*pendingTime_);
      pendingTime_.reset();
    }
    // A building in no loaded tile is found through the search index, which the scene requests
    // once the view has settled: an unknown id is reported only when the index is there (or failed).
    if (!pendingSelect_.empty()) {
      if (viewer_->select(pendingSelect_)) {
        pendingSelect_.clear();
      } else if (viewer_->city() == nullptr || viewer_->city()->searchIndexSettled()) {
        viewer_->reportError("The building '" + pendingSelect_ +
                             "' in the link is not in this city; nothing is selected.");
        pendingSelect_.clear();
      }
    }
  }

  const MemoryInfo memory = browser::memoryInfo();
  mirror_.beginFrame();
  ui::Widgets widgets(mirror_);
  panel_.setCursor(cursor_);
  panel_.draw(*viewer_, widgets, memory, host_);
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
