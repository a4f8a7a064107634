// Dear ImGui's platform backend for the browser, in the style of ImGui's own backends
// (imgui_impl_glfw, imgui_impl_sdl): it feeds a browser's input to the current ImGui context and
// sets the display for each frame. It knows no browser API: the platform layer queues events
// (KeyboardEvent.code names, CSS pixels from the canvas's top-left corner) and the app hands them
// here, so the backend builds and is tested natively. The renderer backend (imgui_impl_opengl3)
// is separate, as in ImGui's examples.
//
// Use, on the thread that owns the ImGui context:
//   ImGui::CreateContext(); <app's io flags and style>; imguiBrowserInit();
//   each frame: imguiBrowserNewFrame(...); <renderer>_NewFrame(); ImGui::NewFrame();
//               feed the frame's events (imguiBrowserPointerDown, ...); draw; ImGui::Render().
//   at the end: imguiBrowserShutdown(); ImGui::DestroyContext().
//
// ImGui 1.86 samples its input state once a frame, in NewFrame: a press and its release fed
// between two NewFrames would cancel out and the click be lost. The app asks
// imguiBrowserMustDeferButtonUp / imguiBrowserMustDeferKeyUp and holds such a release (and the
// events after it, to keep their order) until the next frame.
//
// Keyboard: the app routes each key press with routeKeyDown (the UI's keyboard state decides) and
// hands the UI's keys here. Tab and Shift+Tab move the keyboard focus through every control the
// panels registered in the last frame (imguiBrowserTabStop, called by ui::Widgets), in the order
// they were drawn, across windows, with ImGui's navigation highlight; Space (and Enter) then press
// it, arrows move between neighbours, Escape leaves the UI to the 3D view.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace qv::ui {

/// Installs the backend on the current ImGui context (precondition: one exists and has no
/// platform backend): names it, maps ImGui's navigation and editing keys. Returns false (and
/// changes nothing) without a context or when a platform backend is already installed.
bool imguiBrowserInit();
/// Removes the backend from the current context (no-op when it is not installed).
void imguiBrowserShutdown();

/// Starts a frame's input: display size in CSS pixels, device pixels per CSS pixel, and the time
/// since the last frame in seconds (kept at least 0.1 ms, as ImGui requires a positive step).
/// Call before ImGui::NewFrame(); clears the "pressed this frame" record.
void imguiBrowserNewFrame(double cssWidth, double cssHeight, double devicePixelRatio, double deltaSeconds);

/// Whether a point (CSS pixels) lies on a window ImGui drew in the last frame. Decided from the
/// windows' rectangles, because ImGui 1.86 updates its hover state only once a frame and the app
/// routes each event to the UI or the scene as it arrives.
bool imguiBrowserCovers(double x, double y);

/// True when releasing `button` (0 left, 1 middle, 2 right, 3 and 4 extra; clamped to 0..4)
/// now would be lost: it was pressed since the last imguiBrowserNewFrame.
bool imguiBrowserMustDeferButtonUp(int button);
/// The same for a key, by KeyboardEvent.code ("Tab", "KeyA").
bool imguiBrowserMustDeferKeyUp(std::string_view code);

/// Pointer events in CSS pixels. A wheel over a window scrolls it and returns true; elsewhere it
/// only moves ImGui's pointer and returns false (the app gives it to the scene). `wheelY` is in
/// CSS pixels, > 0 away from the user; 100 px is one ImGui wheel step.
void imguiBrowserPointerDown(int button, double x, double y);
void imguiBrowserPointerUp(int button);
void imguiBrowserPointerMove(double x, double y);
bool imguiBrowserWheel(double x, double y, double wheelY);

/// Touch (the app decides taps and drags with qv::TouchGestureClassifier). A tap on a window's
/// title bar (anywhere on it but its close button) toggles the window collapsed, a larger target
/// for a finger than the collapse arrow; returns true when it did (the tap is then used up).
/// Otherwise the app feeds the tap as a click: imguiBrowserPointerMove on one frame (ImGui must
/// see the pointer over the item first), imguiBrowserPointerDown on the next, PointerUp after.
bool imguiBrowserTapTitleBar(double x, double y);
/// A finger dragged `dyCss` CSS pixels down over a window: scrolls the innermost window under
/// (x, y) that can scroll, by the same distance (content follows the finger). Returns false when
/// no window under the point scrolls.
bool imguiBrowserTouchScroll(double x, double y, double dyCss);

/// A key by KeyboardEvent.code with the modifier state of that event. Keys ImGui does not use
/// only update the modifiers. A Tab press moves the keyboard focus to the next stop (Shift: the
/// previous one, wrapping around; from the 3D view, with no focus shown, the first or the last);
/// Escape closes an open pop-up, or else releases the keyboard.
void imguiBrowserKey(std::string_view code, bool down, bool shift, bool ctrl, bool alt);
/// Typed text (UTF-8); ignored unless ImGui wants the keyboard (a text field or window has focus).
void imguiBrowserText(std::string_view utf8);

/// True while a text field is being edited: keys are for it, not for the app's shortcuts.
bool imguiBrowserWantsTextInput();

/// The keyboard as the UI holds it.
enum class UiKeyboard : std::uint8_t {
  None,        ///< nothing in the UI has the keyboard: keys are the viewer's shortcuts
  Navigating,  ///< a control shows the keyboard focus (after Tab): navigation keys are the UI's
  Typing,      ///< a text field is being edited: every key is the UI's
};

/// Where a key press goes: to the UI (imguiBrowserKey), to the app's shortcuts, or both.
struct KeyRoute {
  bool ui = false;
  bool app = false;
};

/// Decides where a key press (KeyboardEvent.code) goes, from the UI's keyboard state. Pure.
/// Tab is always the UI's (it moves the focus into and through the panels); while typing every
/// key is the UI's (a text field swallows the shortcuts); while navigating the navigation keys
/// (arrows, Space, Enter, Escape, PageUp/PageDown, Home/End) are the UI's and the rest are
/// shortcuts; otherwise every key but Tab is a shortcut. Releases always go to both.
KeyRoute routeKeyDown(std::string_view code, UiKeyboard state);

/// The UI's keyboard state now: live, so a Tab or Escape handled earlier among this frame's events
/// counts for the next one.
UiKeyboard imguiBrowserKeyboard();

/// Updates only the modifier keys (a key press the UI does not get). Modifiers reach ImGui at the
/// next imguiBrowserNewFrame, with the keys (ImGui 1.86 asserts they do not change within a frame).
void imguiBrowserModifiers(bool shift, bool ctrl, bool alt);

/// What a stop of the Tab order is, for the keys that act on it.
enum class TabStopKind : std::uint8_t {
  Press,  ///< button, checkbox, header, drop-down, list row: Space or Enter presses it
  Value,  ///< slider: Space then arrows change it, Enter types a value (ImGui's own keys)
  Text,   ///< text field: reaching it by Tab starts editing it
};

/// Registers the control with ImGui ID `id` (the item just submitted, in the current window) as
/// the next stop of the Tab order. `description` is what the control is, for screen readers
/// ("Export CSV, button"). Stops registered in one frame are the order of the next; no-op without
/// the backend or in a collapsed window.
void imguiBrowserTabStop(unsigned id, std::string_view description, TabStopKind kind);

/// The description of the control showing the keyboard focus, or "" when none does (as drawn
/// this frame when called after the panels, else as in the last frame).
std::string imguiBrowserFocusedControl();

/// Hands the keyboard back to the 3D view: ends any text edit, hides the focus highlight, closes
/// open pop-ups and unfocuses the windows.
void imguiBrowserReleaseKeyboard();

}  // namespace qv::ui
