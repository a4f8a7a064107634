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
#pragma once

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
/// only update the modifiers.
void imguiBrowserKey(std::string_view code, bool down, bool shift, bool ctrl, bool alt);
/// Typed text (UTF-8); ignored unless ImGui wants the keyboard (a text field or window has focus).
void imguiBrowserText(std::string_view utf8);

/// True while a text field is being edited: keys are for it, not for the app's shortcuts.
bool imguiBrowserWantsTextInput();

}  // namespace qv::ui
