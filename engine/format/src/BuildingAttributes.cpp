#include "qv/format/BuildingAttributes.h"

#include <array>
#include <utility>

namespace qv {
namespace {

struct TypeInfo {
  std::string_view code;
  std::string_view description;
};

constexpr std::array<TypeInfo, static_cast<std::size_t>(StructuralType::Count)> kTypes = {{
    {"unknown", "Unknown structural system"},
    {"W1", "Wood, light frame"},
    {"W2", "Wood, commercial and industrial"},
    {"S1L", "Steel moment frame, low-rise"},
    {"S1M", "Steel moment frame, mid-rise"},
    {"S1H", "Steel moment frame, high-rise"},
    {"S2L", "Steel braced frame, low-rise"},
    {"S2M", "Steel braced frame, mid-rise"},
    {"S2H", "Steel braced frame, high-rise"},
    {"C1L", "Concrete moment frame, low-rise"},
    {"C1M", "Concrete moment frame, mid-rise"},
    {"C1H", "Concrete moment frame, high-rise"},
    {"C2L", "Concrete shear walls, low-rise"},
    {"C2M", "Concrete shear walls, mid-rise"},
    {"C2H", "Concrete shear walls, high-rise"},
    {"C3L", "Concrete frame with masonry infill, low-rise"},
    {"C3M", "Concrete frame with masonry infill, mid-rise"},
    {"C3H", "Concrete frame with masonry infill, high-rise"},
    {"PC1", "Precast concrete tilt-up walls"},
    {"RM1L", "Reinforced masonry bearing walls, low-rise"},
    {"RM1M", "Reinforced masonry bearing walls, mid-rise"},
    {"URML", "Unreinforced masonry bearing walls, low-rise"},
    {"URMM", "Unreinforced masonry bearing walls, mid-rise"},
    {"MH", "Mobile home"},
}};

constexpr std::array<std::string_view, static_cast<std::size_t>(CodeEra::Count)> kEras = {
    "unknown", "pre-code", "low-code", "moderate-code", "high-code"};

}  // namespace

std::string_view structuralTypeCode(StructuralType type) {
  const auto i = static_cast<std::size_t>(type);
  return i < kTypes.size() ? kTypes[i].code : kTypes[0].code;
}

std::string_view structuralTypeDescription(StructuralType type) {
  const auto i = static_cast<std::size_t>(type);
  return i < kTypes.size() ? kTypes[i].description : kTypes[0].description;
}

StructuralType parseStructuralType(std::string_view code) {
  for (std::size_t i = 1; i < kTypes.size(); ++i) {
    if (kTypes[i].code == code) return static_cast<StructuralType>(i);
  }
  return StructuralType::Unknown;
}

std::string_view codeEraName(CodeEra era) {
  const auto i = static_cast<std::size_t>(era);
  return i < kEras.size() ? kEras[i] : kEras[0];
}

CodeEra parseCodeEra(std::string_view name) {
  for (std::size_t i = 1; i < kEras.size(); ++i) {
    if (kEras[i] == name) return static_cast<CodeEra>(i);
  }
  return CodeEra::Unknown;
}

std::string_view importanceName(Importance importance) {
  return importance == Importance::Critical ? "critical" : "general";
}

std::vector<std::string_view> importanceReasonNames(unsigned reasons) {
  static constexpr std::pair<unsigned, std::string_view> kNames[] = {
      {kReasonHospital, "hospital"}, {kReasonFireStation, "fire_station"},
      {kReasonPolice, "police"},     {kReasonSchool, "school"},
      {kReasonTall, "tall"},         {kReasonComplex, "complex"},
      {kReasonShelter, "shelter"}};
  std::vector<std::string_view> names;
  for (const auto& [bit, name] : kNames) {
    if ((reasons & bit) != 0) names.push_back(name);
  }
  return names;
}

namespace {
struct NoteRow {
  unsigned bit;
  std::string_view name;
  std::string_view text;
};
constexpr NoteRow kNotes[] = {
    {kNoteZeroHeight, "zero-height", "height=0 is tagged but the building stands above ground: height inferred"},
    {kNoteStoreysFromNave, "storeys-from-nave",
     "storeys from the nave or main body (the outline's height, or height minus roof:height), not the "
     "towers or spire"},
    {kNoteLevelsConflict, "levels-conflict",
     "the tagged height and levels give storeys under 2.2 m or over 7 m: storeys inferred from the height"},
    {kNoteOldStoreyHeight, "old-storey-height", "built before 1890: storeys inferred at 4.5 m floor to floor"},
    {kNotePreFrameMasonry, "pre-frame-masonry",
     "built before 1890, before steel and concrete frames: masonry bearing walls"},
    {kNoteTraditionalMasonry, "traditional-masonry",
     "religious building, tower or chimney built before 1950 or undated: masonry bearing walls"},
    {kNoteRoofAppendage, "roof-appendage",
     "height and storeys stop at the roof: a spire, mast or antenna part above it is drawn but is not "
     "structure"},
    {kNoteTypeFromUse, "type-from-use",
     "no structure or material tag: the modelled type is a guess from use and height, and the damage "
     "is the mixture over the Hazus building types of its occupancy and height"},
};
}  // namespace

std::vector<std::string_view> attributeNoteNames(unsigned notes) {
  std::vector<std::string_view> names;
  for (const NoteRow& row : kNotes) {
    if ((notes & row.bit) != 0) names.push_back(row.name);
  }
  return names;
}

std::string_view attributeNoteText(unsigned note) {
  for (const NoteRow& row : kNotes) {
    if (row.bit == note) return row.text;
  }
  return {};
}

std::string_view valueSourceName(ValueSource source) {
  return source == ValueSource::Tagged ? "tagged" : "inferred";
}

}  // namespace qv
