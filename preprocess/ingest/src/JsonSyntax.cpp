#include "qv/prep/JsonSyntax.h"

#include <cstdio>
#include <utility>

namespace qv::prep {
namespace {

std::string describeByte(char c) {
  if (c >= 0x20 && c < 0x7f) return std::string("'") + c + "'";
  char text[16];
  std::snprintf(text, sizeof text, "byte 0x%02X", static_cast<unsigned>(static_cast<unsigned char>(c)));
  return text;
}

/// A recursive-descent recogniser of RFC 8259 (no values are built), UTF-8 checked first. Only
/// runs after simdjson has failed, so it favours clear messages over speed.
class JsonSyntaxChecker {
 public:
  explicit JsonSyntaxChecker(std::string_view text) : s_(text) {}

  std::optional<JsonSyntaxProblem> check() {
    if (const auto bad = firstInvalidUtf8()) return JsonSyntaxProblem{*bad, "invalid UTF-8"};
    skipSpaces();
    if (!value(0)) return problem_;
    skipSpaces();
    if (i_ != s_.size())
      return JsonSyntaxProblem{i_, "unexpected " + describeByte(s_[i_]) + " after the end of the JSON text"};
    return std::nullopt;
  }

 private:
  static constexpr int kMaxDepth = 1024;

  bool fail(std::string what) {
    problem_ = JsonSyntaxProblem{i_, std::move(what)};
    return false;
  }
  bool atEnd() const { return i_ >= s_.size(); }
  char peek() const { return s_[i_]; }
  void skipSpaces() {
    while (!atEnd() && (peek() == ' ' || peek() == '\t' || peek() == '\n' || peek() == '\r')) ++i_;
  }
  bool expect(char c, const char* context) {
    skipSpaces();
    if (atEnd()) return fail(std::string("unexpected end of file, expected '") + c + "' " + context);
    if (peek() != c) return fail("unexpected " + describeByte(peek()) + ", expected '" + c + "' " + context);
    ++i_;
    return true;
  }

  bool value(int depth) {
    if (depth > kMaxDepth) return fail("nesting deeper than 1024 levels");
    skipSpaces();
    if (atEnd()) return fail("unexpected end of file, expected a value");
    switch (peek()) {
      case '{':
        return object(depth);
      case '[':
        return array(depth);
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

  bool object(int depth) {
    ++i_;  // {
    skipSpaces();
    if (!atEnd() && peek() == '}') {
      ++i_;
      return true;
    }
    while (true) {
      skipSpaces();
      if (atEnd()) return fail("unexpected end of file in an object, expected a member name");
      if (peek() != '"') return fail("unexpected " + describeByte(peek()) + ", expected a member name in quotes");
      if (!string() || !expect(':', "after a member name") || !value(depth + 1)) return false;
      skipSpaces();
      if (atEnd()) return fail("unexpected end of file in an object, expected ',' or '}'");
      if (peek() == '}') {
        ++i_;
        return true;
      }
      if (peek() != ',') return fail("unexpected " + describeByte(peek()) + " in an object, expected ',' or '}'");
      ++i_;
    }
  }

  bool array(int depth) {
    ++i_;  // [
    skipSpaces();
    if (!atEnd() && peek() == ']') {
      ++i_;
      return true;
    }
    while (true) {
      if (!value(depth + 1)) return false;
      skipSpaces();
      if (atEnd()) return fail("unexpected end of file in an array, expected ',' or ']'");
      if (peek() == ']') {
        ++i_;
        return true;
      }
      if (peek() != ',') return fail("unexpected " + describeByte(peek()) + " in an array, expected ',' or ']'");
      ++i_;
    }
  }

  bool string() {
    ++i_;  // "
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
          for (int k = 1; k <= 4; ++k) {
            if (i_ + static_cast<std::size_t>(k) >= s_.size() ||
                std::string_view("0123456789abcdefABCDEF").find(s_[i_ + static_cast<std::size_t>(k)]) ==
                    std::string_view::npos) {
              return fail("invalid \\u escape in a string");
            }
          }
          i_ += 4;
        } else if (std::string_view("\"\\/bfnrt").find(e) == std::string_view::npos) {
          return fail("invalid escape \\" + std::string(1, e) + " in a string");
        }
      }
      ++i_;
    }
    return fail("unexpected end of file in a string (missing closing quote)");
  }

  bool literal(std::string_view word) {
    if (s_.substr(i_, word.size()) != word) return fail("unexpected " + describeByte(peek()) + ", expected a value");
    i_ += word.size();
    return true;
  }

  bool number() {
    const std::size_t start = i_;
    auto digits = [&] {
      const std::size_t from = i_;
      while (!atEnd() && peek() >= '0' && peek() <= '9') ++i_;
      return i_ > from;
    };
    if (peek() == '-') ++i_;
    if (!atEnd() && peek() == '0') {
      ++i_;
    } else if (!digits()) {
      i_ = start;
      return fail("invalid number");
    }
    if (!atEnd() && peek() == '.') {
      ++i_;
      if (!digits()) return fail("invalid number: digits expected after '.'");
    }
    if (!atEnd() && (peek() == 'e' || peek() == 'E')) {
      ++i_;
      if (!atEnd() && (peek() == '+' || peek() == '-')) ++i_;
      if (!digits()) return fail("invalid number: digits expected in the exponent");
    }
    return true;
  }

  std::optional<std::size_t> firstInvalidUtf8() const {
    std::size_t i = 0;
    while (i < s_.size()) {
      const auto c = static_cast<unsigned char>(s_[i]);
      std::size_t extra = 0;
      if (c < 0x80) {
        ++i;
        continue;
      }
      if (c >= 0xC2 && c <= 0xDF)
        extra = 1;
      else if (c >= 0xE0 && c <= 0xEF)
        extra = 2;
      else if (c >= 0xF0 && c <= 0xF4)
        extra = 3;
      else
        return i;
      if (i + extra >= s_.size()) return i;
      for (std::size_t k = 1; k <= extra; ++k) {
        if ((static_cast<unsigned char>(s_[i + k]) & 0xC0) != 0x80) return i;
      }
      // Unicode's table of well-formed sequences (as simdjson checks): no overlong forms, no
      // surrogates (U+D800..DFFF), nothing above U+10FFFF.
      const auto second = static_cast<unsigned char>(s_[i + 1]);
      if ((c == 0xE0 && second < 0xA0) || (c == 0xED && second > 0x9F) || (c == 0xF0 && second < 0x90) ||
          (c == 0xF4 && second > 0x8F)) {
        return i;
      }
      i += extra + 1;
    }
    return std::nullopt;
  }

  std::string_view s_;
  std::size_t i_ = 0;
  JsonSyntaxProblem problem_{0, ""};
};

}  // namespace

std::optional<JsonSyntaxProblem> findJsonSyntaxProblem(std::string_view text) {
  return JsonSyntaxChecker(text).check();
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

}  // namespace qv::prep
