#include "qv/core/NumberFormat.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace qv {

std::string formatDouble(double value, int significantDigits) {
  // 17 significant digits, a sign, a point of up to a few bytes, "e-308" and the terminator.
  char buffer[40];
  const int digits = std::clamp(significantDigits, 1, 17);
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  if (!std::isfinite(value)) return buffer;
  // printf writes the decimal point of the process's C locale (',' after setlocale(LC_ALL,
  // "de_DE.UTF-8"), a multi-byte one in a few locales): whatever is not a digit, sign or exponent
  // is that point, and becomes '.'. (localeconv() would say which, but is not thread-safe.)
  std::string text;
  bool inPoint = false;
  for (const char* c = buffer; *c != '\0'; ++c) {
    const bool numeric = (*c >= '0' && *c <= '9') || std::strchr("+-e", *c) != nullptr;
    if (numeric)
      text.push_back(*c);
    else if (!inPoint)
      text.push_back('.');
    inPoint = !numeric;
  }
  return text;
}

}  // namespace qv
