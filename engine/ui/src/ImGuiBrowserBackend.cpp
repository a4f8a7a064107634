#include "qv/ui/ImGuiBrowserBackend.h"

#include <imgui.h>
#include <imgui_internal.h>  // ImGuiContext::Windows (imguiBrowserCovers, touch helpers); navigation state (Tab order)

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

// A control of the Tab order: where it was drawn in the last frame.
struct TabStop {
  ImGuiID id = 0;
  ImGuiID window = 0;
  ImGuiID focusScope = 0;
  ImRect rect;  // absolute, as last drawn (to scroll it into view)
  std::string description;
  TabStopKind kind = TabStopKind::Press;
};

// What was pressed since the last imguiBrowserNewFrame (io.BackendPlatformUserData).
struct BackendData {
  std::array<bool, 5> buttonsPressed{};
  std::vector<std::string> keysPressed;
  // Wheel steps over a window since the last imguiBrowserNewFrame. ImGui reads the wheel in
  // NewFrame and clears it at the end of the frame, and the app feeds input after NewFrame: held
  // here and handed over at the next frame's start, so that ImGui scrolls the window under it.
  float pendingWheel = 0.0f;
  // The Tab order: the stops of the last complete frame, and those the current frame registers.
  std::vector<TabStop> stops;
  std::vector<TabStop> stopsBuilding;
  // Modifier keys as of the last event, handed to ImGui at the next frame's start with the keys
  // (ImGui asserts that they do not change within a frame).
  bool shift = false, ctrl = false, alt = false;
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

// An open pop-up (a drop-down's list) holds the keyboard until it closes.
bool anyPopupOpen() {
  const ImGuiContext* g = ImGui::GetCurrentContext();
  return g != nullptr && g->OpenPopupStack.Size > 0;
}

// Shows the keyboard focus on `stop` (ImGui's navigation highlight), bringing its window to the
// front and scrolling it into view; a text field starts being edited, as when it is clicked.
void focusStop(const TabStop& stop) {
  ImGuiContext& g = *ImGui::GetCurrentContext();
  ImGuiWindow* window = ImGui::FindWindowByID(stop.window);
  if (window == nullptr) return;
  if (g.ActiveId != 0 && g.ActiveId != stop.id) ImGui::ClearActiveID();
  ImGui::FocusWindow(window);  // also closes pop-ups (an open drop-down) above other windows
  ImGui::SetNavID(stop.id, ImGuiNavLayer_Main, stop.focusScope, ImGui::WindowRectAbsToRel(window, stop.rect));
  g.NavInputSource = ImGuiInputSource_Keyboard;
  g.NavDisableHighlight = false;
  g.NavDisableMouseHover = true;
  if (stop.rect.GetWidth() > 0.0f)
    ImGui::ScrollToRectEx(window, stop.rect, ImGuiScrollFlags_KeepVisibleEdgeX | ImGuiScrollFlags_KeepVisibleEdgeY);
  if (stop.kind == TabStopKind::Text) {
    g.NavNextActivateId = stop.id;
    g.NavNextActivateFlags = ImGuiActivateFlags_PreferInput;
  }
}

// Tab (+1) or Shift+Tab (-1): the stop after (before) the one showing the focus, wrapping around;
// from the 3D view (no focus shown: ImGui keeps a navigation id it does not show, e.g. a window's
// first item when it appears) the first (last) stop.
void moveFocus(BackendData& data, int direction) {
  const std::vector<TabStop>& stops = data.stops;
  if (stops.empty()) return;
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const ImGuiID current = g.NavDisableHighlight ? 0 : g.NavId;
  const auto n = static_cast<std::ptrdiff_t>(stops.size());
  std::ptrdiff_t at = -1;
  for (std::ptrdiff_t i = 0; i < n && current != 0; ++i) {
    if (stops[static_cast<std::size_t>(i)].id == current) at = i;
  }
  const std::ptrdiff_t next = at < 0 ? (direction > 0 ? 0 : n - 1) : ((at + direction) % n + n) % n;
  focusStop(stops[static_cast<std::size_t>(next)]);
}

bool isNavigationKey(std::string_view code) {
  constexpr std::array<std::string_view, 12> kNavigation = {"ArrowLeft", "ArrowRight", "ArrowUp",     "ArrowDown",
                                                            "Space",     "Enter",      "NumpadEnter", "Escape",
                                                            "PageUp",    "PageDown",   "Home",        "End"};
  return std::find(kNavigation.begin(), kNavigation.end(), code) != kNavigation.end();
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
    data->stops.swap(data->stopsBuilding);
    data->stopsBuilding.clear();
    io.KeyShift = data->shift;
    io.KeyCtrl = data->ctrl;
    io.KeyAlt = data->alt;
    // ImGui 1.86 presses the focused control with Space only (Enter types into sliders and text
    // fields); Enter presses buttons, checkboxes, headers and rows too, as on a web page.
    const ImGuiContext& g = *ImGui::GetCurrentContext();
    const bool enter = io.KeysDown[keysDownIndex("Enter")] || io.KeysDown[keysDownIndex("NumpadEnter")];
    if (enter && g.ActiveId == 0 && g.NavId != 0 && !g.NavDisableHighlight) {
      for (const TabStop& stop : data->stops) {
        if (stop.id == g.NavId && stop.kind == TabStopKind::Press) io.NavInputs[ImGuiNavInput_Activate] = 1.0f;
      }
    }
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

void imguiBrowserModifiers(bool shift, bool ctrl, bool alt) {
  if (BackendData* data = backendData()) {
    data->shift = shift;
    data->ctrl = ctrl;
    data->alt = alt;
    return;
  }
  ImGuiIO& io = ImGui::GetIO();
  io.KeyShift = shift;
  io.KeyCtrl = ctrl;
  io.KeyAlt = alt;
}

void imguiBrowserKey(std::string_view code, bool down, bool shift, bool ctrl, bool alt) {
  ImGuiIO& io = ImGui::GetIO();
  imguiBrowserModifiers(shift, ctrl, alt);
  BackendData* backend = backendData();
  // Tab is ours: ImGui 1.86 tabs only through text fields and sliders (and turns a slider into a
  // text field); our order reaches every control. ImGui never sees the Tab key.
  if (code == "Tab" && !ctrl && !alt) {
    if (down && backend != nullptr) moveFocus(*backend, shift ? -1 : +1);
    return;
  }
  if (code == "Escape" && down && !anyPopupOpen()) {
    imguiBrowserReleaseKeyboard();
    return;
  }
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

KeyRoute routeKeyDown(std::string_view code, UiKeyboard state) {
  if (code == "Tab" || state == UiKeyboard::Typing) return KeyRoute{true, false};
  if (state == UiKeyboard::Navigating && isNavigationKey(code)) return KeyRoute{true, false};
  return KeyRoute{false, true};
}

UiKeyboard imguiBrowserKeyboard() {
  const ImGuiContext* g = ImGui::GetCurrentContext();
  if (g == nullptr) return UiKeyboard::None;
  // A text field is being edited now (io.WantTextInput follows one frame late).
  if (g->ActiveId != 0 && g->InputTextState.ID == g->ActiveId) return UiKeyboard::Typing;
  if ((g->NavWindow != nullptr && g->NavId != 0 && !g->NavDisableHighlight) || anyPopupOpen())
    return UiKeyboard::Navigating;
  return UiKeyboard::None;
}

void imguiBrowserTabStop(unsigned id, std::string_view description, TabStopKind kind) {
  BackendData* data = backendData();
  const ImGuiContext* g = ImGui::GetCurrentContext();
  if (data == nullptr || id == 0 || g->CurrentWindow == nullptr || g->CurrentWindow->SkipItems) return;
  ImGuiWindow* window = g->CurrentWindow;
  if ((window->Flags & ImGuiWindowFlags_NoNavInputs) != 0) return;
  TabStop stop;
  stop.id = id;
  stop.window = window->ID;
  stop.focusScope = window->DC.NavFocusScopeIdCurrent;
  if (g->LastItemData.ID == id) stop.rect = g->LastItemData.NavRect;
  stop.description = std::string(description);
  stop.kind = kind;
  data->stopsBuilding.push_back(std::move(stop));
}

std::string imguiBrowserFocusedControl() {
  const BackendData* data = backendData();
  const ImGuiContext* g = ImGui::GetCurrentContext();
  if (data == nullptr || g->NavId == 0 || g->NavDisableHighlight) return {};
  // This frame's description when the control was drawn already (its state may have changed).
  for (const std::vector<TabStop>* stops : {&data->stopsBuilding, &data->stops}) {
    for (const TabStop& stop : *stops) {
      if (stop.id == g->NavId) return stop.description;
    }
  }
  return {};
}

void imguiBrowserReleaseKeyboard() {
  ImGuiContext* g = ImGui::GetCurrentContext();
  if (g == nullptr) return;
  if (g->ActiveId != 0) ImGui::ClearActiveID();
  g->NavDisableHighlight = true;
  g->NavNextActivateId = 0;     // a text field about to start its edit ('/' just pressed) does not
  ImGui::FocusWindow(nullptr);  // closes pop-ups, cancels pending moves; ImGui's NavActive turns off
}

}  // namespace qv::ui
