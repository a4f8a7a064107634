// The structural damage state of a building: what the response tiles store per building and what
// the seismic library's classification from drift (qv/seismic/Damage.h) gives. One definition for
// the writer, the reader and the analysis.
#pragma once

#include <cstdint>
#include <string_view>

namespace qv {

/// Stored as a byte: the values are fixed by the summary format (docs/formats.md).
enum class DamageState : std::uint8_t {
  None = 0,
  Slight = 1,
  Moderate = 2,
  Extensive = 3,
  Complete = 4,
  NoResult = 255  ///< the building has no result (see NoResultReason in ResponseTile.h)
};
/// "none", "slight", "moderate", "extensive", "complete"; "no_result" for NoResult and any value
/// outside the enumeration.
std::string_view damageStateName(DamageState state);

}  // namespace qv
