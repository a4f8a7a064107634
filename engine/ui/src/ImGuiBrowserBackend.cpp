#include "qv/ui/ImGuiBrowserBackend.h"

#include <imgui.h>
#include <imgui_internal.h>  // ImGuiContext::Windows, for imguiBrowserCovers and the touch helpers

#include <algorithm>
#include <array>
#include <cfloat>
#include <string>
#include <vector>

namespace qv::ui {
namespace {

constexpr const char* kBackendName = "quakeview-browser";

// ImGui 1.86 keyboard: our own indices into io.KeysDown (1-based positions in this table) for the
// keys ImGui needs, by KeyboardEvent.code.
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

// What was pressed since the last imguiBrowserNewFrame (io.BackendPlatformUserData).
struct BackendData {
  std::array<bool, 5> buttonsPressed{};
  std::vector<std::string> keysPressed;
  // Wheel steps over a window since the last imguiBrowserNewFrame. ImGui reads the wheel in
  // NewFrame and clears it at the end of the frame, and the app feeds input after NewFrame: held
  // here and handed over at the next frame's start, so that ImGui scrolls the window under it.
  float pendingWheel = 0.0f;
};

BackendData* backendData() {
  if (ImGui::GetCurrentContext() == nullptr) return nullptr;
  return static_cast<BackendData*>(ImGui::GetIO().BackendPlatformUserData);
}

std::size_t buttonIndex(int button) {
  return static_cast<std::size_t>(std::clamp(button, 0, 4));
}

int keysDownIndex(std::string_view code) {
  for (std::size_t i = 0; i < kImGuiKeys.size(); ++i) {
    if (code == kImGuiKeys[i].code) return static_cast<int>(i) + 1;
  }
  return -1;
}

ImVec2 point(double x, double y) {
  return ImVec2(static_cast<float>(x), static_cast<float>(y));
}

// The front-most window ImGui drew last frame that contains the point (child windows included),
// or null. ImGuiContext::Windows is in display order, back to front.
ImGuiWindow* windowAt(double x, double y) {
  ImGuiContext* context = ImGui::GetCurrentContext();
  if (context == nullptr) return nullptr;
  const ImVec2 p = point(x, y);
  for (int i = context->Windows.Size - 1; i >= 0; --i) {
    ImGuiWindow* window = context->Windows[i];
    if (window->WasActive && !window->Hidden && window->Rect().Contains(p)) return window;
  }
  return nullptr;
}

}  // namespace

bool imguiBrowserInit() {
  if (ImGui::GetCurrentContext() == nullptr) return false;
  ImGuiIO& io = ImGui::GetIO();
  if (io.BackendPlatformUserData != nullptr || io.BackendPlatformName != nullptr) return false;
  io.BackendPlatformUserData = new BackendData();
  io.BackendPlatformName = kBackendName;
  for (std::size_t i = 0; i < kImGuiKeys.size(); ++i) io.KeyMap[kImGuiKeys[i].imguiKey] = static_cast<int>(i) + 1;
  return true;
}

void imguiBrowserShutdown() {
  BackendData* data = backendData();
  if (data == nullptr) return;
  ImGuiIO& io = ImGui::GetIO();
  delete data;
  io.BackendPlatformUserData = nullptr;
  io.BackendPlatformName = nullptr;
}

void imguiBrowserNewFrame(double cssWidth, double cssHeight, double devicePixelRatio, double deltaSeconds) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = point(cssWidth, cssHeight);
  const auto scale = static_cast<float>(devicePixelRatio);
  io.DisplayFramebufferScale = ImVec2(scale, scale);
  io.DeltaTime = static_cast<float>(std::max(deltaSeconds, 1e-4));
  if (BackendData* data = backendData()) {
    data->buttonsPressed.fill(false);
    data->keysPressed.clear();
    io.MouseWheel += data->pendingWheel;
    data->pendingWheel = 0.0f;
  }
}

bool imguiBrowserCovers(double x, double y) {
  const ImGuiContext* context = ImGui::GetCurrentContext();
  if (context == nullptr) return false;
  const ImVec2 p = point(x, y);
  for (const ImGuiWindow* window : context->Windows) {
    if (window->WasActive && !window->Hidden && window->Rect().Contains(p)) return true;
  }
  return false;
}

bool imguiBrowserMustDeferButtonUp(int button) {
  const BackendData* data = backendData();
  return data != nullptr && data->buttonsPressed[buttonIndex(button)];
}

bool imguiBrowserMustDeferKeyUp(std::string_view code) {
  const BackendData* data = backendData();
  return data != nullptr &&
         std::find(data->keysPressed.begin(), data->keysPressed.end(), code) != data->keysPressed.end();
}

void imguiBrowserPointerDown(int button, double x, double y) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = point(x, y);
  io.MouseDown[buttonIndex(button)] = true;
  if (BackendData* data = backendData()) data->buttonsPressed[buttonIndex(button)] = true;
}

void imguiBrowserPointerUp(int button) {
  ImGui::GetIO().MouseDown[buttonIndex(button)] = false;
}

void imguiBrowserPointerMove(double x, double y) {
  ImGui::GetIO().MousePos = point(x, y);
}

bool imguiBrowserWheel(double x, double y, double wheelY) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = point(x, y);
  if (!imguiBrowserCovers(x, y)) return false;
  const auto steps = static_cast<float>(-wheelY / 100.0);
  if (BackendData* data = backendData()) {
    data->pendingWheel += steps;
  } else {
    io.MouseWheel += steps;
  }
  return true;
}

bool imguiBrowserTapTitleBar(double x, double y) {
  ImGuiWindow* window = windowAt(x, y);
  if (window == nullptr || (window->Flags & (ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoCollapse)) != 0) {
    return false;
  }
  const ImRect bar = window->TitleBarRect();
  if (!bar.Contains(point(x, y))) return false;
  // The close button is a square as tall as the bar at its right end: a tap there is a click.
  if (window->HasCloseButton && x >= static_cast<double>(bar.Max.x - window->TitleBarHeight())) return false;
  ImGui::SetWindowCollapsed(window, !window->Collapsed);
  return true;
}

bool imguiBrowserTouchScroll(double x, double y, double dyCss) {
  for (ImGuiWindow* window = windowAt(x, y); window != nullptr; window = window->ParentWindow) {
    if (window->ScrollMax.y > 0.0f) {
      // Several moves in one frame add up: each starts from the target the last one set.
      const float from = window->ScrollTarget.y < FLT_MAX ? window->ScrollTarget.y : window->Scroll.y;
      ImGui::SetScrollY(window, from - static_cast<float>(dyCss));
      return true;
    }
  }
  return false;
}

void imguiBrowserKey(std::string_view code, bool down, bool shift, bool ctrl, bool alt) {
  ImGuiIO& io = ImGui::GetIO();
  io.KeyShift = shift;
  io.KeyCtrl = ctrl;
  io.KeyAlt = alt;
  const int index = keysDownIndex(code);
  if (index >= 0) io.KeysDown[index] = down;
  if (BackendData* data = backendData(); data != nullptr && down) data->keysPressed.emplace_back(code);
}

void imguiBrowserText(std::string_view utf8) {
  ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) return;
  const std::string text(utf8);  // ImGui wants a terminated string
  io.AddInputCharactersUTF8(text.c_str());
}

bool imguiBrowserWantsTextInput() {
  return ImGui::GetIO().WantTextInput;
}

}  // namespace qv::ui
