// Floor displacements of an animated building from its modal coordinates (the hot loop of the
// floor-displacement and skeletal animators): rows[f].dx = shapesX[f] · cx, rows[f].dy =
// shapesY[f] · cy for floors f = 0 … floors − 1, with shapes floor-major (mx and my modes per
// floor; HistoryDirection::shapes) and metres out. Both directions in one pass over the rows; for
// up to 6 modes each (the encoder's default limit) the mode counts are compile-time constants, so
// the dot products unroll (in WebAssembly a loop of three to six iterations costs more than its
// multiplications); up to 8 (the format's limit) take a general loop with the same result.
#pragma once

#include <cstddef>

#include "qv/scene/RenderDevice.h"

namespace qv {

void floorDisplacements(const float* shapesX, const float* cx, std::size_t mx, const float* shapesY, const float* cy,
                        std::size_t my, std::size_t floors, FloorGpuRecord* rows);

}  // namespace qv
