// TextMirror: the plain-text copy of what the panels show. Dear ImGui draws pixels; every widget
// the UI layer emits also writes its visible text here, window by window and section by section
// (a collapsing header starts a section), so that `quakeview.uiText()` gives tests and dashboards
// what a person sees, and the page's accessible HTML copy (its outline) gives it to screen readers.
#pragma once

#include <cstdint>
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
  /// A run of lines under one heading: a window's lines before its first collapsing header
  /// (heading ""), or a header's (none when it is collapsed).
  struct Section {
    std::string heading;
    bool open = true;
    std::vector<std::string> lines;
  };
  struct Window {
    std::string title;
    std::vector<Section> sections;  ///< the first has the heading ""
  };
  /// The layout beside the text, for tests and tools that must point at a control (a tap on a
  /// phone): each window drawn (its title, rectangle, folded to its title bar or not) and each
  /// control recorded in it (its visible label and rectangle).
  struct LaidOutWindow {
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
  /// A collapsing header: `shown` goes into the plain text ("v Animation"), `label` ("Animation")
  /// starts a section of the current window.
  void heading(std::string_view shown, std::string_view label, bool open);
  void endWindow();
  /// The text of the last completed frame: "== Title ==\nline\nline\n\n== Other ==\n...".
  [[nodiscard]] const std::string& text() const { return published_; }
  /// The last completed frame, structured.
  [[nodiscard]] const std::vector<Window>& windows() const { return publishedWindows_; }
  /// The last completed frame's accessible outline (accessibleOutline) as JSON
  /// {"revision": n, "sections": [{"heading": "...", "lines": ["...", ...]}, ...]}.
  [[nodiscard]] const std::string& outlineJson() const { return outlineJson_; }
  /// Grows by one each time a frame's outline differs from the previous frame's (starts at 0), so
  /// the page rewrites its HTML copy only when the content changed.
  [[nodiscard]] std::uint64_t outlineRevision() const { return outlineRevision_; }
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
  std::vector<Window> windows_;
  std::vector<Window> publishedWindows_;
  std::vector<TextMirror::Section> outline_;
  std::string outlineJson_;
  std::uint64_t outlineRevision_ = 0;
  std::string window_;  ///< the title of the window being built
  std::vector<LaidOutWindow> buildingLayout_, publishedLayout_;
  std::vector<Item> buildingItems_, publishedItems_;
};

/// The outline a screen reader gets of the panels (the page turns each section into a heading and
/// its lines): what the windows say, with headings a person can jump between, without what changes
/// every frame for no reader's benefit. Pure. Rules, in window order:
/// - the control panel ("QuakeView"): its lines before the first header under "Earthquake and data"
///   (the city, its source and whether the shaking is a SCENARIO or ACTUAL), without the frame rate
///   line ("FPS: ..."); then one section per collapsing header with its lines ("Consequences" holds
///   the totals, "Damage and colours" the legend); a collapsed header's section says so, and
///   "Performance" keeps only its heading (live measurements);
/// - the inspection window ("Building <id>") as "Selected building: <its first line, the name>"
///   (the id when the name is "(no name)"), with all its lines;
/// - the map overlay ("Map": cursor coordinates and scale) is left out;
/// - any other window (errors, active filters) under its title.
std::vector<TextMirror::Section> accessibleOutline(const std::vector<TextMirror::Window>& windows);

}  // namespace qv
