// TextMirror: the plain-text copy of what the panels show. Dear ImGui draws pixels; every widget
// the UI layer emits also writes its visible text here, window by window, so that
// `quakeview.uiText()` gives tests, screen readers and dashboards what a person sees.
#pragma once

#include <string>
#include <string_view>

namespace qv {

class TextMirror {
 public:
  /// Starts a frame's text (clears the previous frame's).
  void beginFrame();
  void beginWindow(std::string_view title);
  void line(std::string_view text);
  void endWindow();
  /// The text of the last completed frame: "== Title ==\nline\nline\n\n== Other ==\n...".
  [[nodiscard]] const std::string& text() const { return published_; }
  /// Publishes the frame being built (call after the last window).
  void endFrame();

 private:
  std::string building_;
  std::string published_;
};

}  // namespace qv
