#include "qv/seismic/Damage.h"

#include <cstddef>

#include "qv/seismic/BuildingModel.h"

namespace qv::seismic {
namespace {

using Thresholds = std::array<double, 4>;
struct TypeThresholds {
  Thresholds high, moderate, low, pre;  // Hazus 5.1 Tables 5-9a, 5-9b, 5-9c, 5-9d
};

// Indexed by StructuralType (0 = Unknown, resolved before lookup). Rows for C3 and URM repeat the
// low-code values at the high and moderate levels (Hazus does not define them there).
constexpr TypeThresholds kThresholds[] = {
    /* Unknown */ {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}},
    /* W1   */
    {{.004, .012, .040, .100}, {.004, .0099, .0306, .075}, {.004, .0099, .0306, .075}, {.0032, .0079, .0245, .060}},
    /* W2   */
    {{.004, .012, .040, .100}, {.004, .0099, .0306, .075}, {.004, .0099, .0306, .075}, {.0032, .0079, .0245, .060}},
    /* S1L  */
    {{.006, .012, .030, .080}, {.006, .0104, .0235, .060}, {.006, .0096, .0203, .050}, {.0048, .0076, .0162, .040}},
    /* S1M  */
    {{.004, .008, .020, .0533}, {.004, .0069, .0157, .040}, {.004, .0064, .0135, .0333}, {.0032, .0051, .0108, .0267}},
    /* S1H  */
    {{.003, .006, .015, .040}, {.003, .0052, .0118, .030}, {.003, .0048, .0101, .025}, {.0024, .0038, .0081, .020}},
    /* S2L  */
    {{.005, .010, .030, .080}, {.005, .0087, .0233, .060}, {.005, .008, .020, .050}, {.004, .0064, .016, .040}},
    /* S2M  */
    {{.0033, .0067, .020, .0533},
     {.0033, .0058, .0156, .040},
     {.0033, .0053, .0133, .0333},
     {.0027, .0043, .0107, .0267}},
    /* S2H  */
    {{.0025, .005, .015, .040}, {.0025, .0043, .0117, .030}, {.0025, .004, .010, .025}, {.002, .0032, .008, .020}},
    /* C1L  */
    {{.005, .010, .030, .080}, {.005, .0087, .0233, .060}, {.005, .008, .020, .050}, {.004, .0064, .016, .040}},
    /* C1M  */
    {{.0033, .0067, .020, .0533},
     {.0033, .0058, .0156, .040},
     {.0033, .0053, .0133, .0333},
     {.0027, .0043, .0107, .0267}},
    /* C1H  */
    {{.0025, .005, .015, .040}, {.0025, .0043, .0117, .030}, {.0025, .004, .010, .025}, {.002, .0032, .008, .020}},
    /* C2L  */
    {{.004, .010, .030, .080}, {.004, .0084, .0232, .060}, {.004, .0076, .0197, .050}, {.0032, .0061, .0158, .040}},
    /* C2M  */
    {{.0027, .0067, .020, .0533},
     {.0027, .0056, .0154, .040},
     {.0027, .0051, .0132, .0333},
     {.0021, .0041, .0105, .0267}},
    /* C2H  */
    {{.002, .005, .015, .040}, {.002, .0042, .0116, .030}, {.002, .0038, .0099, .025}, {.0016, .0031, .0079, .020}},
    /* C3L  */
    {{.003, .006, .015, .035}, {.003, .006, .015, .035}, {.003, .006, .015, .035}, {.0024, .0048, .012, .028}},
    /* C3M  */
    {{.002, .004, .010, .0233}, {.002, .004, .010, .0233}, {.002, .004, .010, .0233}, {.0016, .0032, .008, .0187}},
    /* C3H  */
    {{.0015, .003, .0075, .0175}, {.0015, .003, .0075, .0175}, {.0015, .003, .0075, .0175}, {.0012, .0024, .006, .014}},
    /* PC1  */
    {{.004, .008, .024, .070}, {.004, .007, .0187, .0525}, {.004, .0064, .0161, .0438}, {.0032, .0051, .0128, .035}},
    /* RM1L */
    {{.004, .008, .024, .070}, {.004, .0069, .0187, .0525}, {.004, .0064, .0161, .0438}, {.0032, .0051, .0128, .035}},
    /* RM1M */
    {{.0027, .0053, .016, .0467},
     {.0027, .0046, .0125, .035},
     {.0027, .0043, .0107, .0292},
     {.0021, .0034, .0086, .0233}},
    /* URML */
    {{.003, .006, .015, .035}, {.003, .006, .015, .035}, {.003, .006, .015, .035}, {.0024, .0048, .012, .028}},
    /* URMM */
    {{.002, .004, .010, .0233}, {.002, .004, .010, .0233}, {.002, .004, .010, .0233}, {.0016, .0032, .008, .0187}},
    /* MH   */
    {{.004, .008, .024, .070}, {.004, .008, .024, .070}, {.004, .008, .024, .070}, {.0032, .0064, .0192, .056}},
};
static_assert(sizeof kThresholds / sizeof kThresholds[0] == static_cast<std::size_t>(StructuralType::Count));

}  // namespace

std::string_view damageStateName(DamageState state) {
  switch (state) {
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
  }
  return "none";
}

std::array<double, 4> hazusDriftThresholds(StructuralType type, CodeEra era, int storeys) {
  const StructuralType t = resolvedStructuralType(type, storeys);
  const TypeThresholds& row = kThresholds[static_cast<std::size_t>(t)];
  switch (resolvedCodeEra(t, era)) {
    case CodeEra::HighCode:
      return row.high;
    case CodeEra::LowCode:
      return row.low;
    case CodeEra::PreCode:
      return row.pre;
    default:
      return row.moderate;
  }
}

DamageState classifyDamage(double peakDriftRatio, const std::array<double, 4>& thresholds) {
  int state = 0;
  for (int k = 0; k < 4; ++k) {
    const double t = thresholds[static_cast<std::size_t>(k)];
    if (t > 0.0 && peakDriftRatio >= t) state = k + 1;
  }
  return static_cast<DamageState>(state);
}

}  // namespace qv::seismic
