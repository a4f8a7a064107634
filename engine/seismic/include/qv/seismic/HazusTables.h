// The HAZUS 5.1 earthquake tables that engine::seismic ships (one home for these values: the
// deterministic thresholds of Damage.h and the probabilities and consequences of Loss.h read them).
//
// Source: hazus_data_eq.json of the NHERI SimCenter Damage and Loss Model Library (BSD 3-Clause,
// engine/seismic/data/LICENSE-DamageAndLossModelLibrary), whose values come from the FEMA Hazus 5.1
// Earthquake Model Technical Manual (2022). src/HazusTables.cpp is generated from that file by
// scripts/gen-hazus-tables.py; tests/seismic/TestHazusTables.cpp checks every value against it.
// Shipped: the 23 structural types of qv::StructuralType, the file's 13 other building types (S3,
// S4, S5, PC2, RM2: no model of ours, but a type mixture may hold them) and the 28 occupancy classes
// (the lifeline and ground-failure groups are not).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace qv::seismic::hazus {

inline constexpr std::size_t kStructuralTypes = 23;       ///< rows: qv::StructuralType 1..23 (W1 .. MH) at 0..22
inline constexpr std::size_t kExtraStructuralTypes = 13;  ///< S3, S4L..H, S5L..H, PC2L..H, RM2L..H
inline constexpr std::size_t kCodeEras = 4;           ///< columns: qv::CodeEra 1..4 (pre, low, moderate, high) at 0..3
inline constexpr std::size_t kOccupancies = 28;       ///< rows: qv::seismic::Occupancy (RES1 .. EDU2)
inline constexpr std::size_t kPopulationClasses = 5;  ///< Residential, Commercial, Educational, Industrial, Hotels

/// One structural type ("Structural_Fragility_Groups").
struct StructuralRow {
  std::string_view code;  ///< the file's key, e.g. "C1M"
  /// Median peak inter-storey drift ratio at slight, moderate, extensive, complete, per era
  /// (index CodeEra - 1; "EDP_limits").
  std::array<std::array<double, 4>, kCodeEras> driftLimits;
  /// Whether the file has the type at that era; where it does not (C3 and URM at moderate and
  /// high code) the row repeats the low-code values, as Hazus permits those types only up to low code.
  std::array<bool, kCodeEras> inFile;
  double collapseProbability;  ///< P(collapse | complete damage) ("P_collapse")
  /// Injury rates in PERCENT of the occupants, severity 1..4, given DS1, DS2, DS3, DS4 without
  /// collapse, and collapse ("Injury_rates": DS1..DS4, Collapse).
  std::array<std::array<double, 4>, 5> injuryRatesPercent;
};

/// One occupancy class; every array is indexed slight, moderate, extensive, complete.
struct OccupancyRow {
  std::string_view code;                                  ///< "RES1" ...
  std::array<double, 4> structuralRepairCostPercent;      ///< of replacement value ("Repair_cost")
  std::array<double, 4> structuralRepairTimeDays;         ///< building repair (clean-up and construction) time
  std::array<double, 4> nsDriftRepairCostPercent;         ///< non-structural drift-sensitive
  std::array<double, 4> nsAccelerationRepairCostPercent;  ///< non-structural acceleration-sensitive
};

/// Share of a class's occupants present at night, by day and at commute time ("Population_Distribution").
struct PopulationRow {
  std::string_view name;        ///< "Residential", "Commercial", "Educational", "Industrial", "Hotels"
  std::array<double, 3> share;  ///< night, day, commute (fractions, 0..1)
};

extern const std::array<double, kCodeEras> kStructuralBeta;  ///< lognormal beta per era (ln units)
extern const std::array<StructuralRow, kStructuralTypes> kStructural;
extern const std::array<StructuralRow, kExtraStructuralTypes> kExtraStructural;
/// The row of a Hazus building type by its code ("C1M", "S5L", ...) in kStructural or
/// kExtraStructural; nullptr for a code Hazus does not have.
const StructuralRow* structuralRowByCode(std::string_view code);
extern const std::array<OccupancyRow, kOccupancies> kOccupancy;
extern const std::array<double, 4> kNsDriftLimits;  ///< median peak inter-storey drift ratios
extern const double kNsDriftBeta;
/// Median peak floor accelerations in g, per era (index CodeEra - 1).
extern const std::array<std::array<double, 4>, kCodeEras> kNsAccelerationLimitsG;
extern const double kNsAccelerationBeta;
/// The file's "Offset" of the acceleration group (1: in SimCenter's pelicun the demand is read one
/// floor above the component's location, i.e. the floor the contents hang from or sit below).
/// Not used by Loss.h, which takes the building's peak floor acceleration (documented there).
extern const double kNsAccelerationOffset;
extern const std::array<PopulationRow, kPopulationClasses> kPopulationDistribution;
/// "Parts_of_day": for each hour 0..23, 0 night, 1 day, 2 commute.
extern const std::array<std::uint8_t, 24> kPartOfDayByHour;

}  // namespace qv::seismic::hazus
