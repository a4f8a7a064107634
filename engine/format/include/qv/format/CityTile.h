// City tiles (.qvt): the buildings of one quadtree node with their footprints, roof
// triangulations and attributes. Specification: docs/formats.md ("City tile"). One codec serves
// the writer (quakeview-prep) and the reader (the viewer).
//
// Coordinates in a decoded tile are metres relative to the tile origin (originX/Y, metres east and
// north of the tileset origin) in float; on disk they are 16-bit quantized over `extent` metres.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"

namespace qv {

/// The version encodeCityTile writes. Version 2 dropped the bone and weight of every LOD2 vertex
/// (MESH); decodeCityTile still reads version 1 and ignores them.
inline constexpr std::uint16_t kCityTileVersion = 2;
inline constexpr std::uint16_t kOldestCityTileVersion = 1;

/// Largest counts a tile may declare; a decoder refuses more before allocating.
struct CityTileLimits {
  std::uint32_t maxBuildings = 1u << 20;
  std::uint32_t maxParts = 1u << 22;
  std::uint32_t maxRings = 1u << 23;
  std::uint32_t maxVertices = 1u << 25;
  std::uint32_t maxTriangles = 1u << 25;
  std::uint32_t maxMeshes = 1u << 16;         ///< LOD2 models (MESH section)
  std::uint32_t maxMeshVertices = 1u << 24;   ///< model and far vertices, all models together
  std::uint32_t maxMeshTriangles = 1u << 24;  ///< model and far triangles, all models together
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

/// Where a LOD2 model came from. Stored as a number: only ever gains values.
enum class MeshSource : std::uint8_t { CityJson = 0, Obj = 1, OsmParts = 2, Synthetic = 3, Other = 255 };
/// "cityjson", "obj", "osm-parts", "synthetic" (synth-city's towers), "other"
std::string_view meshSourceName(MeshSource source);

/// Surface kinds of LOD2 triangles, in the order their groups are stored.
enum class MeshSurfaceKind : std::uint8_t { Wall = 0, Roof = 1, Ground = 2, Other = 3 };
inline constexpr std::size_t kMeshSurfaceKinds = 4;

/// At most this many storeys in a LOD2 model (the limit of version 1's one-byte bones, kept).
inline constexpr std::uint16_t kMaxMeshStoreys = 255;

/// A LOD2 building model (MESH section): a mesh re-meshed at the building's floor levels and a
/// simplified static far mesh. Positions are tile-local metres in x and y (like
/// `CityTile::vertices`) and metres above the building's ground in z, in [0, topM]. The viewer
/// animates each vertex by the floors below and above it, weighted by its height
/// (qv/anim/FloorBlend.h): no per-vertex bones or weights are stored. Triangles are
/// counter-clockwise seen from outside. Inner (coarse) tiles carry only far meshes.
struct TileMesh {
  std::uint32_t building = 0;  ///< index into CityTile::buildings; strictly increasing over meshes
  MeshSource source = MeshSource::Other;
  std::uint16_t storeys = 1;         ///< = the building's storeys, ≤ kMaxMeshStoreys
  std::uint32_t verticesBefore = 0;  ///< vertex count as imported, before re-meshing (for `info`)
  float topM = 1.0f;                 ///< z quantization extent: qz × topM / 65535, [0.01, 10000] m
  std::vector<glm::vec3> positions;  ///< the model's vertices
  /// 3 indices per triangle into `positions`, grouped by kind: trianglesPerKind[0] wall
  /// triangles first, then roof, ground, other.
  std::vector<std::uint32_t> triangles;
  std::array<std::uint32_t, kMeshSurfaceKinds> trianglesPerKind{};
  std::vector<glm::vec3> farPositions;      ///< at most 65535
  std::vector<std::uint16_t> farTriangles;  ///< 3 indices per triangle into farPositions
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
  /// LOD2 models of some buildings (optional MESH section; empty: the section is not written).
  std::vector<TileMesh> meshes;
};

/// A building's gross floor area, m²: over its parts, each part's area times the whole storeys
/// (the building's storey height) between its bottom and top, both clipped to the building's
/// structural span [minHeightM, heightM] (so masts, spires and roof structures above it, or parts
/// lower than half a storey, add nothing). 0 when the building has no parts; callers then fall back
/// to footprint x storeys. A setback tower's floor area is its tiers', not its base's times its storeys.
double buildingFloorAreaM2(const CityTile& tile, const TileBuilding& building);

/// Serializes a tile (version kCityTileVersion). Vertices outside [0, extent] are clamped (mesh z outside [0, topM]
/// too); the caller chooses origin and extent to cover its buildings and meshes (quantization step = extent / 65535).
/// Meshes must satisfy the contract of TileMesh (sizes, indices, order). The decoder accepts |origin| <= 1e7 m and
/// extent in [1e-6, 1e8] m, part and building heights in [-1000, 10000] m.
std::vector<std::uint8_t> encodeCityTile(const CityTile& tile);

/// Parses and validates a tile. `name` (a file name or URL) prefixes every error message, which
/// also names the section and byte offset. Never reads out of bounds, never throws.
Result<CityTile> decodeCityTile(std::span<const std::uint8_t> bytes, std::string_view name,
                                const CityTileLimits& limits = {});

}  // namespace qv
