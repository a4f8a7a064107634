#include <catch2/catch.hpp>

#include <type_traits>

#include "qv/format/ResponseTile.h"
#include "qv/seismic/Damage.h"

using namespace qv;
using namespace qv::seismic;

TEST_CASE("Hazus drift thresholds per type and era", "[seismic][damage]") {
  // Hazus 5.1 Tables 5-9a (high code) and 5-9d (pre-code).
  CHECK(hazusDriftThresholds(StructuralType::C1L, CodeEra::HighCode) == std::array<double, 4>{.005, .010, .030, .080});
  CHECK(hazusDriftThresholds(StructuralType::W1, CodeEra::HighCode) == std::array<double, 4>{.004, .012, .040, .100});
  CHECK(hazusDriftThresholds(StructuralType::S1H, CodeEra::PreCode) ==
        std::array<double, 4>{.0024, .0038, .0081, .020});
  CHECK(hazusDriftThresholds(StructuralType::C2M, CodeEra::ModerateCode) ==
        std::array<double, 4>{.0027, .0056, .0154, .040});
  // URM is not designed to high code: low-code values apply; unknown era = moderate code.
  CHECK(hazusDriftThresholds(StructuralType::URML, CodeEra::HighCode) ==
        hazusDriftThresholds(StructuralType::URML, CodeEra::LowCode));
  CHECK(hazusDriftThresholds(StructuralType::S2L, CodeEra::Unknown) ==
        hazusDriftThresholds(StructuralType::S2L, CodeEra::ModerateCode));
  // Unknown type: C1 of the height class.
  CHECK(hazusDriftThresholds(StructuralType::Unknown, CodeEra::HighCode, 12) ==
        hazusDriftThresholds(StructuralType::C1H, CodeEra::HighCode));

  // Every table row ascends, and lower code levels are never more tolerant.
  for (int t = 1; t < static_cast<int>(StructuralType::Count); ++t) {
    const auto type = static_cast<StructuralType>(t);
    const auto high = hazusDriftThresholds(type, CodeEra::HighCode);
    const auto pre = hazusDriftThresholds(type, CodeEra::PreCode);
    for (int k = 0; k < 4; ++k) {
      const auto i = static_cast<std::size_t>(k);
      CHECK(pre[i] <= high[i]);
      if (k > 0) CHECK(high[i] > high[i - 1]);
    }
  }
}

TEST_CASE("Damage states from drift are monotonic", "[seismic][damage]") {
  const auto t = hazusDriftThresholds(StructuralType::C1L, CodeEra::HighCode);
  CHECK(classifyDamage(0.0, t) == DamageState::None);
  CHECK(classifyDamage(0.00499, t) == DamageState::None);
  CHECK(classifyDamage(0.005, t) == DamageState::Slight);
  CHECK(classifyDamage(0.02, t) == DamageState::Moderate);
  CHECK(classifyDamage(0.05, t) == DamageState::Extensive);
  CHECK(classifyDamage(0.2, t) == DamageState::Complete);
  CHECK(classifyDamage(0.2, std::array<double, 4>{}) == DamageState::None);
  DamageState previous = DamageState::None;
  for (double drift = 0.0; drift < 0.15; drift += 0.0005) {
    const DamageState s = classifyDamage(drift, t);
    CHECK(static_cast<int>(s) >= static_cast<int>(previous));
    previous = s;
  }
  CHECK(previous == DamageState::Complete);
  CHECK(damageStateName(DamageState::Extensive) == "extensive");
}

TEST_CASE("The damage state from drift is the one response tiles store, with one name each", "[seismic][damage]") {
  // One type: a classification goes into a building's response without a conversion.
  STATIC_REQUIRE(std::is_same_v<qv::seismic::DamageState, qv::DamageState>);
  const auto t = hazusDriftThresholds(StructuralType::C1L, CodeEra::HighCode);
  qv::BuildingResponse response;  // a building of a response tile
  CHECK(response.damage == DamageState::NoResult);
  response.damage = classifyDamage(0.05, t);
  CHECK(response.damage == DamageState::Extensive);
  // The names the tools and the viewer write, from both spellings of the function.
  CHECK(qv::seismic::damageStateName(DamageState::None) == "none");
  CHECK(qv::seismic::damageStateName(DamageState::Slight) == "slight");
  CHECK(qv::seismic::damageStateName(DamageState::Moderate) == "moderate");
  CHECK(qv::damageStateName(DamageState::Extensive) == "extensive");
  CHECK(qv::damageStateName(DamageState::Complete) == "complete");
  CHECK(qv::seismic::damageStateName(DamageState::NoResult) == "no_result");
}
