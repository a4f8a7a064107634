#include "qv/format/GroundTile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"
#include "qv/core/Text.h"
#include "qv/format/StoredFile.h"

namespace qv {
namespace {

constexpr std::array<std::uint8_t, 4> kMagic = {'Q', 'V', 'G', 'T'};
constexpr std::size_t kHeaderSize = 56;
constexpr std::size_t kSectionEntrySize = 12;
constexpr std::size_t kVertexSize = 4;         // qx, qy u16
constexpr std::size_t kRunSize = 9;            // class u8, first triangle u32, triangle count u32
constexpr std::size_t kLabelFixedSize = 15;    // kind, rank, qx, qy, angle, length, text length
constexpr std::uint16_t kFlagWideIndices = 1;  // triangle indices are u32 (set exactly when V > 65535)
constexpr std::uint16_t kKnownFlags = kFlagWideIndices;
constexpr std::size_t kMaxLabelTextBytes = 255;
// The same bounds as the city tiles (CityTile.cpp): below a micrometre, extent / 65535 nears the
// denormal floats and vertices lose precision.
constexpr float kMinExtentM = 1.0e-6f;
constexpr float kMaxExtentM = 1.0e8f;
constexpr double kMaxOriginM = 1.0e7;
constexpr float kMaxLabelLengthM = 1.0e8f;
// pi/2 rounded to float is 1.5707964 (just above pi/2): the largest float angle a writer can hold
// for "straight up" is accepted, the same value negated is not.
constexpr float kHalfPi = static_cast<float>(std::numbers::pi / 2.0);

// Section fourccs in the one order a version 1 file holds them.
constexpr std::array<const char*, 4> kSectionNames = {"VERT", "TRIS", "RUNS", "LABL"};

std::uint32_t tag(const char* t) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(t[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(t[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(t[2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(t[3])) << 24;
}

std::string tagName(std::uint32_t t) {
  std::string s(4, ' ');
  for (std::size_t i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((t >> (8 * i)) & 0xFFu);
    s[i] = (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

std::uint64_t padded4(std::uint64_t n) {
  return (n + 3) / 4 * 4;
}

std::uint16_t quantize(float v, float extent) {
  const float q = std::round(v / extent * 65535.0f);
  if (!(q >= 0.0f)) return 0;  // NaN too
  return static_cast<std::uint16_t>(std::min(q, 65535.0f));
}

/// The longest prefix of `text` of at most kMaxLabelTextBytes bytes that does not cut a UTF-8
/// sequence (the encoder's guard; the contract asks callers for at most 255 bytes).
std::string_view clippedText(std::string_view text) {
  if (text.size() <= kMaxLabelTextBytes) return text;
  std::size_t n = kMaxLabelTextBytes;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0u) == 0x80u) --n;
  return text.substr(0, n);
}

/// Why a label text is refused, or nullptr: empty, not UTF-8, or holding a control character
/// (C0 below U+0020, DEL, C1 U+0080..U+009F, which UTF-8 writes as C2 80..C2 9F).
const char* labelTextProblem(std::string_view text) {
  if (text.empty()) return "empty text";
  if (!isValidUtf8(text)) return "text is not valid UTF-8";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b < 0x20 || b == 0x7F) return "text holds a control character";
    if (b == 0xC2 && i + 1 < text.size()) {
      const auto next = static_cast<unsigned char>(text[i + 1]);
      if (next >= 0x80 && next <= 0x9F) return "text holds a control character";
    }
  }
  return nullptr;
}

struct Section {
  std::span<const std::uint8_t> data;
  std::size_t offset = 0;
};

Result<GroundTile> decodeGroundFile(std::span<const std::uint8_t> bytes, std::string_view name,
                                    const GroundTileLimits& limits) {
  const std::string prefix = std::string(name) + ": ";
  auto error = [&](const std::string& message) { return Error{prefix + message}; };
  auto at = [](std::uint64_t offset) { return " at byte " + std::to_string(offset); };

  if (bytes.size() < kHeaderSize) {
    return error("not a ground tile: " + std::to_string(bytes.size()) + " bytes is shorter than the " +
                 std::to_string(kHeaderSize) + "-byte header");
  }
  if (std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
    return error("not a ground tile: the file does not start with \"QVGT\"");
  }
  ByteReader header(bytes.subspan(4, kHeaderSize - 4), 4);
  const std::uint16_t version = header.u16("version");
  if (version != kGroundTileVersion) {
    return error("unsupported ground tile version " + std::to_string(version) + " (this build reads version " +
                 std::to_string(kGroundTileVersion) + ")");
  }
  const std::uint16_t flags = header.u16("flags");
  const std::uint32_t fileSize = header.u32("file size");
  const std::uint32_t storedCrc = header.u32("checksum");
  const std::uint32_t vertexCount = header.u32("vertex count");
  const std::uint32_t triangleCount = header.u32("triangle count");
  const std::uint32_t labelCount = header.u32("label count");
  const std::uint16_t runCount = header.u16("run count");
  const std::uint16_t sectionCount = header.u16("section count");
  GroundTile tile;
  tile.originX = header.f64("origin x");
  tile.originY = header.f64("origin y");
  tile.extent = header.f32("extent");
  const std::uint32_t reserved = header.u32("reserved");
  if (!header.ok()) return error("header: " + header.error());  // unreachable: the size was checked

  if (fileSize != bytes.size()) {
    return error("truncated or padded: the header says " + std::to_string(fileSize) + " bytes, the file has " +
                 std::to_string(bytes.size()));
  }
  const std::uint32_t crc = crc32(bytes.subspan(16));
  if (crc != storedCrc) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "checksum mismatch: stored %08x, computed %08x (corrupt file)", storedCrc,
                  crc);
    return error(buffer);
  }
  // A decoded tile re-encodes to the same bytes: flags this version does not define are refused,
  // not ignored, and the one flag must say what the vertex count implies.
  if ((flags & ~kKnownFlags) != 0) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "header at byte 6: unknown flags 0x%04x", flags & ~kKnownFlags);
    return error(buffer);
  }
  const bool wide = (flags & kFlagWideIndices) != 0;
  if (wide != (vertexCount > 65535)) {
    return error("header at byte 6: the wide-index flag is " + std::string(wide ? "set" : "clear") + " for " +
                 std::to_string(vertexCount) + " vertices (set exactly when there are more than 65535)");
  }
  if (vertexCount > limits.maxVertices) {
    return error("header at byte 16: " + std::to_string(vertexCount) + " vertices exceeds the limit of " +
                 std::to_string(limits.maxVertices));
  }
  if (triangleCount > limits.maxTriangles) {
    return error("header at byte 20: " + std::to_string(triangleCount) + " triangles exceeds the limit of " +
                 std::to_string(limits.maxTriangles));
  }
  if (labelCount > limits.maxLabels) {
    return error("header at byte 24: " + std::to_string(labelCount) + " labels exceeds the limit of " +
                 std::to_string(limits.maxLabels));
  }
  constexpr auto kClassCount = static_cast<std::uint16_t>(GroundClass::Count);
  if (runCount > kClassCount) {
    return error("header at byte 28: " + std::to_string(runCount) + " runs, more than the " +
                 std::to_string(kClassCount) + " ground classes");
  }
  if (sectionCount != kSectionNames.size()) {
    return error("header at byte 30: " + std::to_string(sectionCount) + " sections, a version " +
                 std::to_string(kGroundTileVersion) + " ground tile has 4 (VERT, TRIS, RUNS, LABL)");
  }
  if (!(std::abs(tile.originX) <= kMaxOriginM) || !(std::abs(tile.originY) <= kMaxOriginM)) {
    return error("header at byte 32: origin (" + std::to_string(tile.originX) + ", " + std::to_string(tile.originY) +
                 ") is not within 1e7 m of the tileset origin");
  }
  if (!(tile.extent >= kMinExtentM && tile.extent <= kMaxExtentM)) {
    return error("header at byte 48: extent " + std::to_string(tile.extent) + " m is outside [1e-6, 1e8] m");
  }
  if (reserved != 0) return error("header at byte 52: reserved field is " + std::to_string(reserved) + ", not 0");

  // Section table: the four sections in their order, each where the previous one ends (padded to
  // 4 bytes with zeros), with the sizes the counts give; the file ends after the last one.
  const std::uint64_t indexSize = wide ? 4 : 2;
  const std::array<std::uint64_t, 4> expectedSizes = {std::uint64_t{vertexCount} * kVertexSize,
                                                      std::uint64_t{triangleCount} * 3 * indexSize,
                                                      std::uint64_t{runCount} * kRunSize, 0};
  std::array<Section, 4> sections;
  ByteReader table(bytes.subspan(kHeaderSize), kHeaderSize);
  std::uint64_t expectedOffset = kHeaderSize + kSectionNames.size() * kSectionEntrySize;
  for (std::size_t i = 0; i < kSectionNames.size(); ++i) {
    const std::size_t entryAt = table.offset();
    const std::uint32_t id = table.u32("section id");
    const std::uint32_t offset = table.u32("section offset");
    const std::uint32_t size = table.u32("section size");
    if (!table.ok()) return error("section table: " + table.error());
    const char* wanted = kSectionNames[i];
    if (id != tag(wanted)) {
      return error("section table" + at(entryAt) + ": section " + tagName(id) + " where " + wanted +
                   " belongs (a version 1 ground tile holds VERT, TRIS, RUNS, LABL in this order)");
    }
    if (offset != expectedOffset) {
      return error("section table" + at(entryAt) + ": section " + wanted + " at byte " + std::to_string(offset) +
                   ", expected at byte " + std::to_string(expectedOffset));
    }
    if (offset > bytes.size() || size > bytes.size() - offset) {
      return error("section " + std::string(wanted) + at(offset) + " with " + std::to_string(size) +
                   " bytes lies outside the file of " + std::to_string(bytes.size()) + " bytes");
    }
    if (i < 3 && size != expectedSizes[i]) {
      static constexpr std::array<const char*, 3> kWhat = {" vertices", " triangles", " runs"};
      const std::uint32_t counts[3] = {vertexCount, triangleCount, runCount};
      return error("section " + std::string(wanted) + at(offset) + " holds " + std::to_string(size) +
                   " bytes, the header declares " + std::to_string(counts[i]) + kWhat[i] + " (" +
                   std::to_string(expectedSizes[i]) + " bytes)");
    }
    // Labels are checked one by one below; this bounds what the label count may allocate.
    if (i == 3 && std::uint64_t{size} < std::uint64_t{labelCount} * kLabelFixedSize) {
      return error("section LABL" + at(offset) + " holds " + std::to_string(size) + " bytes, too few for the " +
                   std::to_string(labelCount) + " labels the header declares (" + std::to_string(kLabelFixedSize) +
                   " bytes each at least)");
    }
    sections[i] = {bytes.subspan(offset, size), offset};
    const std::uint64_t end = std::uint64_t{offset} + size;
    const std::uint64_t paddedEnd = padded4(end);
    if (paddedEnd > bytes.size()) {
      return error("section " + std::string(wanted) + at(offset) + ": its padding runs past the end of the file");
    }
    for (std::uint64_t b = end; b < paddedEnd; ++b) {
      if (bytes[static_cast<std::size_t>(b)] != 0) return error("padding" + at(b) + " after " + wanted + " is not 0");
    }
    expectedOffset = paddedEnd;
  }
  if (expectedOffset != bytes.size()) {
    return error("section LABL" + at(sections[3].offset) + ": " + std::to_string(bytes.size() - expectedOffset) +
                 " bytes after the last section");
  }

  // VERT
  {
    const Section& s = sections[0];
    ByteReader r(s.data, s.offset);
    const float scale = tile.extent / 65535.0f;
    tile.vertices.resize(vertexCount);
    for (glm::vec2& v : tile.vertices) {
      const float x = static_cast<float>(r.u16("vertex x")) * scale;
      const float y = static_cast<float>(r.u16("vertex y")) * scale;
      v = {x, y};
    }
    if (!r.ok()) return error("section VERT: " + r.error());
  }
  // TRIS
  {
    const Section& s = sections[1];
    ByteReader r(s.data, s.offset);
    tile.triangles.resize(std::size_t{triangleCount} * 3);
    for (std::uint32_t& index : tile.triangles) {
      const std::size_t indexAt = r.offset();
      index = wide ? r.u32("triangle index") : r.u16("triangle index");
      if (index >= vertexCount) {
        return error("section TRIS" + at(indexAt) + ": triangle index " + std::to_string(index) + " beyond the " +
                     std::to_string(vertexCount) + " vertices");
      }
    }
    if (!r.ok()) return error("section TRIS: " + r.error());
  }
  // RUNS: classes increasing, each run starting where the previous ends, together covering every
  // triangle.
  {
    const Section& s = sections[2];
    ByteReader r(s.data, s.offset);
    tile.runs.resize(runCount);
    std::uint64_t cursor = 0;
    for (std::size_t k = 0; k < tile.runs.size(); ++k) {
      GroundRun& run = tile.runs[k];
      const std::size_t runAt = r.offset();
      const std::uint8_t groundClass = r.u8("run class");
      run.firstTriangle = r.u32("run first triangle");
      run.triangleCount = r.u32("run triangle count");
      if (!r.ok()) return error("section RUNS: " + r.error());
      const std::string where = "section RUNS" + at(runAt) + ": run " + std::to_string(k);
      if (groundClass >= static_cast<std::uint8_t>(GroundClass::Count)) {
        return error(where + ": unknown ground class " + std::to_string(groundClass));
      }
      run.groundClass = static_cast<GroundClass>(groundClass);
      if (k > 0 && groundClass <= static_cast<std::uint8_t>(tile.runs[k - 1].groundClass)) {
        return error(where + ": class " + std::string(groundClassName(run.groundClass)) + " after " +
                     std::string(groundClassName(tile.runs[k - 1].groundClass)) +
                     " (runs are in increasing class order, each class once)");
      }
      if (run.firstTriangle != cursor) {
        return error(where + " starts at triangle " + std::to_string(run.firstTriangle) +
                     ", the runs before it end at " + std::to_string(cursor));
      }
      cursor += run.triangleCount;
      if (cursor > triangleCount) {
        return error(where + " ends at triangle " + std::to_string(cursor) + ", beyond the " +
                     std::to_string(triangleCount) + " triangles");
      }
    }
    if (cursor != triangleCount) {
      return error("section RUNS" + at(s.offset) + ": the runs cover " + std::to_string(cursor) + " of the " +
                   std::to_string(triangleCount) + " triangles");
    }
  }
  // LABL
  {
    const Section& s = sections[3];
    ByteReader r(s.data, s.offset);
    const float scale = tile.extent / 65535.0f;
    tile.labels.resize(labelCount);
    for (std::size_t k = 0; k < tile.labels.size(); ++k) {
      GroundLabel& label = tile.labels[k];
      const std::size_t labelAt = r.offset();
      const std::uint8_t kind = r.u8("label kind");
      label.rank = r.u8("label rank");
      const float x = static_cast<float>(r.u16("label x")) * scale;
      const float y = static_cast<float>(r.u16("label y")) * scale;
      label.position = {x, y};
      label.angleRad = r.f32("label angle");
      label.lengthM = r.f32("label length");
      const std::uint8_t textLength = r.u8("label text length");
      const std::size_t textAt = r.offset();
      const std::span<const std::uint8_t> text = r.bytes(textLength, "label text");
      if (!r.ok()) return error("section LABL: label " + std::to_string(k) + ": " + r.error());
      const std::string where = "section LABL" + at(labelAt) + ": label " + std::to_string(k);
      if (kind >= static_cast<std::uint8_t>(GroundLabelKind::Count)) {
        return error(where + ": unknown label kind " + std::to_string(kind));
      }
      label.kind = static_cast<GroundLabelKind>(kind);
      if (!(label.angleRad > -kHalfPi && label.angleRad <= kHalfPi)) {
        return error(where + ": angle " + std::to_string(label.angleRad) + " rad is outside (-pi/2, pi/2]");
      }
      if (!(label.lengthM >= 0.0f && label.lengthM <= kMaxLabelLengthM)) {
        return error(where + ": length " + std::to_string(label.lengthM) + " m is outside [0, 1e8] m");
      }
      label.text.assign(reinterpret_cast<const char*>(text.data()), text.size());
      if (const char* problem = labelTextProblem(label.text)) {
        return error("section LABL" + at(textAt) + ": label " + std::to_string(k) + ": " + problem);
      }
    }
    if (r.remaining() != 0) {
      return error("section LABL" + at(r.offset()) + ": " + std::to_string(r.remaining()) +
                   " bytes after the last label");
    }
  }
  return tile;
}

}  // namespace

std::string_view groundClassName(GroundClass c) {
  switch (c) {
    case GroundClass::Land:
      return "land";
    case GroundClass::Green:
      return "green";
    case GroundClass::Forest:
      return "forest";
    case GroundClass::Park:
      return "park";
    case GroundClass::Water:
      return "water";
    case GroundClass::Path:
      return "path";
    case GroundClass::Rail:
      return "rail";
    case GroundClass::Street:
      return "street";
    case GroundClass::Major:
      return "major";
    case GroundClass::Motorway:
      return "motorway";
    case GroundClass::Count:
      break;
  }
  return "unknown";
}

std::string_view groundLabelKindName(GroundLabelKind k) {
  switch (k) {
    case GroundLabelKind::Street:
      return "street";
    case GroundLabelKind::Water:
      return "water";
    case GroundLabelKind::Park:
      return "park";
    case GroundLabelKind::Neighbourhood:
      return "neighbourhood";
    case GroundLabelKind::Settlement:
      return "settlement";
    case GroundLabelKind::Count:
      break;
  }
  return "unknown";
}

std::vector<std::uint8_t> encodeGroundTile(const GroundTile& tile) {
  const float extent = tile.extent > 0.0f ? tile.extent : 1.0f;
  const bool wide = tile.vertices.size() > 65535;
  ByteWriter vert, tris, runs, labl;
  vert.reserve(tile.vertices.size() * kVertexSize);
  for (const glm::vec2& v : tile.vertices) {
    vert.u16(quantize(v.x, extent));
    vert.u16(quantize(v.y, extent));
  }
  tris.reserve(tile.triangles.size() * (wide ? 4 : 2));
  for (std::uint32_t index : tile.triangles) {
    if (wide)
      tris.u32(index);
    else
      tris.u16(static_cast<std::uint16_t>(index));
  }
  for (const GroundRun& run : tile.runs) {
    runs.u8(static_cast<std::uint8_t>(run.groundClass));
    runs.u32(run.firstTriangle);
    runs.u32(run.triangleCount);
  }
  for (const GroundLabel& label : tile.labels) {
    const std::string_view text = clippedText(label.text);
    labl.u8(static_cast<std::uint8_t>(label.kind));
    labl.u8(label.rank);
    labl.u16(quantize(label.position.x, extent));
    labl.u16(quantize(label.position.y, extent));
    labl.f32(label.angleRad);
    labl.f32(label.lengthM);
    labl.u8(static_cast<std::uint8_t>(text.size()));
    labl.bytes(std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  }
  const std::array<const ByteWriter*, 4> sections = {&vert, &tris, &runs, &labl};

  ByteWriter out;
  std::size_t offset = kHeaderSize + sections.size() * kSectionEntrySize;
  {
    std::size_t total = offset;
    for (const ByteWriter* s : sections) total += static_cast<std::size_t>(padded4(s->size()));
    out.reserve(total);
  }
  out.bytes(kMagic);
  out.u16(kGroundTileVersion);
  out.u16(wide ? kFlagWideIndices : 0);
  out.u32(0);  // file size, patched below
  out.u32(0);  // CRC, patched below
  out.u32(static_cast<std::uint32_t>(tile.vertices.size()));
  out.u32(static_cast<std::uint32_t>(tile.triangles.size() / 3));
  out.u32(static_cast<std::uint32_t>(tile.labels.size()));
  out.u16(static_cast<std::uint16_t>(tile.runs.size()));
  out.u16(static_cast<std::uint16_t>(sections.size()));
  out.f64(tile.originX);
  out.f64(tile.originY);
  out.f32(extent);
  out.u32(0);  // reserved
  for (std::size_t i = 0; i < sections.size(); ++i) {
    out.u32(tag(kSectionNames[i]));
    out.u32(static_cast<std::uint32_t>(offset));
    out.u32(static_cast<std::uint32_t>(sections[i]->size()));
    offset += static_cast<std::size_t>(padded4(sections[i]->size()));
  }
  for (const ByteWriter* s : sections) {
    out.bytes(s->data());
    out.align(4);
  }
  out.patchU32(8, static_cast<std::uint32_t>(out.size()));
  const auto& bytes = out.data();
  out.patchU32(12, crc32(std::span(bytes).subspan(16)));
  return out.take();
}

Result<GroundTile> decodeGroundTile(std::span<const std::uint8_t> bytes, std::string_view name,
                                    const GroundTileLimits& limits) {
  std::vector<std::uint8_t> storage;
  auto file = storedFileBytes(bytes, name, storage);
  if (!file.ok()) return Error{file.error()};
  return decodeGroundFile(*file, name, limits);
}

}  // namespace qv
