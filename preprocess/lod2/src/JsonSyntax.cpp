#include "JsonSyntax.h"

#include <cstdio>
#include <utility>

namespace qv::prep::detail {
namespace {

std::string describeByte(char c) {
  if (c >= 0x20 && c < 0x7f) return std::string("'") + c + "'";
  char text[16];
  std::snprintf(text, sizeof text, "byte 0x%02X", static_cast<unsigned>(static_cast<unsigned char>(c)));
  return text;
}

/// A recursive-descent recogniser of RFC 8259 (no values are built). Only runs after simdjson has
/// failed, so it favours clear messages over speed.
class Checker {
 public:
  explicit Checker(std::string_view text) : s_(text) {}

  std::optional<JsonSyntaxProblem> check() {
    skipSpaces();
    if (!value(0)) return problem_;
    skipSpaces();
    if (i_ != s_.size()) return JsonSyntaxProblem{i_, "unexpected " + describeByte(s_[i_]) + " after the JSON text"};
    return std::nullopt;
  }

 private:
  static constexpr int kMaxDepth = 1024;

  bool fail(std::string what) {
    problem_ = JsonSyntaxProblem{i_, std::move(what)};
    return false;
  }
  [[nodiscard]] bool atEnd() const { return i_ >= s_.size(); }
  [[nodiscard]] char peek() const { return s_[i_]; }
  void skipSpaces() {
    while (!atEnd() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r')) ++i_;
  }

  bool value(int depth) {
    if (depth > kMaxDepth) return fail("nesting deeper than 1024 levels");
    skipSpaces();
    if (atEnd()) return fail("unexpected end of file, expected a value");
    switch (peek()) {
      case '{':
        return container(depth, '}', true);
      case '[':
        return container(depth, ']', false);
      case '"':
        return string();
      case 't':
        return literal("true");
      case 'f':
        return literal("false");
      case 'n':
        return literal("null");
      default:
        if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return number();
        return fail("unexpected " + describeByte(peek()) + ", expected a value");
    }
  }

  bool container(int depth, char close, bool isObject) {
    const char* what = isObject ? "an object" : "an array";
    ++i_;
    skipSpaces();
    if (!atEnd() && peek() == close) {
      ++i_;
      return true;
    }
    while (true) {
      skipSpaces();
      if (isObject) {
        if (atEnd()) return fail("unexpected end of file in an object, expected a member name");
        if (peek() != '"') return fail("unexpected " + describeByte(peek()) + ", expected a member name in quotes");
        if (!string()) return false;
        skipSpaces();
        if (atEnd() || peek() != ':')
          return fail(atEnd() ? "unexpected end of file, expected ':'"
                              : "unexpected " + describeByte(peek()) + ", expected ':' after a member name");
        ++i_;
      }
      if (!value(depth + 1)) return false;
      skipSpaces();
      if (atEnd()) return fail(std::string("unexpected end of file in ") + what + ", expected ',' or '" + close + "'");
      if (peek() == close) {
        ++i_;
        return true;
      }
      if (peek() != ',')
        return fail("unexpected " + describeByte(peek()) + " in " + what + ", expected ',' or '" + close + "'");
      ++i_;
    }
  }

  bool string() {
    ++i_;  // opening quote
    while (!atEnd()) {
      const char c = peek();
      if (c == '"') {
        ++i_;
        return true;
      }
      if (static_cast<unsigned char>(c) < 0x20) return fail("control character " + describeByte(c) + " in a string");
      if (c == '\\') {
        ++i_;
        if (atEnd()) break;
        const char e = peek();
        if (e == 'u') {
          for (int k = 0; k < 4; ++k) {
            ++i_;
            if (atEnd()) return fail("unexpected end of file in a \\u escape");
            const char h = peek();
            const bool hex = (h >= '0' && h <= '9') || (h >= 'a' && h <= 'f') || (h >= 'A' && h <= 'F');
            if (!hex) return fail("invalid \\u escape");
          }
        } else if (e != '"' && e != '\\' && e != '/' && e != 'b' && e != 'f' && e != 'n' && e != 'r' && e != 't') {
          return fail("invalid escape \\" + std::string(1, e));
        }
      }
      ++i_;
    }
    return fail("unexpected end of file in a string");
  }

  bool literal(std::string_view word) {
    if (s_.substr(i_, word.size()) != word) return fail("unexpected " + describeByte(peek()) + ", expected a value");
    i_ += word.size();
    return true;
  }

  bool digits() {
    if (atEnd() || peek() < '0' || peek() > '9') return fail("expected a digit in a number");
    while (!atEnd() && peek() >= '0' && peek() <= '9') ++i_;
    return true;
  }

  bool number() {
    if (peek() == '-') ++i_;
    if (!atEnd() && peek() == '0') {
      ++i_;
    } else if (!digits()) {
      return false;
    }
    if (!atEnd() && peek() == '.') {
      ++i_;
      if (!digits()) return false;
    }
    if (!atEnd() && (peek() == 'e' || peek() == 'E')) {
      ++i_;
      if (!atEnd() && (peek() == '+' || peek() == '-')) ++i_;
      if (!digits()) return false;
    }
    return true;
  }

  std::string_view s_;
  std::size_t i_ = 0;
  JsonSyntaxProblem problem_;
};

}  // namespace

std::optional<JsonSyntaxProblem> findJsonSyntaxProblem(std::string_view text) {
  return Checker(text).check();
}

std::string lineColumn(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace qv::prep::detail
