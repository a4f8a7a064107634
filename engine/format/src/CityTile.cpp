#include "qv/format/CityTile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"
#include "qv/format/StoredFile.h"

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
const std::uint32_t kMesh = tag("MESH");

// MESH: a u32 model count, the model records, then each model's data in record order.
constexpr std::size_t kMeshRecordSize = 44;
constexpr std::size_t kMeshVertexSize = 6;          // qx, qy, qz u16
constexpr std::size_t kMeshVertexSizeVersion1 = 8;  // qx, qy, qz u16, bone u8, weight u8 (read and ignored)
constexpr std::size_t kFarVertexSize = 6;           // qx, qy, qz u16
// A centimetre at least: below, top / 65535 nears the denormal floats and heights lose precision.
constexpr float kMinMeshTopM = 0.01f;
constexpr float kMaxMeshTopM = 10000.0f;

std::uint64_t padded4(std::uint64_t n) {
  return (n + 3) / 4 * 4;
}

/// Bytes of one model's vertices in a tile of `version`: version 1 stored a bone and a weight per
/// vertex (8 bytes, no padding needed), version 2 only the position (6 bytes, padded to 4).
std::uint64_t meshVertexBytes(std::uint16_t version, std::uint64_t vertices) {
  return version == 1 ? vertices * kMeshVertexSizeVersion1 : padded4(vertices * kMeshVertexSize);
}

/// Bytes of one model's data after the records; u32 indices when the mesh has more vertices than
/// u16 can index.
std::uint64_t meshDataBytes(std::uint16_t version, std::uint64_t vertices, std::uint64_t triangles,
                            std::uint64_t farVertices, std::uint64_t farTriangles) {
  const std::uint64_t indexSize = vertices > 65535 ? 4 : 2;
  return meshVertexBytes(version, vertices) + padded4(triangles * 3 * indexSize) +
         padded4(farVertices * kFarVertexSize + farTriangles * 3 * 2);
}

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

void encodeMeshes(const CityTile& tile, float extent, ByteWriter& out) {
  out.u32(static_cast<std::uint32_t>(tile.meshes.size()));
  for (const TileMesh& m : tile.meshes) {
    out.u32(m.building);
    out.u8(static_cast<std::uint8_t>(m.source));
    out.u8(0);
    out.u16(m.storeys);
    out.u32(static_cast<std::uint32_t>(m.positions.size()));
    for (std::uint32_t n : m.trianglesPerKind) out.u32(n);
    out.u32(static_cast<std::uint32_t>(m.farPositions.size()));
    out.u32(static_cast<std::uint32_t>(m.farTriangles.size() / 3));
    out.u32(m.verticesBefore);
    out.f32(m.topM);
  }
  for (const TileMesh& m : tile.meshes) {
    const float top = m.topM > 0.0f ? m.topM : 1.0f;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      out.u16(quantize(m.positions[i].x, extent));
      out.u16(quantize(m.positions[i].y, extent));
      out.u16(quantize(m.positions[i].z, top));
    }
    out.align(4);
    const bool wide = m.positions.size() > 65535;
    for (std::uint32_t index : m.triangles) {
      if (wide)
        out.u32(index);
      else
        out.u16(static_cast<std::uint16_t>(index));
    }
    out.align(4);
    for (const glm::vec3& p : m.farPositions) {
      out.u16(quantize(p.x, extent));
      out.u16(quantize(p.y, extent));
      out.u16(quantize(p.z, top));
    }
    for (std::uint16_t index : m.farTriangles) out.u16(index);
    out.align(4);
  }
}

/// Decodes the MESH section into tile.meshes once the buildings are known. Every count is checked
/// against the limits and the bytes left before anything is allocated.
Status decodeMeshes(std::span<const std::uint8_t> data, std::size_t sectionOffset, std::uint16_t version,
                    CityTile& tile, const CityTileLimits& limits) {
  auto error = [&](std::size_t at, const std::string& message) {
    return Error{"section MESH at byte " + std::to_string(at) + ": " + message};
  };
  ByteReader r(data, sectionOffset);
  const std::uint32_t count = r.u32("mesh count");
  if (!r.ok()) return Error{"section MESH: " + r.error()};
  if (count > limits.maxMeshes) {
    return error(sectionOffset,
                 std::to_string(count) + " models exceeds the limit of " + std::to_string(limits.maxMeshes));
  }
  if (std::uint64_t{count} * kMeshRecordSize > r.remaining()) {
    return error(sectionOffset, std::to_string(count) + " models need " +
                                    std::to_string(std::uint64_t{count} * kMeshRecordSize) +
                                    " bytes of records, the section holds " + std::to_string(r.remaining()));
  }
  struct Record {
    std::uint32_t vertices = 0, farVertices = 0, farTriangles = 0;
    std::uint64_t triangles = 0;
    std::size_t offset = 0;
  };
  std::vector<Record> records(count);
  tile.meshes.resize(count);
  std::uint64_t vertexTotal = 0, triangleTotal = 0, dataBytes = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    TileMesh& m = tile.meshes[k];
    Record& rec = records[k];
    rec.offset = r.offset();
    m.building = r.u32("mesh building index");
    const std::uint8_t source = r.u8("mesh source");
    r.u8("reserved");
    m.storeys = r.u16("mesh storeys");
    rec.vertices = r.u32("mesh vertex count");
    for (std::uint32_t& n : m.trianglesPerKind) {
      n = r.u32("mesh triangle count");
      rec.triangles += n;
    }
    rec.farVertices = r.u32("far vertex count");
    rec.farTriangles = r.u32("far triangle count");
    m.verticesBefore = r.u32("vertices before re-meshing");
    m.topM = r.f32("mesh top");
    m.source = source <= static_cast<std::uint8_t>(MeshSource::Synthetic) ? static_cast<MeshSource>(source)
                                                                          : MeshSource::Other;
    if (m.building >= tile.buildings.size()) {
      return error(rec.offset, "model " + std::to_string(k) + " names building " + std::to_string(m.building) + " of " +
                                   std::to_string(tile.buildings.size()));
    }
    if (k > 0 && m.building <= tile.meshes[k - 1].building) {
      return error(rec.offset, "model " + std::to_string(k) + ": building indices are not increasing");
    }
    const std::uint16_t buildingStoreys = tile.buildings[m.building].attributes.storeys;
    if (m.storeys == 0 || m.storeys > kMaxMeshStoreys || m.storeys != buildingStoreys) {
      return error(rec.offset, "model " + std::to_string(k) + " has " + std::to_string(m.storeys) +
                                   " storeys, its building " + std::to_string(buildingStoreys) + " (at most " +
                                   std::to_string(kMaxMeshStoreys) + ")");
    }
    if (!(m.topM >= kMinMeshTopM && m.topM <= kMaxMeshTopM)) {
      return error(rec.offset,
                   "model " + std::to_string(k) + ": top " + std::to_string(m.topM) + " m is outside [0.01, 10000] m");
    }
    if (rec.farVertices > 65535) {
      return error(rec.offset, "model " + std::to_string(k) + ": " + std::to_string(rec.farVertices) +
                                   " far vertices (at most 65535)");
    }
    vertexTotal += std::uint64_t{rec.vertices} + rec.farVertices;
    triangleTotal += rec.triangles + rec.farTriangles;
    if (vertexTotal > limits.maxMeshVertices || triangleTotal > limits.maxMeshTriangles) {
      return error(rec.offset, "the models declare " + std::to_string(vertexTotal) + " vertices and " +
                                   std::to_string(triangleTotal) + " triangles, more than the limits of " +
                                   std::to_string(limits.maxMeshVertices) + " and " +
                                   std::to_string(limits.maxMeshTriangles));
    }
    dataBytes += meshDataBytes(version, rec.vertices, rec.triangles, rec.farVertices, rec.farTriangles);
  }
  if (!r.ok()) return Error{"section MESH: " + r.error()};
  if (dataBytes != r.remaining()) {
    return error(r.offset(), "the models declare " + std::to_string(dataBytes) + " bytes of vertices and triangles, " +
                                 "the section holds " + std::to_string(r.remaining()));
  }

  const float scaleXY = tile.extent / 65535.0f;
  for (std::uint32_t k = 0; k < count; ++k) {
    TileMesh& m = tile.meshes[k];
    const Record& rec = records[k];
    const float scaleZ = m.topM / 65535.0f;
    m.positions.resize(rec.vertices);
    for (std::uint32_t i = 0; i < rec.vertices; ++i) {
      const float x = static_cast<float>(r.u16("vertex x")) * scaleXY;
      const float y = static_cast<float>(r.u16("vertex y")) * scaleXY;
      const float z = static_cast<float>(r.u16("vertex z")) * scaleZ;
      m.positions[i] = {x, y, z};
      // Version 1's bone and weight: a function of the height the viewer recomputes (docs/lod2.md).
      if (version == 1) r.skip(2, "bone and weight");
    }
    const std::uint64_t vertexBytes = std::uint64_t{rec.vertices} * kMeshVertexSize;
    if (version != 1) r.skip(static_cast<std::size_t>(padded4(vertexBytes) - vertexBytes), "padding");
    const bool wide = rec.vertices > 65535;
    m.triangles.resize(static_cast<std::size_t>(rec.triangles) * 3);
    for (std::uint32_t& index : m.triangles) {
      const std::size_t at = r.offset();
      index = wide ? r.u32("triangle index") : r.u16("triangle index");
      if (index >= rec.vertices) {
        return error(at, "model " + std::to_string(k) + ": triangle index " + std::to_string(index) + " beyond its " +
                             std::to_string(rec.vertices) + " vertices");
      }
    }
    const std::uint64_t indexBytes = m.triangles.size() * std::uint64_t{wide ? 4u : 2u};
    r.skip(static_cast<std::size_t>(padded4(indexBytes) - indexBytes), "padding");
    m.farPositions.resize(rec.farVertices);
    for (glm::vec3& p : m.farPositions) {
      const float x = static_cast<float>(r.u16("far vertex x")) * scaleXY;
      const float y = static_cast<float>(r.u16("far vertex y")) * scaleXY;
      const float z = static_cast<float>(r.u16("far vertex z")) * scaleZ;
      p = {x, y, z};
    }
    m.farTriangles.resize(std::size_t{rec.farTriangles} * 3);
    for (std::uint16_t& index : m.farTriangles) {
      const std::size_t at = r.offset();
      index = r.u16("far triangle index");
      if (index >= rec.farVertices) {
        return error(at, "model " + std::to_string(k) + ": far triangle index " + std::to_string(index) +
                             " beyond its " + std::to_string(rec.farVertices) + " far vertices");
      }
    }
    const std::uint64_t farBytes = m.farPositions.size() * std::uint64_t{kFarVertexSize} + m.farTriangles.size() * 2;
    r.skip(static_cast<std::size_t>(padded4(farBytes) - farBytes), "padding");
  }
  if (!r.ok()) return Error{"section MESH: " + r.error()};
  return {};
}

}  // namespace

std::string_view meshSourceName(MeshSource source) {
  switch (source) {
    case MeshSource::CityJson:
      return "cityjson";
    case MeshSource::Obj:
      return "obj";
    case MeshSource::OsmParts:
      return "osm-parts";
    case MeshSource::Synthetic:
      return "synthetic";
    case MeshSource::Other:
      break;
  }
  return "other";
}

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
  bldg.reserve(tile.buildings.size() * 36);
  strs.reserve(tile.buildings.size() * 24);
  part.reserve(tile.parts.size() * 20);
  ring.reserve(tile.ringVertexCounts.size() * 2);
  vert.reserve(tile.vertices.size() * 4);
  tris.reserve(tile.roofTriangles.size() * 2);
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
    bldg.u8(a.notes);
    bldg.u16(a.occupants);  // 0: not given (reserved, so 0, in tiles written before)
    bldg.f32(a.footprintAreaM2);
    bldg.f32(static_cast<float>(a.centroidX));
    bldg.f32(static_cast<float>(a.centroidY));
    bldg.f32(a.replacementValueUsd);  // 0: not given (as above)
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
  ByteWriter mesh;
  if (!tile.meshes.empty()) encodeMeshes(tile, extent, mesh);

  struct Section {
    std::uint32_t id;
    const ByteWriter* data;
  };
  std::vector<Section> sections = {{kBldg, &bldg}, {kPart, &part}, {kRing, &ring},
                                   {kVert, &vert}, {kTris, &tris}, {kStrs, &strs}};
  // Optional: a tile without LOD2 models is byte for byte what readers before MESH wrote.
  if (!tile.meshes.empty()) sections.push_back({kMesh, &mesh});

  ByteWriter out;
  {
    std::size_t total = kHeaderSize + sections.size() * kSectionEntrySize;
    for (const Section& s : sections) total += (s.data->size() + 3) / 4 * 4;
    out.reserve(total);
  }
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

namespace {
Result<CityTile> decodeTileFile(std::span<const std::uint8_t> bytes, std::string_view name,
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
  if (version < kOldestCityTileVersion || version > kCityTileVersion) {
    return error("unsupported city tile version " + std::to_string(version) + " (this build reads versions " +
                 std::to_string(kOldestCityTileVersion) + " to " + std::to_string(kCityTileVersion) + ")");
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
  Found bldg, part, ring, vert, tris, strs, mesh;
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
    else if (id == kMesh)
      mesh = f;
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
    a.notes = b.u8("attribute notes");
    a.occupants = b.u16("occupants");
    a.footprintAreaM2 = b.f32("footprint area");
    a.centroidX = b.f32("centroid x");
    a.centroidY = b.f32("centroid y");
    a.replacementValueUsd = b.f32("replacement value");
    if (!std::isfinite(a.replacementValueUsd) || a.replacementValueUsd < 0.0f) {
      return error("section BLDG near byte " + std::to_string(b.offset()) + ": invalid replacement value");
    }
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
  if (mesh.present) {
    const Status meshes = decodeMeshes(mesh.data, mesh.offset, version, tile, limits);
    if (!meshes.ok()) return error(meshes.error());
  }
  return tile;
}
}  // namespace

Result<CityTile> decodeCityTile(std::span<const std::uint8_t> bytes, std::string_view name,
                                const CityTileLimits& limits) {
  std::vector<std::uint8_t> storage;
  auto file = storedFileBytes(bytes, name, storage);
  if (!file.ok()) return Error{file.error()};
  return decodeTileFile(*file, name, limits);
}

double buildingFloorAreaM2(const CityTile& tile, const TileBuilding& building) {
  const BuildingAttributes& a = building.attributes;
  const double storeyM = a.storeyHeightM();
  if (!(storeyM > 0) || a.storeys == 0) return 0;
  double area = 0;
  for (std::uint32_t p = building.firstPart; p < building.firstPart + building.partCount && p < tile.parts.size();
       ++p) {
    const TilePart& part = tile.parts[p];
    const double bottom = std::max<double>(part.minHeightM, a.minHeightM);
    const double top = std::min<double>(part.heightM, a.heightM);
    const double levels = top > bottom ? std::round((top - bottom) / storeyM) : 0.0;
    if (levels <= 0) continue;
    double partArea = 0;
    std::uint32_t v = part.firstVertex;
    for (std::uint16_t r = 0; r < part.ringCount && part.firstRing + r < tile.ringVertexCounts.size(); ++r) {
      const std::uint32_t n = tile.ringVertexCounts[part.firstRing + r];
      if (v + n > tile.vertices.size()) break;
      double twice = 0;  // shoelace
      for (std::uint32_t i = 0; i < n; ++i) {
        const glm::vec2 p0 = tile.vertices[v + i], p1 = tile.vertices[v + (i + 1) % n];
        twice += static_cast<double>(p0.x) * p1.y - static_cast<double>(p1.x) * p0.y;
      }
      partArea += (r == 0 ? 0.5 : -0.5) * std::abs(twice);  // outer ring first, then holes
      v += n;
    }
    area += std::max(partArea, 0.0) * std::min<double>(levels, a.storeys);
  }
  return area;
}

}  // namespace qv
