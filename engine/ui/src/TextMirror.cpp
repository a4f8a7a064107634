#include "qv/ui/TextMirror.h"

#include "qv/core/JsonWriter.h"

namespace qv {
namespace {

constexpr std::string_view kPanelTitle = "QuakeView";
constexpr std::string_view kInspectionPrefix = "Building ";

bool startsWith(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

}  // namespace

void TextMirror::beginFrame() {
  building_.clear();
  windows_.clear();
  buildingLayout_.clear();
  buildingItems_.clear();
}

void TextMirror::beginWindow(std::string_view title) {
  if (!building_.empty()) building_ += '\n';
  building_ += "== ";
  building_ += title;
  building_ += " ==\n";
  windows_.push_back(Window{std::string(title), {Section{}}});
  window_ = title;
}

void TextMirror::line(std::string_view text) {
  building_ += text;
  building_ += '\n';
  if (windows_.empty()) windows_.push_back(Window{std::string(), {Section{}}});
  windows_.back().sections.back().lines.emplace_back(text);
}

void TextMirror::heading(std::string_view shown, std::string_view label, bool open) {
  building_ += shown;
  building_ += '\n';
  if (windows_.empty()) windows_.push_back(Window{std::string(), {Section{}}});
  windows_.back().sections.push_back(Section{std::string(label), open, {}});
}

void TextMirror::endWindow() {}

void TextMirror::endFrame() {
  published_ = building_;
  publishedWindows_ = windows_;
  publishedLayout_ = buildingLayout_;
  publishedItems_ = buildingItems_;
  std::vector<Section> outline = accessibleOutline(publishedWindows_);
  const bool changed = outline.size() != outline_.size() || [&] {
    for (std::size_t i = 0; i < outline.size(); ++i) {
      if (outline[i].heading != outline_[i].heading || outline[i].lines != outline_[i].lines) return true;
    }
    return false;
  }();
  if (!changed && !outlineJson_.empty()) return;
  if (changed) ++outlineRevision_;
  outline_ = std::move(outline);
  JsonWriter w;
  w.beginObject().field("revision", outlineRevision_).key("sections").beginArray();
  for (const Section& s : outline_) {
    w.beginObject().field("heading", s.heading).key("lines").beginArray();
    for (const std::string& l : s.lines) w.value(l);
    w.endArray().endObject();
  }
  w.endArray().endObject();
  outlineJson_ = w.take();
}

std::vector<TextMirror::Section> accessibleOutline(const std::vector<TextMirror::Window>& windows) {
  std::vector<TextMirror::Section> out;
  for (const TextMirror::Window& window : windows) {
    if (window.title == "Map") continue;
    if (window.title == kPanelTitle) {
      for (const TextMirror::Section& s : window.sections) {
        TextMirror::Section section;
        if (s.heading.empty()) {
          section.heading = "Earthquake and data";
          for (const std::string& l : s.lines) {
            if (!startsWith(l, "FPS:")) section.lines.push_back(l);
          }
        } else if (!s.open) {
          section.heading = s.heading + " (collapsed in the panel)";
        } else if (s.heading == "Performance") {
          section.heading = s.heading;
          section.lines.emplace_back("Live measurements (not repeated here).");
        } else {
          section.heading = s.heading;
          section.lines = s.lines;
        }
        if (!section.lines.empty() || !s.heading.empty()) out.push_back(std::move(section));
      }
      continue;
    }
    TextMirror::Section section;
    section.heading = window.title;
    for (const TextMirror::Section& s : window.sections) {
      if (!s.heading.empty()) section.lines.push_back(s.heading + (s.open ? "" : " (collapsed)"));
      section.lines.insert(section.lines.end(), s.lines.begin(), s.lines.end());
    }
    if (startsWith(window.title, kInspectionPrefix)) {
      const std::string id = window.title.substr(kInspectionPrefix.size());
      const bool named = !section.lines.empty() && section.lines.front() != "(no name)";
      section.heading = "Selected building: " + (named ? section.lines.front() : id);
    }
    out.push_back(std::move(section));
  }
  return out;
}

void TextMirror::windowRect(MirrorRect rect, bool collapsed) {
  buildingLayout_.push_back(LaidOutWindow{window_, rect, collapsed});
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
  for (const LaidOutWindow& win : publishedLayout_) {
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
