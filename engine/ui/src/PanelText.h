// Text the control panel's files share (ControlPanel.cpp, ControlPanelLegend.cpp): labels and
// number formats. Internal to engine/ui.
#pragma once

#include <string>

#include "qv/ui/Widgets.h"

namespace qv::panel {

inline constexpr double kFeetPerMetre = 3.280839895;
inline constexpr const char* kDamageLabels[6] = {"None", "Slight", "Moderate", "Extensive", "Complete", "No result"};

/// "12.34 %" of a ratio.
inline std::string percent(double ratio) {
  return ui::format("%.2f %%", ratio * 100.0);
}

}  // namespace qv::panel
