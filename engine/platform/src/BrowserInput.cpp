#include "qv/platform/BrowserInput.h"

#include <emscripten/html5.h>

#include <cstring>

namespace qv {
namespace {

InputEvent mouseEvent(InputEvent::Type type, const EmscriptenMouseEvent* e) {
  InputEvent ev;
  ev.type = type;
  ev.button = e->button;
  ev.x = static_cast<double>(e->targetX);
  ev.y = static_cast<double>(e->targetY);
  ev.shift = e->shiftKey != 0;
  ev.ctrl = e->ctrlKey != 0 || e->metaKey != 0;
  ev.alt = e->altKey != 0;
  return ev;
}

EM_BOOL onMouse(int type, const EmscriptenMouseEvent* e, void* user) {
  auto* input = static_cast<BrowserInput*>(user);
  switch (type) {
    case EMSCRIPTEN_EVENT_MOUSEDOWN:
      input->push(mouseEvent(InputEvent::Type::PointerDown, e));
      return EM_TRUE;
    case EMSCRIPTEN_EVENT_MOUSEUP:
      input->push(mouseEvent(InputEvent::Type::PointerUp, e));
      return EM_TRUE;
    case EMSCRIPTEN_EVENT_MOUSEMOVE:
      input->push(mouseEvent(InputEvent::Type::PointerMove, e));
      return EM_TRUE;
    default:
      return EM_FALSE;
  }
}

// Mouse up and move outside the canvas still end or continue a drag: listen on the window too,
// converting to canvas coordinates with the canvas's client rectangle.
EM_BOOL onWindowMouse(int type, const EmscriptenMouseEvent* e, void* user) {
  auto* input = static_cast<BrowserInput*>(user);
  if (type == EMSCRIPTEN_EVENT_MOUSEUP) {
    InputEvent ev = mouseEvent(InputEvent::Type::PointerUp, e);
    input->push(std::move(ev));
  }
  return EM_FALSE;
}

EM_BOOL onWheel(int, const EmscriptenWheelEvent* e, void* user) {
  auto* input = static_cast<BrowserInput*>(user);
  InputEvent ev = mouseEvent(InputEvent::Type::Wheel, &e->mouse);
  double dy = e->deltaY;
  if (e->deltaMode == DOM_DELTA_LINE) dy *= 40.0;
  if (e->deltaMode == DOM_DELTA_PAGE) dy *= 800.0;
  ev.wheelY = dy;
  input->push(std::move(ev));
  return EM_TRUE;
}

EM_BOOL onTouch(int type, const EmscriptenTouchEvent* e, void* user) {
  auto* input = static_cast<BrowserInput*>(user);
  InputEvent ev;
  ev.type = InputEvent::Type::Touch;
  for (int i = 0; i < e->numTouches; ++i) {
    const EmscriptenTouchPoint& t = e->touches[i];
    const bool ended = (type == EMSCRIPTEN_EVENT_TOUCHEND || type == EMSCRIPTEN_EVENT_TOUCHCANCEL) && t.isChanged;
    if (ended) continue;
    ev.touches.push_back(TouchPoint{static_cast<std::int32_t>(t.identifier), static_cast<double>(t.targetX),
                                    static_cast<double>(t.targetY)});
  }
  input->push(std::move(ev));
  return EM_TRUE;
}

EM_BOOL onKey(int type, const EmscriptenKeyboardEvent* e, void* user) {
  auto* input = static_cast<BrowserInput*>(user);
  InputEvent ev;
  ev.shift = e->shiftKey != 0;
  ev.ctrl = e->ctrlKey != 0 || e->metaKey != 0;
  ev.alt = e->altKey != 0;
  if (type == EMSCRIPTEN_EVENT_KEYPRESS) {
    ev.type = InputEvent::Type::Text;
    ev.code = e->key;
    if (ev.code.size() > 4 || ev.code.empty()) return EM_FALSE;  // "Enter" etc. are not text
    input->push(std::move(ev));
    return EM_TRUE;
  }
  ev.type = type == EMSCRIPTEN_EVENT_KEYDOWN ? InputEvent::Type::KeyDown : InputEvent::Type::KeyUp;
  ev.code = e->code;
  // Tab moves the focus through the panels (ImGuiBrowserBackend), never out of the canvas: the
  // browser's own Tab would leave it (in a text field too).
  if (ev.code == "Tab") {
    input->push(std::move(ev));
    return EM_TRUE;
  }
  const bool isText = std::strlen(e->key) == 1 && !ev.ctrl;
  input->push(std::move(ev));
  // Let printable keys through on keydown so the browser produces keypress (text input); block
  // navigation keys from scrolling the page.
  if (isText) return EM_FALSE;
  return input->uiWantsKeyboard() ? EM_FALSE : EM_TRUE;
}

}  // namespace

BrowserInput::BrowserInput(const char* canvasSelector) : selector_(canvasSelector) {
  const char* c = selector_.c_str();
  emscripten_set_mousedown_callback(c, this, EM_TRUE, onMouse);
  emscripten_set_mouseup_callback(c, this, EM_TRUE, onMouse);
  emscripten_set_mousemove_callback(c, this, EM_TRUE, onMouse);
  emscripten_set_mouseup_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, this, EM_TRUE, onWindowMouse);
  emscripten_set_wheel_callback(c, this, EM_TRUE, onWheel);
  emscripten_set_touchstart_callback(c, this, EM_TRUE, onTouch);
  emscripten_set_touchmove_callback(c, this, EM_TRUE, onTouch);
  emscripten_set_touchend_callback(c, this, EM_TRUE, onTouch);
  emscripten_set_touchcancel_callback(c, this, EM_TRUE, onTouch);
  emscripten_set_keydown_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, this, EM_TRUE, onKey);
  emscripten_set_keyup_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, this, EM_TRUE, onKey);
  emscripten_set_keypress_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, this, EM_TRUE, onKey);
}

BrowserInput::~BrowserInput() {
  const char* c = selector_.c_str();
  emscripten_set_mousedown_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_mouseup_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_mousemove_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_mouseup_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, nullptr, EM_TRUE, nullptr);
  emscripten_set_wheel_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_touchstart_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_touchmove_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_touchend_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_touchcancel_callback(c, nullptr, EM_TRUE, nullptr);
  emscripten_set_keydown_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, nullptr, EM_TRUE, nullptr);
  emscripten_set_keyup_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, nullptr, EM_TRUE, nullptr);
  emscripten_set_keypress_callback(EMSCRIPTEN_EVENT_TARGET_WINDOW, nullptr, EM_TRUE, nullptr);
}

std::vector<InputEvent> BrowserInput::drain() {
  std::vector<InputEvent> out;
  out.swap(queue_);
  return out;
}

Key cameraKeyForCode(const std::string& code) {
  if (code == "ArrowLeft" || code == "KeyA") return Key::Left;
  if (code == "ArrowRight" || code == "KeyD") return Key::Right;
  if (code == "ArrowUp" || code == "KeyW") return Key::Up;
  if (code == "ArrowDown" || code == "KeyS") return Key::Down;
  if (code == "KeyQ") return Key::TurnLeft;
  if (code == "KeyE") return Key::TurnRight;
  if (code == "PageUp") return Key::TiltUp;
  if (code == "PageDown") return Key::TiltDown;
  if (code == "Equal" || code == "NumpadAdd") return Key::ZoomIn;
  if (code == "Minus" || code == "NumpadSubtract") return Key::ZoomOut;
  if (code == "KeyR" || code == "Home") return Key::Reset;
  return Key::Count;
}

}  // namespace qv
