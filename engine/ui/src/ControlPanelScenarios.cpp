// The control panel's Scenarios section: the earthquakes of the city folder's catalogue
// (qv/scene/CityScenarios.h), the one shown marked, each one's event type once its manifest has
// been read; a click shows another (Viewer::selectScenario).
#include <imgui.h>

#include "qv/ui/ControlPanel.h"

namespace qv {
namespace {

// "SCENARIO", "ACTUAL", or what is known instead.
std::string scenarioStateText(const ScenarioStatus& s) {
  switch (s.state) {
    case ScenarioState::Ready:
      if (!s.hasResponse) return "no earthquake results";
      return s.eventType.empty() ? std::string("event type not stated") : s.eventType;
    case ScenarioState::NotReady:
      return "not ready";
    case ScenarioState::Broken:
      return "cannot be read";
    case ScenarioState::Checking:
      return "checking...";
    case ScenarioState::Unchecked:
      break;
  }
  return "not checked yet";
}

}  // namespace

void ControlPanel::drawScenarios(Viewer& viewer, ui::Widgets& w) {
  const CityScenarios* scenarios = viewer.scenarios();
  if (scenarios == nullptr || !scenarios->available()) return;
  const std::vector<ScenarioStatus>& list = scenarios->scenarios();
  const ScenarioStatus* current = scenarios->current();
  const ScenarioSwitch& change = viewer.scenarioSwitch();
  // One line in view whatever the section's state: which of the city's scenarios this is.
  if (current != nullptr) {
    const std::size_t position = static_cast<std::size_t>(current - list.data()) + 1;
    w.textWrapped(ui::format("Scenario %zu of %zu: ", position, list.size()) + current->entry.name);
  } else {
    const ScenarioStatus* same = nullptr;
    for (const ScenarioStatus& s : list) {
      if (s.sameResultsAsOpen) same = &s;
    }
    w.textWrapped(same != nullptr ? "Scenario: \"" + same->entry.name + "\" (the same results, opened as " +
                                        scenarios->openFileName() + ")"
                                  : ui::format("Scenario: %s, not one of the city's %zu scenarios",
                                               scenarios->openFileName().c_str(), list.size()));
  }
  const ScenarioStatus* target = scenarios->find(change.index);
  if (target != nullptr &&
      (change.state == ScenarioSwitch::State::Checking || change.state == ScenarioSwitch::State::Loading) &&
      target != current) {
    w.textWrapped("Opening \"" + target->entry.name + "\"...");
  }
  if (!section(w, "Scenarios", false)) return;
  for (const ScenarioStatus& s : list) {
    const bool shown = &s == current;
    std::string row = s.entry.name + ": " + scenarioStateText(s);
    if (shown) {
      row += " (shown)";
    } else if (s.sameResultsAsOpen) {
      row += " (the same results as shown)";
    }
    row += "##scenario" + std::to_string(s.entry.index);
    if (w.selectable(row.c_str(), shown) && !shown) viewer.selectScenario(s.entry.index);
    if ((s.state == ScenarioState::NotReady || s.state == ScenarioState::Broken) && !s.problem.empty()) {
      ImGui::Indent();
      w.textWrapped(s.problem);
      ImGui::Unindent();
    }
  }
  if (change.state == ScenarioSwitch::State::Failed && !change.problem.empty()) {
    w.textColored(0.75f, 0.1f, 0.05f, change.problem);
  }
  w.textWrapped("A click shows another scenario in the same view; the link follows it.");
}

}  // namespace qv
