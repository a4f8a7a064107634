#include "qv/ui/TextMirror.h"

#include "qv/core/JsonWriter.h"

namespace qv {

void TextMirror::beginFrame() {
  building_.clear();
  buildingWindows_.clear();
  buildingItems_.clear();
}

void TextMirror::beginWindow(std::string_view title) {
  if (!building_.empty()) building_ += '\n';
  building_ += "== ";
  building_ += title;
  building_ += " ==\n";
  window_ = title;
}

void TextMirror::line(std::string_view text) {
  building_ += text;
  building_ += '\n';
}

void TextMirror::endWindow() {}

void TextMirror::endFrame() {
  published_ = building_;
  publishedWindows_ = buildingWindows_;
  publishedItems_ = buildingItems_;
}

void TextMirror::windowRect(MirrorRect rect, bool collapsed) {
  buildingWindows_.push_back(Window{window_, rect, collapsed});
}

void TextMirror::item(std::string_view label, MirrorRect rect) {
  buildingItems_.push_back(Item{window_, std::string(label), rect});
}

namespace {
void writeRect(JsonWriter& w, const MirrorRect& r) {
  w.field("x", r.x).field("y", r.y).field("width", r.width).field("height", r.height);
}
}  // namespace

std::string TextMirror::layoutJson() const {
  JsonWriter w;
  w.beginObject().key("windows").beginArray();
  for (const Window& win : publishedWindows_) {
    w.beginObject().field("title", win.title);
    writeRect(w, win.rect);
    w.field("collapsed", win.collapsed).endObject();
  }
  w.endArray().key("items").beginArray();
  for (const Item& item : publishedItems_) {
    w.beginObject().field("window", item.window).field("label", item.label);
    writeRect(w, item.rect);
    w.endObject();
  }
  w.endArray().endObject();
  return w.take();
}

}  // namespace qv
