#include "qv/core/Text.h"

#include <cstdint>

namespace qv {
namespace {

constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

struct Decoded {
  char32_t codePoint = 0;
  std::size_t length = 1;  ///< bytes consumed: the sequence, or the maximal invalid subpart
  bool valid = false;
};

// Decodes the sequence starting at text[i] (i < text.size()) by the table of Unicode §3.9
// (Table 3-7, well-formed byte sequences).
Decoded decodeAt(std::string_view text, std::size_t i) {
  const auto b0 = static_cast<unsigned char>(text[i]);
  if (b0 < 0x80) return {b0, 1, true};
  int need = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  char32_t cp = 0;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    need = 1;
    cp = b0 & 0x1Fu;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    need = 2;
    cp = b0 & 0x0Fu;
    if (b0 == 0xE0) lo = 0xA0;
    if (b0 == 0xED) hi = 0x9F;  // no surrogates
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    need = 3;
    cp = b0 & 0x07u;
    if (b0 == 0xF0) lo = 0x90;
    if (b0 == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
  } else {
    return {0, 1, false};
  }
  for (int k = 1; k <= need; ++k) {
    const std::size_t at = i + static_cast<std::size_t>(k);
    if (at >= text.size()) return {0, static_cast<std::size_t>(k), false};
    const auto b = static_cast<unsigned char>(text[at]);
    const unsigned char low = k == 1 ? lo : 0x80, high = k == 1 ? hi : 0xBF;
    if (b < low || b > high) return {0, static_cast<std::size_t>(k), false};
    cp = (cp << 6) | (b & 0x3Fu);
  }
  return {cp, static_cast<std::size_t>(need) + 1, true};
}

enum class Display { Keep, Space, Visible, Remove };

Display classify(char32_t cp) {
  if (cp == '\t' || cp == '\n' || cp == '\r' || cp == 0x0B || cp == 0x0C || cp == 0x85 || cp == 0x2028 ||
      cp == 0x2029) {
    return Display::Space;
  }
  if (cp < 0x20 || (cp >= 0x7F && cp <= 0x9F)) return Display::Visible;
  if ((cp >= 0x202A && cp <= 0x202E) || (cp >= 0x2066 && cp <= 0x2069) || cp == 0x200E || cp == 0x200F ||
      cp == 0x061C) {
    return Display::Remove;
  }
  return Display::Keep;
}

bool isPlainAscii(std::string_view text) {
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7F) return false;
  }
  return true;
}

}  // namespace

bool isValidUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const Decoded d = decodeAt(text, i);
    if (!d.valid) return false;
    i += d.length;
  }
  return true;
}

std::string toValidUtf8(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const Decoded d = decodeAt(text, i);
    if (d.valid) {
      out.append(text.substr(i, d.length));
    } else {
      out.append(kReplacement);
    }
    i += d.length;
  }
  return out;
}

bool needsDisplayCleaning(std::string_view text) {
  if (isPlainAscii(text)) return false;
  for (std::size_t i = 0; i < text.size();) {
    const Decoded d = decodeAt(text, i);
    if (!d.valid || classify(d.codePoint) != Display::Keep) return true;
    i += d.length;
  }
  return false;
}

std::string displaySafe(std::string_view text) {
  if (!needsDisplayCleaning(text)) return std::string(text);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const Decoded d = decodeAt(text, i);
    if (!d.valid) {
      out.append(kReplacement);
    } else {
      switch (classify(d.codePoint)) {
        case Display::Keep:
          out.append(text.substr(i, d.length));
          break;
        case Display::Space:
          out += ' ';
          break;
        case Display::Visible:
          out.append(kReplacement);
          break;
        case Display::Remove:
          break;
      }
    }
    i += d.length;
  }
  return out;
}

}  // namespace qv
