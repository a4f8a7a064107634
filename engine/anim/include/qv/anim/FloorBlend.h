// Skinning by height: which two floor levels a vertex follows and how much of each, the rule the
// building vertex shader applies (engine/render/src/Shaders.cpp, where `level`, `f0` and `f1` are
// computed) to every vertex of an animated building, LOD1 rings and LOD2 models alike. A C++
// mirror of that GLSL, so the rule is tested natively; the shader and this function must change
// together.
//
// Floor level k of a building sits at baseZ + k × storeyHeight (k = 0 ground … storeys roof). A
// vertex at height z between levels k and k + 1 moves by (1 − w) × displacement(k) + w ×
// displacement(k + 1), w = (z − level k) / storeyHeight: a vertex on a floor follows that floor
// exactly, one midway between two floors follows both by half. Below the ground it follows the
// ground, above the roof the roof. LOD2 tiles therefore store no bone indices or weights: they are
// this function of the vertex's height and the floor levels the shader has (docs/lod2.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace qv {

struct FloorBlend {
  int lower = 0;             ///< floor level at or below the vertex, 0 … storeys
  int upper = 0;             ///< lower + 1, or storeys at and above the roof
  float upperWeight = 0.0f;  ///< share of `upper`'s displacement, [0, 1); `lower` gets the rest
};

/// The blend of a vertex at height `zMeters` (same frame as `baseZMeters`, metres) in a building
/// of `storeys` (≥ 1) storeys of `storeyHeightMeters` (> 0) metres above `baseZMeters`.
inline FloorBlend floorBlendAt(float zMeters, float baseZMeters, float storeyHeightMeters, int storeys) {
  const float level = std::clamp((zMeters - baseZMeters) / storeyHeightMeters, 0.0f, static_cast<float>(storeys));
  FloorBlend b;
  b.lower = std::min(static_cast<int>(std::floor(level)), storeys);
  b.upper = std::min(b.lower + 1, storeys);
  b.upperWeight = level - static_cast<float>(b.lower);
  return b;
}

/// The displacement (one component, metres) of a vertex with blend `b`, given the displacements of
/// the building's floor levels 0 … storeys (`floorDisplacement[k]`).
template <typename Displacements>
float blendedDisplacement(const FloorBlend& b, const Displacements& floorDisplacement) {
  const float lower = floorDisplacement[static_cast<std::size_t>(b.lower)];
  const float upper = floorDisplacement[static_cast<std::size_t>(b.upper)];
  return lower + (upper - lower) * b.upperWeight;  // GLSL mix(lower, upper, w)
}

}  // namespace qv
