// Re-meshing of LOD2 models for storey-by-storey deformation (what the seed paper did by hand in
// Blender): every triangle is cut at each floor plane so no triangle spans two storeys, then edges
// longer than a target length are split at their midpoints. Vertices stay on the original surface
// (no smoothing), sharp edges and per-triangle semantics are kept, cut points are shared between
// neighbouring triangles (no cracks), so surface area and enclosed volume do not change.
#pragma once

#include <cstdint>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// The floor levels of a building: level k (0 .. storeys) at baseM + k × storeyHeightM metres.
struct FloorLevels {
  double baseM = 0.0;          ///< floor 0 (minHeightM)
  double storeyHeightM = 0.0;  ///< > 0
  std::uint16_t storeys = 1;   ///< >= 1; level `storeys` is the roof

  [[nodiscard]] double levelM(int k) const { return baseM + static_cast<double>(k) * storeyHeightM; }
};

/// Floor levels of a building: base minHeightM, storeys (at least 1), storey height
/// (heightM - minHeightM) / storeys (BuildingAttributes::storeyHeightM in double precision).
/// Precondition: heightM > minHeightM.
FloorLevels floorLevels(const BuildingAttributes& attributes);

/// Heights within this distance of a floor level count as on it (1 µm).
inline constexpr double kFloorToleranceM = 1e-6;

struct RemeshOptions {
  /// Longest edge after re-meshing, metres; 0: half the storey height (at least minAutoEdgeM).
  double maxEdgeM = 0.0;
  double minAutoEdgeM = 0.5;
  /// Also subdivide flat triangles (horizontal, all corners at one height: flat roofs, ground
  /// faces) inside. Off by default: skinning moves such a triangle as a whole, so only its edges
  /// shared with rising triangles are split (to keep the mesh free of cracks).
  bool splitFlatTriangles = false;
  /// Refuse to grow a mesh beyond this many vertices (an error rather than running out of memory).
  std::uint32_t maxVertices = 4'000'000;
};

/// The edge length the re-meshing aims at for these floors and options.
double targetEdgeLengthM(const FloorLevels& floors, const RemeshOptions& options);

/// Merges vertices at bitwise-identical positions (parts of one building imported separately) and
/// drops triangles that then repeat an index. Triangle order and kinds are kept.
Lod2Mesh weldVertices(const Lod2Mesh& mesh);

/// Cuts the mesh at every floor level (0 .. storeys) so that each triangle's z-range lies within one
/// storey band (below the base, between two levels, or above the roof; within kFloorToleranceM),
/// then splits every edge longer than the target length at its midpoint until none is left (at most
/// 64 rounds). Fails when the result would exceed options.maxVertices, naming the limit.
Result<Lod2Mesh> remeshForFloors(const Lod2Mesh& mesh, const FloorLevels& floors, const RemeshOptions& options = {});

}  // namespace qv::prep
