// What the product knows about one building besides its geometry: identity, use, heights and
// storeys (with whether each was tagged or inferred), and the seismic attributes the response step
// uses. Shared by preprocess (which infers them), the tile codec (which stores them) and the
// viewer (which shows them).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace qv {

/// Whether a value came from the source data or was inferred by documented rules.
enum class ValueSource : std::uint8_t { Tagged = 0, Inferred = 1 };

/// HAZUS-MH model building types (FEMA, Hazus Earthquake Model Technical Manual, Table 3-1),
/// with their height classes (L low-rise, M mid-rise, H high-rise). Values are stored in tiles:
/// never renumber, only append.
enum class StructuralType : std::uint8_t {
  Unknown = 0,
  W1 = 1,   ///< wood, light frame
  W2 = 2,   ///< wood, commercial and industrial
  S1L = 3,  ///< steel moment frame, low-rise (1-3 storeys)
  S1M = 4,  ///< steel moment frame, mid-rise (4-7)
  S1H = 5,  ///< steel moment frame, high-rise (8+)
  S2L = 6,  ///< steel braced frame
  S2M = 7,
  S2H = 8,
  C1L = 9,  ///< concrete moment frame
  C1M = 10,
  C1H = 11,
  C2L = 12,  ///< concrete shear walls
  C2M = 13,
  C2H = 14,
  C3L = 15,  ///< concrete frame with unreinforced masonry infill walls
  C3M = 16,
  C3H = 17,
  PC1 = 18,   ///< precast concrete tilt-up walls
  RM1L = 19,  ///< reinforced masonry bearing walls with wood or metal deck diaphragms
  RM1M = 20,
  URML = 21,  ///< unreinforced masonry bearing walls, low-rise (1-2)
  URMM = 22,  ///< unreinforced masonry bearing walls, mid-rise (3+)
  MH = 23,    ///< mobile homes
  Count
};

/// HAZUS seismic design level, chosen from the construction date (see docs/attributes.md).
enum class CodeEra : std::uint8_t { Unknown = 0, PreCode = 1, LowCode = 2, ModerateCode = 3, HighCode = 4, Count };

/// General building stock vs critical facilities (the paper's data LOD1/LOD2 split).
enum class Importance : std::uint8_t { General = 0, Critical = 1 };

/// Why a building is critical (bit flags).
enum ImportanceReason : std::uint8_t {
  kReasonNone = 0,
  kReasonHospital = 1,
  kReasonFireStation = 2,
  kReasonPolice = 4,
  kReasonSchool = 8,
  kReasonTall = 16,     ///< taller than 100 m
  kReasonComplex = 32,  ///< assembled from several parts (setbacks, towers on podiums)
  kReasonShelter = 64,  ///< emergency shelters, civic centres
};

/// Why a height, storey count or structural type was inferred against what the data says, or what
/// a plausibility rule changed (bit flags; docs/attributes.md "Plausibility rules"). Stored in
/// tiles: never renumber, only add bits.
enum AttributeNote : std::uint8_t {
  kNoteNone = 0,
  kNoteZeroHeight = 1,           ///< height=0 tagged on a building above ground: the height is inferred
  kNoteStoreysFromNave = 2,      ///< storeys from the nave or main body, not the towers or spire
  kNoteLevelsConflict = 4,       ///< tagged height and levels imply storeys under 2.2 m or over 7 m
  kNoteOldStoreyHeight = 8,      ///< built before 1890: storeys inferred at 19th-century floor heights
  kNotePreFrameMasonry = 16,     ///< built before 1890, before steel and concrete frames: masonry
  kNoteTraditionalMasonry = 32,  ///< a religious building, tower or chimney before 1950 (or undated): masonry
  kNoteRoofAppendage = 64,       ///< a spire, mast or antenna part above the roof: drawn, not in the height
  kNoteTypeFromUse = 128,        ///< no structure or material tag: the type is a guess from use and height
};

struct BuildingAttributes {
  std::string id;             ///< stable id: w<osm way>, r<osm relation>, s<n>, cj:<id>, g:<id or index>
  std::string name;           ///< may be empty
  std::string use;            ///< normalized use: office, residential, retail, hospital, school, ...
  std::string address;        ///< "350 5th Avenue, 10118 New York" from addr:*; may be empty
  std::string material;       ///< building:material, may be empty
  std::string structure;      ///< building:structure, may be empty
  std::string amenity;        ///< amenity tag, may be empty
  float heightM = 0.0f;       ///< top of the building above ground, metres
  float minHeightM = 0.0f;    ///< bottom of the lowest storey above ground (0 for most buildings)
  std::uint16_t storeys = 1;  ///< number of storeys between minHeightM and heightM (>= 1)
  ValueSource heightSource = ValueSource::Inferred;
  ValueSource storeysSource = ValueSource::Inferred;
  std::int16_t startYear = 0;  ///< construction year, 0 when unknown
  StructuralType structuralType = StructuralType::Unknown;
  CodeEra codeEra = CodeEra::Unknown;
  Importance importance = Importance::General;
  std::uint8_t importanceReasons = kReasonNone;
  std::uint8_t lod = 1;            ///< 1: extruded footprint, 2: detailed model
  std::uint8_t notes = kNoteNone;  ///< AttributeNote bits: why values were inferred or changed
  float footprintAreaM2 = 0.0f;    ///< area of the ground footprint
  /// People in the building at peak occupancy, as the data states it (a GeoJSON property); 0:
  /// not given (the consequences then infer it from floor area and use).
  std::uint16_t occupants = 0;
  /// Replacement value in US dollars, as the data states it; 0: not given (inferred then).
  float replacementValueUsd = 0.0f;
  double centroidX = 0.0;  ///< metres east of the city origin
  double centroidY = 0.0;  ///< metres north of the city origin

  bool operator==(const BuildingAttributes&) const = default;

  /// Height of one storey in metres (floor k sits at minHeightM + k × this).
  [[nodiscard]] float storeyHeightM() const {
    return storeys > 0 ? (heightM - minHeightM) / static_cast<float>(storeys) : heightM;
  }
};

/// "C1M", "URML", ... ("unknown" for Unknown or out-of-range values).
std::string_view structuralTypeCode(StructuralType type);
/// "Concrete moment frame, mid-rise", ...
std::string_view structuralTypeDescription(StructuralType type);
/// Parses a code such as "C1M"; Unknown when not recognised.
StructuralType parseStructuralType(std::string_view code);
/// "pre-code", "low-code", "moderate-code", "high-code", "unknown".
std::string_view codeEraName(CodeEra era);
CodeEra parseCodeEra(std::string_view name);
std::string_view importanceName(Importance importance);  ///< "general" / "critical"
/// The names of the reasons set in `reasons` (ImportanceReason bits), in bit order: "hospital",
/// "fire_station", "police", "school", "tall", "complex", "shelter".
std::vector<std::string_view> importanceReasonNames(unsigned reasons);
std::string_view valueSourceName(ValueSource source);  ///< "tagged" / "inferred"
/// The codes of the notes set in `notes` (AttributeNote bits), in bit order: "zero-height",
/// "storeys-from-nave", "levels-conflict", "old-storey-height", "pre-frame-masonry",
/// "traditional-masonry".
std::vector<std::string_view> attributeNoteNames(unsigned notes);
/// The sentence a user sees for one AttributeNote bit (docs/attributes.md); empty for others.
std::string_view attributeNoteText(unsigned note);

}  // namespace qv
