// Reads the saved inputs of one fuzz target (tests/fuzz/regressions/<target>/) for the regression
// tests in the ordinary unit test builds (native and WebAssembly).
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace qv::fuzz {

struct SavedInput {
  std::string path;
  std::vector<std::uint8_t> bytes;
};

/// Every file of tests/fuzz/regressions/<target>/, sorted by name (none when the folder is absent:
/// replays use requiredInputs, which fails on that).
inline std::vector<SavedInput> savedInputs(const std::string& sourceDir, const std::string& target) {
  std::vector<SavedInput> inputs;
  const std::filesystem::path folder = std::filesystem::path(sourceDir) / "tests/fuzz/regressions" / target;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream file(entry.path(), std::ios::binary);
    SavedInput input{entry.path().string(), {}};
    input.bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    inputs.push_back(std::move(input));
  }
  std::sort(inputs.begin(), inputs.end(), [](const SavedInput& a, const SavedInput& b) { return a.path < b.path; });
  return inputs;
}

/// savedInputs for a replay test: a missing or empty folder is an error (a replay of nothing would
/// pass while asserting nothing). Returns the inputs and sets `problem` when there are none.
inline std::vector<SavedInput> requiredInputs(const std::string& sourceDir, const std::string& target,
                                              std::string& problem) {
  auto inputs = savedInputs(sourceDir, target);
  problem = inputs.empty() ? "no saved inputs in tests/fuzz/regressions/" + target + " (a replay needs at least one)"
                           : std::string();
  return inputs;
}

}  // namespace qv::fuzz
