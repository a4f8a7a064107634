#include "qv/format/CityTile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"

namespace qv {
namespace {

constexpr std::array<std::uint8_t, 4> kMagic = {'Q', 'V', 'C', 'T'};
constexpr std::size_t kHeaderSize = 48;
constexpr std::size_t kSectionEntrySize = 12;
constexpr std::size_t kBuildingRecordSize = 40;
constexpr std::size_t kPartRecordSize = 20;
constexpr std::uint16_t kFlagCoarse = 1;
constexpr float kMinExtentM = 1.0e-6f;
constexpr float kMaxExtentM = 1.0e8f;
constexpr std::uint16_t kFlagHeightTagged = 1;
constexpr std::uint16_t kFlagStoreysTagged = 2;

std::uint32_t tag(const char (&t)[5]) {
  return static_cast<std::uint32_t>(t[0]) | static_cast<std::uint32_t>(t[1]) << 8 |
         static_cast<std::uint32_t>(t[2]) << 16 | static_cast<std::uint32_t>(t[3]) << 24;
}

std::string tagName(std::uint32_t t) {
  std::string s(4, ' ');
  for (std::size_t i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((t >> (8 * i)) & 0xFFu);
    s[i] = (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

const std::uint32_t kBldg = tag("BLDG");
const std::uint32_t kPart = tag("PART");
const std::uint32_t kRing = tag("RING");
const std::uint32_t kVert = tag("VERT");
const std::uint32_t kTris = tag("TRIS");
const std::uint32_t kStrs = tag("STRS");

struct RoofName {
  RoofShape shape;
  std::string_view name;
};
constexpr std::array<RoofName, 12> kRoofNames = {{{RoofShape::Flat, "flat"},
                                                  {RoofShape::Gabled, "gabled"},
                                                  {RoofShape::Hipped, "hipped"},
                                                  {RoofShape::Pyramidal, "pyramidal"},
                                                  {RoofShape::Skillion, "skillion"},
                                                  {RoofShape::Dome, "dome"},
                                                  {RoofShape::Onion, "onion"},
                                                  {RoofShape::Round, "round"},
                                                  {RoofShape::Gambrel, "gambrel"},
                                                  {RoofShape::Mansard, "mansard"},
                                                  {RoofShape::HalfHipped, "half-hipped"},
                                                  {RoofShape::Saltbox, "saltbox"}}};

std::uint16_t quantize(float v, float extent) {
  const float q = std::round(v / extent * 65535.0f);
  return static_cast<std::uint16_t>(std::clamp(q, 0.0f, 65535.0f));
}

}  // namespace

RoofShape parseRoofShape(std::string_view value) {
  if (value.empty()) return RoofShape::Flat;
  for (const RoofName& r : kRoofNames) {
    if (r.name == value) return r.shape;
  }
  return RoofShape::Other;
}

std::string_view roofShapeName(RoofShape shape) {
  for (const RoofName& r : kRoofNames) {
    if (r.shape == shape) return r.name;
  }
  return "other";
}

std::vector<std::uint8_t> encodeCityTile(const CityTile& tile) {
  const float extent = tile.extent > 0.0f ? tile.extent : 1.0f;
  // Sections first, each into its own writer, then the header and table in front of them.
  ByteWriter bldg, part, ring, vert, tris, strs;
  for (const TileBuilding& b : tile.buildings) {
    const BuildingAttributes& a = b.attributes;
    bldg.u16(b.partCount);
    std::uint16_t flags = 0;
    if (a.heightSource == ValueSource::Tagged) flags |= kFlagHeightTagged;
    if (a.storeysSource == ValueSource::Tagged) flags |= kFlagStoreysTagged;
    bldg.u16(flags);
    bldg.f32(a.heightM);
    bldg.f32(a.minHeightM);
    bldg.u16(a.storeys);
    bldg.i16(a.startYear);
    bldg.u8(static_cast<std::uint8_t>(a.structuralType));
    bldg.u8(static_cast<std::uint8_t>(a.codeEra));
    bldg.u8(static_cast<std::uint8_t>(a.importance));
    bldg.u8(a.importanceReasons);
    bldg.u8(a.lod);
    bldg.u8(0);
    bldg.u16(0);
    bldg.f32(a.footprintAreaM2);
    bldg.f32(static_cast<float>(a.centroidX));
    bldg.f32(static_cast<float>(a.centroidY));
    bldg.u32(0);  // reserved
    for (const std::string* s : {&a.id, &a.name, &a.use, &a.address, &a.material, &a.structure, &a.amenity}) {
      strs.string(*s);
    }
  }
  for (const TilePart& p : tile.parts) {
    part.u16(p.ringCount);
    part.u8(static_cast<std::uint8_t>(p.roofShape));
    part.u8(0);
    part.u32(p.triangleCount);
    part.f32(p.minHeightM);
    part.f32(p.heightM);
    part.f32(p.roofHeightM);
  }
  for (std::uint16_t n : tile.ringVertexCounts) ring.u16(n);
  for (const glm::vec2& v : tile.vertices) {
    vert.u16(quantize(v.x, extent));
    vert.u16(quantize(v.y, extent));
  }
  for (std::uint16_t i : tile.roofTriangles) tris.u16(i);

  struct Section {
    std::uint32_t id;
    const ByteWriter* data;
  };
  const std::array<Section, 6> sections = {
      {{kBldg, &bldg}, {kPart, &part}, {kRing, &ring}, {kVert, &vert}, {kTris, &tris}, {kStrs, &strs}}};

  ByteWriter out;
  out.bytes(kMagic);
  out.u16(kCityTileVersion);
  out.u16(tile.coarse ? kFlagCoarse : 0);
  out.u32(0);  // file size, patched below
  out.u32(0);  // CRC, patched below
  out.u32(static_cast<std::uint32_t>(tile.buildings.size()));
  out.u32(static_cast<std::uint32_t>(tile.parts.size()));
  out.f64(tile.originX);
  out.f64(tile.originY);
  out.f32(extent);
  out.u16(static_cast<std::uint16_t>(sections.size()));
  out.u16(0);
  std::size_t offset = kHeaderSize + sections.size() * kSectionEntrySize;
  for (const Section& s : sections) {
    out.u32(s.id);
    out.u32(static_cast<std::uint32_t>(offset));
    out.u32(static_cast<std::uint32_t>(s.data->size()));
    offset += (s.data->size() + 3) / 4 * 4;
  }
  for (const Section& s : sections) {
    out.bytes(s.data->data());
    out.align(4);
  }
  out.patchU32(8, static_cast<std::uint32_t>(out.size()));
  const auto& bytes = out.data();
  out.patchU32(12, crc32(std::span(bytes).subspan(16)));
  return out.take();
}

Result<CityTile> decodeCityTile(std::span<const std::uint8_t> bytes, std::string_view name,
                                const CityTileLimits& limits) {
  const std::string prefix = std::string(name) + ": ";
  auto error = [&](const std::string& message) { return Error{prefix + message}; };

  if (bytes.size() < kHeaderSize) {
    return error("not a city tile: " + std::to_string(bytes.size()) + " bytes is shorter than the " +
                 std::to_string(kHeaderSize) + "-byte header");
  }
  if (std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
    return error("not a city tile: the file does not start with \"QVCT\"");
  }
  ByteReader header(bytes.subspan(4, kHeaderSize - 4), 4);
  const std::uint16_t version = header.u16("version");
  if (version != kCityTileVersion) {
    return error("unsupported city tile version " + std::to_string(version) + " (this build reads version " +
                 std::to_string(kCityTileVersion) + ")");
  }
  const std::uint16_t flags = header.u16("flags");
  const std::uint32_t fileSize = header.u32("file size");
  const std::uint32_t storedCrc = header.u32("checksum");
  const std::uint32_t buildingCount = header.u32("building count");
  const std::uint32_t partCount = header.u32("part count");
  CityTile tile;
  tile.coarse = (flags & kFlagCoarse) != 0;
  tile.originX = header.f64("origin x");
  tile.originY = header.f64("origin y");
  tile.extent = header.f32("extent");
  const std::uint16_t sectionCount = header.u16("section count");
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
  if (!(std::abs(tile.originX) <= 1e7) || !(std::abs(tile.originY) <= 1e7)) {
    return error("header at byte 24: invalid origin");
  }
  // A micrometre at least: below, extent / 65535 is a denormal float and vertices lose precision.
  if (!(tile.extent >= kMinExtentM && tile.extent <= kMaxExtentM)) {
    return error("header at byte 40: extent " + std::to_string(tile.extent) + " m is outside [1e-6, 1e8] m");
  }
  if (buildingCount > limits.maxBuildings) {
    return error("header at byte 16: " + std::to_string(buildingCount) + " buildings exceeds the limit of " +
                 std::to_string(limits.maxBuildings));
  }
  if (partCount > limits.maxParts) {
    return error("header at byte 20: " + std::to_string(partCount) + " parts exceeds the limit of " +
                 std::to_string(limits.maxParts));
  }

  // Section table.
  struct Found {
    std::span<const std::uint8_t> data;
    std::size_t offset = 0;
    bool present = false;
  };
  Found bldg, part, ring, vert, tris, strs;
  ByteReader table(bytes.subspan(kHeaderSize), kHeaderSize);
  for (std::uint16_t i = 0; i < sectionCount; ++i) {
    const std::uint32_t id = table.u32("section id");
    const std::uint32_t offset = table.u32("section offset");
    const std::uint32_t size = table.u32("section size");
    if (!table.ok()) return error("section table: " + table.error());
    if (offset > bytes.size() || size > bytes.size() - offset || offset < kHeaderSize) {
      return error("section " + tagName(id) + " at byte " + std::to_string(offset) + " with " + std::to_string(size) +
                   " bytes lies outside the file");
    }
    Found f{bytes.subspan(offset, size), offset, true};
    if (id == kBldg)
      bldg = f;
    else if (id == kPart)
      part = f;
    else if (id == kRing)
      ring = f;
    else if (id == kVert)
      vert = f;
    else if (id == kTris)
      tris = f;
    else if (id == kStrs)
      strs = f;
    // Unknown sections are skipped: version 1 readers ignore sections added later.
  }
  for (const auto& [f, n] : {std::pair{&bldg, "BLDG"}, std::pair{&part, "PART"}, std::pair{&ring, "RING"},
                             std::pair{&vert, "VERT"}, std::pair{&tris, "TRIS"}, std::pair{&strs, "STRS"}}) {
    if (!f->present) return error(std::string("required section ") + n + " is missing");
  }
  if (bldg.data.size() != static_cast<std::size_t>(buildingCount) * kBuildingRecordSize) {
    return error("section BLDG at byte " + std::to_string(bldg.offset) + " holds " + std::to_string(bldg.data.size()) +
                 " bytes, expected " + std::to_string(buildingCount) + " records of " +
                 std::to_string(kBuildingRecordSize));
  }
  if (part.data.size() != static_cast<std::size_t>(partCount) * kPartRecordSize) {
    return error("section PART at byte " + std::to_string(part.offset) + " holds " + std::to_string(part.data.size()) +
                 " bytes, expected " + std::to_string(partCount) + " records of " + std::to_string(kPartRecordSize));
  }

  // Parts: ring and triangle counts give every range by prefix sums.
  tile.parts.resize(partCount);
  std::uint64_t ringTotal = 0, triangleTotal = 0;
  {
    ByteReader r(part.data, part.offset);
    for (TilePart& p : tile.parts) {
      p.ringCount = r.u16("part ring count");
      p.roofShape = static_cast<RoofShape>(r.u8("roof shape"));
      r.u8("reserved");
      p.triangleCount = r.u32("part triangle count");
      p.minHeightM = r.f32("part min height");
      p.heightM = r.f32("part height");
      p.roofHeightM = r.f32("roof height");
      p.firstRing = static_cast<std::uint32_t>(ringTotal);
      p.firstTriangle = static_cast<std::uint32_t>(triangleTotal);
      ringTotal += p.ringCount;
      triangleTotal += p.triangleCount;
      // Comparisons are false for NaN: every value is tested with its valid range, not the invalid one.
      if (!std::isfinite(p.minHeightM) || !std::isfinite(p.heightM) || p.heightM < p.minHeightM ||
          p.heightM > 10000.0f || p.minHeightM < -1000.0f || !(p.roofHeightM >= 0.0f && p.roofHeightM <= 10000.0f)) {
        return error("section PART near byte " + std::to_string(r.offset()) + ": invalid part heights");
      }
      if (p.ringCount == 0)
        return error("section PART near byte " + std::to_string(r.offset()) + ": part without rings");
    }
    if (!r.ok()) return error("section PART: " + r.error());
  }
  if (ringTotal > limits.maxRings || ring.data.size() != ringTotal * 2) {
    return error("section RING at byte " + std::to_string(ring.offset) + " holds " + std::to_string(ring.data.size()) +
                 " bytes, the parts declare " + std::to_string(ringTotal) + " rings");
  }
  if (triangleTotal > limits.maxTriangles || tris.data.size() != triangleTotal * 6) {
    return error("section TRIS at byte " + std::to_string(tris.offset) + " holds " + std::to_string(tris.data.size()) +
                 " bytes, the parts declare " + std::to_string(triangleTotal) + " triangles");
  }
  tile.ringVertexCounts.resize(static_cast<std::size_t>(ringTotal));
  std::uint64_t vertexTotal = 0;
  {
    ByteReader r(ring.data, ring.offset);
    for (std::uint16_t& n : tile.ringVertexCounts) {
      n = r.u16("ring vertex count");
      if (n < 3)
        return error("section RING near byte " + std::to_string(r.offset()) + ": a ring has fewer than 3 vertices");
      vertexTotal += n;
    }
  }
  if (vertexTotal > limits.maxVertices || vert.data.size() != vertexTotal * 4) {
    return error("section VERT at byte " + std::to_string(vert.offset) + " holds " + std::to_string(vert.data.size()) +
                 " bytes, the rings declare " + std::to_string(vertexTotal) + " vertices");
  }
  tile.vertices.resize(static_cast<std::size_t>(vertexTotal));
  {
    ByteReader r(vert.data, vert.offset);
    const float scale = tile.extent / 65535.0f;
    for (glm::vec2& v : tile.vertices) {
      const float x = static_cast<float>(r.u16("vertex x")) * scale;
      const float y = static_cast<float>(r.u16("vertex y")) * scale;
      v = {x, y};
    }
  }
  std::uint32_t vertexCursor = 0;
  std::size_t partIndex = 0;
  for (TilePart& p : tile.parts) {
    p.firstVertex = vertexCursor;
    std::uint32_t count = 0;
    for (std::uint32_t k = 0; k < p.ringCount; ++k) count += tile.ringVertexCounts[p.firstRing + k];
    p.vertexCount = count;
    vertexCursor += count;
    if (count > 65535) {
      return error("section PART at byte " + std::to_string(part.offset + partIndex * kPartRecordSize) + ": part " +
                   std::to_string(partIndex) + " has " + std::to_string(count) + " vertices (at most 65535)");
    }
    ++partIndex;
  }
  tile.roofTriangles.resize(static_cast<std::size_t>(triangleTotal) * 3);
  {
    ByteReader r(tris.data, tris.offset);
    for (std::uint16_t& i : tile.roofTriangles) i = r.u16("triangle index");
  }
  for (const TilePart& p : tile.parts) {
    for (std::size_t i = p.firstTriangle * std::size_t{3}; i < (p.firstTriangle + std::size_t{p.triangleCount}) * 3;
         ++i) {
      if (tile.roofTriangles[i] >= p.vertexCount) {
        return error("section TRIS at byte " + std::to_string(tris.offset + i * 2) + ": triangle index " +
                     std::to_string(tile.roofTriangles[i]) + " beyond its part's " + std::to_string(p.vertexCount) +
                     " vertices");
      }
    }
  }

  // Buildings and their strings.
  tile.buildings.resize(buildingCount);
  ByteReader b(bldg.data, bldg.offset);
  ByteReader s(strs.data, strs.offset);
  std::uint64_t partCursor = 0;
  for (TileBuilding& building : tile.buildings) {
    BuildingAttributes& a = building.attributes;
    building.partCount = b.u16("building part count");
    building.firstPart = static_cast<std::uint32_t>(partCursor);
    partCursor += building.partCount;
    const std::uint16_t bflags = b.u16("building flags");
    a.heightSource = (bflags & kFlagHeightTagged) != 0 ? ValueSource::Tagged : ValueSource::Inferred;
    a.storeysSource = (bflags & kFlagStoreysTagged) != 0 ? ValueSource::Tagged : ValueSource::Inferred;
    a.heightM = b.f32("height");
    a.minHeightM = b.f32("min height");
    a.storeys = b.u16("storeys");
    a.startYear = b.i16("start year");
    const std::uint8_t type = b.u8("structural type");
    const std::uint8_t era = b.u8("code era");
    const std::uint8_t importance = b.u8("importance");
    a.importanceReasons = b.u8("importance reasons");
    a.lod = b.u8("lod");
    b.skip(3, "reserved");
    a.footprintAreaM2 = b.f32("footprint area");
    a.centroidX = b.f32("centroid x");
    a.centroidY = b.f32("centroid y");
    b.skip(4, "reserved");
    a.structuralType = type < static_cast<std::uint8_t>(StructuralType::Count) ? static_cast<StructuralType>(type)
                                                                               : StructuralType::Unknown;
    a.codeEra = era < static_cast<std::uint8_t>(CodeEra::Count) ? static_cast<CodeEra>(era) : CodeEra::Unknown;
    a.importance = importance == 1 ? Importance::Critical : Importance::General;
    if (building.partCount == 0 || partCursor > partCount) {
      return error("section BLDG near byte " + std::to_string(b.offset()) + ": building parts exceed the PART section");
    }
    // The same height bounds as the parts; every test is written so that NaN fails it.
    if (!(a.minHeightM >= -1000.0f && a.heightM >= a.minHeightM && a.heightM <= 10000.0f) || a.storeys == 0 ||
        !(std::abs(a.centroidX) <= 1.0e7) || !(std::abs(a.centroidY) <= 1.0e7) || !(a.footprintAreaM2 >= 0.0f) ||
        !std::isfinite(a.footprintAreaM2)) {
      return error("section BLDG near byte " + std::to_string(b.offset()) + ": invalid building values");
    }
    for (std::string* str : {&a.id, &a.name, &a.use, &a.address, &a.material, &a.structure, &a.amenity}) {
      *str = s.string("building string");
    }
    if (!s.ok()) return error("section STRS: " + s.error());
    if (a.id.empty()) return error("section STRS near byte " + std::to_string(s.offset()) + ": a building has no id");
  }
  if (!b.ok()) return error("section BLDG: " + b.error());
  if (partCursor != partCount) {
    return error("section BLDG at byte " + std::to_string(bldg.offset) + ": the buildings use " +
                 std::to_string(partCursor) + " parts, the header declares " + std::to_string(partCount));
  }
  return tile;
}

}  // namespace qv
