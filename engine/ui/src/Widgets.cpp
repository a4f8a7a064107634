#include "qv/ui/Widgets.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numeric>

#include <imgui.h>

#include "qv/core/Text.h"
#include "qv/ui/ImGuiBrowserBackend.h"

namespace qv::ui {
namespace {

// Text as the screen and the mirror show it: names and addresses come from OpenStreetMap and ids
// and values from links, so control characters, line breaks and bidirectional overrides are
// cleaned (qv::displaySafe) before ImGui draws them or a screen reader reads them. Clean text is
// passed through without a copy.
class Shown {
 public:
  explicit Shown(std::string_view text) : view_(text) {
    if (needsDisplayCleaning(text)) {
      owned_ = displaySafe(text);
      view_ = owned_;
    }
  }
  Shown(const Shown&) = delete;
  Shown& operator=(const Shown&) = delete;
  [[nodiscard]] std::string_view view() const { return view_; }
  [[nodiscard]] const char* begin() const { return view_.data(); }
  [[nodiscard]] const char* end() const { return view_.data() + view_.size(); }
  /// NUL-terminated (labels): the cleaned copy, or a copy of the original.
  [[nodiscard]] std::string str() const { return std::string(view_); }

 private:
  std::string owned_;
  std::string_view view_;
};

// Registers the control just drawn (label `label`, in the current ID scope) in the keyboard's Tab
// order, described for screen readers as "visible label, role[, state]".
void tabStop(const char* label, std::string_view role, TabStopKind kind, std::string_view state = {}) {
  const std::string_view v = visibleLabel(label);
  std::string description(v);
  description += ", ";
  description += role;
  if (!state.empty()) {
    description += ", ";
    description += state;
  }
  imguiBrowserTabStop(ImGui::GetID(label), description, kind);
}

}  // namespace

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
  const Shown t(title);
  mirror_.beginWindow(visibleLabel(t.view()));
  return ImGui::Begin(t.str().c_str(), open, flags);
}

void Widgets::end() {
  const ImVec2 pos = ImGui::GetWindowPos();
  const ImVec2 size = ImGui::GetWindowSize();
  mirror_.windowRect(MirrorRect{pos.x, pos.y, size.x, size.y}, ImGui::IsWindowCollapsed());
  ImGui::End();
  mirror_.endWindow();
}

void Widgets::text(std::string_view raw) {
  const Shown t(raw);
  ImGui::TextUnformatted(t.begin(), t.end());
  mirror_.line(t.view());
}

void Widgets::textColored(float r, float g, float b, std::string_view raw) {
  const Shown t(raw);
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(r, g, b, 1.0f));
  ImGui::PushTextWrapPos(0.0f);  // statements in colour (SCENARIO, warnings) are read whole
  ImGui::TextUnformatted(t.begin(), t.end());
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
  mirror_.line(t.view());
}

void Widgets::textWrapped(std::string_view raw) {
  const Shown t(raw);
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(t.begin(), t.end());
  ImGui::PopTextWrapPos();
  mirror_.line(t.view());
}

void Widgets::separator() {
  ImGui::Separator();
}

void Widgets::sameLine() {
  ImGui::SameLine();
}

bool Widgets::button(const char* label) {
  mirror_.line(format("[%.*s]", static_cast<int>(visibleLabel(label).size()), visibleLabel(label).data()));
  const bool pressed = ImGui::Button(label);
  recordItem(label);
  tabStop(label, "button", TabStopKind::Press);
  return pressed;
}

void Widgets::recordItem(const char* label) {
  const ImVec2 min = ImGui::GetItemRectMin();
  const ImVec2 max = ImGui::GetItemRectMax();
  mirror_.item(visibleLabel(label), MirrorRect{min.x, min.y, max.x - min.x, max.y - min.y});
}

bool Widgets::checkbox(const char* label, bool* value) {
  const bool changed = ImGui::Checkbox(label, value);
  recordItem(label);
  tabStop(label, "checkbox", TabStopKind::Press, *value ? "checked" : "not checked");
  const auto v = visibleLabel(label);
  mirror_.line(format("[%c] %.*s", *value ? 'x' : ' ', static_cast<int>(v.size()), v.data()));
  return changed;
}

bool Widgets::radio(const char* label, bool active) {
  const bool clicked = ImGui::RadioButton(label, active);
  tabStop(label, "radio button", TabStopKind::Press, active ? "selected" : "not selected");
  const auto v = visibleLabel(label);
  mirror_.line(format("(%c) %.*s", active ? '*' : ' ', static_cast<int>(v.size()), v.data()));
  return clicked;
}

bool Widgets::sliderFloat(const char* label, float* value, float min, float max, const char* fmt, bool logarithmic) {
  const bool changed = ImGui::SliderFloat(label, value, min, max, fmt, logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
  char shown[64];
  std::snprintf(shown, sizeof shown, fmt, static_cast<double>(*value));
  tabStop(label, "slider", TabStopKind::Value, shown);
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: %s", static_cast<int>(v.size()), v.data(), shown));
  return changed;
}

bool Widgets::sliderDouble(const char* label, double* value, double min, double max, const char* fmt) {
  const bool changed = ImGui::SliderScalar(label, ImGuiDataType_Double, value, &min, &max, fmt);
  char shown[64];
  std::snprintf(shown, sizeof shown, fmt, *value);
  tabStop(label, "slider", TabStopKind::Value, shown);
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: %s", static_cast<int>(v.size()), v.data(), shown));
  return changed;
}

bool Widgets::sliderInt(const char* label, int* value, int min, int max) {
  const bool changed = ImGui::SliderInt(label, value, min, max);
  tabStop(label, "slider", TabStopKind::Value, std::to_string(*value));
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: %d", static_cast<int>(v.size()), v.data(), *value));
  return changed;
}

bool Widgets::combo(const char* label, int* current, const char* const items[], int count) {
  const bool changed = ImGui::Combo(label, current, items, count);
  const auto v = visibleLabel(label);
  const char* shown = (*current >= 0 && *current < count) ? items[*current] : "";
  tabStop(label, "drop-down", TabStopKind::Press, shown);
  mirror_.line(format("%.*s: %s", static_cast<int>(v.size()), v.data(), shown));
  return changed;
}

bool Widgets::collapsingHeader(const char* label, bool defaultOpen) {
  const bool open = ImGui::CollapsingHeader(label, defaultOpen ? ImGuiTreeNodeFlags_DefaultOpen : 0);
  recordItem(label);
  tabStop(label, "section", TabStopKind::Press, open ? "expanded" : "collapsed");
  const auto v = visibleLabel(label);
  mirror_.heading(format("%s %.*s", open ? "v" : ">", static_cast<int>(v.size()), v.data()), v, open);
  return open;
}

void Widgets::field(std::string_view label, std::string_view value) {
  const Shown v(value);
  const std::string line = format("%.*s: %.*s", static_cast<int>(label.size()), label.data(),
                                  static_cast<int>(v.view().size()), v.view().data());
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(line.c_str());
  ImGui::PopTextWrapPos();
  mirror_.line(line);
}

bool Widgets::inputText(const char* label, std::string& buffer, bool focus, bool* entered) {
  char text[256];
  const std::size_t n = std::min(buffer.size(), sizeof text - 1);
  std::memcpy(text, buffer.data(), n);
  text[n] = '\0';
  if (focus) ImGui::SetKeyboardFocusHere();
  const bool changed = ImGui::InputText(label, text, sizeof text);
  if (changed) buffer = text;
  tabStop(label, "text field", TabStopKind::Text, buffer);
  // Enter ends the edit (ImGui deactivates the field on it): the caller's "take the first result".
  if (entered != nullptr) {
    *entered = ImGui::IsItemDeactivated() && (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter), false) ||
                                              ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_KeyPadEnter), false));
  }
  const auto v = visibleLabel(label);
  mirror_.line(format("%.*s: [%s]", static_cast<int>(v.size()), v.data(), buffer.c_str()));
  return changed;
}

bool Widgets::selectable(const char* label, bool selected) {
  const Shown shown(label);
  const auto v = visibleLabel(shown.view());
  mirror_.line(format("> %.*s", static_cast<int>(v.size()), v.data()));
  const std::string text = shown.str();
  const bool clicked = ImGui::Selectable(text.c_str(), selected);
  recordItem(text.c_str());
  tabStop(text.c_str(), "list item", TabStopKind::Press, selected ? "selected" : "");
  return clicked;
}

float Widgets::plot(const char* id, const float* values, int count, float minValue, float maxValue, float height,
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
  // A press on the plot seeks, and so does dragging it on while the button stays down (even
  // beyond the plot's ends, clamped); a press that began elsewhere does not.
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID dragging = ImGui::GetID(id);
  if (ImGui::IsItemHovered() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) storage->SetBool(dragging, true);
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) storage->SetBool(dragging, false);
  if (!storage->GetBool(dragging, false) || b.x <= a.x) return -1.0f;
  return std::clamp((ImGui::GetIO().MousePos.x - a.x) / (b.x - a.x), 0.0f, 1.0f);
}

void Widgets::bars(const char* id, const float* values, int count, float maxValue, float height,
                   std::string_view summary) {
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(summary.data(), summary.data() + summary.size());
  ImGui::PopTextWrapPos();
  ImGui::PlotHistogram(id, values, count, 0, nullptr, 0.0f, maxValue, ImVec2(ImGui::GetContentRegionAvail().x, height));
  mirror_.line(summary);
}

void Widgets::meter(std::string_view rawLabel, float fraction, std::string_view rawValue, float r, float g, float b) {
  const Shown label(rawLabel);
  const Shown value(rawValue);
  const float f = std::clamp(std::isfinite(fraction) ? fraction : 0.0f, 0.0f, 1.0f);
  const float labelWidth = ImGui::GetFontSize() * 6.5f;
  const float barWidth = std::max(40.0f, ImGui::GetContentRegionAvail().x - labelWidth - ImGui::GetFontSize() * 5.0f);
  ImGui::TextUnformatted(label.view().data(), label.view().data() + label.view().size());
  ImGui::SameLine(labelWidth);
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float height = ImGui::GetTextLineHeight();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(p, ImVec2(p.x + barWidth, p.y + height), IM_COL32(70, 70, 80, 120));
  draw->AddRectFilled(p, ImVec2(p.x + barWidth * f, p.y + height), ImGui::GetColorU32(ImVec4(r, g, b, 1.0f)));
  ImGui::Dummy(ImVec2(barWidth, height));
  ImGui::SameLine();
  ImGui::TextUnformatted(value.view().data(), value.view().data() + value.view().size());
  mirror_.line(std::string(label.view()) + ": " + std::string(value.view()));
}

namespace {

// The width column c of a fixed-fit table of these cells takes: its widest text, padding and a border.
float columnWidth(const std::vector<std::string>& headers, const std::vector<std::vector<std::string>>& rows,
                  std::size_t c) {
  const ImGuiStyle& style = ImGui::GetStyle();
  const Shown header(headers[c]);
  float column = ImGui::CalcTextSize(header.begin(), header.end()).x;
  for (const auto& row : rows) {
    if (c >= row.size()) continue;
    const Shown cell(row[c]);
    column = std::max(column, ImGui::CalcTextSize(cell.begin(), cell.end()).x);
  }
  return column + style.CellPadding.x * 2.0f + 1.0f;
}

// The widths every column of a fixed-fit table of these cells takes.
std::vector<float> columnWidths(const std::vector<std::string>& headers,
                                const std::vector<std::vector<std::string>>& rows) {
  std::vector<float> widths(headers.size());
  for (std::size_t c = 0; c < headers.size(); ++c) widths[c] = columnWidth(headers, rows, c);
  return widths;
}

}  // namespace

void Widgets::table(const char* id, const std::vector<std::string>& headers,
                    const std::vector<std::vector<std::string>>& rows) {
  const int columns = static_cast<int>(headers.size());
  if (columns == 0) return;
  std::string line;
  for (std::size_t c = 0; c < headers.size(); ++c) line += (c > 0 ? " | " : "") + std::string(Shown(headers[c]).view());
  mirror_.line(line);
  // Too wide for the window (a phone): one table of the first column with each other column in
  // turn, one under the other, so that no column is cut off. The mirror is the same either way.
  const float available = ImGui::GetContentRegionAvail().x;
  const std::vector<float> widths = columns > 2 ? columnWidths(headers, rows) : std::vector<float>{};
  if (columns > 2 && std::accumulate(widths.begin(), widths.end(), 0.0f) > available) {
    for (const auto& row : rows) {
      line.clear();
      for (int c = 0; c < columns; ++c) {
        const std::string cell = static_cast<std::size_t>(c) < row.size() ? row[static_cast<std::size_t>(c)] : "";
        line += (c > 0 ? " | " : "") + std::string(Shown(cell).view());
      }
      mirror_.line(line);
    }
    // A pair still too wide (a long label beside a value with its interval on a phone): the
    // label keeps its width and the value wraps within what is left, rather than being cut off.
    for (int c = 1; c < columns; ++c) {
      const bool wrap = widths[0] + widths[static_cast<std::size_t>(c)] > available;
      ImGui::PushID(c);
      const ImGuiTableFlags sizing = wrap ? ImGuiTableFlags_SizingStretchProp : ImGuiTableFlags_SizingFixedFit;
      if (ImGui::BeginTable(id, 2, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | sizing)) {
        ImGui::TableSetupColumn(std::string(Shown(headers[0]).view()).c_str(),
                                wrap ? ImGuiTableColumnFlags_WidthFixed : ImGuiTableColumnFlags_None);
        ImGui::TableSetupColumn(std::string(Shown(headers[static_cast<std::size_t>(c)]).view()).c_str(),
                                wrap ? ImGuiTableColumnFlags_WidthStretch : ImGuiTableColumnFlags_None);
        ImGui::TableHeadersRow();
        for (const auto& row : rows) {
          ImGui::TableNextRow();
          for (int k : {0, c}) {
            static const std::string kEmpty;
            const std::string& cell =
                static_cast<std::size_t>(k) < row.size() ? row[static_cast<std::size_t>(k)] : kEmpty;
            const Shown text(cell);  // holds a view: `cell` must outlive it
            ImGui::TableSetColumnIndex(k == 0 ? 0 : 1);
            if (wrap && k != 0) ImGui::PushTextWrapPos(0.0f);  // at the column's right edge
            ImGui::TextUnformatted(text.view().data(), text.view().data() + text.view().size());
            if (wrap && k != 0) ImGui::PopTextWrapPos();
          }
        }
        ImGui::EndTable();
      }
      ImGui::PopID();
    }
    return;
  }
  const bool shown =
      ImGui::BeginTable(id, columns, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit);
  if (shown) {
    for (const std::string& h : headers) ImGui::TableSetupColumn(std::string(Shown(h).view()).c_str());
    ImGui::TableHeadersRow();
  }
  for (const auto& row : rows) {
    line.clear();
    if (shown) ImGui::TableNextRow();
    for (int c = 0; c < columns; ++c) {
      const std::string cell = static_cast<std::size_t>(c) < row.size() ? row[static_cast<std::size_t>(c)] : "";
      const Shown text(cell);
      line += (c > 0 ? " | " : "") + std::string(text.view());
      if (shown) {
        ImGui::TableSetColumnIndex(c);
        ImGui::TextUnformatted(text.view().data(), text.view().data() + text.view().size());
      }
    }
    mirror_.line(line);
  }
  if (shown) ImGui::EndTable();
}

int Widgets::sortableTable(const char* id, const std::vector<std::string>& headers,
                           const std::vector<std::vector<std::string>>& rows,
                           const std::vector<std::vector<double>>& keys, int defaultColumn) {
  const int columns = static_cast<int>(headers.size());
  if (columns == 0) return -1;
  std::string line;
  for (std::size_t c = 0; c < headers.size(); ++c) line += (c > 0 ? " | " : "") + std::string(Shown(headers[c]).view());
  mirror_.line(line);
  // The columns share the panel's width in proportion to their content (never wider than the
  // panel); no scrolling region of its own (that would be a child window, out of the panel's
  // layout): the panel scrolls.
  const ImGuiTableFlags flags =
      ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp | ImGuiTableFlags_Sortable;
  const bool shown = ImGui::BeginTable(id, columns, flags);
  // The order: the header's sort (ImGui keeps it per table), by default the default column, largest first.
  int sortColumn = std::clamp(defaultColumn, 0, columns - 1);
  bool descending = true;
  if (shown) {
    for (int c = 0; c < columns; ++c) {
      ImGuiTableColumnFlags columnFlags = ImGuiTableColumnFlags_PreferSortDescending;
      if (c == sortColumn) columnFlags |= ImGuiTableColumnFlags_DefaultSort;
      ImGui::TableSetupColumn(std::string(Shown(headers[static_cast<std::size_t>(c)]).view()).c_str(), columnFlags);
    }
    // The header row as TableHeadersRow draws it, each header in the layout (a click sorts).
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
    for (int c = 0; c < columns; ++c) {
      if (!ImGui::TableSetColumnIndex(c)) continue;
      const char* name = ImGui::TableGetColumnName(c);
      ImGui::PushID(c);
      ImGui::TableHeader(name);
      recordItem(name);
      tabStop(name, "column header", TabStopKind::Press);
      ImGui::PopID();
    }
    if (const ImGuiTableSortSpecs* specs = ImGui::TableGetSortSpecs(); specs != nullptr && specs->SpecsCount > 0) {
      sortColumn = specs->Specs[0].ColumnIndex;
      descending = specs->Specs[0].SortDirection == ImGuiSortDirection_Descending;
    }
  }
  std::vector<std::size_t> order(rows.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto column = static_cast<std::size_t>(sortColumn);
  auto key = [&](std::size_t r) {
    return r < keys.size() && column < keys[r].size() ? keys[r][column] : std::numeric_limits<double>::quiet_NaN();
  };
  auto text = [&](std::size_t r) -> std::string_view {
    return column < rows[r].size() ? std::string_view(rows[r][column]) : std::string_view();
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double ka = key(a), kb = key(b);
    if (std::isnan(ka) || std::isnan(kb)) return descending ? text(b) < text(a) : text(a) < text(b);
    return descending ? kb < ka : ka < kb;
  });
  int clicked = -1;
  for (const std::size_t r : order) {
    const std::vector<std::string>& row = rows[r];
    line = "> ";
    if (shown) ImGui::TableNextRow();
    for (int c = 0; c < columns; ++c) {
      const std::string cell = static_cast<std::size_t>(c) < row.size() ? row[static_cast<std::size_t>(c)] : "";
      const Shown shownText(cell);
      line += (c > 0 ? " | " : "") + std::string(shownText.view());
      if (!shown) continue;
      ImGui::TableSetColumnIndex(c);
      if (c == 0) {
        ImGui::PushID(static_cast<int>(r));
        const std::string label = shownText.str();
        if (ImGui::Selectable(label.c_str(), false, ImGuiSelectableFlags_SpanAllColumns)) clicked = static_cast<int>(r);
        recordItem(label.c_str());
        tabStop(label.c_str(), "table row", TabStopKind::Press);
        ImGui::PopID();
      } else {
        ImGui::TextUnformatted(shownText.view().data(), shownText.view().data() + shownText.view().size());
      }
    }
    mirror_.line(line);
  }
  if (shown) ImGui::EndTable();
  return clicked;
}

void Widgets::swatch(float r, float g, float b, std::string_view raw, bool hatched) {
  const Shown text(raw);
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
  ImGui::TextUnformatted(text.begin(), text.end());
  mirror_.line(text.view());
}

}  // namespace qv::ui
