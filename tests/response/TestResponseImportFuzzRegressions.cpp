// Inputs the response-import fuzzer found (tests/fuzz/regressions/response_import) read as the fuzz
// target reads them: a clean error naming the file, or buildings with finite histories of the
// right size, never a crash or an infinite displacement.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "../fuzz/RegressionInputs.h"
#include "qv/prep/ResponseImport.h"

TEST_CASE("Fuzzer-found response imports are read or rejected cleanly", "[response][import][fuzz]") {
  const auto inputs = qv::fuzz::savedInputs(QUAKEVIEW_SOURCE_DIR, "response_import");
  REQUIRE(!inputs.empty());
  for (const auto& input : inputs) {
    INFO(input.path);
    qv::prep::ImportedResults results;
    const qv::Status read = qv::prep::readImportedResponse(input.path, std::nullopt, results);
    if (!read.ok()) {
      CHECK(read.error().find(std::filesystem::path(input.path).filename().string()) != std::string::npos);
      continue;
    }
    for (const auto& b : results.buildings) {
      CHECK(b.x.size() == b.frames * b.floors);
      for (const float v : b.x) CHECK(std::isfinite(v));
      for (const float v : b.y) CHECK(std::isfinite(v));
    }
  }
}

TEST_CASE("Displacements no building can have are refused with the units hint", "[response][import]") {
  for (const auto& input : qv::fuzz::savedInputs(QUAKEVIEW_SOURCE_DIR, "response_import")) {
    if (input.path.find("float-overflow") == std::string::npos) continue;
    INFO(input.path);
    qv::prep::ImportedResults results;
    const qv::Status read = qv::prep::readImportedResponse(input.path, std::nullopt, results);
    REQUIRE_FALSE(read.ok());
    CHECK(read.error().find("more than 1 km; check the units") != std::string::npos);
  }
}
