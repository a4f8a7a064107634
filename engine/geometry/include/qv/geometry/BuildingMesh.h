// CPU-side building meshes: footprints extruded into walls with one vertex ring per floor level,
// plus a roof from a given triangulation. The vertex layout is what the GPU consumes (the render
// layer uploads these bytes as they are).
//
// Frame: positions are metres relative to a mesh origin chosen by the caller (a tile origin), in
// the city frame (x east, y north, z up). Rings: outer rings counter-clockwise, holes clockwise
// (seen from above), not repeating the first point.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace qv {

/// 20 bytes. `slot` is the building's row in the per-building GPU tables. Walls of storey k are
/// drawn with flat attributes from their bottom-ring vertex (the provoking vertex of both
/// triangles), which lets the shader colour each storey by its own drift.
struct BuildingVertex {
  float x, y, z;
  std::int8_t nx, ny, nz;  ///< unit normal × 127
  std::uint8_t kind;       ///< VertexKind
  std::uint32_t slot;
};
static_assert(sizeof(BuildingVertex) == 20);

enum VertexKind : std::uint8_t { kWall = 0, kRoof = 1, kGround = 2 };
/// Bits OR-ed into BuildingVertex::kind for a LOD2 building's two representations, both in the
/// batch: its model (drawn while LOD2 models are shown) and its LOD1 extrusion (drawn instead when
/// they are not). The low five bits stay the VertexKind. (The shader reads kind as a signed byte.)
inline constexpr std::uint8_t kKindModel = 0x20;
inline constexpr std::uint8_t kKindFallback = 0x40;
inline constexpr std::uint8_t kKindFromNormal = 255;  ///< TriangleMeshInput::kinds: decide by the normal

struct MeshData {
  std::vector<BuildingVertex> vertices;
  std::vector<std::uint32_t> indices;  ///< triangles, counter-clockwise seen from outside
  /// Of the triangles, those of LOD2 models (kKindModel) and of their LOD1 fallbacks
  /// (kKindFallback): only one of the two sets is drawn (FrameUniforms::showModels).
  std::size_t modelTriangles = 0;
  std::size_t fallbackTriangles = 0;

  void clear() {
    vertices.clear();
    indices.clear();
    modelTriangles = fallbackTriangles = 0;
  }
  [[nodiscard]] std::size_t triangleCount() const { return indices.size() / 3; }
  /// The triangles drawn with LOD2 models shown or not.
  [[nodiscard]] std::size_t drawnTriangles(bool showModels) const {
    return triangleCount() - (showModels ? fallbackTriangles : modelTriangles);
  }
};

/// One footprint (polygon with holes) extruded between two heights.
struct ExtrusionInput {
  std::span<const glm::vec2> points;             ///< all rings' points, relative to the mesh origin
  std::span<const std::uint32_t> ringEnds;       ///< ring i is points[ringEnds[i-1] (or 0), ringEnds[i])
  std::span<const std::uint32_t> roofTriangles;  ///< indices into points; empty: no roof
  float baseZ = 0.0f;                            ///< metres
  float topZ = 0.0f;                             ///< metres, > baseZ
  /// Heights strictly between baseZ and topZ where a vertex ring is placed (floor levels),
  /// ascending. Empty: a plain prism (two rings).
  std::span<const float> levels;
  std::uint32_t slot = 0;
};

/// Appends the walls (and roof) of `input` to `mesh`. Degenerate edges (shorter than 1 mm) are
/// skipped. Returns the number of triangles appended.
std::size_t appendExtrusion(MeshData& mesh, const ExtrusionInput& input);

/// A triangle mesh (a LOD2 model) to append with flat shading.
struct TriangleMeshInput {
  std::span<const glm::vec3> positions;      ///< relative to the mesh origin, before `offset`
  std::span<const std::uint32_t> triangles;  ///< 3 indices per triangle, counter-clockwise from outside
  /// VertexKind per triangle, or kKindFromNormal; empty: all from the normal (up: roof, down:
  /// ground, else wall).
  std::span<const std::uint8_t> kinds;
  glm::vec3 offset{0.0f};  ///< added to every position (metres)
  std::uint32_t slot = 0;
};

/// Appends `input` flat-shaded: each triangle gets three vertices of its own with its face normal.
/// Each triangle's lowest vertex is made its last (the provoking vertex, which carries the storey
/// the shader colours it by: re-meshed models have no triangle spanning two storeys, and a vertex
/// on the floor plane above belongs to the next storey). Triangles with an index out of range or
/// no area are skipped. Returns the number of triangles appended.
std::size_t appendTriangleMesh(MeshData& mesh, const TriangleMeshInput& input);

/// A building's floors: levels at groundZ + k·storeyHeightM for k = 1, 2, … below `storeys` (and
/// below 1000, where a corrupt count or height stops).
struct FloorGrid {
  float groundZ = 0.0f;        ///< z of the building's lowest floor (metres)
  float storeyHeightM = 0.0f;  ///< metres; no levels unless > 0.1
  int storeys = 1000;          ///< levels k < storeys
};

/// The floor levels of `floors` strictly between baseZ and topZ, more than `marginM` from both, in
/// ascending order, appended to `out`: the rings a part of a building gets inside it. The one
/// place floor levels are computed (viewer, test scenes).
void floorLevelsBetween(const FloorGrid& floors, float baseZ, float topZ, float marginM, std::vector<float>& out);

/// floorLevelsBetween for a building standing at z = 0 with storeys `storeyHeight` metres tall and
/// any count of them, 1 mm from baseZ and topZ.
void floorLevelsBetween(float baseZ, float topZ, float storeyHeight, std::vector<float>& out);

/// Fan triangulation of a convex ring (indices into that ring starting at `first`). For test
/// scenes and coarse prisms only: real footprints come with a triangulation from preprocess.
void triangulateConvexRing(std::uint32_t first, std::uint32_t count, std::vector<std::uint32_t>& out);

}  // namespace qv
