// LOD2 building models: real shapes for critical and complex buildings, animated per storey by
// skeletal animation (one bone per floor level, chained from the ground up). This header is the
// data contract between prep::lod2 (which imports, re-meshes and skins the models) and the tile
// writer (which stores them); docs/lod2.md describes the whole pipeline.
//
// Frames and units: positions are in the city frame (metres east and north of the city origin,
// double precision) with z in metres above the model's ground (its lowest vertex, see
// docs/lod2.md "Heights"). Triangles are counter-clockwise seen from outside.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "qv/format/BuildingAttributes.h"

namespace qv::prep {

/// Largest model the importers accept: height above its ground, and width or depth (the footprint
/// rule of docs/attributes.md, "too-large"), metres. Larger ones come from broken coordinates or a
/// wrong unit, and would overflow the float attributes and the re-meshing budget.
inline constexpr double kMaxModelHeightM = 10000.0;
inline constexpr double kMaxModelExtentM = 2000.0;

/// What a triangle is part of. Values may be stored: never renumber, only append.
enum class SurfaceKind : std::uint8_t { Wall = 0, Roof = 1, Ground = 2, Other = 3 };

/// "wall", "roof", "ground", "other".
std::string_view surfaceKindName(SurfaceKind kind);

struct Lod2Mesh {
  std::vector<glm::dvec3> positions;     ///< city frame: metres east, north of the city origin; z metres above ground
  std::vector<std::uint32_t> triangles;  ///< counter-clockwise seen from outside, 3 indices each
  std::vector<SurfaceKind> kinds;        ///< one per triangle (CityJSON semantics; OBJ/OSM: by normal)

  [[nodiscard]] std::size_t triangleCount() const { return triangles.size() / 3; }
};

/// The full-detail mesh the viewer skins to the building's floors. Its skin is not stored: the
/// viewer derives each vertex's two floors and weight from its height (qv/anim/FloorBlend.h), so
/// re-meshing at the floor levels is all the skinning preprocessing does.
struct SkinnedMesh {
  Lod2Mesh mesh;          ///< as imported, then after re-meshing
  bool finished = false;  ///< re-meshed at the building's floor levels (finishModel)
};

struct Lod2Model {
  /// The building it replaces (w…/r…/s…/g:…) or a new id cj:<CityJSON id> / obj:<file stem>.
  std::string id;
  bool replacesExisting = false;
  std::string source;  ///< "cityjson:DH_01_subs.city.json", "obj:tower.obj", "osm-parts"
  /// Full attributes, lod = 2. New buildings: from the CityJSON attributes and the geometry.
  /// Replacements: the existing ones, heightM and storeys kept unless the model is taller.
  BuildingAttributes attributes;
  /// Outer ring of the model's ground projection (counter-clockwise, first point not repeated),
  /// for matching and as the LOD1 fallback.
  std::vector<glm::dvec2> footprint;
  /// Full detail. Before finishModel() (Lod2Finish.h) `mesh` holds the model as imported and
  /// `finished` is false.
  SkinnedMesh skinned;
  Lod2Mesh farMesh;                  ///< simplified static mesh for far views (meshoptimizer, no skin)
  std::uint32_t verticesBefore = 0;  ///< vertices as imported (CityJSON: the vertices its faces use)
  std::uint32_t verticesAfter = 0;   ///< vertices of skinned.mesh after re-meshing
};

/// Total area of the triangles, square metres.
double surfaceAreaM2(const Lod2Mesh& mesh);

/// Signed-volume sum (divergence theorem, tetrahedra against the frame's origin), cubic metres.
/// The enclosed volume for a closed, outward-oriented mesh; also exact for a mesh open only in the
/// plane z = 0 (a prism without its ground face), whose missing faces contribute nothing.
double enclosedVolumeM3(const Lod2Mesh& mesh);

/// Area of the horizontal cross-section at height z, square metres: the triangles crossing the
/// plane give oriented segments (solid on the left) whose shoelace sum is the section's area, for
/// closed outward-oriented meshes. Pieces that overlap in space (stacked S3DB parts) count each.
/// z should not coincide with a vertex height (pick a height between floors).
double crossSectionAreaM2(const Lod2Mesh& mesh, double z);

/// Lowest and highest z of the positions (0, 0 for an empty mesh).
struct HeightRange {
  double minZ = 0.0;
  double maxZ = 0.0;
};
HeightRange heightRange(const Lod2Mesh& mesh);

/// The kind of a triangle without semantics, from its (not necessarily unit) normal: facing up by
/// more than 15 degrees from vertical → Roof; facing down likewise → Ground when `atBase` (all of
/// its vertices within 1 cm of the model's lowest point), else Other (soffits, overhangs); the rest
/// (within 15 degrees of vertical, or degenerate) → Wall.
SurfaceKind kindFromNormal(const glm::dvec3& normal, bool atBase);

}  // namespace qv::prep
