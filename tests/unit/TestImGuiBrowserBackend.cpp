#include <catch2/catch.hpp>

#include <imgui.h>

#include <cstring>
#include <functional>
#include <string>

#include "HeadlessImGui.h"
#include "qv/ui/ImGuiBrowserBackend.h"
#include "qv/ui/TextMirror.h"
#include "qv/ui/Widgets.h"

using namespace qv;

namespace {

// A headless ImGui context with the browser backend installed, as the app sets it up (no
// renderer backend: frames are built and thrown away).
struct BackendFixture {
  BackendFixture() : installed(ui::imguiBrowserInit()) {}
  ~BackendFixture() { ui::imguiBrowserShutdown(); }
  BackendFixture(const BackendFixture&) = delete;
  BackendFixture& operator=(const BackendFixture&) = delete;

  // One frame of a 1280 x 720 canvas with a 200 x 150 window at (100, 100) holding what `draw`
  // adds. The app feeds a frame's events between begin() and end(), as here between frames.
  void begin() {
    ui::imguiBrowserNewFrame(1280.0, 720.0, 2.0, 1.0 / 60.0);
    ImGui::NewFrame();
  }
  void end(const std::function<void()>& draw) {
    ImGui::SetNextWindowPos(ImVec2(100.0f, 100.0f));
    ImGui::SetNextWindowSize(ImVec2(200.0f, 150.0f));
    ImGui::Begin("Panel");
    draw();
    ImGui::End();
    ImGui::Render();
  }
  void frame(const std::function<void()>& draw) {
    begin();
    end(draw);
  }

  HeadlessImGui imgui;  // before `installed`: the backend installs on this context
  bool installed = false;
};

}  // namespace

TEST_CASE("The browser backend installs once per ImGui context", "[ui][backend]") {
  CHECK_FALSE(ui::imguiBrowserInit());  // no context
  BackendFixture fixture;
  CHECK(fixture.installed);
  CHECK(std::strcmp(ImGui::GetIO().BackendPlatformName, "quakeview-browser") == 0);
  CHECK_FALSE(ui::imguiBrowserInit());
  ui::imguiBrowserShutdown();
  CHECK(ImGui::GetIO().BackendPlatformName == nullptr);
  CHECK(ui::imguiBrowserInit());
}

TEST_CASE("Each frame ImGui gets the canvas's CSS size, its pixel ratio and a positive time step", "[ui][backend]") {
  BackendFixture fixture;
  ui::imguiBrowserNewFrame(800.0, 600.0, 1.5, 0.0);
  const ImGuiIO& io = ImGui::GetIO();
  CHECK(io.DisplaySize.x == 800.0f);
  CHECK(io.DisplaySize.y == 600.0f);
  CHECK(io.DisplayFramebufferScale.x == 1.5f);
  CHECK(io.DeltaTime > 0.0f);
  ui::imguiBrowserNewFrame(800.0, 600.0, 1.5, 0.02);
  CHECK(io.DeltaTime == Approx(0.02f));
}

TEST_CASE("Events over a drawn window go to the UI, events beside it to the scene", "[ui][backend]") {
  BackendFixture fixture;
  fixture.frame([] {});
  fixture.begin();  // the app routes events after NewFrame: the window drawn last frame counts
  CHECK(ui::imguiBrowserCovers(150.0, 150.0));
  CHECK(ui::imguiBrowserCovers(299.0, 249.0));
  CHECK_FALSE(ui::imguiBrowserCovers(50.0, 50.0));
  CHECK_FALSE(ui::imguiBrowserCovers(350.0, 150.0));
  // The wheel scrolls the window under the pointer; elsewhere it is left to the scene (the camera).
  const float before = ImGui::GetIO().MouseWheel;
  CHECK(ui::imguiBrowserWheel(150.0, 150.0, 100.0));
  CHECK_FALSE(ui::imguiBrowserWheel(600.0, 400.0, 100.0));
  CHECK(ImGui::GetIO().MousePos.x == 600.0f);
  fixture.end([] {});
  // Input arrives after NewFrame, which is where ImGui scrolls the hovered window: the step over
  // the window is held until the next frame starts and handed over before its NewFrame.
  ui::imguiBrowserNewFrame(800.0, 600.0, 1.0, 0.016);
  CHECK(ImGui::GetIO().MouseWheel - before == Approx(-1.0f));
}

TEST_CASE("A click whose press and release arrive in one frame still presses a button", "[ui][backend]") {
  BackendFixture fixture;
  ImVec2 centre;
  int clicks = 0;
  auto draw = [&] {
    if (ImGui::Button("Play")) ++clicks;
    const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
    centre = ImVec2((min.x + max.x) / 2.0f, (min.y + max.y) / 2.0f);
  };
  fixture.frame(draw);
  // Both events were queued by the browser before this frame: the release has to wait.
  ui::imguiBrowserPointerMove(centre.x, centre.y);
  ui::imguiBrowserPointerDown(0, centre.x, centre.y);
  CHECK(ui::imguiBrowserMustDeferButtonUp(0));
  CHECK_FALSE(ui::imguiBrowserMustDeferButtonUp(2));
  fixture.frame(draw);
  CHECK_FALSE(ui::imguiBrowserMustDeferButtonUp(0));
  ui::imguiBrowserPointerUp(0);
  fixture.frame(draw);
  CHECK(clicks == 1);
}

TEST_CASE("Typing reaches a focused text field, and its keys are not the viewer's shortcuts", "[ui][backend]") {
  BackendFixture fixture;
  char buffer[32] = "";
  bool focus = true;
  auto draw = [&] {
    if (focus) ImGui::SetKeyboardFocusHere();
    focus = false;
    ImGui::InputText("##search", buffer, sizeof buffer);
  };
  SECTION("focused") {
    for (int i = 0; i < 3; ++i) fixture.frame(draw);
    REQUIRE(ui::imguiBrowserWantsTextInput());
    ui::imguiBrowserText("ab");
    fixture.frame(draw);
    CHECK(std::string(buffer) == "ab");
    // Backspace pressed and released within one frame: the release waits, the key still edits.
    ui::imguiBrowserKey("Backspace", true, false, false, false);
    CHECK(ui::imguiBrowserMustDeferKeyUp("Backspace"));
    CHECK_FALSE(ui::imguiBrowserMustDeferKeyUp("Tab"));
    fixture.frame(draw);
    CHECK_FALSE(ui::imguiBrowserMustDeferKeyUp("Backspace"));
    ui::imguiBrowserKey("Backspace", false, false, false, false);
    fixture.frame(draw);
    CHECK(std::string(buffer) == "a");
  }
  SECTION("not focused") {
    focus = false;
    for (int i = 0; i < 3; ++i) fixture.frame(draw);
    CHECK_FALSE(ui::imguiBrowserWantsTextInput());
    ui::imguiBrowserText("ab");
    fixture.frame(draw);
    CHECK(std::string(buffer).empty());
  }
}

TEST_CASE("Pressing or dragging on a plot says where along it, to seek the time there", "[ui][backend]") {
  BackendFixture fixture;
  TextMirror mirror;
  const float values[4] = {0.0f, 1.0f, -1.0f, 0.0f};
  float seek = -1.0f;
  ImVec2 min, max;
  auto draw = [&] {
    ui::Widgets w(mirror);
    ImGui::Text("Above the plot");
    seek = w.plot("##motion", values, 4, -1.0f, 1.0f, 40.0f, 0.5f, "Ground motion");
    min = ImGui::GetItemRectMin();
    max = ImGui::GetItemRectMax();
  };
  fixture.frame(draw);
  CHECK(seek < 0.0f);
  const float y = (min.y + max.y) / 2.0f;
  const auto at = [&](float fraction) { return min.x + (max.x - min.x) * fraction; };
  // Press at a quarter of the plot: the next frame says 0.25; drag to three quarters: 0.75.
  ui::imguiBrowserPointerMove(at(0.25f), y);
  ui::imguiBrowserPointerDown(0, at(0.25f), y);
  fixture.frame(draw);
  CHECK(seek == Approx(0.25f).margin(0.01f));
  ui::imguiBrowserPointerMove(at(0.75f), y);
  fixture.frame(draw);
  CHECK(seek == Approx(0.75f).margin(0.01f));
  // Dragged past the end: clamped.
  ui::imguiBrowserPointerMove(max.x + 50.0f, y);
  fixture.frame(draw);
  CHECK(seek == Approx(1.0f));
  ui::imguiBrowserPointerUp(0);
  fixture.frame(draw);
  CHECK(seek < 0.0f);
  // A press that began above the plot and moves onto it does not seek.
  ui::imguiBrowserPointerMove(at(0.5f), min.y - 20.0f);
  ui::imguiBrowserPointerDown(0, at(0.5f), min.y - 20.0f);
  fixture.frame(draw);
  ui::imguiBrowserPointerMove(at(0.5f), y);
  fixture.frame(draw);
  CHECK(seek < 0.0f);
  ui::imguiBrowserPointerUp(0);
  fixture.frame(draw);
}

TEST_CASE("Keys go to the UI or to the viewer's shortcuts by what holds the keyboard", "[ui][backend][keys]") {
  using ui::UiKeyboard;
  struct Row {
    const char* code;
    UiKeyboard state;
    bool ui;
    bool app;
  };
  // Tab always moves the focus; a text field swallows everything (typing "e" must not turn the
  // camera, Space must not play); a focused control takes the keys that move and press it.
  const Row rows[] = {
      {"Tab", UiKeyboard::None, true, false},          {"Tab", UiKeyboard::Typing, true, false},
      {"KeyE", UiKeyboard::None, false, true},         {"KeyE", UiKeyboard::Typing, true, false},
      {"KeyE", UiKeyboard::Navigating, false, true},   {"Space", UiKeyboard::None, false, true},
      {"Space", UiKeyboard::Typing, true, false},      {"Space", UiKeyboard::Navigating, true, false},
      {"ArrowUp", UiKeyboard::None, false, true},      {"ArrowUp", UiKeyboard::Navigating, true, false},
      {"Enter", UiKeyboard::Navigating, true, false},  {"Escape", UiKeyboard::None, false, true},
      {"Escape", UiKeyboard::Navigating, true, false}, {"Escape", UiKeyboard::Typing, true, false},
      {"Slash", UiKeyboard::None, false, true},        {"Slash", UiKeyboard::Navigating, false, true},
      {"Slash", UiKeyboard::Typing, true, false},      {"PageDown", UiKeyboard::Navigating, true, false},
  };
  for (const Row& row : rows) {
    INFO(row.code << " in state " << static_cast<int>(row.state));
    const ui::KeyRoute route = ui::routeKeyDown(row.code, row.state);
    CHECK(route.ui == row.ui);
    CHECK(route.app == row.app);
  }
}

TEST_CASE("Tab reaches every control in drawing order, with Space and Enter pressing it and Escape leaving",
          "[ui][backend][keys]") {
  BackendFixture fixture;
  ImGui::GetIO().ConfigFlags |=
      ImGuiConfigFlags_NavEnableKeyboard | ImGuiConfigFlags_NavNoCaptureKeyboard;  // as the app
  TextMirror mirror;
  bool critical = false;
  int exports = 0;
  std::string search;
  auto draw = [&] {
    ui::Widgets w(mirror);
    w.collapsingHeader("Find and filter");
    w.checkbox("Critical facilities only", &critical);
    if (w.button("Export CSV")) ++exports;
    w.inputText("Search (/)", search);
  };
  // One key press and its release, in two frames as the app delivers them.
  auto press = [&](const char* code, bool shift = false) {
    fixture.begin();
    ui::imguiBrowserKey(code, true, shift, false, false);
    fixture.end(draw);
    fixture.begin();
    ui::imguiBrowserKey(code, false, shift, false, false);
    fixture.end(draw);
  };
  fixture.frame(draw);
  fixture.frame(draw);
  CHECK(ui::imguiBrowserKeyboard() == ui::UiKeyboard::None);
  CHECK(ui::imguiBrowserFocusedControl().empty());

  press("Tab");
  CHECK(ui::imguiBrowserFocusedControl() == "Find and filter, section, expanded");
  CHECK(ui::imguiBrowserKeyboard() == ui::UiKeyboard::Navigating);
  press("Tab");
  CHECK(ui::imguiBrowserFocusedControl() == "Critical facilities only, checkbox, not checked");
  press("Space");
  CHECK(critical);
  CHECK(ui::imguiBrowserFocusedControl() == "Critical facilities only, checkbox, checked");
  press("Tab");
  CHECK(ui::imguiBrowserFocusedControl() == "Export CSV, button");
  press("Enter");
  CHECK(exports == 1);
  press("Space");
  CHECK(exports == 2);

  // A text field reached by Tab is being edited: typing goes in, the keys are not shortcuts.
  press("Tab");
  CHECK(ui::imguiBrowserKeyboard() == ui::UiKeyboard::Typing);
  fixture.begin();
  ui::imguiBrowserText("esb");
  fixture.end(draw);
  CHECK(search == "esb");

  // Past the last control Tab wraps to the first, ending the edit; Shift+Tab goes back.
  press("Tab");
  CHECK(ui::imguiBrowserFocusedControl() == "Find and filter, section, expanded");
  CHECK(ui::imguiBrowserKeyboard() == ui::UiKeyboard::Navigating);
  press("Tab", true);
  CHECK(ui::imguiBrowserKeyboard() == ui::UiKeyboard::Typing);
  press("Tab", true);
  CHECK(ui::imguiBrowserFocusedControl() == "Export CSV, button");

  // Space on a header folds it.
  press("Tab");
  press("Tab");
  CHECK(ui::imguiBrowserFocusedControl() == "Find and filter, section, expanded");
  press("Space");
  CHECK(ui::imguiBrowserFocusedControl() == "Find and filter, section, collapsed");

  // Escape hands the keyboard back to the 3D view.
  press("Escape");
  CHECK(ui::imguiBrowserKeyboard() == ui::UiKeyboard::None);
  CHECK(ui::imguiBrowserFocusedControl().empty());
  CHECK(exports == 2);
}

TEST_CASE("A tap on a window's title bar folds and unfolds it, except on its close button", "[ui][backend][touch]") {
  BackendFixture fixture;
  bool collapsed = false;
  const auto draw = [&] { collapsed = ImGui::IsWindowCollapsed(); };
  fixture.frame(draw);
  fixture.frame(draw);
  REQUIRE_FALSE(collapsed);
  fixture.begin();
  CHECK_FALSE(ui::imguiBrowserTapTitleBar(150.0, 200.0));  // the window's body: a click, not a fold
  CHECK_FALSE(ui::imguiBrowserTapTitleBar(50.0, 105.0));   // beside the window
  CHECK(ui::imguiBrowserTapTitleBar(150.0, 105.0));
  fixture.end(draw);
  fixture.frame(draw);
  CHECK(collapsed);
  fixture.begin();
  CHECK(ui::imguiBrowserTapTitleBar(150.0, 105.0));
  fixture.end(draw);
  fixture.frame(draw);
  CHECK_FALSE(collapsed);

  // A window with a close button: its right end stays the button's.
  bool open = true;
  const auto closable = [&] {
    ImGui::SetNextWindowPos(ImVec2(500.0f, 100.0f));
    ImGui::SetNextWindowSize(ImVec2(200.0f, 150.0f));
    ImGui::Begin("Closable", &open);
    ImGui::End();
  };
  fixture.frame([&] { closable(); });
  fixture.frame([&] { closable(); });
  fixture.begin();
  CHECK_FALSE(ui::imguiBrowserTapTitleBar(695.0, 105.0));
  CHECK(ui::imguiBrowserTapTitleBar(600.0, 105.0));
  fixture.end([&] { closable(); });
}

TEST_CASE("A finger dragged over a window scrolls it with the finger, elsewhere nothing scrolls",
          "[ui][backend][touch]") {
  BackendFixture fixture;
  float scrollY = 0.0f, scrollMaxY = 0.0f;
  const auto draw = [&] {
    for (int i = 0; i < 40; ++i) ImGui::Text("line %d", i);
    scrollY = ImGui::GetScrollY();
    scrollMaxY = ImGui::GetScrollMaxY();
  };
  fixture.frame(draw);
  fixture.frame(draw);
  REQUIRE(scrollMaxY > 100.0f);
  fixture.begin();
  // Two moves in one frame add up: the finger went up 30 px then 20 px more.
  CHECK(ui::imguiBrowserTouchScroll(150.0, 200.0, -30.0));
  CHECK(ui::imguiBrowserTouchScroll(150.0, 170.0, -20.0));
  CHECK_FALSE(ui::imguiBrowserTouchScroll(50.0, 50.0, -20.0));  // no window there
  fixture.end(draw);
  fixture.frame(draw);
  CHECK(scrollY == Approx(50.0f));
  // Down again, beyond the top: it stops at the top.
  fixture.begin();
  CHECK(ui::imguiBrowserTouchScroll(150.0, 150.0, 500.0));
  fixture.end(draw);
  fixture.frame(draw);
  CHECK(scrollY == 0.0f);

  // A window whose content fits does not take the drag.
  const auto oneLine = [] { ImGui::Text("one line"); };
  fixture.frame(oneLine);
  fixture.frame(oneLine);
  fixture.begin();
  CHECK_FALSE(ui::imguiBrowserTouchScroll(150.0, 200.0, -30.0));
  fixture.end(oneLine);
}
