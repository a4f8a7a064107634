#include <catch2/catch.hpp>

#include <imgui.h>

#include <string>
#include <vector>

#include "HeadlessImGui.h"
#include "qv/ui/PanelPicture.h"

namespace {

/// One ImGui frame with a window at (40, 30), 300 x 200, showing `text`, and when `second`, a
/// second window at (200, 100), 400 x 150, over it. Returns the frame's draw data.
ImDrawData& frame(const std::string& text, bool second) {
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(40, 30));
  ImGui::SetNextWindowSize(ImVec2(300, 200));
  ImGui::Begin("Panel");
  ImGui::TextUnformatted(text.c_str());
  ImGui::End();
  if (second) {
    ImGui::SetNextWindowPos(ImVec2(200, 100));
    ImGui::SetNextWindowSize(ImVec2(400, 150));
    ImGui::Begin("Inspection");
    ImGui::TextUnformatted("Building 42");
    ImGui::End();
  }
  ImGui::Render();
  return *ImGui::GetDrawData();
}

}  // namespace

TEST_CASE("panelRects gives each window's screen rectangle, in drawing order and framebuffer pixels", "[ui][panels]") {
  HeadlessImGui imgui;
  for (int i = 0; i < 3; ++i) frame("t = 1.00 s", true);  // windows settle over the first frames
  ImDrawData& data = frame("t = 1.00 s", true);
  std::vector<qv::PixelRect> rects = qv::ui::panelRects(data);
  REQUIRE(rects.size() == 2);
  // The window's own rectangle (its antialiased border's fringe reaches up to 2 pixels beyond it).
  CHECK(rects[0].x0 >= 38);
  CHECK(rects[0].x0 <= 40);
  CHECK(rects[0].y0 >= 28);
  CHECK(rects[0].y0 <= 30);
  CHECK(rects[0].x1 >= 340);
  CHECK(rects[0].x1 <= 342);
  CHECK(rects[0].y1 >= 230);
  CHECK(rects[0].y1 <= 232);
  CHECK(rects[1].x0 <= 200);
  CHECK(rects[1].x1 >= 600);
  CHECK(rects[1].x1 <= 602);

  // At a device pixel ratio of 2 the rectangles are in the framebuffer's pixels.
  data.FramebufferScale = ImVec2(2.0f, 2.0f);
  rects = qv::ui::panelRects(data);
  REQUIRE(rects.size() == 2);
  CHECK(rects[0].x0 >= 76);
  CHECK(rects[0].x1 >= 680);
  CHECK(rects[0].x1 <= 684);
}

TEST_CASE("drawDataKey is the same for the same picture and changes with any text or window", "[ui][panels]") {
  HeadlessImGui imgui;
  for (int i = 0; i < 3; ++i) frame("t = 1.00 s", false);
  const std::uint64_t first = qv::ui::drawDataKey(frame("t = 1.00 s", false));
  CHECK(qv::ui::drawDataKey(frame("t = 1.00 s", false)) == first);
  // One digit of the time line, same number of glyphs.
  const std::uint64_t later = qv::ui::drawDataKey(frame("t = 1.25 s", false));
  CHECK(later != first);
  CHECK(qv::ui::drawDataKey(frame("t = 1.25 s", false)) == later);
  for (int i = 0; i < 3; ++i) frame("t = 1.25 s", true);
  CHECK(qv::ui::drawDataKey(frame("t = 1.25 s", true)) != later);
}
