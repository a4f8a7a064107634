// fuzz_ground_motion's input layout, shared with the regression test that replays saved inputs.
#pragma once

#include <cstdint>

#include "qv/seismic/GroundMotionReader.h"

namespace qv::fuzz {

/// fuzz_ground_motion's first input byte: the caller's options. Bits 0-1 the format (auto, PEER
/// AT2, values, time-acceleration), bits 2-3 the units (none, g, cm/s2, m/s2), bit 4 a step of
/// 0.01 s, bit 5 a step of 0.02 s (wins over bit 4).
inline seismic::GroundMotionReadOptions groundMotionOptions(std::uint8_t choice) {
  seismic::GroundMotionReadOptions options;
  options.format = static_cast<seismic::GroundMotionFormat>(choice & 3u);
  switch ((choice >> 2) & 3u) {
    case 1:
      options.units = seismic::AccelerationUnit::G;
      break;
    case 2:
      options.units = seismic::AccelerationUnit::CentimetresPerSecond2;
      break;
    case 3:
      options.units = seismic::AccelerationUnit::MetresPerSecond2;
      break;
    default:
      break;
  }
  if ((choice & 16u) != 0) options.timeStepS = 0.01;
  if ((choice & 32u) != 0) options.timeStepS = 0.02;
  return options;
}

}  // namespace qv::fuzz
