// TextMirror: the plain-text copy of what the panels show. Dear ImGui draws pixels; every widget
// the UI layer emits also writes its visible text here, window by window, so that
// `quakeview.uiText()` gives tests, screen readers and dashboards what a person sees.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace qv {

/// Where something the mirror lists appears: CSS pixels from the canvas's top-left corner.
struct MirrorRect {
  float x = 0.0f, y = 0.0f, width = 0.0f, height = 0.0f;
};

class TextMirror {
 public:
  /// The layout beside the text, for tests and tools that must point at a control (a tap on a
  /// phone): each window drawn (its title, rectangle, folded to its title bar or not) and each
  /// control recorded in it (its visible label and rectangle).
  struct Window {
    std::string title;
    MirrorRect rect;
    bool collapsed = false;
  };
  struct Item {
    std::string window;  ///< the title of the window it is in
    std::string label;
    MirrorRect rect;
  };

  /// Starts a frame's text (clears the previous frame's).
  void beginFrame();
  void beginWindow(std::string_view title);
  void line(std::string_view text);
  void endWindow();
  /// The text of the last completed frame: "== Title ==\nline\nline\n\n== Other ==\n...".
  [[nodiscard]] const std::string& text() const { return published_; }
  /// Publishes the frame being built (call after the last window).
  void endFrame();

  /// The current window's rectangle (call before endWindow) and a control in it.
  void windowRect(MirrorRect rect, bool collapsed);
  void item(std::string_view label, MirrorRect rect);
  /// The last completed frame's layout as JSON: {"windows": [{title, x, y, width, height,
  /// collapsed}], "items": [{window, label, x, y, width, height}]}, windows in drawing order.
  [[nodiscard]] std::string layoutJson() const;

 private:
  std::string building_;
  std::string published_;
  std::string window_;  ///< the title of the window being built
  std::vector<Window> buildingWindows_, publishedWindows_;
  std::vector<Item> buildingItems_, publishedItems_;
};

}  // namespace qv
