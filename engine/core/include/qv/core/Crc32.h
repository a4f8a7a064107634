// CRC-32 (IEEE 802.3 polynomial 0xEDB88320, reflected, initial and final XOR 0xFFFFFFFF): the
// checksum of zlib, PNG and gzip, so `python3 -c "import zlib; print(zlib.crc32(data))"` checks a
// file by hand. Written here because the WASM build has no zlib (Emscripten's port would need a
// download) and the function is twenty lines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace qv {

/// CRC-32 of `bytes`, continuing from `previous` (0 to start).
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t previous = 0);

}  // namespace qv
