#include "qv/core/ByteIO.h"

namespace qv {

void ByteWriter::f32(float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  u32(bits);
}

void ByteWriter::f64(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  u64(bits);
}

void ByteWriter::varint(std::uint64_t v) {
  while (v >= 0x80) {
    bytes_.push_back(static_cast<std::uint8_t>((v & 0x7Fu) | 0x80u));
    v >>= 7;
  }
  bytes_.push_back(static_cast<std::uint8_t>(v));
}

void ByteWriter::string(std::string_view s) {
  varint(s.size());
  bytes_.insert(bytes_.end(), s.begin(), s.end());
}

void ByteWriter::patchU32(std::size_t offset, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) bytes_[offset + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

void ByteWriter::align(std::size_t alignment) {
  while (bytes_.size() % alignment != 0) bytes_.push_back(0);
}

void ByteReader::fail(std::string_view message) {
  if (!error_.empty()) return;
  error_ = std::string(message) + " at byte " + std::to_string(offset());
}

bool ByteReader::need(std::size_t n, const char* what) {
  if (!error_.empty()) return false;
  if (n > bytes_.size() - pos_) {
    fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes, " +
         std::to_string(bytes_.size() - pos_) + " left");
    return false;
  }
  return true;
}

std::uint8_t ByteReader::u8(const char* what) {
  if (!need(1, what)) return 0;
  return bytes_[pos_++];
}

std::uint16_t ByteReader::u16(const char* what) {
  if (!need(2, what)) return 0;
  const auto v = static_cast<std::uint16_t>(bytes_[pos_] | (bytes_[pos_ + 1] << 8));
  pos_ += 2;
  return v;
}

std::uint32_t ByteReader::u32(const char* what) {
  if (!need(4, what)) return 0;
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(bytes_[pos_ + i]) << (8 * i);
  pos_ += 4;
  return v;
}

std::uint64_t ByteReader::u64(const char* what) {
  if (!need(8, what)) return 0;
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(bytes_[pos_ + i]) << (8 * i);
  pos_ += 8;
  return v;
}

float ByteReader::f32(const char* what) {
  const std::uint32_t bits = u32(what);
  float v = 0.0f;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

double ByteReader::f64(const char* what) {
  const std::uint64_t bits = u64(what);
  double v = 0.0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::uint64_t ByteReader::varint(const char* what) {
  std::uint64_t v = 0;
  for (int shift = 0; shift < 70; shift += 7) {
    const std::uint8_t b = u8(what);
    if (!ok()) return 0;
    // The tenth byte holds bit 63 only: anything more would be silently cut off.
    if (shift == 63 && (b & 0x7Eu) != 0) {
      fail(std::string("varint in ") + what + " overflows 64 bits");
      return 0;
    }
    v |= static_cast<std::uint64_t>(b & 0x7Fu) << shift;
    if ((b & 0x80u) == 0) return v;
  }
  fail(std::string("malformed varint in ") + what);
  return 0;
}

std::string ByteReader::string(const char* what, std::size_t maxLength) {
  const std::uint64_t length = varint(what);
  if (!ok()) return {};
  if (length > maxLength) {
    fail(std::string(what) + " is " + std::to_string(length) + " bytes long (limit " + std::to_string(maxLength) + ")");
    return {};
  }
  const auto b = bytes(static_cast<std::size_t>(length), what);
  return std::string(b.begin(), b.end());
}

std::span<const std::uint8_t> ByteReader::bytes(std::size_t n, const char* what) {
  if (!need(n, what)) return {};
  const auto out = bytes_.subspan(pos_, n);
  pos_ += n;
  return out;
}

}  // namespace qv
