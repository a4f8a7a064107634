#include "qv/ui/Widgets.h"

#include <cstdarg>
#include <cstdio>

#include <imgui.h>

namespace qv::ui {

std::string_view visibleLabel(std::string_view label) {
  const auto hashes = label.find("##");
  return hashes == std::string_view::npos ? label : label.substr(0, hashes);
}

std::string format(const char* fmt, ...) {
  char buffer[512];
  va_list args;
  va_start(args, fmt);
  const int n = std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  if (n < 0) return {};
  if (static_cast<std::size_t>(n) < sizeof buffer) return std::string(buffer, static_cast<std::size_t>(n));
  std::string big(static_cast<std::size_t>(n) + 1, '\0');
  va_start(args, fmt);
  std::vsnprintf(big.data(), big.size(), fmt, args);
  va_end(args);
  big.resize(static_cast<std::size_t>(n));
  return big;
}

bool Widgets::begin(const char* title, bool* open, int flags) {
  mirror_.beginWindow(visibleLabel(title));
  return ImGui::Begin(title, open, flags);
}

void Widgets::end() {
  ImGui::End();
  mirror_.endWindow();
}

void Widgets::text(std::string_view t) {
  ImGui::TextUnformatted(t.data(), t.data() + t.size());
  mirror_.line(t);
}

void Widgets::textColored(float r, float g, float b, std::string_view t) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(r, g, b, 1.0f));
  ImGui::TextUnformatted(t.data(), t.data() + t.size());
  ImGui::PopStyleColor();
  mirror_.line(t);
}

void Widgets::textWrapped(std::string_view t) {
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(t.data(), t.data() + t.size());
  ImGui::PopTextWrapPos();
  mirror_.line(t);
}

void Widgets::separator() {
  ImGui::Separator();
}

void Widgets::sameLine() {
  ImGui::SameLine();
}

bool Widgets::button(const char* label) {
  mirror_.line(format("[%.*s]", static_cast<int>(visibleLabel(label).size()), visibleLabel(label).data()));
  return ImGui::Button(label);
}

bool Widgets::checkbox(const char* label, bool* value) {
  const bool changed = ImGui::Checkbox(label, value);
  const auto v = visibleLabel(label);
  mirror_.line(format("[%c] %.*s", *value ? 'x' : ' ', static_cast<int>(v.size()), v.data()));
  return changed;
}

bool Widgets::radio(const char* label, bool active) {
  const bool clicked = ImGui::RadioButton(label, active);
  const auto v = visibleLabel(label);
  mirror_.line(format("(%c) %.*s", active ? '*' : ' ', static_cast<int>(v.size()), v.data()));
  return clicked;
}

bool Widgets::sliderFloat(const char* label, float* value, float min, float max, const char* fmt, bool logarithmic) {
  const bool changed = ImGui::SliderFloat(label, value, min, max, fmt, logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
  char shown[64];
  std::snprintf(shown, sizeof shown, fmt, static_cast<double>(*value));
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: %s", static_cast<int>(v.size()), v.data(), shown));
  return changed;
}

bool Widgets::sliderDouble(const char* label, double* value, double min, double max, const char* fmt) {
  const bool changed = ImGui::SliderScalar(label, ImGuiDataType_Double, value, &min, &max, fmt);
  char shown[64];
  std::snprintf(shown, sizeof shown, fmt, *value);
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: %s", static_cast<int>(v.size()), v.data(), shown));
  return changed;
}

bool Widgets::sliderInt(const char* label, int* value, int min, int max) {
  const bool changed = ImGui::SliderInt(label, value, min, max);
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: %d", static_cast<int>(v.size()), v.data(), *value));
  return changed;
}

bool Widgets::combo(const char* label, int* current, const char* const items[], int count) {
  const bool changed = ImGui::Combo(label, current, items, count);
  const auto v = visibleLabel(label);
  const char* shown = (*current >= 0 && *current < count) ? items[*current] : "";
  mirror_.line(format("%.*s: %s", static_cast<int>(v.size()), v.data(), shown));
  return changed;
}

bool Widgets::collapsingHeader(const char* label, bool defaultOpen) {
  const bool open = ImGui::CollapsingHeader(label, defaultOpen ? ImGuiTreeNodeFlags_DefaultOpen : 0);
  const auto v = visibleLabel(label);
  mirror_.line(format("%s %.*s", open ? "v" : ">", static_cast<int>(v.size()), v.data()));
  return open;
}

void Widgets::field(std::string_view label, std::string_view value) {
  const std::string line =
      format("%.*s: %.*s", static_cast<int>(label.size()), label.data(), static_cast<int>(value.size()), value.data());
  ImGui::TextUnformatted(line.c_str());
  mirror_.line(line);
}

}  // namespace qv::ui
