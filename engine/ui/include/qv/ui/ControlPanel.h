// The control panel (Dear ImGui): live performance figures, playback, display options.
#pragma once

#include "qv/scene/Viewer.h"
#include "qv/ui/Widgets.h"

namespace qv {

class ControlPanel {
 public:
  /// Draws the panel for this frame. Call between ImGui::NewFrame and ImGui::Render.
  void draw(Viewer& viewer, ui::Widgets& w, const MemoryInfo& memory);
};

}  // namespace qv
