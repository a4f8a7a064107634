// City tiles (.qvt): the buildings of one quadtree node with their footprints, roof
// triangulations and attributes. Specification: docs/formats.md ("City tile"). One codec serves
// the writer (quakeview-prep) and the reader (the viewer).
//
// Coordinates in a decoded tile are metres relative to the tile origin (originX/Y, metres east and
// north of the tileset origin) in float; on disk they are 16-bit quantized over `extent` metres.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"

namespace qv {

inline constexpr std::uint16_t kCityTileVersion = 1;

/// Largest counts a tile may declare; a decoder refuses more before allocating.
struct CityTileLimits {
  std::uint32_t maxBuildings = 1u << 20;
  std::uint32_t maxParts = 1u << 22;
  std::uint32_t maxRings = 1u << 23;
  std::uint32_t maxVertices = 1u << 25;
  std::uint32_t maxTriangles = 1u << 25;
};

enum class RoofShape : std::uint8_t {
  Flat = 0,
  Gabled,
  Hipped,
  Pyramidal,
  Skillion,
  Dome,
  Onion,
  Round,
  Gambrel,
  Mansard,
  HalfHipped,
  Saltbox,
  Other = 255
};
RoofShape parseRoofShape(std::string_view osmValue);  ///< "" and "flat" -> Flat, unknown -> Other
std::string_view roofShapeName(RoofShape shape);

/// One extruded piece: rings (outer first) between two heights, with its roof triangulation.
struct TilePart {
  std::uint32_t firstVertex = 0;  ///< into CityTile::vertices
  std::uint32_t vertexCount = 0;
  std::uint32_t firstRing = 0;  ///< into CityTile::ringVertexCounts
  std::uint16_t ringCount = 0;
  std::uint32_t firstTriangle = 0;  ///< into CityTile::roofTriangles (in triangles)
  std::uint32_t triangleCount = 0;
  float minHeightM = 0.0f;
  float heightM = 0.0f;
  float roofHeightM = 0.0f;
  RoofShape roofShape = RoofShape::Flat;
};

struct TileBuilding {
  BuildingAttributes attributes;  ///< centroidX/Y are tile-local here
  std::uint32_t firstPart = 0;    ///< into CityTile::parts
  std::uint16_t partCount = 0;
};

struct CityTile {
  bool coarse = false;              ///< an inner node's simplified prisms (no floor rings are drawn)
  double originX = 0.0;             ///< metres east of the tileset origin
  double originY = 0.0;             ///< metres north of the tileset origin
  float extent = 1.0f;              ///< quantization extent in metres (vertices lie in [0, extent]²)
  std::vector<glm::vec2> vertices;  ///< tile-local metres
  std::vector<std::uint16_t> ringVertexCounts;
  /// Triangles as index triples local to their part's vertices (counter-clockwise from above).
  std::vector<std::uint16_t> roofTriangles;
  std::vector<TilePart> parts;
  std::vector<TileBuilding> buildings;
};

/// Serializes a tile. Vertices outside [0, extent] are clamped; the caller chooses origin and
/// extent to cover its buildings (quantization step = extent / 65535). The decoder accepts
/// |origin| <= 1e7 m and extent in [1e-6, 1e8] m, part and building heights in [-1000, 10000] m.
std::vector<std::uint8_t> encodeCityTile(const CityTile& tile);

/// Parses and validates a tile. `name` (a file name or URL) prefixes every error message, which
/// also names the section and byte offset. Never reads out of bounds, never throws.
Result<CityTile> decodeCityTile(std::span<const std::uint8_t> bytes, std::string_view name,
                                const CityTileLimits& limits = {});

}  // namespace qv
