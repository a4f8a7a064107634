// Browser input (emscripten/html5.h callbacks on the canvas and window), queued as plain events
// in CSS pixels relative to the canvas's top-left corner. The app drains the queue once a frame,
// so input never runs engine code from inside a browser callback.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "qv/scene/CameraController.h"

namespace qv {

struct InputEvent {
  enum class Type : std::uint8_t { PointerDown, PointerUp, PointerMove, Wheel, Touch, KeyDown, KeyUp, Text };
  Type type = Type::PointerMove;
  int button = 0;           ///< 0 left, 1 middle, 2 right
  double x = 0.0, y = 0.0;  ///< CSS pixels from the canvas's top-left corner
  double wheelY = 0.0;      ///< CSS pixels of scroll, > 0 away from the user
  bool shift = false, ctrl = false, alt = false;
  std::string code;                 ///< KeyboardEvent.code for keys ("ArrowLeft", "KeyW"), the text for Text
  std::vector<TouchPoint> touches;  ///< for Touch: all current touches
};

class BrowserInput {
 public:
  /// Registers the callbacks on `canvasSelector` (e.g. "#canvas") and on the window (keys).
  explicit BrowserInput(const char* canvasSelector);
  ~BrowserInput();
  BrowserInput(const BrowserInput&) = delete;
  BrowserInput& operator=(const BrowserInput&) = delete;

  /// Moves the queued events out (oldest first).
  std::vector<InputEvent> drain();
  /// Events wait to be drained.
  [[nodiscard]] bool pending() const { return !queue_.empty(); }

  /// Set each frame by the app: when true, keys are left to the UI (e.g. a text field has focus)
  /// and not prevented from reaching the page.
  void setUiWantsKeyboard(bool wants) { uiWantsKeyboard_ = wants; }

  // Called from the C callbacks.
  void push(InputEvent event) { queue_.push_back(std::move(event)); }
  [[nodiscard]] bool uiWantsKeyboard() const { return uiWantsKeyboard_; }

 private:
  std::string selector_;
  std::vector<InputEvent> queue_;
  bool uiWantsKeyboard_ = false;
};

/// Maps a KeyboardEvent.code to a camera key (Key::Count when it is not one).
Key cameraKeyForCode(const std::string& code);

}  // namespace qv
