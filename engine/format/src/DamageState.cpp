#include "qv/format/DamageState.h"

namespace qv {

std::string_view damageStateName(DamageState s) {
  switch (s) {
    case DamageState::None:
      return "none";
    case DamageState::Slight:
      return "slight";
    case DamageState::Moderate:
      return "moderate";
    case DamageState::Extensive:
      return "extensive";
    case DamageState::Complete:
      return "complete";
    default:
      return "no_result";
  }
}

}  // namespace qv
