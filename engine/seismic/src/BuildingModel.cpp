#include "qv/seismic/BuildingModel.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "Tridiagonal.h"
#include "qv/core/NumberFormat.h"
#include "qv/seismic/Damage.h"

namespace qv::seismic {
namespace {

struct Point {
  double dy, ay, du, au;  // Dy (in), Ay (g), Du (in), Au (g)
};
struct TypeCapacity {
  Point high, moderate, low, pre;  // Hazus 5.1 Tables 5-7a, 5-7b, 5-7c, 5-7d
  double heightFt;                 // typical roof height, Hazus Table 5-1 (3-2 in some editions)
  double alpha2;                   // Hazus Table 5-5 (fraction of height at the pushover displacement)
};

// Code-based capacity curves (yield and ultimate points) of the Hazus Earthquake Model Technical
// Manual. Rows for C3 and URM repeat the low-code curve at the higher levels (not defined there).
// Cross-checks: 2π sqrt(Dy / (Ay g)) gives the Hazus elastic periods (W1 0.35 s, S1L 0.50 s, C1L
// 0.40 s, S1H 2.21 s, ...), and drift threshold × α2 × height gives the Hazus spectral-displacement
// medians of the fragility curves (W1 slight: 0.004 × 0.75 × 168 in = 0.50 in).
constexpr TypeCapacity kCapacity[] = {
    /* Unknown */ {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, 0, 0},
    /* W1   */
    {{0.48, 0.400, 11.51, 1.200},
     {0.36, 0.300, 6.48, 0.900},
     {0.24, 0.200, 4.32, 0.600},
     {0.24, 0.200, 4.32, 0.600},
     14,
     0.75},
    /* W2   */
    {{0.63, 0.400, 12.53, 1.000},
     {0.31, 0.200, 4.70, 0.500},
     {0.16, 0.100, 2.35, 0.250},
     {0.16, 0.100, 2.35, 0.250},
     24,
     0.75},
    /* S1L  */
    {{0.61, 0.250, 14.67, 0.749},
     {0.31, 0.125, 5.50, 0.375},
     {0.15, 0.062, 2.29, 0.187},
     {0.15, 0.062, 2.75, 0.187},
     24,
     0.75},
    /* S1M  */
    {{1.78, 0.156, 28.40, 0.468},
     {0.89, 0.078, 10.65, 0.234},
     {0.44, 0.039, 4.44, 0.117},
     {0.44, 0.039, 5.33, 0.117},
     60,
     0.75},
    /* S1H  */
    {{4.66, 0.098, 55.88, 0.293},
     {2.33, 0.049, 20.96, 0.147},
     {1.16, 0.024, 8.73, 0.073},
     {1.16, 0.024, 10.48, 0.073},
     156,
     0.60},
    /* S2L  */
    {{0.63, 0.400, 10.02, 0.800},
     {0.31, 0.200, 3.76, 0.400},
     {0.16, 0.100, 1.57, 0.200},
     {0.16, 0.100, 1.88, 0.200},
     24,
     0.75},
    /* S2M  */
    {{2.43, 0.333, 25.88, 0.667},
     {1.21, 0.167, 9.70, 0.333},
     {0.61, 0.083, 4.04, 0.167},
     {0.61, 0.083, 4.85, 0.167},
     60,
     0.75},
    /* S2H  */
    {{7.75, 0.254, 61.97, 0.508},
     {3.87, 0.127, 23.24, 0.254},
     {1.94, 0.063, 9.68, 0.127},
     {1.94, 0.063, 11.62, 0.127},
     156,
     0.60},
    /* C1L  */
    {{0.39, 0.250, 9.39, 0.749},
     {0.20, 0.125, 3.52, 0.375},
     {0.10, 0.062, 1.47, 0.187},
     {0.10, 0.062, 1.76, 0.187},
     20,
     0.75},
    /* C1M  */
    {{1.15, 0.208, 18.44, 0.624},
     {0.58, 0.104, 6.91, 0.312},
     {0.29, 0.052, 2.88, 0.156},
     {0.29, 0.052, 3.46, 0.156},
     50,
     0.75},
    /* C1H  */
    {{2.01, 0.098, 24.13, 0.293},
     {1.01, 0.049, 9.05, 0.147},
     {0.50, 0.024, 3.77, 0.073},
     {0.50, 0.024, 4.52, 0.073},
     120,
     0.60},
    /* C2L  */
    {{0.48, 0.400, 9.59, 1.000},
     {0.24, 0.200, 3.60, 0.500},
     {0.12, 0.100, 1.50, 0.250},
     {0.12, 0.100, 1.80, 0.250},
     20,
     0.75},
    /* C2M  */
    {{1.04, 0.333, 13.84, 0.833},
     {0.52, 0.167, 5.19, 0.417},
     {0.26, 0.083, 2.16, 0.208},
     {0.26, 0.083, 2.60, 0.208},
     50,
     0.75},
    /* C2H  */
    {{2.94, 0.254, 29.39, 0.635},
     {1.47, 0.127, 11.02, 0.317},
     {0.74, 0.063, 4.59, 0.159},
     {0.74, 0.063, 5.51, 0.159},
     120,
     0.60},
    /* C3L  */
    {{0.12, 0.100, 1.35, 0.225},
     {0.12, 0.100, 1.35, 0.225},
     {0.12, 0.100, 1.35, 0.225},
     {0.12, 0.100, 1.35, 0.225},
     20,
     0.75},
    /* C3M  */
    {{0.26, 0.083, 1.95, 0.188},
     {0.26, 0.083, 1.95, 0.188},
     {0.26, 0.083, 1.95, 0.188},
     {0.26, 0.083, 1.95, 0.188},
     50,
     0.75},
    /* C3H  */
    {{0.74, 0.063, 4.13, 0.143},
     {0.74, 0.063, 4.13, 0.143},
     {0.74, 0.063, 4.13, 0.143},
     {0.74, 0.063, 4.13, 0.143},
     120,
     0.60},
    /* PC1  */
    {{0.72, 0.600, 11.51, 1.200},
     {0.36, 0.300, 4.32, 0.600},
     {0.18, 0.150, 1.80, 0.300},
     {0.18, 0.150, 2.16, 0.300},
     15,
     0.75},
    /* RM1L */
    {{0.64, 0.533, 10.23, 1.066},
     {0.32, 0.267, 3.84, 0.533},
     {0.16, 0.133, 1.60, 0.267},
     {0.16, 0.133, 1.92, 0.267},
     20,
     0.75},
    /* RM1M */
    {{1.38, 0.444, 14.76, 0.889},
     {0.69, 0.222, 5.54, 0.444},
     {0.35, 0.111, 2.31, 0.222},
     {0.35, 0.111, 2.77, 0.222},
     50,
     0.75},
    /* URML */
    {{0.24, 0.200, 2.40, 0.400},
     {0.24, 0.200, 2.40, 0.400},
     {0.24, 0.200, 2.40, 0.400},
     {0.24, 0.200, 2.40, 0.400},
     15,
     0.75},
    /* URMM */
    {{0.27, 0.111, 1.81, 0.222},
     {0.27, 0.111, 1.81, 0.222},
     {0.27, 0.111, 1.81, 0.222},
     {0.27, 0.111, 1.81, 0.222},
     35,
     0.75},
    /* MH   */
    {{0.18, 0.150, 2.16, 0.300},
     {0.18, 0.150, 2.16, 0.300},
     {0.18, 0.150, 2.16, 0.300},
     {0.18, 0.150, 2.16, 0.300},
     10,
     1.00},
};
static_assert(sizeof kCapacity / sizeof kCapacity[0] == static_cast<std::size_t>(StructuralType::Count));

enum class Family {
  Wood,
  SteelMoment,
  SteelBraced,
  ConcreteMoment,
  ConcreteWall,
  ConcreteInfill,
  Precast,
  Masonry,
  Mobile
};

Family familyOf(StructuralType t) {
  switch (t) {
    case StructuralType::W1:
    case StructuralType::W2:
      return Family::Wood;
    case StructuralType::S1L:
    case StructuralType::S1M:
    case StructuralType::S1H:
      return Family::SteelMoment;
    case StructuralType::S2L:
    case StructuralType::S2M:
    case StructuralType::S2H:
      return Family::SteelBraced;
    case StructuralType::C2L:
    case StructuralType::C2M:
    case StructuralType::C2H:
      return Family::ConcreteWall;
    case StructuralType::C3L:
    case StructuralType::C3M:
    case StructuralType::C3H:
      return Family::ConcreteInfill;
    case StructuralType::PC1:
      return Family::Precast;
    case StructuralType::RM1L:
    case StructuralType::RM1M:
    case StructuralType::URML:
    case StructuralType::URMM:
      return Family::Masonry;
    case StructuralType::MH:
      return Family::Mobile;
    default:
      return Family::ConcreteMoment;  // C1 and (resolved) Unknown
  }
}

}  // namespace

double HazusCapacity::postYieldStiffnessRatio() const {
  const double initial = yieldAccelerationG / yieldDisplacementIn;
  const double post = (ultimateAccelerationG - yieldAccelerationG) / (ultimateDisplacementIn - yieldDisplacementIn);
  return post / initial;
}

StructuralType resolvedStructuralType(StructuralType type, int storeys) {
  const auto index = static_cast<std::size_t>(type);
  if (type != StructuralType::Unknown && index < static_cast<std::size_t>(StructuralType::Count)) return type;
  if (storeys <= 3) return StructuralType::C1L;
  if (storeys <= 7) return StructuralType::C1M;
  return StructuralType::C1H;
}

CodeEra resolvedCodeEra(StructuralType type, CodeEra era) {
  CodeEra e = era;
  if (e != CodeEra::PreCode && e != CodeEra::LowCode && e != CodeEra::ModerateCode && e != CodeEra::HighCode) {
    e = CodeEra::ModerateCode;
  }
  const Family f = familyOf(type);
  const bool lowOnly = f == Family::ConcreteInfill || type == StructuralType::URML || type == StructuralType::URMM;
  if (lowOnly && (e == CodeEra::HighCode || e == CodeEra::ModerateCode)) e = CodeEra::LowCode;
  return e;
}

HazusCapacity hazusCapacity(StructuralType type, CodeEra era, int storeys) {
  const StructuralType t = resolvedStructuralType(type, storeys);
  const TypeCapacity& row = kCapacity[static_cast<std::size_t>(t)];
  Point p = row.moderate;
  switch (resolvedCodeEra(t, era)) {
    case CodeEra::HighCode:
      p = row.high;
      break;
    case CodeEra::LowCode:
      p = row.low;
      break;
    case CodeEra::PreCode:
      p = row.pre;
      break;
    default:
      break;
  }
  return {p.dy, p.ay, p.du, p.au, row.heightFt, row.alpha2};
}

double unitFloorMassKgPerM2(StructuralType type, int storeys) {
  switch (familyOf(resolvedStructuralType(type, storeys))) {
    case Family::Wood:
      return 300.0;
    case Family::SteelMoment:
    case Family::SteelBraced:
      return 700.0;
    case Family::Mobile:
      return 150.0;
    default:
      return 1000.0;  // concrete, precast, masonry
  }
}

double codePeriodS(StructuralType type, double heightM, int storeys) {
  // ASCE 7-16 Table 12.8-2, SI coefficients (US: 0.028 / 0.016 / 0.02 with h in feet).
  switch (familyOf(resolvedStructuralType(type, storeys))) {
    case Family::SteelMoment:
      return 0.0724 * std::pow(heightM, 0.8);
    case Family::ConcreteMoment:
      return 0.0466 * std::pow(heightM, 0.9);
    default:
      return 0.0488 * std::pow(heightM, 0.75);
  }
}

BoucWenStorey hazusBoucWen(StructuralType type, CodeEra era, double storeyHeightM, int storeys) {
  const StructuralType t = resolvedStructuralType(type, storeys);
  const HazusCapacity c = hazusCapacity(t, era, storeys);
  const Family f = familyOf(t);
  BoucWenStorey law;
  law.alpha = c.postYieldStiffnessRatio();
  law.exponent = f == Family::SteelMoment || f == Family::SteelBraced ? 2.0 : 1.0;
  law.gammaShare = 0.5;
  law.yieldDisplacementM = c.yieldDriftRatio() * storeyHeightM;
  return law;
}

Result<ShearBuilding> buildingModelFromAttributes(const BuildingAttributes& a, const BuildingModelOptions& o) {
  auto bad = [&](const std::string& what) { return fail("building " + a.id + ": " + what); };
  if (!(o.dampingRatio >= 0.0 && o.dampingRatio <= 0.5)) return bad("damping ratio out of [0, 0.5]");
  if (!(o.topToBaseStiffnessRatio > 0.0 && o.topToBaseStiffnessRatio <= 1.0))
    return bad("top-to-base stiffness ratio out of (0, 1]");
  if (!(o.periodFactor >= 0.2 && o.periodFactor <= 5.0)) return bad("period factor out of [0.2, 5]");
  if (!(o.defaultStoreyHeightM >= 1.0 && o.defaultStoreyHeightM <= 60.0))
    return bad("default storey height out of [1, 60] m");
  const int n = a.storeys;
  if (n < 1 || n > 200) return bad(std::to_string(n) + " storeys (1 to 200 are modelled)");
  const double area = static_cast<double>(a.footprintAreaM2);
  if (!(std::isfinite(area) && area > 0.0 && area <= 1e6))
    return bad("footprint area " + formatDouble(area) + " m2 (must be in (0, 1e6])");
  const double top = static_cast<double>(a.heightM);
  const double bottom = static_cast<double>(a.minHeightM);
  if (!std::isfinite(top) || !std::isfinite(bottom)) return bad("height is not a finite number");
  const double height = top > bottom && top > 0.0 ? top - bottom : o.defaultStoreyHeightM * n;
  const double storeyHeight = height / n;
  if (!(storeyHeight >= 1.0 && storeyHeight <= 60.0))
    return bad("storey height " + formatDouble(storeyHeight) + " m (" + formatDouble(height) + " m over " +
               std::to_string(n) + " storeys; 1 to 60 m per storey are modelled)");

  const StructuralType type = resolvedStructuralType(a.structuralType, n);
  const CodeEra era = resolvedCodeEra(type, a.codeEra);
  const auto count = static_cast<std::size_t>(n);
  ShearBuilding b;
  b.structuralType = type;
  b.codeEra = era;
  b.floorMassKg.assign(count, area * unitFloorMassKgPerM2(type, n));
  b.storeyHeightM.assign(count, storeyHeight);
  // Stiffness profile, then the scale that gives the code period: ω² scales with the stiffness.
  std::vector<double> profile(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double position = n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
    profile[i] = 1.0 - (1.0 - o.topToBaseStiffnessRatio) * position;
  }
  std::vector<double> diagonal(count);
  std::vector<double> offDiagonal(count, 0.0);
  const double m = b.floorMassKg[0];
  for (std::size_t i = 0; i < count; ++i) {
    const double above = i + 1 < count ? profile[i + 1] : 0.0;
    diagonal[i] = (profile[i] + above) / m;
    if (i + 1 < count) offDiagonal[i] = -above / m;
  }
  if (!detail::symmetricTridiagonalEigen(diagonal, offDiagonal, nullptr) || !(diagonal[0] > 0.0)) {
    return bad("modal analysis of the stiffness profile failed");
  }
  const double period = codePeriodS(type, height, n) * o.periodFactor;
  const double omega1 = 6.283185307179586477 / period;
  const double scale = omega1 * omega1 / diagonal[0];
  b.storeyStiffnessNPerM.resize(count);
  for (std::size_t i = 0; i < count; ++i) b.storeyStiffnessNPerM[i] = scale * profile[i];
  const double omega2 = count > 1 ? std::sqrt(diagonal[1] * scale) : 0.0;
  b.damping = Damping::rayleighFromModes(o.dampingRatio, omega1, omega2);
  if (o.nonlinear) b.hysteresis.assign(count, hazusBoucWen(type, era, storeyHeight, n));
  b.damageDriftThresholds = hazusDriftThresholds(type, era, n);
  return b;
}

std::vector<Result<ShearBuilding>> buildingModelsFromAttributes(std::span<const BuildingAttributes> attributes,
                                                                const BuildingModelOptions& options) {
  std::vector<Result<ShearBuilding>> out;
  out.reserve(attributes.size());
  for (const BuildingAttributes& a : attributes) out.push_back(buildingModelFromAttributes(a, options));
  return out;
}

}  // namespace qv::seismic
