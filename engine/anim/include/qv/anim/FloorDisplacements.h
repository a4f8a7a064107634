// Floor displacements of an animated building from its modal coordinates (the hot loop of the
// floor-displacement and skeletal animators): rows[f].dxMeters = shapesX[f] · cx,
// rows[f].dyMeters = shapesY[f] · cy for floors f = 0 … floors − 1, with shapes floor-major (mx
// and my modes per floor; HistoryDirection::shapes) and metres out. `Row` is any struct with
// float members dxMeters and dyMeters (the scene's FloorGpuRecord); nothing else of it is written.
// Both directions in one pass over the rows; for up to 6 modes each (the encoder's default limit)
// the mode counts are compile-time constants, so the dot products unroll (in WebAssembly a loop
// of three to six iterations costs more than its multiplications); up to 8 (the format's limit)
// take a general loop with the same result.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

namespace qv {
namespace floor_detail {

template <typename Row, int MX, int MY>
void unrolled(const float* shapesX, const float* cx, const float* shapesY, const float* cy, std::size_t floors,
              Row* rows) {
  for (std::size_t f = 0; f < floors; ++f, shapesX += MX, shapesY += MY) {
    float vx = 0.0f, vy = 0.0f;
    for (int k = 0; k < MX; ++k) vx += shapesX[k] * cx[k];
    for (int k = 0; k < MY; ++k) vy += shapesY[k] * cy[k];
    rows[f].dxMeters = vx;
    rows[f].dyMeters = vy;
  }
}

// Any mode counts (the format allows up to 8).
template <typename Row>
void anyModes(const float* shapesX, const float* cx, std::size_t mx, const float* shapesY, const float* cy,
              std::size_t my, std::size_t floors, Row* rows) {
  for (std::size_t f = 0; f < floors; ++f, shapesX += mx, shapesY += my) {
    float vx = 0.0f, vy = 0.0f;
    for (std::size_t k = 0; k < mx; ++k) vx += shapesX[k] * cx[k];
    for (std::size_t k = 0; k < my; ++k) vy += shapesY[k] * cy[k];
    rows[f].dxMeters = vx;
    rows[f].dyMeters = vy;
  }
}

template <typename Row>
using FloorKernel = void (*)(const float*, const float*, const float*, const float*, std::size_t, Row*);

template <typename Row, int MX, int... MY>
constexpr std::array<FloorKernel<Row>, sizeof...(MY)> kernelRow(std::integer_sequence<int, MY...>) {
  return {&unrolled<Row, MX, MY>...};
}

template <typename Row, int... MX>
constexpr std::array<std::array<FloorKernel<Row>, 7>, sizeof...(MX)> kernelTable(std::integer_sequence<int, MX...>) {
  return {kernelRow<Row, MX>(std::make_integer_sequence<int, 7>{})...};
}

// kFloorKernels<Row>[mx][my] for 0 … 6 modes each (the encoder's default at most 6).
template <typename Row>
constexpr auto kFloorKernels = kernelTable<Row>(std::make_integer_sequence<int, 7>{});

}  // namespace floor_detail

template <typename Row>
void floorDisplacements(const float* shapesX, const float* cx, std::size_t mx, const float* shapesY, const float* cy,
                        std::size_t my, std::size_t floors, Row* rows) {
  constexpr auto& kernels = floor_detail::kFloorKernels<Row>;
  if (mx < kernels.size() && my < kernels[0].size()) {
    kernels[mx][my](shapesX, cx, shapesY, cy, floors, rows);
  } else {
    floor_detail::anyModes(shapesX, cx, mx, shapesY, cy, my, floors, rows);
  }
}

}  // namespace qv
