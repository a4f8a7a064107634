// Building attribute rules shared by every path that makes buildings (the OSM and GeoJSON readers,
// the synthetic city generator): parsing of OSM length/level/date values, normalized use, storey
// heights and default heights by use, height and storey inference, the HAZUS-style structural
// type, the design-code era and the importance class. The rules and their sources are documented
// in docs/attributes.md; the tables there and here must agree (tests/ingest/TestAttributes.cpp).
//
// Nothing here throws or allocates beyond the returned strings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "qv/format/BuildingAttributes.h"

namespace qv::prep {

/// The unit of a plain number in a height value ("30" means 30 m in OSM, 30 ft in NYC's data).
enum class LengthUnit : std::uint8_t { Meters, Feet };

/// Parses "metres"/"m" and "feet"/"ft" (the --height-unit option); nullopt otherwise.
std::optional<LengthUnit> parseLengthUnit(std::string_view name);

/// Parses an OSM length to metres: "30", "30.5", "30 m", "30m", "100 ft", "100 feet", "12'",
/// "12'6\"", "12' 6\"", "1,5" (a decimal comma followed by one or two digits). A plain number is in
/// `plainUnit`. Returns nullopt for anything else: garbage ("concrete"), several values ("5;6"),
/// negative or non-finite numbers, thousands separators ("1,500").
std::optional<double> parseLengthMeters(std::string_view text, LengthUnit plainUnit = LengthUnit::Meters);

/// Parses building:levels / building:min_level: a number >= 0 ("12", "2.5", "-1" for min_level is
/// accepted by parseMinLevel only). Nullopt for garbage ("concrete", "5;6", "", "12 floors").
std::optional<double> parseLevels(std::string_view text);
/// building:min_level may be negative (underground); the caller clamps it to the ground.
std::optional<double> parseMinLevel(std::string_view text);

/// The construction year of a start_date value: "1931", "1931-05-01", "~1931", "1930s", "c. 1931",
/// "before 1900", "1930..1931" (the first year). Years outside 1000..2100 and text without a year
/// give nullopt.
std::optional<int> parseStartYear(std::string_view text);

/// Normalized use from the building=* value and the stored amenity value (normalizeFacility's, so
/// that use and facility category follow from the same tags; docs/attributes.md, "Use"):
/// "residential", "house", "office", "commercial", "retail", "hotel", "industrial", "warehouse",
/// "school", "university", "hospital", "clinic", "fire_station", "ambulance_station", "police",
/// "shelter", "religious", "civic",
/// "transportation", "parking", "sports", "roof", "shed", "service", "construction",
/// "mobile_home", "other" (a specific building value not in the table) or "unknown"
/// (building=yes and no telling amenity).
std::string normalizeUse(std::string_view buildingTag, std::string_view amenity);

/// Typical floor-to-floor height in metres for a normalized use (docs/attributes.md, table
/// "Storey height by use"; CTBUH height calculator values). Unknown uses get 3.5 m.
float storeyHeightForUse(std::string_view use);

/// Default number of storeys for a building with neither height nor levels tagged, by use
/// (docs/attributes.md, table "Default heights").
int defaultStoreysForUse(std::string_view use);
/// defaultStoreysForUse(use) × storeyHeightForUse(use), metres.
float defaultHeightForUse(std::string_view use);

/// Tagged height values of one building or part, already parsed (nullopt = not tagged or garbage).
struct HeightTags {
  std::optional<double> heightM;     ///< height
  std::optional<double> minHeightM;  ///< min_height
  std::optional<double> levels;      ///< building:levels (counted from the ground, as in S3DB)
  std::optional<double> minLevel;    ///< building:min_level (levels skipped below this part)
};

/// Heights and storeys of one building or part, each with where it came from.
struct ResolvedHeights {
  float heightM = 0.0f;                ///< top above ground
  float minHeightM = 0.0f;             ///< bottom above ground, < heightM
  std::uint16_t storeys = 1;           ///< storeys between minHeightM and heightM, >= 1
  std::uint16_t levelsFromGround = 1;  ///< storeys from the ground to heightM (S3DB building:levels)
  ValueSource heightSource = ValueSource::Inferred;
  ValueSource storeysSource = ValueSource::Inferred;
};

/// The rules of docs/attributes.md "Storeys and height": height from the tag; else levels × storey
/// height of the use; else `fallbackHeightM` when given (a part without heights inherits its
/// building's), else the default of the use. Storeys from levels − min_level; else
/// round((height − min height) / storey height), at least 1. min height from min_height, else
/// min_level × storey height, else 0; a min height at or above the height is ignored (0).
ResolvedHeights resolveHeights(const HeightTags& tags, std::string_view use,
                               std::optional<double> fallbackHeightM = std::nullopt);

/// Storey heights a building can have, metres: tagged height and levels that give storeys outside
/// [kMinPlausibleStoreyM, kMaxPlausibleStoreyM] are in conflict (docs/attributes.md
/// "Plausibility rules").
inline constexpr double kMinPlausibleStoreyM = 2.2;
inline constexpr double kMaxPlausibleStoreyM = 7.0;
/// Tagged storeys from which a building is a high-rise (HAZUS H class) whose floor count a mapper
/// knew: in a conflict over 7 m it keeps as many storeys as the range allows.
inline constexpr int kHighRiseStoreys = 8;
/// Buildings begun before this year predate steel and concrete frames in New York (the Tower
/// Building, 1889, was the city's first skeleton frame): masonry bearing walls.
inline constexpr int kFrameEraYear = 1890;
/// Floor-to-floor height of buildings begun before kFrameEraYear, metres (12-15 ft upper floors).
inline constexpr double kOldStoreyHeightM = 4.5;

/// Why a building is underground (not drawn above ground, not analysed), or empty when it is not:
/// "location=underground", or "layer=-2 with no height above ground" (a negative layer with
/// neither a height above 0 nor building:levels above 0). `heightM` and `levels` are the parsed
/// tags (nullopt when absent or garbage).
std::string undergroundReason(std::string_view location, std::string_view layer, std::optional<double> heightM,
                              std::optional<double> levels);

/// What the storey rules know beyond the attributes.
struct StoreyEvidence {
  /// The height of the nave or main body when it differs from the top: the outline's own height
  /// under taller parts, else the height of the largest part, or height − roof:height.
  std::optional<double> mainBodyHeightM;
};

/// The storey rules of docs/attributes.md "Plausibility rules", in order, on attributes whose use,
/// heights, storeys (with sources) and startYear are set; sets `notes` bits and returns one
/// message per rule that overrode a tag (for the ingest warnings, without the building id):
///  1. a religious building or tower whose storeys are not tagged: storeys from its main body;
///  2. tagged height and storeys giving storeys under 2.2 m or over 7 m (not for religious
///     buildings and towers): storeys from the height at the use's storey height, or for a
///     high-rise (8+ tagged storeys) over 7 m, ceil(height / 7 m) (inferred);
///  3. storeys inferred and built before 1890: storeys at max(use storey height, 4.5 m).
std::vector<std::string> applyStoreyRules(BuildingAttributes& attributes, const StoreyEvidence& evidence);

/// HAZUS model building type (docs/attributes.md "Structural type"), first matching rule wins:
/// building:structure, then building:material (masonry of 8+ storeys is taken as cladding of a
/// frame), then use × storeys × construction year. `storeys` <= 0 means unknown (then estimated
/// from heightM at 3.5 m a storey); `startYear` 0 means unknown. Height class: steel and concrete
/// L 1–3, M 4–7, H 8+; URM L 1–2, M 3+; RM1 L 1–3, M 4+.
/// `fromUse` (optional) is set to whether only the use, height and era decided (no structure or
/// material tag said anything): the type is then a guess (kNoteTypeFromUse).
StructuralType inferStructuralType(std::string_view use, float heightM, int storeys, std::string_view material,
                                   std::string_view structure, int startYear, bool* fromUse = nullptr);

/// HAZUS design level from the construction year (docs/attributes.md "Code era"): before 1941
/// pre-code, 1941–1975 low-code, 1976–1994 moderate-code, 1995 on high-code; 0 (or a year before
/// 1000) gives Unknown.
CodeEra inferCodeEra(int startYear);

/// Height above which the tall reason bit is set (a level-of-detail reason, not criticality), metres.
inline constexpr float kTallBuildingHeightM = 100.0f;

/// The stored amenity value (docs/attributes.md "Facility categories"): the amenity tag when set,
/// else the facility another tag names, for qv::classifyFacility: amenity=shelter (OSM's weather
/// shelter) "weather_shelter"; social_facility=shelter (alone or with amenity=social_facility)
/// "shelter"; emergency=ambulance_station "ambulance_station", healthcare=hospital "hospital",
/// healthcare=clinic or doctor "clinic",
/// power=plant "power_plant", power=substation "substation", shop=mall "mall",
/// industrial=chemical "chemical_works", industrial=refinery or oil "refinery"; else empty.
std::string normalizeFacility(std::string_view amenity, std::string_view emergency, std::string_view healthcare,
                              std::string_view socialFacility, std::string_view power, std::string_view shop,
                              std::string_view industrial);

/// Sets attributes.importanceReasons from use, amenity and heightM (hospital, fire station,
/// police, school, shelter for community centres and shelters; tall over 100 m;
/// complex when assembled from parts: `hasParts`), then attributes.importance: Critical exactly
/// when qv::classifyFacility gives Essential or SchoolShelter (height and parts are not
/// criticality; they stay reason bits for the level of detail).
void classifyImportance(BuildingAttributes& attributes, bool hasParts);

/// Fills structuralType, codeEra and importance of attributes whose use, heightM, storeys,
/// material, structure, startYear and amenity are set (the last step of every building path).
void inferSeismicAttributes(BuildingAttributes& attributes, bool hasParts);

/// "350 5th Avenue, 10118 New York" from addr:housenumber, addr:street, addr:postcode, addr:city;
/// missing pieces are left out ("5th Avenue", "350 5th Avenue, New York"); empty when all are.
std::string formatAddress(std::string_view houseNumber, std::string_view street, std::string_view postcode,
                          std::string_view city);

}  // namespace qv::prep
