// The file helpers of quakeview-prep that the merge of a sharded response relies on: a file's size
// and CRC-32 read through a small buffer (equal to qv::crc32 of its bytes, across buffer edges),
// a clear message for a missing file, and parallelFor running every index exactly once.
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "qv/core/Crc32.h"
#include "qv/prep/Files.h"

namespace fs = std::filesystem;

TEST_CASE("fileDigest gives the size and CRC-32 of a file larger than its buffer, and names a missing file") {
  const fs::path dir = fs::temp_directory_path() / ("qv-files-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // 2.5 MiB + 3 bytes of a pattern: the 1 MiB reads end mid-file and the last one is short.
  std::vector<std::uint8_t> bytes((5u << 19) + 3);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>((i * 2654435761u) >> 13);
  const std::string path = (dir / "data.bin").string();
  REQUIRE(qv::prep::writeFileAtomic(path, bytes).ok());
  const auto digest = qv::prep::fileDigest(path);
  REQUIRE(digest.ok());
  CHECK(digest->bytes == bytes.size());
  CHECK(digest->crc32 == qv::crc32(bytes));
  // "123456789" is CRC-32's check value 0xCBF43926.
  const std::string check = "123456789";
  REQUIRE(
      qv::prep::writeFileAtomic((dir / "check").string(), std::vector<std::uint8_t>(check.begin(), check.end())).ok());
  CHECK(qv::prep::fileDigest((dir / "check").string())->crc32 == 0xCBF43926u);
  const auto empty = (dir / "empty").string();
  REQUIRE(qv::prep::writeFileAtomic(empty, std::vector<std::uint8_t>{}).ok());
  CHECK(qv::prep::fileDigest(empty)->bytes == 0);
  CHECK(qv::prep::fileDigest(empty)->crc32 == 0);

  const auto missing = qv::prep::fileDigest((dir / "missing.qvh").string());
  REQUIRE_FALSE(missing.ok());
  CHECK_THAT(missing.error(), Catch::Contains("missing.qvh") && Catch::Contains("No such file"));
  fs::remove_all(dir);
}

TEST_CASE("parallelFor runs every index once on any number of threads") {
  for (const unsigned threads : {0u, 1u, 2u, 7u}) {
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{5}, std::size_t{1000}}) {
      std::vector<std::atomic<int>> runs(count);
      qv::prep::parallelFor(count, threads, [&](std::size_t i) { ++runs[i]; });
      for (std::size_t i = 0; i < count; ++i) {
        INFO("threads " << threads << ", count " << count << ", index " << i);
        CHECK(runs[i] == 1);
      }
    }
  }
}
