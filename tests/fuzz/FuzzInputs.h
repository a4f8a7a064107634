// How the fuzz targets turn their input bytes into decoder calls, shared with the regression
// tests that replay saved inputs (tests/fuzz/regressions/) in the ordinary unit test builds.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "qv/core/Crc32.h"

namespace qv::fuzz {

/// The binary formats (city, search and response tiles) share a header: the file size at byte 8
/// and the CRC-32 of bytes [16, end) at byte 12. Returns a copy of `bytes` with both made right
/// (unchanged when shorter than 16 bytes), so that mutations reach past the integrity checks.
inline std::vector<std::uint8_t> withValidSizeAndCrc(std::span<const std::uint8_t> bytes) {
  std::vector<std::uint8_t> out(bytes.begin(), bytes.end());
  if (out.size() < 16) return out;
  auto put = [&](std::size_t at, std::uint32_t v) {
    for (std::size_t i = 0; i < 4; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
  };
  put(8, static_cast<std::uint32_t>(out.size()));
  put(12, crc32(std::span<const std::uint8_t>(out).subspan(16)));
  return out;
}

}  // namespace qv::fuzz
