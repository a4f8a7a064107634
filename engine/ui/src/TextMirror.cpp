#include "qv/ui/TextMirror.h"

namespace qv {

void TextMirror::beginFrame() {
  building_.clear();
}

void TextMirror::beginWindow(std::string_view title) {
  if (!building_.empty()) building_ += '\n';
  building_ += "== ";
  building_ += title;
  building_ += " ==\n";
}

void TextMirror::line(std::string_view text) {
  building_ += text;
  building_ += '\n';
}

void TextMirror::endWindow() {}

void TextMirror::endFrame() {
  published_ = building_;
}

}  // namespace qv
