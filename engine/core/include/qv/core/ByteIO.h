// Little-endian byte writing and bounds-checked reading for the binary formats.
//
// ByteReader never reads past its span: every read checks the bytes left and, on a short read,
// records the first failure (what was being read and at which byte offset) and returns zeros, so
// a decoder can read a whole record and check `ok()` once. Nothing throws.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace qv {

class ByteWriter {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(v); }
  void u16(std::uint16_t v) { put(v); }
  void u32(std::uint32_t v) { put(v); }
  void u64(std::uint64_t v) { put(v); }
  void i16(std::int16_t v) { put(static_cast<std::uint16_t>(v)); }
  void i32(std::int32_t v) { put(static_cast<std::uint32_t>(v)); }
  void f32(float v);
  void f64(double v);
  /// Unsigned LEB128.
  void varint(std::uint64_t v);
  /// varint length, then the bytes.
  void string(std::string_view s);
  void bytes(std::span<const std::uint8_t> b) {
    if (b.empty()) return;
    // resize + memcpy rather than insert: GCC 12 misreports insert of a span (-Wstringop-overflow).
    const std::size_t at = bytes_.size();
    bytes_.resize(at + b.size());
    std::memcpy(bytes_.data() + at, b.data(), b.size());
  }
  void fourcc(const char (&tag)[5]) { bytes(std::span(reinterpret_cast<const std::uint8_t*>(tag), 4)); }
  /// Overwrites 4 bytes at `offset` (for sizes and offsets known only later).
  void patchU32(std::size_t offset, std::uint32_t v);
  void align(std::size_t alignment);

  /// Makes room for `n` more bytes (writers that know their size avoid regrowing).
  void reserve(std::size_t n) { bytes_.reserve(bytes_.size() + n); }

  [[nodiscard]] std::size_t size() const { return bytes_.size(); }
  [[nodiscard]] const std::vector<std::uint8_t>& data() const { return bytes_; }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  template <typename T>
  void put(T v) {
    // Little-endian whatever the host, assembled in a small array and appended at once (the
    // compiler turns the loop into one store; byte-wise push_back checks capacity every byte).
    std::uint8_t b[sizeof(T)];
    for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = static_cast<std::uint8_t>(v >> (8 * i));
    const std::size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, b, sizeof(T));
  }
  std::vector<std::uint8_t> bytes_;
};

class ByteReader {
 public:
  /// `baseOffset` is added to offsets in error messages (for readers of a sub-span).
  explicit ByteReader(std::span<const std::uint8_t> bytes, std::size_t baseOffset = 0)
      : bytes_(bytes), base_(baseOffset) {}

  std::uint8_t u8(const char* what);
  std::uint16_t u16(const char* what);
  std::uint32_t u32(const char* what);
  std::uint64_t u64(const char* what);
  std::int16_t i16(const char* what) { return static_cast<std::int16_t>(u16(what)); }
  std::int32_t i32(const char* what) { return static_cast<std::int32_t>(u32(what)); }
  float f32(const char* what);
  double f64(const char* what);
  /// Unsigned LEB128 of at most 10 bytes.
  std::uint64_t varint(const char* what);
  /// A varint length then that many bytes; at most maxLength bytes.
  std::string string(const char* what, std::size_t maxLength = 4096);
  /// A view of the next n bytes (empty and failed when fewer remain).
  std::span<const std::uint8_t> bytes(std::size_t n, const char* what);
  void skip(std::size_t n, const char* what) { (void)bytes(n, what); }

  [[nodiscard]] bool ok() const { return error_.empty(); }
  [[nodiscard]] const std::string& error() const { return error_; }
  /// Records a failure (the first one wins) at the current offset.
  void fail(std::string_view message);
  [[nodiscard]] std::size_t offset() const { return base_ + pos_; }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }

 private:
  bool need(std::size_t n, const char* what);
  std::span<const std::uint8_t> bytes_;
  std::size_t base_ = 0;
  std::size_t pos_ = 0;
  std::string error_;
};

}  // namespace qv
