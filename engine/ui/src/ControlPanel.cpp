#include "qv/ui/ControlPanel.h"

#include <imgui.h>

namespace qv {
namespace {

std::string megabytes(std::uint64_t bytes) {
  return ui::format("%.1f MB", static_cast<double>(bytes) / (1024.0 * 1024.0));
}

}  // namespace

void ControlPanel::draw(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory) {
  ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330.0f, 0.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.88f);
  if (w.begin("QuakeView")) {
    const StatsSummary s = viewer.stats();
    w.text(ui::format("FPS: %.1f   frame: %.2f ms", s.fps, s.frameMs.total));

    if (w.collapsingHeader("Animation")) {
      if (w.button(viewer.playing() ? "Pause##transport" : "Play##transport")) {
        if (viewer.playing())
          viewer.pause();
        else
          viewer.play();
      }
      w.sameLine();
      if (w.button("Reset view")) viewer.controller().reset();
      double t = viewer.time();
      if (w.sliderDouble("Time (s)", &t, 0.0, viewer.duration(), "%.2f")) viewer.setTime(t);
      float speed = static_cast<float>(viewer.speed());
      if (w.sliderFloat("Speed", &speed, 0.1f, 4.0f, "%.2fx")) viewer.setSpeed(speed);
      float amplitude = viewer.amplitude();
      if (w.sliderFloat("Amplitude", &amplitude, 1.0f, 100.0f, "%.0fx", true)) viewer.setAmplitude(amplitude);
      static const char* const modes[] = {"Current inter-storey drift", "Peak drift", "Damage state", "Neutral"};
      int mode = static_cast<int>(viewer.colorMode());
      if (w.combo("Colour", &mode, modes, 4)) viewer.setColorMode(static_cast<ColorMode>(mode));
    }

    if (w.collapsingHeader("Performance")) {
      w.text(ui::format("cull %.2f  lod %.2f  animate %.2f ms", s.frameMs.cull, s.frameMs.lod, s.frameMs.animate));
      w.text(
          ui::format("upload %.2f  render %.2f  total %.2f ms", s.frameMs.upload, s.frameMs.render, s.frameMs.total));
      w.text(ui::format("draw calls %.0f   triangles %.0f", s.drawCalls, s.triangles));
      w.text(ui::format("buildings: %u loaded, %u visible, %u animated", s.latest.buildingsLoaded,
                        s.latest.buildingsVisible, s.latest.buildingsAnimated));
      w.text(ui::format("upload %.1f KB/frame", s.uploadBytes / 1024.0));
      w.text("memory: " + megabytes(memory.heapBytes) + " live, " + megabytes(memory.heapReservedBytes) + " reserved");
    }
  }
  w.end();

  if (!viewer.errors().empty()) {
    ImGui::SetNextWindowPos(ImVec2(10.0f, ImGui::GetIO().DisplaySize.y - 10.0f), ImGuiCond_Always, ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.9f);
    if (w.begin("Errors", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      const auto& errors = viewer.errors();
      const std::size_t first = errors.size() > 8 ? errors.size() - 8 : 0;
      if (first > 0) w.text(ui::format("(%zu earlier messages not shown)", first));
      for (std::size_t i = first; i < errors.size(); ++i) w.textColored(0.85f, 0.15f, 0.1f, errors[i]);
    }
    w.end();
  }
}

}  // namespace qv
