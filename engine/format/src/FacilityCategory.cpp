#include "qv/format/FacilityCategory.h"

#include <array>

namespace qv {
namespace {

struct Rule {
  std::string_view value;
  FacilityCategory category;
};

// amenity values (OSM amenity=*, and the values the ingest step folds in from emergency=*,
// healthcare=*, social_facility=*, power=*, shop=mall and industrial=*; docs/attributes.md).
constexpr Rule kAmenityRules[] = {
    {"hospital", FacilityCategory::Essential},
    {"fire_station", FacilityCategory::Essential},
    {"police", FacilityCategory::Essential},
    {"ambulance_station", FacilityCategory::Essential},
    {"school", FacilityCategory::SchoolShelter},
    {"kindergarten", FacilityCategory::SchoolShelter},
    {"college", FacilityCategory::SchoolShelter},
    {"university", FacilityCategory::SchoolShelter},
    {"shelter", FacilityCategory::SchoolShelter},
    {"community_centre", FacilityCategory::SchoolShelter},
    {"fuel", FacilityCategory::Hazardous},
    {"power_plant", FacilityCategory::Hazardous},
    {"substation", FacilityCategory::Hazardous},
    {"chemical_works", FacilityCategory::Hazardous},
    {"refinery", FacilityCategory::Hazardous},
    {"theatre", FacilityCategory::HighOccupancy},
    {"cinema", FacilityCategory::HighOccupancy},
    {"place_of_worship", FacilityCategory::HighOccupancy},
    {"arts_centre", FacilityCategory::HighOccupancy},
    {"conference_centre", FacilityCategory::HighOccupancy},
    {"events_venue", FacilityCategory::HighOccupancy},
    {"bus_station", FacilityCategory::HighOccupancy},
    {"mall", FacilityCategory::HighOccupancy},
};

// Normalized uses (qv::prep::normalizeUse); "sports" holds stadiums, arenas and sports halls.
constexpr Rule kUseRules[] = {
    {"hospital", FacilityCategory::Essential},       {"fire_station", FacilityCategory::Essential},
    {"police", FacilityCategory::Essential},         {"ambulance_station", FacilityCategory::Essential},
    {"school", FacilityCategory::SchoolShelter},     {"shelter", FacilityCategory::SchoolShelter},
    {"university", FacilityCategory::SchoolShelter}, {"religious", FacilityCategory::HighOccupancy},
    {"sports", FacilityCategory::HighOccupancy},     {"transportation", FacilityCategory::HighOccupancy},
};

constexpr std::array<std::string_view, 5> kNames = {"none", "essential", "school_shelter", "high_occupancy",
                                                    "hazardous"};
constexpr std::array<std::string_view, 5> kLabels = {"general", "essential", "school or shelter", "high occupancy",
                                                     "hazardous"};
constexpr std::array<std::string_view, 5> kSources = {
    "",
    "Hazus 5.1 Inventory Technical Manual, Essential Facilities; FEMA lifelines Safety and Security, Health and "
    "Medical",
    "Hazus 5.1 Inventory Technical Manual, Essential Facilities (schools); FEMA lifeline Food, Water, Shelter",
    "places of assembly, large lodging and retail, transit (QuakeView rule, docs/attributes.md)",
    "FEMA lifeline Hazardous Material"};

}  // namespace

FacilityClass classifyFacility(std::string_view use, std::string_view amenity, float footprintAreaM2,
                               std::uint16_t storeys, unsigned reasons) {
  // An outpatient clinic has no beds: not an essential medical care facility (its use is "clinic";
  // tiles prepared before that say "hospital").
  if (amenity == "clinic") return {};
  // Rank: essential, school or shelter, hazardous, high occupancy, none.
  auto rank = [](FacilityCategory c) {
    constexpr std::array<int, 5> kRank = {0, 4, 3, 1, 2};
    return kRank[static_cast<std::size_t>(c)];
  };
  FacilityClass best;
  auto consider = [&](FacilityCategory category, std::string_view kind) {
    if (rank(category) > rank(best.category)) best = {category, kind};
  };
  for (const Rule& r : kAmenityRules) {
    if (r.value == amenity) consider(r.category, r.value);
  }
  for (const Rule& r : kUseRules) {
    if (r.value == use) consider(r.category, r.value);
  }
  if ((reasons & kReasonShelter) != 0) consider(FacilityCategory::SchoolShelter, "shelter");
  const float floorAreaM2 = footprintAreaM2 * static_cast<float>(storeys > 0 ? storeys : 1);
  if ((use == "hotel" || use == "retail") && floorAreaM2 >= kLargeFloorAreaM2) {
    consider(FacilityCategory::HighOccupancy, use == "hotel" ? "large_hotel" : "large_retail");
  }
  return best;
}

FacilityClass classifyFacility(const BuildingAttributes& a) {
  return classifyFacility(a.use, a.amenity, a.footprintAreaM2, a.storeys, a.importanceReasons);
}

std::string facilityKindLabel(std::string_view kind) {
  std::string out(kind);
  for (char& c : out) {
    if (c == '_') c = ' ';
  }
  return out;
}

std::string_view facilityCategoryName(FacilityCategory category) {
  const auto i = static_cast<std::size_t>(category);
  return i < kNames.size() ? kNames[i] : kNames[0];
}

std::string_view facilityCategoryLabel(FacilityCategory category) {
  const auto i = static_cast<std::size_t>(category);
  return i < kLabels.size() ? kLabels[i] : kLabels[0];
}

std::string_view facilityCategorySource(FacilityCategory category) {
  const auto i = static_cast<std::size_t>(category);
  return i < kSources.size() ? kSources[i] : kSources[0];
}

std::optional<FacilityCategory> parseFacilityCategory(std::string_view name) {
  for (std::size_t i = 1; i < kNames.size(); ++i) {
    if (kNames[i] == name) return static_cast<FacilityCategory>(i);
  }
  return std::nullopt;
}

}  // namespace qv
