#include "qv/ui/Widgets.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>

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
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(line.c_str());
  ImGui::PopTextWrapPos();
  mirror_.line(line);
}

bool Widgets::inputText(const char* label, std::string& buffer, bool focus) {
  char text[256];
  const std::size_t n = std::min(buffer.size(), sizeof text - 1);
  std::memcpy(text, buffer.data(), n);
  text[n] = '\0';
  if (focus) ImGui::SetKeyboardFocusHere();
  const bool changed = ImGui::InputText(label, text, sizeof text);
  if (changed) buffer = text;
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: [%s]", static_cast<int>(v.size()), v.data(), buffer.c_str()));
  return changed;
}

bool Widgets::selectable(const char* label, bool selected) {
  const auto v = visibleLabel(label);
  mirror_.line(format("> %.*s", static_cast<int>(v.size()), v.data()));
  return ImGui::Selectable(label, selected);
}

void Widgets::plot(const char* id, const float* values, int count, float minValue, float maxValue, float height,
                   float cursorFraction, std::string_view summary) {
  // The summary is the plot's caption on screen and its text for screen readers.
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(summary.data(), summary.data() + summary.size());
  ImGui::PopTextWrapPos();
  ImGui::PlotLines(id, values, count, 0, nullptr, minValue, maxValue, ImVec2(ImGui::GetContentRegionAvail().x, height));
  const ImVec2 a = ImGui::GetItemRectMin();
  const ImVec2 b = ImGui::GetItemRectMax();
  if (cursorFraction >= 0.0f && cursorFraction <= 1.0f) {
    const float x = a.x + (b.x - a.x) * cursorFraction;
    ImGui::GetWindowDrawList()->AddLine(ImVec2(x, a.y), ImVec2(x, b.y), IM_COL32(20, 90, 200, 255), 2.0f);
  }
  mirror_.line(summary);
}

void Widgets::bars(const char* id, const float* values, int count, float maxValue, float height,
                   std::string_view summary) {
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(summary.data(), summary.data() + summary.size());
  ImGui::PopTextWrapPos();
  ImGui::PlotHistogram(id, values, count, 0, nullptr, 0.0f, maxValue, ImVec2(ImGui::GetContentRegionAvail().x, height));
  mirror_.line(summary);
}

void Widgets::swatch(float r, float g, float b, std::string_view text, bool hatched) {
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float size = ImGui::GetTextLineHeight();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(p, ImVec2(p.x + size * 1.6f, p.y + size), ImGui::GetColorU32(ImVec4(r, g, b, 1.0f)));
  if (hatched) {
    for (float x = -size; x < size * 1.6f; x += 4.0f) {
      draw->AddLine(ImVec2(p.x + std::max(x, 0.0f), p.y + std::max(0.0f, -x)),
                    ImVec2(p.x + std::min(x + size, size * 1.6f), p.y + std::min(size, size * 1.6f - x)),
                    IM_COL32(60, 60, 70, 160));
    }
  }
  draw->AddRect(p, ImVec2(p.x + size * 1.6f, p.y + size), IM_COL32(80, 80, 80, 255));
  ImGui::Dummy(ImVec2(size * 1.6f, size));
  ImGui::SameLine();
  ImGui::TextUnformatted(text.data(), text.data() + text.size());
  mirror_.line(text);
}

}  // namespace qv::ui
