// The GPU tables' layout as GLSL: the constants and row readers the shaders use, generated from
// the C++ definitions (qv/scene/RenderDevice.h, qv/geometry/BuildingMesh.h) so the two cannot
// drift apart. The render layer inserts the block at the `@CONSTANTS@` marker of its shader
// sources when it builds a program, as it inserts the palette at `@PALETTE@`. Pure: no GL.
#pragma once

#include <string>
#include <string_view>

namespace qv {

/// GLSL ES 3.00 declarations, one per line:
/// - `const int kTableWidth` (kGpuTableWidth) and `const int kBuildingTexels`;
/// - the BuildingFlag bits as `const uint kFlagSelected`, `kFlagDimmed`, `kFlagHidden`;
/// - the vertex kinds as `const int kKindMask` (the low bits holding a VertexKind), `kKindWall`,
///   `kKindRoof`, `kKindGround`, `kKindModel`, `kKindFallback` (BuildingVertex::kind, read as
///   an int by the shader);
/// - the ColorMode values as `const int kMode<Name>`;
/// - the damage sentinels and the loss-code packing as floats (`kDamageComplete`,
///   `kDamageNoResult`, `kDamagePending`, `kLossCodeLevels`, `kLossCodeExpectedFactor`,
///   `kLossCodeTagFactor`);
/// - `vec4 texel(sampler2D table, int i)`: texel i of a data texture;
/// - `struct BuildingRow` with BuildingGpuRecord's fields by name and `BuildingRow
///   readBuilding(sampler2D table, int slot)`, and `struct FloorRow` with FloorGpuRecord's fields
///   and `FloorRow readFloor(sampler2D table, int i)`: each field read from the texel and component
///   its offset in the C++ struct gives.
std::string glslConstants();

/// `source` with every `@CONSTANTS@` replaced by glslConstants().
std::string withGlslConstants(std::string_view source);

}  // namespace qv
