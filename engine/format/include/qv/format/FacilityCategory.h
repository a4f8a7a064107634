// Facility categories as emergency managers use them: which buildings matter for response and
// recovery beyond their damage. Derived (never stored) from what city tiles and the search index
// already hold: the normalized use, the amenity value (which the ingest step also fills from a few
// facility tags, docs/attributes.md "Facility categories"), the floor area and the old importance
// reason bits. Height and parts are NOT criticality: a 300 m office tower is category None.
//
// Sources:
//  - FEMA, Hazus 5.1 Inventory Technical Manual (2022), section "Essential Facilities": medical
//    care facilities, emergency response facilities (fire stations, police stations, emergency
//    operations centres) and schools.
//  - FEMA, Community Lifelines Implementation Toolkit (2023): Safety and Security (law enforcement,
//    fire service, search and rescue); Health and Medical (medical care, patient movement: EMS);
//    Food, Water, Shelter (shelters); Hazardous Material (facilities, HAZMAT, pollutants).
// High occupancy (places of assembly, large lodging and retail, transit) is this product's choice
// for buildings where many people gather; see docs/attributes.md for the exact rules.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "qv/format/BuildingAttributes.h"

namespace qv {

/// A building's facility category. Not stored in tiles (derived by classifyFacility); the search
/// index (version 3) carries it as one byte: never renumber, only append.
enum class FacilityCategory : std::uint8_t {
  None = 0,           ///< general building stock (whatever its height or parts)
  Essential = 1,      ///< hospitals, fire, police and ambulance stations (Hazus essential facilities)
  SchoolShelter = 2,  ///< schools, universities, shelters (Hazus: schools; FEMA lifeline: shelter)
  HighOccupancy = 3,  ///< stadiums, theatres, places of worship, malls, transit stations, large hotels
  Hazardous = 4,      ///< fuel stations, power plants and substations, chemical works and refineries
  Count
};

/// Bit of `category` in a category mask (BuildingFilters::categories): 1 << category.
constexpr unsigned facilityCategoryBit(FacilityCategory category) {
  return 1u << static_cast<unsigned>(category);
}
/// What "critical facilities" means everywhere in the product: Essential or SchoolShelter.
inline constexpr unsigned kCriticalCategories =
    facilityCategoryBit(FacilityCategory::Essential) | facilityCategoryBit(FacilityCategory::SchoolShelter);

/// Floor area (footprint × storeys) from which a hotel or a retail building is high-occupancy,
/// square metres (roughly a 150-room hotel or a shopping centre; the product's choice).
inline constexpr float kLargeFloorAreaM2 = 10000.0f;

/// A category and the rule that gave it.
struct FacilityClass {
  FacilityCategory category = FacilityCategory::None;
  /// The facility kind that decided it ("hospital", "fire_station", "school", "stadium", "fuel",
  /// ...; static strings); empty for None.
  std::string_view kind;
};

/// The category of a building from its normalized `use`, its `amenity` value, its floor area
/// (`footprintAreaM2` × `storeys`, square metres; 0 when unknown) and ImportanceReason bits
/// (`reasons`; only kReasonShelter is read, for tiles written before the shelter amenity was kept).
/// Amenity clinic gives None (a clinic without beds is not a Hazus essential facility); otherwise
/// the most critical (Essential, SchoolShelter, Hazardous, HighOccupancy) of what these rules give
/// (docs/attributes.md "Facility categories"):
///  - Essential: amenity hospital, fire_station, police, ambulance_station; use hospital,
///    fire_station, police;
///  - SchoolShelter: amenity school, kindergarten, college, university, shelter,
///    community_centre; use school, university; the shelter reason bit;
///  - Hazardous: amenity fuel, power_plant, substation, chemical_works, refinery;
///  - HighOccupancy: amenity theatre, cinema, place_of_worship, arts_centre, conference_centre,
///    events_venue, bus_station, mall; use religious, sports, transportation; use hotel or retail
///    with a floor area of at least kLargeFloorAreaM2.
FacilityClass classifyFacility(std::string_view use, std::string_view amenity, float footprintAreaM2,
                               std::uint16_t storeys, unsigned reasons);
/// classifyFacility on a building's stored attributes.
FacilityClass classifyFacility(const BuildingAttributes& attributes);

/// What a person reads for a kind: its words ("fire_station" -> "fire station", "large_hotel" ->
/// "large hotel").
std::string facilityKindLabel(std::string_view kind);

/// "none", "essential", "school_shelter", "high_occupancy", "hazardous" (the names the link's
/// filter, exports and `quakeview-prep info --json` use); "none" for out-of-range values.
std::string_view facilityCategoryName(FacilityCategory category);
/// What a person reads: "general", "essential", "school or shelter", "high occupancy", "hazardous".
std::string_view facilityCategoryLabel(FacilityCategory category);
/// The source a category comes from, one line ("Hazus 5.1 Inventory Technical Manual, Essential
/// Facilities"); empty for None.
std::string_view facilityCategorySource(FacilityCategory category);
/// Parses a name facilityCategoryName gives (not "none"); nullopt otherwise.
std::optional<FacilityCategory> parseFacilityCategory(std::string_view name);

}  // namespace qv
