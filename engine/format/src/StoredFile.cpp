#include "qv/format/StoredFile.h"

#include <zstd.h>

#include <string>

namespace qv {

bool isCompressedFile(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 4 && bytes[0] == 0x28 && bytes[1] == 0xB5 && bytes[2] == 0x2F && bytes[3] == 0xFD;
}

Result<std::span<const std::uint8_t>> storedFileBytes(std::span<const std::uint8_t> bytes, std::string_view name,
                                                      std::vector<std::uint8_t>& storage) {
  if (!isCompressedFile(bytes)) return bytes;
  const std::string prefix = std::string(name) + ": compressed file (Zstandard frame): ";
  const unsigned long long declared = ZSTD_getFrameContentSize(bytes.data(), bytes.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) return Error{prefix + "the frame header is damaged or truncated"};
  if (declared == ZSTD_CONTENTSIZE_UNKNOWN) {
    return Error{prefix + "the frame does not declare its content size (not written by quakeview-prep)"};
  }
  const std::size_t frame = ZSTD_findFrameCompressedSize(bytes.data(), bytes.size());
  if (ZSTD_isError(frame)) {
    return Error{prefix + "the frame is damaged or truncated (" + ZSTD_getErrorName(frame) + ") in " +
                 std::to_string(bytes.size()) + " bytes"};
  }
  if (frame != bytes.size()) {
    return Error{prefix + std::to_string(bytes.size() - frame) + " bytes follow the frame's end at byte " +
                 std::to_string(frame)};
  }
  if (declared > kMaxStoredFileBytes || declared > kMaxStoredFileRatio * bytes.size()) {
    return Error{prefix + "declares " + std::to_string(declared) + " bytes from " + std::to_string(bytes.size()) +
                 ", over the limit (1 GiB, and " + std::to_string(kMaxStoredFileRatio) + " times the stored size)"};
  }
  storage.resize(static_cast<std::size_t>(declared));
  const std::size_t got = ZSTD_decompress(storage.data(), storage.size(), bytes.data(), bytes.size());
  if (ZSTD_isError(got)) {
    storage.clear();
    return Error{prefix + "cannot be decompressed: " + ZSTD_getErrorName(got)};
  }
  if (got != declared) {
    storage.clear();
    return Error{prefix + "expanded to " + std::to_string(got) + " bytes, the frame declares " +
                 std::to_string(declared)};
  }
  return std::span<const std::uint8_t>(storage);
}

Result<std::vector<std::uint8_t>> unpackStoredFile(std::span<const std::uint8_t> bytes, std::string_view name) {
  if (!isCompressedFile(bytes)) return std::vector<std::uint8_t>(bytes.begin(), bytes.end());
  std::vector<std::uint8_t> storage;
  auto view = storedFileBytes(bytes, name, storage);
  if (!view.ok()) return Error{view.error()};
  return storage;
}

}  // namespace qv
