// The far-view mesh of a LOD2 model: the original mesh simplified by meshoptimizer's
// meshopt_simplify (edge collapses under a quadric error bound), static, without skin.
#pragma once

#include "qv/prep/Lod2Model.h"

namespace qv::prep {

struct FarMeshOptions {
  /// Aim at this fraction of the triangles (the simplifier stops earlier when the error bound is
  /// reached, so simple shapes such as boxes stay as they are).
  double targetTriangleRatio = 0.2;
  /// Largest geometric deviation, as a fraction of the model's size (meshopt_simplifyScale).
  float maxRelativeError = 0.02f;
};

/// The simplified mesh: vertices welded first, unused vertices dropped, kinds taken from the normals
/// (collapses merge faces of different kinds). Returns the welded mesh with its own kinds when
/// nothing can be removed within the bounds.
Lod2Mesh simplifyFarMesh(const Lod2Mesh& mesh, const FarMeshOptions& options = {});

}  // namespace qv::prep
