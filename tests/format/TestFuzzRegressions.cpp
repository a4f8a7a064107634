// Inputs the fuzzers found (tests/fuzz/regressions/<target>/) replayed through the format decoders.
// Each must end in a clean error that names the file, never a crash; files named valid-* are
// inputs that decode (they broke a round trip) and must decode, re-encode and decode again. The
// binary inputs are decoded as saved and with their size and checksum fields made right, as the
// fuzz targets do.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "../fuzz/FuzzInputs.h"
#include "../fuzz/RegressionInputs.h"
#include "qv/format/CityTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/format/Tileset.h"

using namespace qv;

namespace {

template <typename TResult>
void requireCleanError(const TResult& result, const std::string& name) {
  REQUIRE_FALSE(result.ok());
  INFO(result.error());
  CHECK(result.error().rfind(name + ": ", 0) == 0);
  CHECK(result.error().size() > name.size() + 2);
}

bool expectedValid(const std::string& path) {
  return std::filesystem::path(path).filename().string().rfind("valid-", 0) == 0;
}

template <typename TDecode, typename TEncode>
void replayBinary(const char* target, TDecode decode, TEncode encode) {
  std::string missing;
  const auto inputs = fuzz::requiredInputs(QUAKEVIEW_SOURCE_DIR, target, missing);
  INFO(missing);
  REQUIRE(missing.empty());
  for (const fuzz::SavedInput& input : inputs) {
    SECTION(input.path) {
      const auto fixed = fuzz::withValidSizeAndCrc(input.bytes);
      if (expectedValid(input.path)) {
        const auto decoded = decode(fixed, input.path);
        INFO((decoded.ok() ? std::string() : decoded.error()));
        REQUIRE(decoded.ok());
        const auto again = decode(encode(*decoded), input.path);
        INFO((again.ok() ? std::string() : again.error()));
        CHECK(again.ok());
      } else {
        requireCleanError(decode(input.bytes, input.path), input.path);
        requireCleanError(decode(fixed, input.path), input.path);
      }
    }
  }
}

}  // namespace

TEST_CASE("Fuzzer-found city tiles are rejected cleanly", "[format][tile][fuzz]") {
  replayBinary(
      "city_tile", [](const auto& bytes, const std::string& name) { return decodeCityTile(bytes, name); },
      [](const CityTile& tile) { return encodeCityTile(tile); });
}

TEST_CASE("Fuzzer-found search indexes are rejected cleanly", "[format][search][fuzz]") {
  replayBinary(
      "search_index", [](const auto& bytes, const std::string& name) { return decodeSearchIndex(bytes, name); },
      [](const std::vector<SearchEntry>& entries) { return encodeSearchIndex(entries); });
}

TEST_CASE("Fuzzer-found response tiles are rejected cleanly", "[format][response][fuzz]") {
  replayBinary(
      "response_summary", [](const auto& bytes, const std::string& name) { return decodeResponseSummary(bytes, name); },
      [](const ResponseSummaryTile& tile) { return encodeResponseSummary(tile); });
  replayBinary(
      "response_history", [](const auto& bytes, const std::string& name) { return decodeResponseHistory(bytes, name); },
      [](const ResponseHistoryTile& tile) { return encodeResponseHistory(tile); });
}

TEST_CASE("Fuzzer-found tileset manifests are rejected cleanly", "[format][tileset][fuzz]") {
  const auto inputs = fuzz::savedInputs(QUAKEVIEW_SOURCE_DIR, "tileset");
  CHECK_FALSE(inputs.empty());
  for (const fuzz::SavedInput& input : inputs) {
    SECTION(input.path) {
      const std::string_view json(reinterpret_cast<const char*>(input.bytes.data()), input.bytes.size());
      requireCleanError(parseTileset(json, input.path), input.path);
    }
  }
}
