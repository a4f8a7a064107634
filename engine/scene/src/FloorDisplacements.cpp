#include "qv/scene/FloorDisplacements.h"

#include <array>
#include <utility>

namespace qv {
namespace {

template <int MX, int MY>
void unrolled(const float* shapesX, const float* cx, const float* shapesY, const float* cy, std::size_t floors,
              FloorGpuRecord* rows) {
  for (std::size_t f = 0; f < floors; ++f, shapesX += MX, shapesY += MY) {
    float vx = 0.0f, vy = 0.0f;
    for (int k = 0; k < MX; ++k) vx += shapesX[k] * cx[k];
    for (int k = 0; k < MY; ++k) vy += shapesY[k] * cy[k];
    rows[f].dxMeters = vx;
    rows[f].dyMeters = vy;
  }
}

// Any mode counts (the format allows up to 8).
void anyModes(const float* shapesX, const float* cx, std::size_t mx, const float* shapesY, const float* cy,
              std::size_t my, std::size_t floors, FloorGpuRecord* rows) {
  for (std::size_t f = 0; f < floors; ++f, shapesX += mx, shapesY += my) {
    float vx = 0.0f, vy = 0.0f;
    for (std::size_t k = 0; k < mx; ++k) vx += shapesX[k] * cx[k];
    for (std::size_t k = 0; k < my; ++k) vy += shapesY[k] * cy[k];
    rows[f].dxMeters = vx;
    rows[f].dyMeters = vy;
  }
}

using FloorKernel = void (*)(const float*, const float*, const float*, const float*, std::size_t, FloorGpuRecord*);

template <int MX, int... MY>
constexpr std::array<FloorKernel, sizeof...(MY)> kernelRow(std::integer_sequence<int, MY...>) {
  return {&unrolled<MX, MY>...};
}

template <int... MX>
constexpr std::array<std::array<FloorKernel, 7>, sizeof...(MX)> kernelTable(std::integer_sequence<int, MX...>) {
  return {kernelRow<MX>(std::make_integer_sequence<int, 7>{})...};
}

// kFloorKernels[mx][my] for 0 … 6 modes each (the encoder's default at most 6).
constexpr auto kFloorKernels = kernelTable(std::make_integer_sequence<int, 7>{});

}  // namespace

void floorDisplacements(const float* shapesX, const float* cx, std::size_t mx, const float* shapesY, const float* cy,
                        std::size_t my, std::size_t floors, FloorGpuRecord* rows) {
  if (mx < kFloorKernels.size() && my < kFloorKernels[0].size()) {
    kFloorKernels[mx][my](shapesX, cx, shapesY, cy, floors, rows);
  } else {
    anyModes(shapesX, cx, mx, shapesY, cy, my, floors, rows);
  }
}

}  // namespace qv
