// Helpers shared by the fuzz targets: checksum fix-up so mutated files reach the decoders' inner
// sections, and checks that abort (a libFuzzer crash) when a decoder breaks its contract.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "FuzzInputs.h"

namespace qv::fuzz {

/// Stops the run with a message: libFuzzer reports the abort as a crash and saves the input.
[[noreturn]] inline void contractBroken(const char* what, std::string_view detail = {}) {
  std::fprintf(stderr, "fuzz contract broken: %s %.*s\n", what, static_cast<int>(detail.size()), detail.data());
  std::abort();
}

inline void check(bool condition, const char* what, std::string_view detail = {}) {
  if (!condition) contractBroken(what, detail);
}

/// Every decoder error must be a message for a person that names the input.
template <typename TResult>
void checkErrorNamesInput(const TResult& result, std::string_view name) {
  if (result.ok()) return;
  check(result.error().size() > name.size() && result.error().compare(0, name.size(), name) == 0,
        "error message does not start with the input's name:", result.error());
}

}  // namespace qv::fuzz
