// Stored files: a file of the city may be kept on disk (and served) as one Zstandard frame of its
// bytes (docs/formats.md "Compressed files"). Readers take either form; the frame must declare its
// content size (bounded below), so that a hostile frame is refused before anything is allocated,
// and zstd checks its content checksum (quakeview-prep writes one). Writers compress with
// prep::compressStoredFile (preprocess); the viewer only reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"

namespace qv {

/// The largest file a frame may expand to (1 GiB), and the largest ratio of expanded to stored
/// size a reader accepts (a bound on what a few hostile bytes can make it allocate).
inline constexpr std::uint64_t kMaxStoredFileBytes = std::uint64_t{1} << 30;
inline constexpr std::uint64_t kMaxStoredFileRatio = 4096;

/// True when `bytes` start with the Zstandard frame magic (28 B5 2F FD).
[[nodiscard]] bool isCompressedFile(std::span<const std::uint8_t> bytes);

/// The file's bytes from its stored form: `bytes` itself (copied) when it is not a Zstandard
/// frame, else the frame's content. Errors name `name`: a frame without a declared content size,
/// over the limits above, with trailing data, damaged, or whose checksum does not match.
Result<std::vector<std::uint8_t>> unpackStoredFile(std::span<const std::uint8_t> bytes, std::string_view name);

/// The same without a copy of an uncompressed file: the file's bytes, `bytes` itself or the frame's
/// content decompressed into `storage`.
Result<std::span<const std::uint8_t>> storedFileBytes(std::span<const std::uint8_t> bytes, std::string_view name,
                                                      std::vector<std::uint8_t>& storage);

}  // namespace qv
