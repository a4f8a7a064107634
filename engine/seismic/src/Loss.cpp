#include "qv/seismic/Loss.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <string>
#include <vector>

#include "qv/core/SplitMix64.h"
#include "qv/seismic/BuildingModel.h"
#include "qv/seismic/Damage.h"
#include "qv/seismic/HazusTables.h"
#include "qv/seismic/TypeMixture.h"

namespace qv::seismic {
namespace {

static_assert(hazus::kOccupancies == static_cast<std::size_t>(Occupancy::Count));

constexpr double kFt2ToM2 = 0.09290304;
constexpr double kResidentialM2PerResident = 70.0;  // calibrated, docs/losses.md "Occupants"
constexpr double kOfficeM2PerOccupant = 45.0;       // calibrated, docs/losses.md "Occupants"

struct OccupancyAssumptions {
  double m2PerPerson;          // gross floor area per occupant at the class's usual peak presence (see Loss.h)
  double capacityM2PerPerson;  // gross floor area per occupant at the code's egress load: the most it holds
  double costUsdPerM2;         // replacement cost, USD 2022 per m² of floor area (planning value)
};

// Indexed by Occupancy. Usual densities (first column): docs/losses.md "Occupants" gives each
// source; they are calibrated so that the shared Manhattan extract holds its census residents at
// night and its daytime population by day (tests/ingest/TestOccupants.cpp). Capacities: IBC 2018
// Table 1004.5 occupant load factors (ft² per occupant, converted); RES1-RES3 at the code's
// residential 200 ft² gross.
constexpr OccupancyAssumptions kAssumptions[] = {
    /* RES1  */ {60.0, 200 * kFt2ToM2, 1400},                       // ~150 m² house / 2.5 persons (Census 2020)
    /* RES2  */ {36.0, 200 * kFt2ToM2, 700},                        // ~90 m² mobile home / 2.5 persons
    /* RES3  */ {kResidentialM2PerResident, 200 * kFt2ToM2, 1800},  // see kResidentialM2PerResident
    /* RES4  */ {40.0, 200 * kFt2ToM2, 2200},   // hotel: ~45 m² gross a room, 1.7 guests, 85 % occupied, staff
    /* RES5  */ {20.0, 50 * kFt2ToM2, 2300},    // dormitory: ~20 m² gross a bed
    /* RES6  */ {40.0, 120 * kFt2ToM2, 2400},   // nursing home: residents and staff
    /* COM1  */ {45.0, 60 * kFt2ToM2, 1400},    // retail: staff and customers at the busy hour
    /* COM2  */ {150.0, 300 * kFt2ToM2, 1200},  // warehouse
    /* COM3  */ {40.0, 150 * kFt2ToM2, 1600},   // personal and repair services
    /* COM4  */ {kOfficeM2PerOccupant, 150 * kFt2ToM2, 2400},  // see kOfficeM2PerOccupant
    /* COM5  */ {40.0, 150 * kFt2ToM2, 2800},                  // banks
    /* COM6  */ {40.0, 240 * kFt2ToM2, 4300},                  // hospital: in-patients, staff, visitors
    /* COM7  */ {25.0, 100 * kFt2ToM2, 2800},                  // clinic
    /* COM8  */ {15.0, 30 * kFt2ToM2, 2300},                   // restaurants, entertainment
    /* COM9  */ {6.0, 14 * kFt2ToM2, 2500},                    // theatres: seats mostly filled in the evening
    /* COM10 */ {500.0, 200 * kFt2ToM2, 900},                  // parking garage: attendants and drivers
    /* IND1  */ {80.0, 100 * kFt2ToM2, 1600},                  // industry: ~80 m² a worker
    /* IND2  */ {80.0, 100 * kFt2ToM2, 1300},
    /* IND3  */ {80.0, 100 * kFt2ToM2, 2000},
    /* IND4  */ {80.0, 100 * kFt2ToM2, 2000},
    /* IND5  */ {60.0, 100 * kFt2ToM2, 2600},
    /* IND6  */ {60.0, 100 * kFt2ToM2, 1200},  // construction sites
    /* AGR1  */ {500.0, 300 * kFt2ToM2, 900},
    /* REL1  */ {40.0, 30 * kFt2ToM2, 2300},                   // religious: weekday staff and visitors
    /* GOV1  */ {kOfficeM2PerOccupant, 150 * kFt2ToM2, 2300},  // government offices
    /* GOV2  */ {40.0, 150 * kFt2ToM2, 2800},                  // fire, police: crews
    /* EDU1  */ {10.0, 40 * kFt2ToM2, 2300},                   // schools: ~9 m² gross a pupil (NYC) with staff
    /* EDU2  */ {25.0, 150 * kFt2ToM2, 2800},                  // colleges: students, faculty and staff on campus
};
static_assert(sizeof kAssumptions / sizeof kAssumptions[0] == static_cast<std::size_t>(Occupancy::Count));

struct UseRow {
  std::string_view use;
  Occupancy occupancy;
};

constexpr UseRow kUses[] = {
    {"house", Occupancy::RES1},          {"mobile_home", Occupancy::RES2},
    {"residential", Occupancy::RES3},    {"hotel", Occupancy::RES4},
    {"retail", Occupancy::COM1},         {"warehouse", Occupancy::COM2},
    {"office", Occupancy::COM4},         {"commercial", Occupancy::COM4},
    {"transportation", Occupancy::COM4}, {"hospital", Occupancy::COM6},
    {"clinic", Occupancy::COM7},         {"sports", Occupancy::COM8},
    {"parking", Occupancy::COM10},       {"roof", Occupancy::COM10},
    {"industrial", Occupancy::IND2},     {"service", Occupancy::IND2},
    {"tower", Occupancy::IND2},          {"construction", Occupancy::IND6},
    {"shed", Occupancy::AGR1},           {"religious", Occupancy::REL1},
    {"civic", Occupancy::GOV1},          {"fire_station", Occupancy::GOV2},
    {"police", Occupancy::GOV2},         {"school", Occupancy::EDU1},
    {"university", Occupancy::EDU2},     {"ambulance_station", Occupancy::GOV2},
    {"shelter", Occupancy::RES6},
};

double finiteOrZero(double x) {
  return std::isfinite(x) && x > 0 ? x : 0.0;
}

// Standard normal cumulative distribution.
double phi(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0));
}

std::size_t eraColumn(CodeEra era) {
  if (era == CodeEra::Unknown || era >= CodeEra::Count) return 2;  // moderate code
  return static_cast<std::size_t>(era) - 1;
}

const hazus::StructuralRow& structuralRow(StructuralType type, int storeys) {
  StructuralType t = resolvedStructuralType(type, storeys);
  if (t == StructuralType::Unknown || t >= StructuralType::Count) t = StructuralType::C1L;
  return hazus::kStructural[static_cast<std::size_t>(t) - 1];
}

// P(DS >= k) for k = 1..4.
std::array<double, 4> exceedances(const DamageProbabilities& p) {
  return {p.atLeast(1), p.atLeast(2), p.atLeast(3), p.atLeast(4)};
}

// Number of k in 1..4 with v <= P(DS >= k): the state whose cumulative interval holds v (a draw
// near 0 is the most severe).
int stateAt(const std::array<double, 4>& atLeast, double v) {
  int s = 0;
  for (int k = 0; k < 4; ++k) s += v <= atLeast[static_cast<std::size_t>(k)] ? 1 : 0;
  return s;
}

// The 5th and 95th percentiles of `values` (sorted in place; linear interpolation between order
// statistics, R's type 7), widened to contain `expected`.
// Expected people injured at severity 1..4 per occupant present: the damage states' conditional
// injuries weighted by their probabilities, the complete state split into collapse and not.
std::array<double, 4> expectedInjuriesPerOccupant(const DamageProbabilities& structural,
                                                  const ConditionalConsequences& g) {
  const auto& ps = structural.p;
  const double c = g.collapseGivenComplete;
  std::array<double, 4> out{};
  for (std::size_t s = 0; s < 4; ++s) {
    for (std::size_t k = 1; k <= 3; ++k) out[s] += ps[k] * g.injuriesPerOccupant[k][s];
    out[s] += ps[4] * ((1 - c) * g.injuriesPerOccupant[4][s] + c * g.injuriesPerOccupant[5][s]);
  }
  return out;
}

Estimate interval(std::vector<double>& values, double expected) {
  Estimate e;
  e.expected = expected;
  if (values.empty()) return e;
  std::sort(values.begin(), values.end());
  auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(values.size() - 1);
    const auto i = static_cast<std::size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < values.size() ? values[i] * (1 - f) + values[i + 1] * f : values[i];
  };
  e.low = std::min(quantile(0.05), expected);
  e.high = std::max(quantile(0.95), expected);
  return e;
}

// One structural type of a building's damage: its weight (a mixture's share, or 1), its damage-state
// probabilities at the building's drift, and its Hazus row (collapse share, injury rates).
struct TypePart {
  double weight = 0;
  DamageProbabilities damage;
  const hazus::StructuralRow* row = nullptr;
};
constexpr std::size_t kMaxMixtureTypes = 32;  // the mapping's widest row has 13 types, x 2 design levels

// Fills `parts` for an exposure: the mixture's types (renormalised over the known codes; an empty
// or unusable mixture: the modelled type alone), each at the exposure's era (a type Hazus has only
// up to low code, C3, S5 and URM, at low code above it) or, with the year unknown, split between
// pre-code and low code (kUnknownEraPreCodeShare; W1 at low code). Returns how many parts.
std::size_t typeParts(const Exposure& exposure, int storeys, double drift, double demandBeta,
                      std::array<TypePart, kMaxMixtureTypes>& parts) {
  std::array<TypeShare, kMaxMixtureTypes / 2> types{};
  std::size_t count = 0;
  double total = 0;
  for (const TypeShare& share : exposure.typeMixture) {
    if (hazus::structuralRowByCode(share.code) == nullptr || !(share.share > 0) || count == types.size()) continue;
    types[count++] = share;
    total += share.share;
  }
  if (count == 0) {
    types[count++] = {structuralRow(exposure.type, storeys).code, 1.0};
    total = 1.0;
  }
  std::size_t n = 0;
  auto add = [&](const hazus::StructuralRow* row, double weight, std::size_t column) {
    const std::size_t c = row->inFile[column] ? column : 1;  // 1: low code
    parts[n++] = {weight, fragilityProbabilities(row->driftLimits[c], hazus::kStructuralBeta[c], drift, demandBeta),
                  row};
  };
  for (std::size_t i = 0; i < count; ++i) {
    const hazus::StructuralRow* row = hazus::structuralRowByCode(types[i].code);
    const double w = types[i].share / total;
    if (exposure.eraKnown) {
      add(row, w, eraColumn(exposure.era));
    } else if (row->code == "W1") {
      add(row, w, 1);
    } else {
      add(row, w * kUnknownEraPreCodeShare, 0);
      add(row, w * (1 - kUnknownEraPreCodeShare), 1);
    }
  }
  return n;
}

}  // namespace

std::string_view occupancyCode(Occupancy occupancy) {
  const auto i = static_cast<std::size_t>(occupancy);
  return i < hazus::kOccupancies ? hazus::kOccupancy[i].code : std::string_view("unknown");
}

std::string_view occupancyDescription(Occupancy occupancy) {
  static constexpr std::string_view kDescriptions[] = {"single-family dwelling",
                                                       "mobile home",
                                                       "multi-family dwelling",
                                                       "temporary lodging",
                                                       "institutional dormitory",
                                                       "nursing home",
                                                       "retail trade",
                                                       "wholesale trade",
                                                       "personal and repair services",
                                                       "professional and technical services",
                                                       "banks",
                                                       "hospital",
                                                       "medical office or clinic",
                                                       "entertainment and recreation",
                                                       "theatres",
                                                       "parking",
                                                       "heavy industry",
                                                       "light industry",
                                                       "food, drugs, chemicals",
                                                       "metals and minerals processing",
                                                       "high technology",
                                                       "construction",
                                                       "agriculture",
                                                       "church, membership organisation",
                                                       "general government services",
                                                       "emergency response",
                                                       "grade schools",
                                                       "colleges and universities"};
  static_assert(std::size(kDescriptions) == static_cast<std::size_t>(Occupancy::Count));
  const auto i = static_cast<std::size_t>(occupancy);
  return i < std::size(kDescriptions) ? kDescriptions[i] : std::string_view("unknown");
}

Occupancy occupancyFromUse(std::string_view use, int storeys) {
  for (const UseRow& row : kUses) {
    if (row.use == use) return row.occupancy;
  }
  return storeys <= 2 ? Occupancy::RES1 : Occupancy::RES3;
}

Result<TimeOfDay> parseTimeOfDay(std::string_view name) {
  if (name == "night") return TimeOfDay::Night;
  if (name == "day") return TimeOfDay::Day;
  if (name == "commute") return TimeOfDay::Commute;
  return Error{"time of day '" + std::string(name) + "': expected night, day or commute"};
}

std::string_view timeOfDayName(TimeOfDay time) {
  switch (time) {
    case TimeOfDay::Night:
      return "night";
    case TimeOfDay::Day:
      return "day";
    case TimeOfDay::Commute:
      return "commute";
  }
  return "night";
}

TimeOfDay timeOfDayAtHour(int hour) {
  const int h = ((hour % 24) + 24) % 24;
  return static_cast<TimeOfDay>(hazus::kPartOfDayByHour[static_cast<std::size_t>(h)]);
}

double DamageProbabilities::atLeast(int k) const {
  if (k <= 0) return 1.0;
  if (k > 4) return 0.0;
  double sum = 0;
  for (std::size_t j = static_cast<std::size_t>(k); j < 5; ++j) sum += p[j];
  return std::min(sum, 1.0);
}

double DamageProbabilities::expectedState() const {
  double sum = 0;
  for (std::size_t k = 1; k < 5; ++k) sum += static_cast<double>(k) * p[k];
  return sum;
}

int DamageProbabilities::mostLikely() const {
  std::size_t best = 0;
  for (std::size_t k = 1; k < 5; ++k) {
    if (p[k] > p[best]) best = k;
  }
  return static_cast<int>(best);
}

DamageProbabilities fragilityProbabilities(const std::array<double, 4>& medians, double betaFragility, double demand,
                                           double demandBeta) {
  DamageProbabilities out;
  if (!std::isfinite(demand) || demand <= 0) return out;
  const double bd = finiteOrZero(demandBeta);
  const double beta = std::sqrt(betaFragility * betaFragility + bd * bd);
  std::array<double, 6> atLeast{1, 0, 0, 0, 0, 0};  // P(DS >= k), k = 0..4, and 0 beyond
  for (std::size_t k = 0; k < 4; ++k) {
    const double m = medians[k];
    double p = 0;
    if (m > 0) p = beta > 0 ? phi(std::log(demand / m) / beta) : (demand >= m ? 1.0 : 0.0);
    // Medians ascend and the beta is shared, so this only guards rounding.
    atLeast[k + 1] = std::min(p, atLeast[k]);
  }
  for (std::size_t k = 0; k < 5; ++k) out.p[k] = atLeast[k] - atLeast[k + 1];
  return out;
}

DamageProbabilities structuralDamage(StructuralType type, CodeEra era, double medianPeakDriftRatio, double demandBeta,
                                     int storeys) {
  const StructuralType t = resolvedStructuralType(type, storeys);
  const std::size_t column = eraColumn(resolvedCodeEra(t, era));
  return fragilityProbabilities(hazusDriftThresholds(type, era, storeys), hazus::kStructuralBeta[column],
                                medianPeakDriftRatio, demandBeta);
}

double collapseProbability(StructuralType type, const DamageProbabilities& structural, int storeys) {
  return structural.p[4] * structuralRow(type, storeys).collapseProbability;
}

DamageProbabilities nonStructuralDriftDamage(double medianPeakDriftRatio, double demandBeta) {
  return fragilityProbabilities(hazus::kNsDriftLimits, hazus::kNsDriftBeta, medianPeakDriftRatio, demandBeta);
}

DamageProbabilities nonStructuralAccelerationDamage(CodeEra era, double medianPeakFloorAccelerationG,
                                                    double demandBeta) {
  return fragilityProbabilities(hazus::kNsAccelerationLimitsG[eraColumn(era)], hazus::kNsAccelerationBeta,
                                medianPeakFloorAccelerationG, demandBeta);
}

double occupantDensityM2PerPerson(Occupancy occupancy) {
  const auto i = static_cast<std::size_t>(occupancy);
  return i < std::size(kAssumptions) ? kAssumptions[i].m2PerPerson : kAssumptions[2].m2PerPerson;
}

double occupantCapacityM2PerPerson(Occupancy occupancy) {
  const auto i = static_cast<std::size_t>(occupancy);
  return i < std::size(kAssumptions) ? kAssumptions[i].capacityM2PerPerson : kAssumptions[2].capacityM2PerPerson;
}

BuildingOccupants buildingOccupants(const Exposure& exposure) {
  BuildingOccupants out;
  const double floorArea = finiteOrZero(exposure.floorAreaM2);
  const auto occ =
      static_cast<Occupancy>(std::min(static_cast<std::size_t>(exposure.occupancy), hazus::kOccupancies - 1));
  out.capacity = floorArea / occupantCapacityM2PerPerson(occ);
  // People per m² present at each time: the class's usual peak density times HAZUS's share present.
  std::array<double, 3> perM2{};
  for (std::size_t t = 0; t < 3; ++t) {
    const auto time = static_cast<TimeOfDay>(t);
    if (exposure.occupants) {
      perM2[t] = 0;
    } else if (exposure.useKnown) {
      perM2[t] = occupantsPresentShare(occ, time) / occupantDensityM2PerPerson(occ);
    } else {  // no use in the data: the mixed-use profile
      perM2[t] = kUnknownUseResidentialShare * occupantsPresentShare(Occupancy::RES3, time) /
                     occupantDensityM2PerPerson(Occupancy::RES3) +
                 (1 - kUnknownUseResidentialShare) * occupantsPresentShare(Occupancy::COM4, time) /
                     occupantDensityM2PerPerson(Occupancy::COM4);
    }
  }
  for (std::size_t t = 0; t < 3; ++t) {
    const double wanted =
        exposure.occupants ? finiteOrZero(*exposure.occupants) * occupantsPresentShare(occ, static_cast<TimeOfDay>(t))
                           : floorArea * perM2[t];
    out.at[t] = wanted;
    if (wanted > out.capacity) {
      out.at[t] = out.capacity;
      out.capped = true;
    }
  }
  out.inferred = !exposure.occupants.has_value();
  return out;
}

double replacementCostUsdPerM2(Occupancy occupancy) {
  const auto i = static_cast<std::size_t>(occupancy);
  return i < std::size(kAssumptions) ? kAssumptions[i].costUsdPerM2 : kAssumptions[2].costUsdPerM2;
}

std::size_t populationClass(Occupancy occupancy) {
  constexpr std::size_t kResidential = 0, kCommercial = 1, kEducational = 2, kIndustrial = 3, kHotels = 4;
  switch (occupancy) {
    case Occupancy::RES4:
      return kHotels;
    case Occupancy::RES1:
    case Occupancy::RES2:
    case Occupancy::RES3:
    case Occupancy::RES5:
    case Occupancy::RES6:
    case Occupancy::COM6:
      return kResidential;
    case Occupancy::EDU1:
    case Occupancy::EDU2:
      return kEducational;
    case Occupancy::IND1:
    case Occupancy::IND2:
    case Occupancy::IND3:
    case Occupancy::IND4:
    case Occupancy::IND5:
    case Occupancy::IND6:
      return kIndustrial;
    default:
      return kCommercial;
  }
}

double occupantsPresentShare(Occupancy occupancy, TimeOfDay time) {
  const auto t = static_cast<std::size_t>(time);
  return hazus::kPopulationDistribution[populationClass(occupancy)].share[t < 3 ? t : 0];
}

BuildingLoss assessLoss(const Exposure& exposure, double medianPeakDriftRatio, double medianPeakFloorAccelerationG,
                        double demandBetaDrift, double demandBetaAcceleration, TimeOfDay time) {
  BuildingLoss out;
  const int storeys = std::max(exposure.storeys, 1);
  // The structural types judged: the mixture's where the type is not stated, else the modelled one.
  std::array<TypePart, kMaxMixtureTypes> parts{};
  const std::size_t n = typeParts(exposure, storeys, medianPeakDriftRatio, demandBetaDrift, parts);
  out.structural.p = {0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < 5; ++k) out.structural.p[k] += parts[i].weight * parts[i].damage.p[k];
  }
  out.nonStructuralDrift = nonStructuralDriftDamage(medianPeakDriftRatio, demandBetaDrift);
  out.nonStructuralAcceleration =
      nonStructuralAccelerationDamage(exposure.era, medianPeakFloorAccelerationG, demandBetaAcceleration);
  const auto occupancyIndex = std::min(static_cast<std::size_t>(exposure.occupancy), hazus::kOccupancies - 1);
  const hazus::OccupancyRow& occupancy = hazus::kOccupancy[occupancyIndex];
  const Occupancy occ = static_cast<Occupancy>(occupancyIndex);
  const double floorArea = finiteOrZero(exposure.floorAreaM2);

  // P(collapse) and P(collapse | complete) over the types: sum w P4 Pc, and that over sum w P4.
  double complete = 0, collapse = 0, meanCollapseShare = 0;
  for (std::size_t i = 0; i < n; ++i) {
    complete += parts[i].weight * parts[i].damage.p[4];
    collapse += parts[i].weight * parts[i].damage.p[4] * parts[i].row->collapseProbability;
    meanCollapseShare += parts[i].weight * parts[i].row->collapseProbability;
  }
  out.collapse = collapse;
  const double collapseGivenComplete = complete > 0 ? collapse / complete : meanCollapseShare;

  // Occupants present at the time of day (buildingOccupants: usual densities, capped by the floor area).
  const BuildingOccupants occupants = buildingOccupants(exposure);
  out.occupantsAt = occupants.at;
  out.occupantsPresent = occupants.at[std::min(static_cast<std::size_t>(time), std::size_t{2})];
  out.occupantsInferred = occupants.inferred;

  if (exposure.replacementValueUsd) {
    out.replacementValueUsd = finiteOrZero(*exposure.replacementValueUsd);
  } else {
    out.replacementValueUsd = floorArea * replacementCostUsdPerM2(occ);
    out.valueInferred = true;
  }

  // Consequences given each outcome (index 0 none .. 4 complete; injuries 4 complete without
  // collapse, 5 collapse). Rates and ratios are in percent.
  ConditionalConsequences& g = out.given;
  g.collapseGivenComplete = collapseGivenComplete;
  for (std::size_t k = 1; k <= 5; ++k) {
    // The injury rates given outcome k: the types' rates weighted by how likely each type is to be
    // in that outcome (w P_k; complete split into w P4 (1 - Pc) and w P4 Pc), so that the expected
    // injuries below are exactly the mixture of the types' expected injuries.
    std::array<double, 4> rate{};
    double weight = 0;
    for (int pass = 0; pass < 2 && weight <= 0; ++pass) {
      rate = {};
      for (std::size_t i = 0; i < n; ++i) {
        const double pc = parts[i].row->collapseProbability;
        const double inOutcome = k <= 3   ? parts[i].damage.p[k]
                                 : k == 4 ? parts[i].damage.p[4] * (1 - pc)
                                          : parts[i].damage.p[4] * pc;
        // Second pass, the outcome impossible for every type: the types' shares alone.
        const double wi = parts[i].weight * (pass == 0 ? inOutcome : 1.0);
        weight += wi;
        for (std::size_t s = 0; s < 4; ++s) rate[s] += wi * parts[i].row->injuryRatesPercent[k - 1][s];
      }
    }
    for (std::size_t s = 0; s < 4; ++s) {
      g.injuriesPerOccupant[k][s] = weight > 0 ? rate[s] / weight / 100 : 0.0;
    }
  }
  for (std::size_t k = 1; k <= 4; ++k) {
    g.structuralCostUsd[k] = out.replacementValueUsd * occupancy.structuralRepairCostPercent[k - 1] / 100;
    g.nsDriftCostUsd[k] = out.replacementValueUsd * occupancy.nsDriftRepairCostPercent[k - 1] / 100;
    g.nsAccelerationCostUsd[k] = out.replacementValueUsd * occupancy.nsAccelerationRepairCostPercent[k - 1] / 100;
  }

  // Expected values: sums over states of P(state) x consequence(state).
  const auto& ps = out.structural.p;
  const std::array<double, 4> perOccupant = expectedInjuriesPerOccupant(out.structural, g);
  for (std::size_t s = 0; s < 4; ++s) out.injuries[s] = out.occupantsPresent * perOccupant[s];
  for (std::size_t k = 1; k <= 4; ++k) {
    out.repairCostUsd += ps[k] * g.structuralCostUsd[k] + out.nonStructuralDrift.p[k] * g.nsDriftCostUsd[k] +
                         out.nonStructuralAcceleration.p[k] * g.nsAccelerationCostUsd[k];
    out.repairTimeDays += ps[k] * occupancy.structuralRepairTimeDays[k - 1];
  }
  out.tag = {ps[0] + ps[1], ps[2], ps[3] + ps[4]};
  return out;
}

LossTotals totalLosses(std::span<const BuildingLoss> buildings, std::uint64_t seed) {
  LossTotals totals;
  totals.buildings = buildings.size();

  // Exact expected values.
  double occupants = 0;
  for (const BuildingLoss& b : buildings) {
    for (std::size_t k = 0; k < 5; ++k) totals.damageStates[k].expected += b.structural.p[k];
    totals.damaged.expected += b.structural.p[2] + b.structural.p[3] + b.structural.p[4];
    totals.collapsed.expected += b.collapse;
    occupants += b.occupantsPresent;
    for (std::size_t t = 0; t < 3; ++t) totals.occupantsAt[t] += b.occupantsAt[t];
    totals.repairCostUsd.expected += b.repairCostUsd;
    for (std::size_t s = 0; s < 4; ++s) totals.injuries[s].expected += b.injuries[s];
    for (std::size_t t = 0; t < 3; ++t) totals.tags[t].expected += b.tag[t];
  }
  totals.occupants = {occupants, occupants, occupants};
  if (buildings.empty()) return totals;

  // Monte Carlo: per realisation the sums of the quantities below. Buildings outer, realisations
  // inner, so each building's numbers stay in cache and the sums (R x 13) fit in L2.
  enum Quantity : std::size_t { kState0 = 0, kCollapsed = 5, kInjury1 = 6, kCost = 10, kCount = 11 };
  constexpr std::size_t R = kLossRealisations;
  std::vector<double> sums(R * kCount, 0.0);
  SplitMix64 rng{seed};  // splitmix64: fast, well mixed, the same draws on every target
  for (const BuildingLoss& b : buildings) {
    const std::array<double, 4> str = exceedances(b.structural);
    const std::array<double, 4> nsd = exceedances(b.nonStructuralDrift);
    const std::array<double, 4> nsa = exceedances(b.nonStructuralAcceleration);
    const double collapse = b.collapse;
    const ConditionalConsequences& g = b.given;
    for (std::size_t r = 0; r < R; ++r) {
      const double v = rng.uniformOpenClosed();
      const int s = stateAt(str, v);
      const bool collapsed = s == 4 && v <= collapse;
      const auto outcome = static_cast<std::size_t>(collapsed ? 5 : s);
      double* row = &sums[r * kCount];
      row[kState0 + static_cast<std::size_t>(s)] += 1;
      row[kCollapsed] += collapsed ? 1 : 0;
      for (std::size_t i = 0; i < 4; ++i) row[kInjury1 + i] += b.occupantsPresent * g.injuriesPerOccupant[outcome][i];
      row[kCost] += g.structuralCostUsd[static_cast<std::size_t>(s)] +
                    g.nsDriftCostUsd[static_cast<std::size_t>(stateAt(nsd, v))] +
                    g.nsAccelerationCostUsd[static_cast<std::size_t>(stateAt(nsa, v))];
    }
  }

  std::vector<double> values(R);
  auto estimateOf = [&](auto&& valueOf, double expected) {
    for (std::size_t r = 0; r < R; ++r) values[r] = valueOf(&sums[r * kCount]);
    return interval(values, expected);
  };
  for (std::size_t k = 0; k < 5; ++k) {
    totals.damageStates[k] =
        estimateOf([k](const double* row) { return row[kState0 + k]; }, totals.damageStates[k].expected);
  }
  totals.damaged = estimateOf([](const double* row) { return row[kState0 + 2] + row[kState0 + 3] + row[kState0 + 4]; },
                              totals.damaged.expected);
  totals.collapsed = estimateOf([](const double* row) { return row[kCollapsed]; }, totals.collapsed.expected);
  totals.repairCostUsd = estimateOf([](const double* row) { return row[kCost]; }, totals.repairCostUsd.expected);
  for (std::size_t s = 0; s < 4; ++s) {
    totals.injuries[s] = estimateOf([s](const double* row) { return row[kInjury1 + s]; }, totals.injuries[s].expected);
  }
  // Tags follow the structural state: green none + slight, yellow moderate, red extensive + complete.
  totals.tags[0] = estimateOf([](const double* row) { return row[0] + row[1]; }, totals.tags[0].expected);
  totals.tags[1] = estimateOf([](const double* row) { return row[2]; }, totals.tags[1].expected);
  totals.tags[2] = estimateOf([](const double* row) { return row[3] + row[4]; }, totals.tags[2].expected);
  return totals;
}

std::array<CasualtiesAtTime, 3> casualtiesByTimeOfDay(std::span<const BuildingLoss> buildings, std::uint64_t seed) {
  std::array<CasualtiesAtTime, 3> out;
  for (const BuildingLoss& b : buildings) {
    // The building's expected injuries at time t: the people present then times its expected
    // injuries per occupant (exact: the conditional injuries are per occupant).
    const std::array<double, 4> perOccupant = expectedInjuriesPerOccupant(b.structural, b.given);
    for (std::size_t t = 0; t < 3; ++t) {
      const double people = b.occupantsAt[t];
      out[t].occupants += people;
      for (std::size_t s = 0; s < 4; ++s) out[t].injuries[s].expected += people * perOccupant[s];
    }
  }
  if (buildings.empty()) return out;
  // The same draws as totalLosses: one uniform per building and realisation, buildings outer.
  constexpr std::size_t R = kLossRealisations;
  constexpr std::size_t kCount = 12;  // 3 times x 4 severities
  std::vector<double> sums(R * kCount, 0.0);
  SplitMix64 rng{seed};
  for (const BuildingLoss& b : buildings) {
    const std::array<double, 4> str = exceedances(b.structural);
    for (std::size_t r = 0; r < R; ++r) {
      const double v = rng.uniformOpenClosed();
      const int s = stateAt(str, v);
      const auto outcome = static_cast<std::size_t>(s == 4 && v <= b.collapse ? 5 : s);
      double* row = &sums[r * kCount];
      for (std::size_t t = 0; t < 3; ++t) {
        for (std::size_t i = 0; i < 4; ++i)
          row[t * 4 + i] += b.occupantsAt[t] * b.given.injuriesPerOccupant[outcome][i];
      }
    }
  }
  std::vector<double> values(R);
  for (std::size_t t = 0; t < 3; ++t) {
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t r = 0; r < R; ++r) values[r] = sums[r * kCount + t * 4 + i];
      out[t].injuries[i] = interval(values, out[t].injuries[i].expected);
    }
  }
  return out;
}

double functionalProbability(const std::array<double, 5>& structural, double days) {
  double p = 0;
  for (std::size_t k = 0; k < 5; ++k) {
    const RestorationCurve& c = kEssentialFacilityRestoration[k];
    const double restored = c.sigmaDays > 0 ? 0.5 * std::erfc(-(days - c.meanDays) / (c.sigmaDays * std::sqrt(2.0)))
                                            : (days >= c.meanDays ? 1.0 : 0.0);
    p += std::clamp(structural[k], 0.0, 1.0) * restored;
  }
  return std::clamp(p, 0.0, 1.0);
}

LossSpread lossSpread(const BuildingLoss& b) {
  const std::array<double, 4> str = exceedances(b.structural);
  const std::array<double, 4> nsd = exceedances(b.nonStructuralDrift);
  const std::array<double, 4> nsa = exceedances(b.nonStructuralAcceleration);
  // Every outcome is constant between consecutive breakpoints of the draw v in (0, 1]; evaluate each
  // piece at its right end (the outcome there holds on the whole piece, as stateAt compares v <= P).
  std::vector<double> cuts = {0.0, 1.0, b.collapse};
  for (const auto* set : {&str, &nsd, &nsa}) cuts.insert(cuts.end(), set->begin(), set->end());
  for (double& c : cuts) c = std::clamp(c, 0.0, 1.0);
  std::sort(cuts.begin(), cuts.end());
  double cost = 0, cost2 = 0;
  std::array<double, 4> injury{}, injury2{};
  for (std::size_t i = 1; i < cuts.size(); ++i) {
    const double width = cuts[i] - cuts[i - 1];
    if (!(width > 0.0)) continue;
    const double v = cuts[i];
    const int s = stateAt(str, v);
    const bool collapsed = s == 4 && v <= b.collapse;
    const auto outcome = static_cast<std::size_t>(collapsed ? 5 : s);
    const double c = b.given.structuralCostUsd[static_cast<std::size_t>(s)] +
                     b.given.nsDriftCostUsd[static_cast<std::size_t>(stateAt(nsd, v))] +
                     b.given.nsAccelerationCostUsd[static_cast<std::size_t>(stateAt(nsa, v))];
    cost += width * c;
    cost2 += width * c * c;
    for (std::size_t k = 0; k < 4; ++k) {
      const double x = b.occupantsPresent * b.given.injuriesPerOccupant[outcome][k];
      injury[k] += width * x;
      injury2[k] += width * x * x;
    }
  }
  LossSpread out;
  out.repairCostUsd = std::sqrt(std::max(0.0, cost2 - cost * cost));
  for (std::size_t k = 0; k < 4; ++k) out.injuries[k] = std::sqrt(std::max(0.0, injury2[k] - injury[k] * injury[k]));
  return out;
}

Exposure exposureFromAttributes(const BuildingAttributes& a, int storeys, double floorAreaM2) {
  Exposure e;
  e.storeys = std::max(storeys, 1);
  e.type = resolvedStructuralType(a.structuralType, e.storeys);
  e.era = resolvedCodeEra(e.type, a.codeEra);
  e.eraKnown = a.codeEra != CodeEra::Unknown && a.codeEra < CodeEra::Count;
  e.occupancy = occupancyFromUse(a.use, e.storeys);
  e.useKnown = !a.use.empty() && a.use != "unknown";
  if (hasTypeMixture(a)) e.typeMixture = hazusTypeMixture(e.occupancy, e.storeys).shares;  // at the run's storeys
  e.floorAreaM2 = floorAreaM2 > 0 && std::isfinite(floorAreaM2)
                      ? floorAreaM2
                      : static_cast<double>(a.footprintAreaM2) * static_cast<double>(e.storeys);
  if (a.occupants > 0) e.occupants = static_cast<double>(a.occupants);
  if (a.replacementValueUsd > 0.0f) e.replacementValueUsd = static_cast<double>(a.replacementValueUsd);
  return e;
}

}  // namespace qv::seismic
