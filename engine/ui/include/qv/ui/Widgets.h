// Thin wrappers over Dear ImGui widgets that also write their visible text to a TextMirror and
// register every control in the keyboard's Tab order (ImGuiBrowserBackend), in drawing order.
// Keep ImGui's dialect inside the UI layer: panels call these, not ImGui directly, for anything a
// person reads. Labels follow ImGui's "visible##id" convention; only the visible part is mirrored.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "qv/ui/TextMirror.h"

namespace qv::ui {

/// The visible part of an ImGui label ("Play##transport" -> "Play").
std::string_view visibleLabel(std::string_view label);

/// printf-style formatting into a std::string.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

class Widgets {
 public:
  explicit Widgets(TextMirror& mirror) : mirror_(mirror) {}

  /// Begins a window; returns false when collapsed or clipped (its title is still mirrored).
  bool begin(const char* title, bool* open = nullptr, int flags = 0);
  void end();
  void text(std::string_view text);
  void textColored(float r, float g, float b, std::string_view text);
  void textWrapped(std::string_view text);
  void separator();
  void sameLine();
  bool button(const char* label);
  bool checkbox(const char* label, bool* value);
  bool radio(const char* label, bool active);
  bool sliderFloat(const char* label, float* value, float min, float max, const char* fmt = "%.2f",
                   bool logarithmic = false);
  bool sliderDouble(const char* label, double* value, double min, double max, const char* fmt = "%.2f");
  bool sliderInt(const char* label, int* value, int min, int max);
  bool combo(const char* label, int* current, const char* const items[], int count);
  bool collapsingHeader(const char* label, bool defaultOpen = true);
  /// A labelled value row: "label: value".
  void field(std::string_view label, std::string_view value);
  /// A single-line text input; `buffer` holds the text. Mirrored as "label: [text]". `focus` puts
  /// the keyboard in it (editing starts next frame); `entered`, when given, is set to whether the
  /// edit ended with Enter in this frame.
  bool inputText(const char* label, std::string& buffer, bool focus = false, bool* entered = nullptr);
  /// A clickable row; returns true when clicked. Mirrored as "> text"; in the layout (uiLayout) by
  /// its visible text.
  bool selectable(const char* label, bool selected = false);
  /// A line plot of `values` over [0, duration] with a vertical cursor at `cursorFraction` (0..1),
  /// mirrored as `summary` (a plot is pixels: the text says what it shows). Returns where along
  /// the plot (0..1) the left button is pressed or dragged, when the press began on the plot (to
  /// seek there), else a negative value.
  float plot(const char* id, const float* values, int count, float minValue, float maxValue, float height,
             float cursorFraction, std::string_view summary);
  /// A histogram (bars), mirrored as `summary`.
  void bars(const char* id, const float* values, int count, float maxValue, float height, std::string_view summary);
  /// A horizontal bar filled to `fraction` (0..1) in the given colour, with `label` before it and
  /// `value` after it; mirrored as "label: value".
  void meter(std::string_view label, float fraction, std::string_view value, float r, float g, float b);
  /// A table with a header row; cells are text. Mirrored one row a line, cells separated by " | ".
  void table(const char* id, const std::vector<std::string>& headers,
             const std::vector<std::vector<std::string>>& rows);
  /// A table whose rows are sorted by a click on a column's header (again: the other way) and
  /// chosen by a click on the row. `keys[row][column]` orders the rows (NaN: by the cell's text);
  /// `defaultColumn` is sorted on first, largest first. The rows are mirrored in the order shown,
  /// each starting "> " (clickable; in the layout by its first cell). Returns the index (into
  /// `rows`) of the row clicked in this frame, or -1.
  int sortableTable(const char* id, const std::vector<std::string>& headers,
                    const std::vector<std::vector<std::string>>& rows, const std::vector<std::vector<double>>& keys,
                    int defaultColumn);
  /// A filled colour square followed by text on the same line.
  void swatch(float r, float g, float b, std::string_view text, bool hatched = false);

  [[nodiscard]] TextMirror& mirror() { return mirror_; }

 private:
  /// Records the last ImGui item's rectangle in the mirror's layout under its visible label.
  void recordItem(const char* label);

  TextMirror& mirror_;
};

}  // namespace qv::ui
