// Probabilistic damage and its consequences, after the HAZUS 5.1 earthquake methodology: damage-state
// probabilities from lognormal fragilities on the solver's peak drift and peak floor acceleration,
// then occupants present, injuries, repair cost and time, inspection tags, and city totals with a
// 90 % interval. docs/losses.md explains the method, the sources and the limits.
//
// Sources. Fragility medians and betas, collapse shares, injury rates, repair-cost ratios, repair
// times, the population distribution by time of day: the shipped HAZUS tables (HazusTables.h,
// generated from the SimCenter Damage and Loss Model Library's hazus_data_eq.json, BSD 3-Clause,
// values from the FEMA Hazus 5.1 Earthquake Model Technical Manual, 2022). Occupant densities and
// replacement costs per m² (inferred when the data has none) are this project's documented
// assumptions, cited at occupantDensityM2PerPerson and replacementCostUsdPerM2 below.
//
// Units: drift ratios (dimensionless, m/m), accelerations in g, dispersions (betas) in natural-log
// units, areas in m², money in US dollars (2022 price level for the inferred values), time in days.
// Pure: no I/O, no exceptions, no threads, no allocation except in totalLosses (its samples).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "qv/core/Result.h"
#include "qv/format/BuildingAttributes.h"

namespace qv::seismic {

/// The 28 HAZUS occupancy classes (Hazus 5.1 Technical Manual, Table 3-2), in the order of the
/// shipped tables. RES3 is not split into A-F (the repair-cost and repair-time tables do not).
enum class Occupancy : std::uint8_t {
  RES1,   ///< single-family dwelling
  RES2,   ///< mobile home
  RES3,   ///< multi-family dwelling
  RES4,   ///< temporary lodging (hotels, motels)
  RES5,   ///< institutional dormitory
  RES6,   ///< nursing home
  COM1,   ///< retail trade
  COM2,   ///< wholesale trade (warehouses)
  COM3,   ///< personal and repair services
  COM4,   ///< professional and technical services (offices)
  COM5,   ///< banks
  COM6,   ///< hospital
  COM7,   ///< medical office or clinic
  COM8,   ///< entertainment and recreation
  COM9,   ///< theatres
  COM10,  ///< parking
  IND1,   ///< heavy industry
  IND2,   ///< light industry
  IND3,   ///< food, drugs, chemicals
  IND4,   ///< metals and minerals processing
  IND5,   ///< high technology
  IND6,   ///< construction
  AGR1,   ///< agriculture
  REL1,   ///< church, membership organisation
  GOV1,   ///< general government services
  GOV2,   ///< emergency response (fire, police, emergency operations)
  EDU1,   ///< grade schools
  EDU2,   ///< colleges and universities
  Count
};

/// "RES1" .. "EDU2" ("unknown" out of range).
std::string_view occupancyCode(Occupancy occupancy);
/// What the class is, in the Technical Manual's words ("single-family dwelling", "hospital", ...;
/// "unknown" out of range).
std::string_view occupancyDescription(Occupancy occupancy);

/// The occupancy class of one of our normalised uses (BuildingAttributes::use, as produced by
/// preprocess/ingest/src/Attributes.cpp) and storey count. The table (docs/losses.md repeats it):
///   house RES1; mobile_home RES2; residential RES3; hotel RES4; retail COM1; warehouse COM2;
///   office, commercial, transportation COM4; hospital COM6; sports COM8; parking, roof COM10;
///   industrial, service, tower IND2; construction IND6; shed AGR1; religious REL1; civic GOV1;
///   fire_station, police GOV2; school EDU1; university EDU2;
///   anything else (unknown, other, empty): RES1 up to 2 storeys, RES3 above (most of a city's
///   floor area is residential; Hazus's general building stock is dominated by RES1 and RES3).
Occupancy occupancyFromUse(std::string_view use, int storeys);

/// HAZUS's three parts of the day ("Parts_of_day": night 20:00-05:59, day 09:00-15:59, commute
/// 06:00-08:59 and 16:00-19:59).
enum class TimeOfDay : std::uint8_t { Night, Day, Commute };

/// "night", "day", "commute" (case-sensitive); an error naming the value and the accepted ones.
Result<TimeOfDay> parseTimeOfDay(std::string_view name);
std::string_view timeOfDayName(TimeOfDay time);
/// The part of the day of a local hour 0..23 (HAZUS's Parts_of_day; hours outside wrap modulo 24).
TimeOfDay timeOfDayAtHour(int hour);

/// Probabilities of the five damage states none, slight, moderate, extensive, complete.
struct DamageProbabilities {
  std::array<double, 5> p{1, 0, 0, 0, 0};  ///< P(DS = k); each in [0, 1], summing to 1
  /// P(DS >= k) for k in 0..4 (1 for k <= 0, 0 for k > 4).
  [[nodiscard]] double atLeast(int k) const;
  /// The expected state, sum k * P(DS = k), in 0..4.
  [[nodiscard]] double expectedState() const;
  /// The state of highest probability (the lower state on ties).
  [[nodiscard]] int mostLikely() const;
};

/// Damage-state probabilities from a lognormal fragility: P(DS >= k) = Phi(ln(d / m_k) / beta),
/// with medians m_1..m_4 ascending. `beta` is sqrt(betaFragility^2 + demandBeta^2): Hazus combines
/// independent lognormal variabilities by the square root of the sum of their squares (Technical
/// Manual, chapter 5, damage-state variability). A demand <= 0 or not finite
/// gives certainty of no damage.
DamageProbabilities fragilityProbabilities(const std::array<double, 4>& medians, double betaFragility, double demand,
                                           double demandBeta);

/// Structural damage from the median (over a record suite; the peak for one record) of the peak
/// inter-storey drift ratio: the shipped medians of the type and code level (hazusDriftThresholds
/// of Damage.h: Unknown type resolves to C1 by height class, Unknown era to moderate code, C3 and
/// URM above low code to low code) with the file's beta (0.4 at every level). `demandBeta` is the
/// record-to-record dispersion of the drift across the suite (ln units, 0 for one record; negative
/// or non-finite is taken as 0). `storeys` picks the height class of an Unknown type.
DamageProbabilities structuralDamage(StructuralType type, CodeEra era, double medianPeakDriftRatio,
                                     double demandBeta = 0, int storeys = 1);

/// P(collapse) = P(complete) x P_collapse of the type (the share of complete damage that collapses).
double collapseProbability(StructuralType type, const DamageProbabilities& structural, int storeys = 1);

/// Non-structural drift-sensitive components (partitions, facades): medians 0.004, 0.008, 0.025,
/// 0.05 with beta 0.5 (the shipped table; one set for every type and era).
DamageProbabilities nonStructuralDriftDamage(double medianPeakDriftRatio, double demandBeta = 0);

/// Non-structural acceleration-sensitive components (ceilings, equipment, contents anchorage) from
/// the building's peak floor acceleration in g (the peak over its floors; the file's "Offset" of
/// one floor is not modelled: the caller passes the building's maximum), medians per code level,
/// beta 0.6. Unknown era: moderate code.
DamageProbabilities nonStructuralAccelerationDamage(CodeEra era, double medianPeakFloorAccelerationG,
                                                    double demandBeta = 0);

/// Floor area per occupant at the class's usual peak presence, m² of gross floor area: residents
/// for the residential classes (present at night), workers, pupils, patients and visitors for the
/// others (present by day). Usual, not design, densities: US Census household sizes over dwelling
/// areas, office and school space per person as surveyed, hotel rooms at their occupancy. RES3 and
/// COM4 (and GOV1, offices) are calibrated so that the shared Manhattan extract holds its census
/// residents at night and its daytime population by day. docs/losses.md ("Occupants") lists every
/// row and its source.
double occupantDensityM2PerPerson(Occupancy occupancy);

/// Floor area per occupant at the most the class may hold, m² gross: the occupant load factors of
/// the International Building Code 2018, Table 1004.5 (business 150, mercantile 60, industrial 100,
/// storage 300, parking 200, agricultural 300, institutional inpatient 240 and sleeping 120,
/// dormitories 50, residential 200 ft² gross; classrooms 20 and unconcentrated assembly 15 ft² net,
/// taken as 40 and 30 ft² gross). No building holds more people than its floor area over this.
double occupantCapacityM2PerPerson(Occupancy occupancy);

/// A building with no use in the data (OSM `building=yes`) is taken as mixed use: this share of
/// its floor area residential (RES3), the rest offices (COM4), for its occupants only (damage and
/// repair cost use its occupancy class). Calibrated with the densities (docs/losses.md).
inline constexpr double kUnknownUseResidentialShare = 0.25;

/// Replacement cost per m² of floor area, US dollars at a 2022 price level: planning values of this
/// project, rounded, of the order of the RSMeans square-foot construction costs that the Hazus 5.1
/// Inventory Technical Manual uses for its building valuation (e.g. RES1 ~1,400, COM4 ~2,400, COM6
/// ~4,300 USD/m²); not transcribed from that table. Always marked inferred; give real values
/// (Exposure::replacementValueUsd) where they exist. docs/losses.md lists every row.
double replacementCostUsdPerM2(Occupancy occupancy);

/// The HAZUS population class of an occupancy for Population_Distribution: RES4 Hotels;
/// other RES and COM6 (in-patients stay around the clock) Residential; EDU Educational; IND
/// Industrial; everything else Commercial. Index into hazus::kPopulationDistribution.
std::size_t populationClass(Occupancy occupancy);

/// The share (0..1) of an occupancy's occupants present at a time of day.
double occupantsPresentShare(Occupancy occupancy, TimeOfDay time);

/// Where a building's year is unknown, the share of each Hazus type judged at pre-code, the rest at
/// low code (W1 always at low code): Hazus's default mapping scheme for New York (NY1, "based on
/// low seismic design", the FEMA Hazus state database) puts 74.5 % of the non-wood types' shares at
/// pre-code and the rest at low code, and all of W1 at low code. docs/losses.md "Types as
/// distributions".
inline constexpr double kUnknownEraPreCodeShare = 0.75;

/// One Hazus building type's share of a building whose type the data does not state.
struct TypeShare {
  std::string_view code;  ///< a Hazus building type: "W1", "S2H", "URMM", ... (hazus::structuralRowByCode)
  double share = 0;       ///< 0..1
};

/// What is known about one building for its consequences.
struct Exposure {
  StructuralType type = StructuralType::Unknown;
  CodeEra era = CodeEra::Unknown;
  Occupancy occupancy = Occupancy::RES3;
  int storeys = 1;                  ///< >= 1; picks the height class of an Unknown type
  double floorAreaM2 = 0;           ///< total over storeys (footprint x storeys when nothing better)
  std::optional<double> occupants;  ///< people at peak occupancy, tagged; else floor area / density
  bool useKnown = true;             ///< false: the data gives no use (mixed-use occupants)
  /// Non-empty: the type is not stated, and the structural damage, collapse and injuries are the
  /// mixture over these Hazus types (shares summing to 1; hazusTypeMixture), each at `era` (C3, S5
  /// and URM at most low code, as Hazus has them). `type` is then only the modelled one.
  std::span<const TypeShare> typeMixture;
  /// False: the data gives no year. `era` then holds the modelled era (moderate code), and the
  /// structural fragilities are spread over design levels (kUnknownEraPreCodeShare).
  bool eraKnown = true;
  std::optional<double> replacementValueUsd;  ///< given; else floor area x cost per m²
};

/// Consequences given each outcome, kept for totalLosses' sampling (expected values are above).
struct ConditionalConsequences {
  /// Expected people injured at severity 1..4 PER OCCUPANT PRESENT (fractions, not percent) given
  /// none, slight, moderate, extensive, complete without collapse, and collapse (index 0..5):
  /// times BuildingLoss::occupantsPresent they are the building's injuries at the run's time of day,
  /// times occupantsAt[t] those at another time (casualtiesByTimeOfDay).
  std::array<std::array<double, 4>, 6> injuriesPerOccupant{};
  double collapseGivenComplete = 0;               ///< P_collapse of the type
  std::array<double, 5> structuralCostUsd{};      ///< repair cost given the structural state 0..4
  std::array<double, 5> nsDriftCostUsd{};         ///< given the non-structural drift state
  std::array<double, 5> nsAccelerationCostUsd{};  ///< given the acceleration-sensitive state
};

/// The people in one building at night, by day and at commute time (index: TimeOfDay). Tagged
/// occupants (Exposure::occupants, people at peak) times HAZUS's share present at the time;
/// otherwise floor area over the class's usual density (occupantDensityM2PerPerson) times the share,
/// a building of unknown use by the mixed-use profile (kUnknownUseResidentialShare). Never more
/// than `capacity`, floor area over occupantCapacityM2PerPerson.
struct BuildingOccupants {
  std::array<double, 3> at{};
  double capacity = 0;
  bool inferred = false;  ///< from floor area, not the data
  bool capped = false;    ///< some time's count was cut to the capacity
};
BuildingOccupants buildingOccupants(const Exposure& exposure);

/// The expected consequences for one building.
struct BuildingLoss {
  DamageProbabilities structural, nonStructuralDrift, nonStructuralAcceleration;
  double collapse = 0;                  ///< P(collapse)
  double occupantsPresent = 0;          ///< people in the building at the time of day
  std::array<double, 3> occupantsAt{};  ///< at night, by day, at commute time (buildingOccupants)
  bool occupantsInferred = false;       ///< from floor area and the density table, not from the data
  /// Expected people at severity 1..4 (HAZUS: 1 first aid, 2 hospital care, 3 life-threatening,
  /// 4 dead): occupantsPresent x sum over states of P(state) x rate(state) / 100, the complete state
  /// split into collapse (P_collapse of it) and no collapse, as the Hazus 5.1 Technical Manual's
  /// casualty model (chapter "Casualties", indoor casualties by structural damage state) does.
  std::array<double, 4> injuries{};
  double replacementValueUsd = 0;
  bool valueInferred = false;  ///< from floor area x cost per m², not from the data
  /// Expected repair cost: value x sum over k of (P_str(k) RCR_str(k) + P_nsd(k) RCR_nsd(k) +
  /// P_nsa(k) RCR_nsa(k)) / 100, the Hazus building repair-cost model.
  double repairCostUsd = 0;
  /// Expected building repair time, sum over k of P_str(k) x days(k): the file's Repair_time, which
  /// is Hazus's building clean-up and repair (construction) time, not the longer loss-of-function
  /// time (no financing, permits or design delays).
  double repairTimeDays = 0;
  /// P(green), P(yellow), P(red) placards: green = none or slight, yellow = moderate, red = extensive
  /// or complete structural damage (docs/losses.md gives the reasoning: ATC-20-1 placard criteria
  /// against Hazus's damage-state descriptions).
  std::array<double, 3> tag{1, 0, 0};
  ConditionalConsequences given;  ///< for totalLosses
};

/// A building's consequences at a time of day from its response: median peak inter-storey drift
/// ratio and median peak floor acceleration (g) over a suite, with their record-to-record
/// dispersions (ln units; 0 for one record). Floor area, occupants and value below zero or not
/// finite count as 0.
BuildingLoss assessLoss(const Exposure& exposure, double medianPeakDriftRatio, double medianPeakFloorAccelerationG,
                        double demandBetaDrift, double demandBetaAcceleration, TimeOfDay time);

/// An expected value and a 90 % interval (5th and 95th percentiles).
struct Estimate {
  double expected = 0, low = 0, high = 0;
};

/// The casualties of one part of the day: the people present and the injuries at severity 1..4
/// (4: deaths) with their 90 % interval, as totalLosses gives them at the run's time.
struct CasualtiesAtTime {
  double occupants = 0;
  std::array<Estimate, 4> injuries;
};

struct LossTotals {
  std::uint64_t buildings = 0;
  std::array<Estimate, 5> damageStates;  ///< expected building counts none..complete (sum of P)
  /// Buildings with moderate damage or worse (the "damaged" headline: a yellow or red tag). Its
  /// bounds are NaN when read from a consequences file written before it existed.
  Estimate damaged;
  Estimate collapsed, occupants, repairCostUsd;
  /// People present at night, by day and at commute time (sums of BuildingLoss::occupantsAt); NaN
  /// when read from a consequences file written before it existed.
  std::array<double, 3> occupantsAt{};
  std::array<Estimate, 4> injuries;  ///< severity 1..4
  std::array<Estimate, 3> tags;      ///< green, yellow, red building counts
  /// The casualties at night, by day and at commute time (casualtiesByTimeOfDay); absent where not
  /// computed (totalLosses leaves it out; consequences files written before it).
  std::optional<std::array<CasualtiesAtTime, 3>> byTime;
};

/// Number of realisations totalLosses draws.
inline constexpr int kLossRealisations = 500;

/// Totals over buildings. Expected values are exact sums of the buildings' expected values. The
/// 90 % interval is Monte Carlo (kLossRealisations realisations, deterministic for a seed): each
/// realisation draws every building's damage independently of the other buildings; within a
/// building ONE uniform draw sets the structural, drift-sensitive and acceleration-sensitive states
/// together (by inverting each one's cumulative distribution: they share the same demand, so they
/// are taken as fully correlated), collapse is the most severe P(collapse) part of the complete state,
/// and the consequences are those given the drawn states. Occupants present carry no uncertainty
/// here (low = high = expected). Where the expected value lies outside the sampled 5-95 % range
/// (a rare outcome, e.g. 0.01 expected collapses with none in 95 % of realisations) that bound is
/// widened to the expected value, so the interval always contains it. Independence between buildings UNDERSTATES the
/// city-wide spread when the shaking is correlated (one event shakes neighbours alike): read the interval as a lower
/// bound of the real uncertainty. Fast: one uniform per building per realisation.
LossTotals totalLosses(std::span<const BuildingLoss> buildings, std::uint64_t seed = 1);

/// The casualties the same damage would cause at night, by day and at commute time (index:
/// TimeOfDay; HAZUS reports them for 2 AM, 2 PM and 5 PM): each building's injuries given its
/// outcome scale with the people present at that time (BuildingLoss::occupantsAt). Draws as
/// totalLosses with the same `seed` (the same realisations), so the run's own time of day gives
/// exactly totalLosses' injuries.
std::array<CasualtiesAtTime, 3> casualtiesByTimeOfDay(std::span<const BuildingLoss> buildings, std::uint64_t seed = 1);

/// The restoration of an essential facility (hospital, fire or police station, emergency operations
/// centre, school) after each structural damage state: normal curves of the days until it is
/// functional again, mean and standard deviation per state none .. complete (none: functional at
/// once). Values of Hazus-MH 2.1's essential-facility restoration table (Technical Manual, Table
/// 6.11) as the Rt software's healthcare restoration model (Mahsuli and Haukaas, rtx.civil.sharif.edu)
/// implements them: slight 5 ± 1, moderate 20 ± 2, extensive 90 ± 10, complete 180 ± 20 days. Taken
/// from that implementation, not checked against the manual's page (docs/losses.md says so).
struct RestorationCurve {
  double meanDays = 0, sigmaDays = 0;
};
inline constexpr std::array<RestorationCurve, 5> kEssentialFacilityRestoration = {
    {{0, 0}, {5, 1}, {20, 2}, {90, 10}, {180, 20}}};

/// The probability that an essential facility is functional `days` after the earthquake, Hazus's
/// functionality: sum over states of P(DS = k) x Phi((days - mean_k) / sigma_k) with
/// kEssentialFacilityRestoration (state none: 1). On day one it is close to P(none).
double functionalProbability(const std::array<double, 5>& structural, double days);

/// Standard deviations of one building's repair cost (USD) and injuries (people, severity 1..4)
/// under the draw totalLosses makes (one uniform draw sets every component's state), computed
/// exactly by integrating over the draw. Summed as variances over independent buildings they give
/// the normal approximation the viewer uses for the totals of the current view.
struct LossSpread {
  double repairCostUsd = 0;
  std::array<double, 4> injuries{};
};
LossSpread lossSpread(const BuildingLoss& building);

/// A building's exposure from its attributes, as `quakeview-prep response` assesses it: the type and
/// code era the building model resolves (resolvedStructuralType, resolvedCodeEra), the occupancy
/// from its use, the type mixture of its occupancy and storeys where the type is a guess
/// (hasTypeMixture, TypeMixture.h), the floor area given (> 0: e.g. buildingFloorAreaM2 over its parts) else footprint
/// x storeys, and the occupants and replacement value the data gives (BuildingAttributes; inferred
/// when 0).
Exposure exposureFromAttributes(const BuildingAttributes& attributes, int storeys, double floorAreaM2 = 0);

}  // namespace qv::seismic
