// Ground tiles (.qvg): the map under the city in one cell of the ground pyramid: streets,
// railways, water, parks and open land as flat triangles ready to draw, and the names placed on
// them (streets, water, places). Specification: docs/formats.md ("Ground tile"). One codec serves
// the writer (quakeview-prep) and the reader (the viewer).
//
// The ground pyramid is a complete quadtree of square cells over the city (Tileset::ground):
// level 0 is one cell over everything, each level halves the cell. A cell with nothing in it has
// no file. Leaves hold the full detail; an inner cell holds the larger features of its subtree,
// simplified to its geometric error (REPLACE refinement, like the city tiles).
//
// Coordinates in a decoded tile are metres relative to the cell's corner (originX/Y, metres east
// and north of the tileset origin) in float; on disk they are 16-bit quantized over `extent` metres.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/core/Result.h"

namespace qv {

inline constexpr std::uint16_t kGroundTileVersion = 1;

/// What a ground triangle shows. The numeric order is the drawing order (later classes are drawn
/// over earlier ones) and the order of a tile's runs. Stored as a number: only ever gains values
/// (new ones before Count, renumbering is a new tile version).
enum class GroundClass : std::uint8_t {
  Land = 0,      ///< land where the input has a coastline (the rest of the cell is sea)
  Green = 1,     ///< grass, meadow, recreation ground, cemetery, pitch, golf course
  Forest = 2,    ///< forest, wood, scrub
  Park = 3,      ///< leisure=park, garden, playground, nature reserve
  Water = 4,     ///< lakes, ponds, reservoirs, riverbanks (areas) and rivers, canals, streams (lines)
  Path = 5,      ///< footway, cycleway, path, pedestrian, steps, track
  Rail = 6,      ///< railway=rail, light_rail, tram, narrow_gauge (at grade)
  Street = 7,    ///< residential, service, unclassified, living_street, tertiary
  Major = 8,     ///< secondary, primary, trunk and their links
  Motorway = 9,  ///< motorway and motorway_link
  Count = 10
};
std::string_view groundClassName(GroundClass c);  ///< "land", "green", ..., "motorway"

/// What a label names. Stored as a number: only ever gains values.
enum class GroundLabelKind : std::uint8_t {
  Street = 0,         ///< placed along its street: `angleRad` is the street's direction there
  Water = 1,          ///< a lake's or river's name
  Park = 2,           ///< a park's name
  Neighbourhood = 3,  ///< place=neighbourhood, quarter, suburb, borough
  Settlement = 4,     ///< place=city, town, village, hamlet
  Count = 5
};
std::string_view groundLabelKindName(GroundLabelKind k);  ///< "street", "water", ...

/// A run of triangles of one class: [firstTriangle, firstTriangle + triangleCount).
struct GroundRun {
  GroundClass groundClass = GroundClass::Land;
  std::uint32_t firstTriangle = 0;
  std::uint32_t triangleCount = 0;
};

/// A name to draw on the map.
struct GroundLabel {
  GroundLabelKind kind = GroundLabelKind::Street;
  /// Importance, 0 (most) .. 255 (least): placement takes labels in this order, so a motorway's
  /// or a city's name wins over a footway's or a hamlet's where they would overlap.
  std::uint8_t rank = 128;
  glm::vec2 position{0.0f};  ///< cell-local metres (a street label: the middle of its stretch)
  float angleRad = 0.0f;     ///< text direction, counter-clockwise from east, in (-pi/2, pi/2]
  float lengthM = 0.0f;      ///< a street label: length of the straight stretch it may cover; else 0
  std::string text;          ///< UTF-8, 1 .. 255 bytes, no control characters
};

struct GroundTile {
  double originX = 0.0;             ///< the cell's south-west corner, metres east of the tileset origin
  double originY = 0.0;             ///< ... metres north
  float extent = 1.0f;              ///< the cell's side (quantization extent), metres
  std::vector<glm::vec2> vertices;  ///< cell-local metres, in [0, extent]²
  /// 3 indices per triangle into `vertices`, counter-clockwise from above, grouped by run.
  std::vector<std::uint32_t> triangles;
  /// Runs in increasing class order, each class at most once, covering `triangles` in order.
  std::vector<GroundRun> runs;
  std::vector<GroundLabel> labels;  ///< by rank, most important first
};

/// Largest counts a tile may declare; a decoder refuses more before allocating.
struct GroundTileLimits {
  std::uint32_t maxVertices = 1u << 22;
  std::uint32_t maxTriangles = 1u << 22;
  std::uint32_t maxLabels = 1u << 16;
};

/// Serializes a tile (version kGroundTileVersion). Vertices outside [0, extent] are clamped; the
/// tile must satisfy the contract of GroundTile (indices in range, runs ordered and covering the
/// triangles, label texts 1..255 bytes; a longer text is cut at a UTF-8 character boundary). Indices
/// are written as u16 when there are at most 65535 vertices, else as u32.
std::vector<std::uint8_t> encodeGroundTile(const GroundTile& tile);

/// Parses and validates a tile. `name` (a file name or URL) prefixes every error message, which
/// also names the section and byte offset. Never reads out of bounds, never throws. Refuses
/// unknown classes and label kinds, out-of-range indices, unordered runs, label texts that are
/// empty, longer than 255 bytes, not UTF-8 or hold control characters. Takes the file or its stored
/// form (a Zstandard frame, StoredFile.h). A ground tile has one encoding: anything the encoder
/// would not write (unknown sections or flags, non-zero padding) is refused, so a tile that decodes
/// encodes back to the same bytes.
Result<GroundTile> decodeGroundTile(std::span<const std::uint8_t> bytes, std::string_view name,
                                    const GroundTileLimits& limits = {});

}  // namespace qv
