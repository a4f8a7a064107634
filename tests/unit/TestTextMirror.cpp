#include <catch2/catch.hpp>

#include <imgui.h>

#include "qv/scene/NullRenderDevice.h"
#include "qv/ui/ControlPanel.h"
#include "qv/ui/TextMirror.h"

using namespace qv;

namespace {

// A headless ImGui frame: no renderer backend, just the widget logic.
struct HeadlessImGui {
  HeadlessImGui() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(1280.0f, 720.0f);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }
};

std::string drawPanel(Viewer& viewer, TextMirror& mirror) {
  ControlPanel panel;
  ImGui::NewFrame();
  mirror.beginFrame();
  ui::Widgets w(mirror);
  panel.draw(viewer, w, MemoryInfo{5u * 1024u * 1024u, 64u * 1024u * 1024u});
  ImGui::Render();
  mirror.endFrame();
  return mirror.text();
}

}  // namespace

TEST_CASE("The control panel's text mirror shows what the panel says", "[ui]") {
  HeadlessImGui imgui;
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  viewer.frame(1.0 / 50.0);
  TextMirror mirror;
  const std::string text = drawPanel(viewer, mirror);
  CHECK(text.find("== QuakeView ==") != std::string::npos);
  CHECK(text.find("FPS: 50.0") != std::string::npos);
  CHECK(text.find("[Pause]") != std::string::npos);
  CHECK(text.find("draw calls 7") != std::string::npos);
  CHECK(text.find("memory: 5.0 MB live, 64.0 MB reserved") != std::string::npos);
  CHECK(text.find("== Errors ==") == std::string::npos);

  viewer.pause();
  viewer.reportError("tile 0/0/0 failed: HTTP 404");
  const std::string after = drawPanel(viewer, mirror);
  CHECK(after.find("[Play]") != std::string::npos);
  CHECK(after.find("== Errors ==\ntile 0/0/0 failed: HTTP 404") != std::string::npos);
}

TEST_CASE("Labels mirror only their visible part", "[ui]") {
  CHECK(ui::visibleLabel("Play##transport") == "Play");
  CHECK(ui::visibleLabel("Speed") == "Speed");
  CHECK(ui::format("%d storeys, %.1f m", 102, 443.2) == "102 storeys, 443.2 m");
}
