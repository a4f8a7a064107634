// Compact floor-displacement histories for the response history tiles (format in
// qv/format/ResponseTile.h, rationale in docs/formats.md "Response tiles").
//
// Per building and direction, the displacement matrix D (storeys × frames) is projected on its
// leading left singular vectors (the eigenvectors of D Dᵀ, close to the building's mode shapes):
// D ≈ Φ Q. The fewest vectors whose truncation error is small enough are kept; their coordinate
// series Q are resampled at the lowest rate whose linear interpolation stays within the error
// budget (a stiff low-rise building needs a higher rate than a flexible tower), then quantized
// to 8 or 16 bits with a scale per series. The result is checked against the full-rate input,
// and refined (more modes, higher rate, 16 bits) until the largest error at any floor and frame
// is within `toleranceFraction` of the building's peak roof displacement.
#pragma once

#include <cstddef>
#include <span>

#include "qv/format/ResponseTile.h"

namespace qv::prep {

struct HistoryEncodingOptions {
  double toleranceFraction = 0.019;  ///< of the peak roof displacement, at any floor and frame
  double minRateHz = 2.0;            ///< lowest stored sample rate
  int maxModes = 6;                  ///< basis vectors per direction
};

struct EncodedHistory {
  BuildingHistory history;
  double peakRoofM = 0.0;  ///< max over frames of |(x, y)| at the roof
  double maxErrorM = 0.0;  ///< largest reconstruction error, any floor, frame and direction
  int attempts = 0;        ///< encodings tried until the error fitted (1: the first one)
  [[nodiscard]] double relativeError() const { return peakRoofM > 0.0 ? maxErrorM / peakRoofM : 0.0; }
};

/// `x` and `y`: floor displacements in metres, [frame * storeys + i] for floor i + 1 (the ground
/// is not included); `y` may be empty (no Y motion). Frames are dt seconds apart, frame 0 at t = 0.
EncodedHistory encodeHistory(std::span<const float> x, std::span<const float> y, std::size_t storeys,
                             std::size_t frames, double dtSeconds, const HistoryEncodingOptions& options = {});

/// The reconstruction error of `history` against full-rate input, as encodeHistory measures it.
double historyMaxError(const BuildingHistory& history, std::span<const float> x, std::span<const float> y,
                       std::size_t storeys, std::size_t frames, double dtSeconds);

}  // namespace qv::prep
