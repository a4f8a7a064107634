#include "qv/prep/Attributes.h"

#include "qv/format/FacilityCategory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace qv::prep {
namespace {

constexpr double kMetersPerFoot = 0.3048;
constexpr double kMetersPerInch = 0.0254;

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i];
    char y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

bool contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

/// Reads an unsigned decimal number at the front of `text` ("12", "12.5", ".5", "1,5" with a
/// decimal comma followed by one or two digits) and removes it. No sign, no exponent: OSM values
/// with either are garbage. std::from_chars for doubles is avoided on purpose (missing in em++'s
/// libc++; this file is native, but the parsing rules should stay portable).
std::optional<double> takeNumber(std::string_view& text) {
  std::size_t i = 0;
  double value = 0.0;
  bool anyDigit = false;
  while (i < text.size() && isDigit(text[i])) {
    value = value * 10.0 + (text[i] - '0');
    anyDigit = true;
    ++i;
  }
  if (i < text.size() && (text[i] == '.' || text[i] == ',')) {
    const bool comma = text[i] == ',';
    std::size_t j = i + 1;
    double scale = 0.1;
    double fraction = 0.0;
    while (j < text.size() && isDigit(text[j])) {
      fraction += (text[j] - '0') * scale;
      scale *= 0.1;
      ++j;
    }
    const std::size_t fractionDigits = j - i - 1;
    // "1,500" is a thousands separator or a list, not 1.5: only 1-2 digits after a comma.
    if (comma && (fractionDigits == 0 || fractionDigits > 2 || !anyDigit)) return std::nullopt;
    if (!comma && fractionDigits == 0 && !anyDigit) return std::nullopt;
    if (fractionDigits > 0) anyDigit = true;
    value += fraction;
    i = j;
  }
  if (!anyDigit || !std::isfinite(value)) return std::nullopt;
  text.remove_prefix(i);
  return value;
}

std::string_view skipSpaces(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  return text;
}

bool isFeetMark(std::string_view text) {
  return text.starts_with("'") || text.starts_with("\xE2\x80\xB2");
}  // ' or ′
std::size_t feetMarkSize(std::string_view text) {
  return text.starts_with("'") ? 1 : 3;
}
bool isInchMark(std::string_view text) {
  return text == "\"" || text == "\xE2\x80\xB3" || text == "''" || text == "in";
}

struct UseRow {
  std::string_view use;
  float storeyHeightM;
  int defaultStoreys;
};

// Floor-to-floor heights: CTBUH Height Calculator (office 3.9 m, residential and hotel 3.1 m,
// mixed use 3.5 m) where it has a value; the others are typical clear heights plus a 0.5-1 m
// floor zone for halls, workshops and garages. See docs/attributes.md for the reasoning.
constexpr UseRow kUseTable[] = {
    {"residential", 3.1f, 4},    {"house", 3.0f, 2},
    {"hotel", 3.1f, 6},          {"office", 3.9f, 6},
    {"commercial", 3.9f, 2},     {"retail", 4.5f, 1},
    {"industrial", 5.0f, 2},     {"warehouse", 6.0f, 1},
    {"school", 3.9f, 3},         {"university", 3.9f, 4},
    {"hospital", 4.2f, 4},       {"fire_station", 4.5f, 2},
    {"clinic", 3.9f, 2},         {"ambulance_station", 4.5f, 1},
    {"shelter", 3.1f, 3},        {"police", 3.9f, 3},
    {"religious", 6.0f, 1},      {"civic", 4.5f, 2},
    {"transportation", 6.0f, 1}, {"parking", 3.0f, 3},
    {"sports", 6.0f, 1},         {"roof", 4.0f, 1},
    {"shed", 3.0f, 1},           {"service", 3.5f, 1},
    {"construction", 3.5f, 2},   {"mobile_home", 3.0f, 1},
    {"unknown", 3.5f, 2},        {"tower", 4.0f, 3},
};

constexpr UseRow kOtherUse{"other", 3.5f, 2};

const UseRow& useRow(std::string_view use) {
  for (const UseRow& row : kUseTable) {
    if (row.use == use) return row;
  }
  return kOtherUse;
}

struct Mapping {
  std::string_view from;
  std::string_view to;
};

constexpr Mapping kBuildingValues[] = {
    {"apartments", "residential"},
    {"residential", "residential"},
    {"dormitory", "residential"},
    {"terrace", "residential"},
    {"flats", "residential"},
    {"house", "house"},
    {"detached", "house"},
    {"semidetached_house", "house"},
    {"bungalow", "house"},
    {"cabin", "house"},
    {"farm", "house"},
    {"villa", "house"},
    {"hotel", "hotel"},
    {"motel", "hotel"},
    {"office", "office"},
    {"commercial", "commercial"},
    {"retail", "retail"},
    {"supermarket", "retail"},
    {"kiosk", "retail"},
    {"shop", "retail"},
    {"mall", "retail"},
    {"industrial", "industrial"},
    {"factory", "industrial"},
    {"manufacture", "industrial"},
    {"works", "industrial"},
    {"warehouse", "warehouse"},
    {"storage", "warehouse"},
    {"school", "school"},
    {"kindergarten", "school"},
    {"university", "university"},
    {"college", "university"},
    {"hospital", "hospital"},
    {"clinic", "clinic"},
    {"fire_station", "fire_station"},
    {"police", "police"},
    {"church", "religious"},
    {"cathedral", "religious"},
    {"chapel", "religious"},
    {"mosque", "religious"},
    {"synagogue", "religious"},
    {"temple", "religious"},
    {"religious", "religious"},
    {"shrine", "religious"},
    {"monastery", "religious"},
    {"civic", "civic"},
    {"public", "civic"},
    {"government", "civic"},
    {"townhall", "civic"},
    {"train_station", "transportation"},
    {"transportation", "transportation"},
    {"hangar", "transportation"},
    {"parking", "parking"},
    {"garage", "parking"},
    {"garages", "parking"},
    {"carport", "parking"},
    {"sports_centre", "sports"},
    {"stadium", "sports"},
    {"sports_hall", "sports"},
    {"grandstand", "sports"},
    {"roof", "roof"},
    {"shed", "shed"},
    {"construction", "construction"},
    {"static_caravan", "mobile_home"},
    {"hut", "shed"},
    {"greenhouse", "shed"},
    {"barn", "shed"},
    {"boathouse", "shed"},
    {"service", "service"},
    {"ventilation_shaft", "service"},
    {"guardhouse", "service"},
    {"mobile_home", "mobile_home"},
    {"pavilion", "sports"},
    {"tower", "tower"},
    {"bell_tower", "tower"},
    {"chimney", "tower"},
    {"water_tower", "tower"},
    {"minaret", "tower"},
};

constexpr Mapping kAmenityValues[] = {
    {"hospital", "hospital"},
    {"clinic", "clinic"},
    {"school", "school"},
    {"kindergarten", "school"},
    {"university", "university"},
    {"college", "university"},
    {"fire_station", "fire_station"},
    {"ambulance_station", "ambulance_station"},
    {"police", "police"},
    {"shelter", "shelter"},  // the stored value of a social facility that is a shelter
    {"place_of_worship", "religious"},
    {"townhall", "civic"},
    {"courthouse", "civic"},
    {"library", "civic"},
    {"community_centre", "civic"},
    {"arts_centre", "civic"},
    {"theatre", "commercial"},
    {"cinema", "commercial"},
    {"bank", "office"},
    {"restaurant", "retail"},
    {"cafe", "retail"},
    {"fast_food", "retail"},
    {"bar", "retail"},
    {"pub", "retail"},
    {"parking", "parking"},
    {"bus_station", "transportation"},
};

template <std::size_t N>
std::optional<std::string_view> lookup(const Mapping (&table)[N], std::string_view key) {
  for (const Mapping& m : table) {
    if (m.from == key) return m.to;
  }
  return std::nullopt;
}

bool residentialLike(std::string_view use) {
  return use == "residential" || use == "house" || use == "hotel" || use == "mobile_home";
}

enum class Family : std::uint8_t { None, W1, W2, S1, S2, C1, C2, C3, PC1, RM1, URM, MH, Wood, Masonry, Cladding };

StructuralType withHeightClass(Family family, int storeys) {
  const int lmh = storeys <= 3 ? 0 : (storeys <= 7 ? 1 : 2);  // steel and concrete: L 1-3, M 4-7, H 8+
  auto pick = [lmh](StructuralType l, StructuralType m, StructuralType h) { return lmh == 0 ? l : (lmh == 1 ? m : h); };
  switch (family) {
    case Family::W1:
      return StructuralType::W1;
    case Family::W2:
      return StructuralType::W2;
    case Family::S1:
      return pick(StructuralType::S1L, StructuralType::S1M, StructuralType::S1H);
    case Family::S2:
      return pick(StructuralType::S2L, StructuralType::S2M, StructuralType::S2H);
    case Family::C1:
      return pick(StructuralType::C1L, StructuralType::C1M, StructuralType::C1H);
    case Family::C2:
      return pick(StructuralType::C2L, StructuralType::C2M, StructuralType::C2H);
    case Family::C3:
      return pick(StructuralType::C3L, StructuralType::C3M, StructuralType::C3H);
    case Family::PC1:
      return StructuralType::PC1;
    case Family::RM1:
      return storeys <= 3 ? StructuralType::RM1L : StructuralType::RM1M;
    case Family::URM:
      return storeys <= 2 ? StructuralType::URML : StructuralType::URMM;
    case Family::MH:
      return StructuralType::MH;
    case Family::None:
    case Family::Wood:
    case Family::Masonry:
    case Family::Cladding:
      break;
  }
  return StructuralType::Unknown;
}

/// building:structure values (free text in OSM; matched by the words they contain).
Family familyFromStructure(std::string_view s) {
  if (s.empty()) return Family::None;
  if (contains(s, "mobile") || contains(s, "manufactured")) return Family::MH;
  if (contains(s, "precast") || contains(s, "tilt")) return Family::PC1;
  if (contains(s, "reinforced_masonry") || contains(s, "reinforced masonry")) return Family::RM1;
  if (contains(s, "infill")) return Family::C3;
  if (contains(s, "shear")) return Family::C2;
  if (contains(s, "steel") || contains(s, "metal")) return contains(s, "brac") ? Family::S2 : Family::S1;
  if (contains(s, "concrete")) return Family::C1;
  if (contains(s, "wood") || contains(s, "timber")) return Family::Wood;
  if (contains(s, "masonry") || contains(s, "brick") || contains(s, "stone") || contains(s, "load_bearing") ||
      contains(s, "adobe"))
    return Family::Masonry;
  return Family::None;
}

/// building:material values (OSM wiki: the material of the facade; a hint of the structure).
Family familyFromMaterial(std::string_view m, std::string_view use, int storeys) {
  if (m.empty()) return Family::None;
  if (m == "wood" || m == "timber" || m == "timber_framing" || m == "bamboo" || m == "log") return Family::Wood;
  if (m == "precast_concrete") return Family::PC1;
  if (m == "concrete" || m == "reinforced_concrete") return residentialLike(use) ? Family::C2 : Family::C1;
  if (m == "steel" || m == "metal" || m == "aluminium" || m == "metal_plates")
    return storeys >= 4 ? Family::S1 : Family::S2;
  // Glass curtain walls hang on steel frames (offices) or concrete flat slabs with shear walls
  // (residential towers).
  if (m == "glass" || m == "mirror") return residentialLike(use) ? Family::C2 : Family::S1;
  if (m == "brick" || m == "stone" || m == "sandstone" || m == "limestone" || m == "marble" || m == "granite" ||
      m == "masonry" || m == "adobe" || m == "cement_block" || m == "concrete_block" || m == "clay") {
    // Bearing-wall masonry is rare above 7 storeys: a taller brick or stone building is a frame
    // clad in masonry (Manhattan's pre-war skyscrapers are steel frames behind brick and limestone).
    return storeys >= 8 ? Family::Cladding : Family::Masonry;
  }
  return Family::None;  // plaster, copper, vinyl, tiles...: finishes that say nothing of the structure
}

Family familyFromUse(std::string_view use, int storeys, int year) {
  const bool known = year > 0;
  if (use == "mobile_home") return Family::MH;
  if ((use == "house" || use == "shed") && storeys <= 3) return Family::W1;
  if (use == "roof") return Family::S2;  // canopies: light steel (HAZUS S3 is not in the enum)
  if (use == "parking") return Family::C1;
  if (storeys >= 8) return residentialLike(use) && (!known || year >= 1950) ? Family::C2 : Family::S1;
  if ((use == "industrial" || use == "warehouse" || use == "transportation") && storeys <= 3)
    return known && year >= 1950 ? Family::PC1 : Family::URM;
  if (known && year >= 1950) return residentialLike(use) ? Family::C2 : Family::C1;
  if (known && year >= 1900 && storeys >= 4) return Family::C3;
  return Family::URM;  // pre-1950 or unknown low/mid-rise: the older masonry stock
}

bool traditionalMasonryUse(std::string_view use) {
  return use == "religious" || use == "tower";
}

/// The rules that come before building:material (docs/attributes.md "Structural type", rules 2
/// and 3): buildings begun before 1890 stand on bearing walls whatever their height or cladding,
/// and so do religious buildings, towers and chimneys built before 1950 or undated. Wood stays wood
/// (W1/W2 by the caller); the rest is unreinforced masonry. None when neither rule applies. Sets
/// the matching AttributeNote bit in `notes` when given.
Family masonryEraFamily(std::string_view use, std::string_view material, int startYear, std::uint8_t* notes) {
  const bool known = startYear > 0;
  const bool preFrame = known && startYear < kFrameEraYear;
  const bool traditional = traditionalMasonryUse(use) && (!known || startYear < 1950);
  if (!preFrame && !traditional) return Family::None;
  if (notes != nullptr) *notes |= preFrame ? kNotePreFrameMasonry : kNoteTraditionalMasonry;
  const bool wood = material == "wood" || material == "timber" || material == "timber_framing" || material == "log";
  if (wood) return Family::Wood;
  return Family::URM;
}

std::string formatMeters(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f m", v);
  return buffer;
}

}  // namespace

std::string undergroundReason(std::string_view location, std::string_view layer, std::optional<double> heightM,
                              std::optional<double> levels) {
  location = trim(location);
  if (equalsIgnoreCase(location, "underground")) return "location=underground";
  const std::optional<double> layerNumber = parseMinLevel(layer);
  const bool aboveGround = (heightM && *heightM > 0.0) || (levels && *levels > 0.0);
  if (layerNumber && *layerNumber < 0.0 && !aboveGround) {
    return "layer=" + std::string(trim(layer)) + " with no height above ground";
  }
  return {};
}

std::vector<std::string> applyStoreyRules(BuildingAttributes& a, const StoreyEvidence& evidence) {
  std::vector<std::string> messages;
  const double storeyM = storeyHeightForUse(a.use);
  const double span = static_cast<double>(a.heightM) - static_cast<double>(a.minHeightM);
  auto storeysFor = [](double metres, double perStorey) {
    return static_cast<std::uint16_t>(std::clamp(std::round(metres / perStorey), 1.0, 999.0));
  };
  // 1. Religious buildings and towers: the nave or main body carries the storeys, not the spire.
  if (traditionalMasonryUse(a.use) && a.storeysSource == ValueSource::Inferred && evidence.mainBodyHeightM &&
      *evidence.mainBodyHeightM > static_cast<double>(a.minHeightM) &&
      *evidence.mainBodyHeightM < static_cast<double>(a.heightM)) {
    a.storeys = storeysFor(*evidence.mainBodyHeightM - static_cast<double>(a.minHeightM), storeyM);
    a.notes |= kNoteStoreysFromNave;
  }
  // 2. Tagged height and tagged levels in conflict: the height wins (docs/attributes.md: most
  //    heights in New York come from the city's measured roof heights; levels are typed by hand).
  //    A high-rise whose floors were counted keeps the count as nearly as the range allows: its
  //    height includes a spire, mast or crown. Religious buildings and towers are left to rule 1
  //    (their height is the spire's; their tagged levels win).
  if (a.heightSource == ValueSource::Tagged && a.storeysSource == ValueSource::Tagged && a.storeys > 0 && span > 0.0 &&
      !traditionalMasonryUse(a.use)) {
    const double perStorey = span / a.storeys;
    if (perStorey < kMinPlausibleStoreyM || perStorey > kMaxPlausibleStoreyM) {
      const std::uint16_t tagged = a.storeys;
      const bool highRise = perStorey > kMaxPlausibleStoreyM && tagged >= kHighRiseStoreys;
      a.storeys = highRise ? static_cast<std::uint16_t>(std::min(999.0, std::ceil(span / kMaxPlausibleStoreyM)))
                           : storeysFor(span, storeyM);
      a.storeysSource = ValueSource::Inferred;
      a.notes |= kNoteLevelsConflict;
      messages.push_back("height " + formatMeters(span) + " with " + std::to_string(tagged) + " tagged storeys gives " +
                         formatMeters(perStorey) + " storeys (" +
                         (perStorey < kMinPlausibleStoreyM ? "under 2.2 m" : "over 7 m") + "); " +
                         std::to_string(a.storeys) +
                         (highRise ? " storeys of at most 7 m inferred (the height includes a spire, mast or crown)"
                                   : " storeys inferred from the height"));
    }
  }
  // 3. Nineteenth-century buildings had tall floors.
  if (a.storeysSource == ValueSource::Inferred && (a.notes & kNoteStoreysFromNave) == 0 && a.startYear >= 1000 &&
      a.startYear < kFrameEraYear && storeyM < kOldStoreyHeightM) {
    a.storeys = storeysFor(span, kOldStoreyHeightM);
    a.notes |= kNoteOldStoreyHeight;
  }
  return messages;
}

std::optional<LengthUnit> parseLengthUnit(std::string_view name) {
  name = trim(name);
  if (equalsIgnoreCase(name, "m") || equalsIgnoreCase(name, "metres") || equalsIgnoreCase(name, "meters") ||
      equalsIgnoreCase(name, "metre") || equalsIgnoreCase(name, "meter"))
    return LengthUnit::Meters;
  if (equalsIgnoreCase(name, "ft") || equalsIgnoreCase(name, "feet") || equalsIgnoreCase(name, "foot"))
    return LengthUnit::Feet;
  return std::nullopt;
}

std::optional<double> parseLengthMeters(std::string_view text, LengthUnit plainUnit) {
  text = trim(text);
  const std::optional<double> number = takeNumber(text);
  if (!number) return std::nullopt;
  std::string_view rest = skipSpaces(text);
  if (rest.empty()) return plainUnit == LengthUnit::Feet ? *number * kMetersPerFoot : *number;
  if (equalsIgnoreCase(rest, "m") || equalsIgnoreCase(rest, "meter") || equalsIgnoreCase(rest, "meters") ||
      equalsIgnoreCase(rest, "metre") || equalsIgnoreCase(rest, "metres"))
    return *number;
  if (equalsIgnoreCase(rest, "cm")) return *number / 100.0;
  if (equalsIgnoreCase(rest, "ft") || equalsIgnoreCase(rest, "feet") || equalsIgnoreCase(rest, "foot"))
    return *number * kMetersPerFoot;
  if (isInchMark(rest)) return *number * kMetersPerInch;
  if (isFeetMark(rest)) {
    rest.remove_prefix(feetMarkSize(rest));
    rest = skipSpaces(rest);
    if (rest.empty()) return *number * kMetersPerFoot;
    const std::optional<double> inches = takeNumber(rest);
    if (!inches || !isInchMark(skipSpaces(rest))) return std::nullopt;
    return *number * kMetersPerFoot + *inches * kMetersPerInch;
  }
  return std::nullopt;
}

std::optional<double> parseLevels(std::string_view text) {
  text = trim(text);
  const std::optional<double> number = takeNumber(text);
  if (!number || !text.empty()) return std::nullopt;
  return number;
}

std::optional<double> parseMinLevel(std::string_view text) {
  text = trim(text);
  const bool negative = text.starts_with('-');
  if (negative) text.remove_prefix(1);
  const std::optional<double> number = parseLevels(text);
  if (!number) return std::nullopt;
  return negative ? -*number : *number;
}

std::optional<int> parseStartYear(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (!isDigit(text[i]) || (i > 0 && isDigit(text[i - 1]))) continue;
    std::size_t j = i;
    while (j < text.size() && isDigit(text[j])) ++j;
    if (j - i == 4) {
      const int year =
          (text[i] - '0') * 1000 + (text[i + 1] - '0') * 100 + (text[i + 2] - '0') * 10 + (text[i + 3] - '0');
      if (year >= 1000 && year <= 2100) return year;
    }
    i = j;
  }
  return std::nullopt;
}

std::string normalizeUse(std::string_view buildingTag, std::string_view amenity) {
  buildingTag = trim(buildingTag);
  const std::optional<std::string_view> fromBuilding = lookup(kBuildingValues, buildingTag);
  // A generic building value gives way to a telling amenity (building=yes + amenity=hospital), and
  // a medical building to what it is: building=hospital + amenity=clinic is an outpatient clinic
  // (the use and the facility category follow one rule: a "hospital" is an essential facility, a
  // "clinic" is not).
  amenity = trim(amenity);
  const bool generic = !fromBuilding || *fromBuilding == "commercial" || *fromBuilding == "civic" ||
                       (*fromBuilding == "hospital" && amenity == "clinic");
  if (generic) {
    if (const auto fromAmenity = lookup(kAmenityValues, amenity)) return std::string(*fromAmenity);
  }
  if (fromBuilding) return std::string(*fromBuilding);
  if (buildingTag.empty() || buildingTag == "yes") return "unknown";
  return "other";
}

float storeyHeightForUse(std::string_view use) {
  return useRow(use).storeyHeightM;
}

int defaultStoreysForUse(std::string_view use) {
  return useRow(use).defaultStoreys;
}

float defaultHeightForUse(std::string_view use) {
  const UseRow& row = useRow(use);
  return static_cast<float>(row.defaultStoreys) * row.storeyHeightM;
}

ResolvedHeights resolveHeights(const HeightTags& tags, std::string_view use, std::optional<double> fallbackHeightM) {
  constexpr double kMaxStoreys = 999.0;
  const double storeyM = storeyHeightForUse(use);
  ResolvedHeights out;
  const double minLevel = tags.minLevel ? std::max(0.0, *tags.minLevel) : 0.0;

  double minHeight = 0.0;
  if (tags.minHeightM) {
    minHeight = std::max(0.0, *tags.minHeightM);
  } else if (tags.minLevel) {
    minHeight = minLevel * storeyM;
  }

  double height = 0.0;
  const bool levelsUsable = tags.levels && *tags.levels > minLevel;
  if (tags.heightM && *tags.heightM > 0.0) {
    height = *tags.heightM;
    out.heightSource = ValueSource::Tagged;
  } else if (levelsUsable) {
    height = *tags.levels * storeyM;
  } else if (fallbackHeightM && *fallbackHeightM > 0.0) {
    height = *fallbackHeightM;
  } else {
    height = minHeight + defaultHeightForUse(use);
  }
  if (minHeight >= height) minHeight = 0.0;  // inconsistent tags: stand the part on the ground

  if (levelsUsable) {
    out.storeys = static_cast<std::uint16_t>(std::clamp(std::round(*tags.levels - minLevel), 1.0, kMaxStoreys));
    out.levelsFromGround = static_cast<std::uint16_t>(std::clamp(std::round(*tags.levels), 1.0, kMaxStoreys));
    out.storeysSource = ValueSource::Tagged;
  } else {
    out.storeys = static_cast<std::uint16_t>(std::clamp(std::round((height - minHeight) / storeyM), 1.0, kMaxStoreys));
    out.levelsFromGround = static_cast<std::uint16_t>(std::clamp(std::round(height / storeyM), 1.0, kMaxStoreys));
  }
  out.heightM = static_cast<float>(height);
  out.minHeightM = static_cast<float>(minHeight);
  return out;
}

StructuralType inferStructuralType(std::string_view use, float heightM, int storeys, std::string_view material,
                                   std::string_view structure, int startYear, bool* fromUse) {
  if (storeys <= 0) {
    storeys = heightM > 0.0f ? std::max(1, static_cast<int>(std::lround(heightM / 3.5f))) : 1;
  }
  const bool known = startYear > 0;
  auto resolve = [&](Family family) -> Family {
    switch (family) {
      case Family::Wood:
        return storeys <= 3 && (residentialLike(use) || use == "shed" || use == "unknown" || use == "other")
                   ? Family::W1
                   : Family::W2;
      case Family::Masonry:
        return known && startYear >= 1950 ? Family::RM1 : Family::URM;
      default:
        return family;
    }
  };
  Family family = resolve(familyFromStructure(structure));
  if (family == Family::None) family = resolve(masonryEraFamily(use, material, startYear, nullptr));
  if (family == Family::None) family = resolve(familyFromMaterial(material, use, storeys));
  const bool guessed = family == Family::None || family == Family::Cladding;
  if (guessed) family = familyFromUse(use, storeys, startYear);
  if (fromUse != nullptr) *fromUse = guessed;
  return withHeightClass(family, storeys);
}

CodeEra inferCodeEra(int startYear) {
  if (startYear < 1000) return CodeEra::Unknown;
  if (startYear < 1941) return CodeEra::PreCode;
  if (startYear <= 1975) return CodeEra::LowCode;
  if (startYear <= 1994) return CodeEra::ModerateCode;
  return CodeEra::HighCode;
}

void classifyImportance(BuildingAttributes& attributes, bool hasParts) {
  const std::string_view use = attributes.use;
  const std::string_view amenity = attributes.amenity;
  std::uint8_t reasons = kReasonNone;
  if (use == "hospital" || amenity == "hospital" || amenity == "clinic") reasons |= kReasonHospital;
  if (use == "fire_station" || amenity == "fire_station") reasons |= kReasonFireStation;
  if (use == "police" || amenity == "police") reasons |= kReasonPolice;
  if (use == "school" || use == "university" || amenity == "school" || amenity == "kindergarten" ||
      amenity == "college" || amenity == "university")
    reasons |= kReasonSchool;
  if (amenity == "community_centre" || amenity == "shelter") reasons |= kReasonShelter;
  if (attributes.heightM > kTallBuildingHeightM) reasons |= kReasonTall;
  if (hasParts) reasons |= kReasonComplex;
  attributes.importanceReasons = reasons;
  const FacilityCategory category = classifyFacility(attributes).category;
  attributes.importance =
      (facilityCategoryBit(category) & kCriticalCategories) != 0 ? Importance::Critical : Importance::General;
}

std::string normalizeFacility(std::string_view amenity, std::string_view emergency, std::string_view healthcare,
                              std::string_view socialFacility, std::string_view power, std::string_view shop,
                              std::string_view industrial) {
  amenity = trim(amenity);
  // OSM's amenity=shelter is a shelter against the weather (bus stops, gazebos, picnic roofs): no
  // facility. A shelter in the emergency-management sense is a social facility
  // (amenity=social_facility + social_facility=shelter, or the latter alone).
  if (amenity == "shelter") return "weather_shelter";
  if ((amenity.empty() || amenity == "social_facility") && trim(socialFacility) == "shelter") return "shelter";
  if (!amenity.empty()) return std::string(amenity);
  // In order of criticality: emergency response, medical care, hazardous, assembly.
  if (trim(emergency) == "ambulance_station") return "ambulance_station";
  if (trim(healthcare) == "hospital") return "hospital";
  if (trim(healthcare) == "clinic" || trim(healthcare) == "doctor") return "clinic";
  if (trim(power) == "plant") return "power_plant";
  if (trim(power) == "substation") return "substation";
  if (trim(industrial) == "chemical") return "chemical_works";
  if (trim(industrial) == "refinery" || trim(industrial) == "oil") return "refinery";
  if (trim(shop) == "mall") return "mall";
  return {};
}

void inferSeismicAttributes(BuildingAttributes& attributes, bool hasParts) {
  attributes.notes = static_cast<std::uint8_t>(attributes.notes & ~(kNotePreFrameMasonry | kNoteTraditionalMasonry));
  if (familyFromStructure(attributes.structure) == Family::None) {
    masonryEraFamily(attributes.use, attributes.material, attributes.startYear, &attributes.notes);
  }
  bool fromUse = false;
  attributes.structuralType =
      inferStructuralType(attributes.use, attributes.heightM, attributes.storeys, attributes.material,
                          attributes.structure, attributes.startYear, &fromUse);
  attributes.notes =
      static_cast<std::uint8_t>((attributes.notes & ~kNoteTypeFromUse) | (fromUse ? kNoteTypeFromUse : 0));
  attributes.codeEra = inferCodeEra(attributes.startYear);
  classifyImportance(attributes, hasParts);
}

std::string formatAddress(std::string_view houseNumber, std::string_view street, std::string_view postcode,
                          std::string_view city) {
  auto join = [](std::string_view a, std::string_view b, std::string_view separator) {
    std::string out(a);
    if (!a.empty() && !b.empty()) out += separator;
    out += b;
    return out;
  };
  const std::string streetPart = join(trim(houseNumber), trim(street), " ");
  const std::string placePart = join(trim(postcode), trim(city), " ");
  return join(streetPart, placePart, ", ");
}

}  // namespace qv::prep
