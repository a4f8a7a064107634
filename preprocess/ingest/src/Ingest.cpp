// readCity: reads every input into raw features (degrees, kept tags), then projects, cleans, parses
// the tags, attaches building:part features to their outlines and makes the CityModel.
// Projection and cleaning run on a few threads (each feature is independent); everything that
// decides between features (ids, parts) runs after, in input order, so the result is deterministic.
#include "qv/prep/Ingest.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <new>
#include <system_error>
#include <thread>
#include <unordered_map>

#include "RawCity.h"
#include "qv/prep/Attributes.h"
#include "qv/prep/Cleaning.h"
#include "qv/prep/Files.h"
#include "qv/prep/Projection.h"

namespace qv::prep {
namespace {

using detail::FeatureKind;
using detail::RawCity;
using detail::RawFeature;
using detail::WarningLog;

constexpr double kMaxSpanDegrees = 10.0;  ///< a city (or a few merged) fits in this
constexpr double kMaxHeightM = 1000.0;    ///< taller values are typos (the tallest building is 828 m)
constexpr double kMaxLevels = 300.0;      ///< more storeys than any building has: a typo
constexpr double kGridCellM = 64.0;       ///< cell size of the outline index used to find parts' owners
constexpr std::size_t kFeaturesPerThreadMin = 512;
constexpr std::size_t kPointsPerThreadMin = 4096;

const std::string kHeightKey = "height";
const std::string kMinHeightKey = "min_height";
const std::string kLevelsKey = "building:levels";
const std::string kStartDateKey = "start_date";

enum class InputKind : std::uint8_t { Osm, GeoJson, Unknown };

InputKind inputKind(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; });
  auto endsWith = [&](std::string_view suffix) { return name.ends_with(suffix); };
  if (endsWith(".osm") || endsWith(".osm.bz2") || endsWith(".osm.gz") || endsWith(".pbf") || endsWith(".o5m") ||
      endsWith(".opl"))
    return InputKind::Osm;
  if (endsWith(".geojson") || endsWith(".json")) return InputKind::GeoJson;
  return InputKind::Unknown;
}

struct Bounds {
  double minX = std::numeric_limits<double>::infinity();
  double minY = std::numeric_limits<double>::infinity();
  double maxX = -std::numeric_limits<double>::infinity();
  double maxY = -std::numeric_limits<double>::infinity();
  void add(glm::dvec2 p) {
    minX = std::min(minX, p.x);
    minY = std::min(minY, p.y);
    maxX = std::max(maxX, p.x);
    maxY = std::max(maxY, p.y);
  }
  void add(const Bounds& b) {
    minX = std::min(minX, b.minX);
    minY = std::min(minY, b.minY);
    maxX = std::max(maxX, b.maxX);
    maxY = std::max(maxY, b.maxY);
  }
  [[nodiscard]] bool empty() const { return !(minX <= maxX); }
  [[nodiscard]] bool contains(glm::dvec2 p) const { return p.x >= minX && p.x <= maxX && p.y >= minY && p.y <= maxY; }
};

struct Polygon {
  std::vector<glm::dvec2> points;
  std::vector<std::uint32_t> ringEnds;
  double areaM2 = 0.0;
  glm::dvec2 centroid{0.0, 0.0};
};

/// One feature after projection, cleaning and tag parsing.
struct Prepared {
  std::vector<Polygon> polygons;  ///< empty: dropped
  Bounds box;
  double areaM2 = 0.0;
  glm::dvec2 centroid{0.0, 0.0};
  HeightTags heights;
  std::string use;
  std::string facility;  ///< the stored amenity value (normalizeFacility), which the use follows too
  float roofHeightM = 0.0f;
  bool roofHeightTagged = false;
  int startYear = 0;
  std::uint16_t occupants = 0;       ///< given (0: not)
  float replacementValueUsd = 0.0f;  ///< given (0: not)
  bool zeroHeight = false;           ///< height=0 tagged on a building above ground (then inferred)
  std::string undergroundReason;     ///< not empty: underground, neither drawn nor analysed
};

struct WorkerOutput {
  DropCounts drops;
  WarningLog warnings;
};

/// A whole-string finite number ("120", "2.5e6"), or nullopt.
std::optional<double> plainNumber(const std::string& text) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [at, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || at != end || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// Parses the kept tags of one feature, warning (object, tag, value) about garbage.
void parseTags(const RawFeature& feature, Prepared& out, WarningLog& warnings) {
  const detail::RawTags& tags = feature.tags;
  auto warn = [&](const std::string& kind, const std::string& key, const std::string& value, const std::string& what) {
    warnings.add(kind, feature.id + ": " + key + "=" + value + " " + what);
  };
  // Warnings name the key as it appears in the input (GeoJSON property names are configurable);
  // the warning kinds keep the OSM names so that counts add up across formats.
  const IngestOptions* names = feature.propertyNames;
  const std::string& heightKey = names != nullptr ? names->heightProperty : kHeightKey;
  const std::string& minHeightKey = names != nullptr ? names->minHeightProperty : kMinHeightKey;
  const std::string& levelsKey = names != nullptr ? names->levelsProperty : kLevelsKey;
  const std::string& yearKey = names != nullptr ? names->yearProperty : kStartDateKey;
  auto length = [&](const std::string& kind, const std::string& key, const std::string& value,
                    double maxM) -> std::optional<double> {
    if (value.empty()) return std::nullopt;
    const std::optional<double> m = parseLengthMeters(value, feature.plainUnit);
    if (!m) {
      warn(kind + " not a length", key, value, "is not a length; inferred instead");
      return std::nullopt;
    }
    if (*m > maxM) {
      warn(kind + " out of range", key, value, "is out of range; inferred instead");
      return std::nullopt;
    }
    return m;
  };
  out.heights.heightM = length(kHeightKey, heightKey, tags.height, kMaxHeightM);
  out.undergroundReason = undergroundReason(tags.location, tags.layer, out.heights.heightM,
                                            tags.levels.empty() ? std::nullopt : parseLevels(tags.levels));
  if (out.heights.heightM && *out.heights.heightM <= 0.0) {
    // Underground buildings are left out whole (their height=0 is right); any other is told.
    if (out.undergroundReason.empty()) {
      warn("height out of range", heightKey, tags.height, "is not above the ground; inferred instead");
      out.zeroHeight = true;
    }
    out.heights.heightM.reset();
  }
  out.heights.minHeightM = length(kMinHeightKey, minHeightKey, tags.minHeight, kMaxHeightM);
  if (out.heights.heightM && out.heights.minHeightM && *out.heights.minHeightM >= *out.heights.heightM) {
    warn("min_height not below height", minHeightKey, tags.minHeight,
         "is not below " + heightKey + "=" + tags.height + "; the part stands on the ground");
    out.heights.minHeightM.reset();
  }
  if (!tags.levels.empty()) {
    const std::optional<double> levels = parseLevels(tags.levels);
    if (!levels) {
      warn("building:levels not a number", levelsKey, tags.levels, "is not a number; storeys inferred instead");
    } else if (*levels > kMaxLevels) {
      warn("building:levels out of range", levelsKey, tags.levels, "is out of range; storeys inferred instead");
    } else {
      out.heights.levels = levels;
    }
  }
  if (!tags.minLevel.empty()) {
    const std::optional<double> minLevel = parseMinLevel(tags.minLevel);
    if (!minLevel || *minLevel > kMaxLevels) {
      warn("building:min_level not a number", "building:min_level", tags.minLevel, "is not a number; ignored");
    } else {
      out.heights.minLevel = minLevel;
    }
  }
  if (const auto roof = length("roof:height", "roof:height", tags.roofHeight, kMaxHeightM)) {
    out.roofHeightM = static_cast<float>(*roof);
    out.roofHeightTagged = true;
  }
  if (!tags.startDate.empty()) {
    if (const std::optional<int> year = parseStartYear(tags.startDate)) {
      out.startYear = *year;
    } else {
      warn("start_date not a year", yearKey, tags.startDate, "has no year; the code era is unknown");
    }
  }
  // Occupants and replacement value (GeoJSON properties): whole people up to 65,535, dollars.
  if (!tags.occupants.empty()) {
    const std::optional<double> n = plainNumber(tags.occupants);
    if (n && *n >= 0.0 && *n <= 65535.0) {
      out.occupants = static_cast<std::uint16_t>(std::lround(*n));
    } else {
      warn("occupants not a count", names != nullptr ? names->occupantsProperty : "occupants", tags.occupants,
           "is not a number of people (0 to 65535); inferred from floor area and use instead");
    }
  }
  if (!tags.replacementValue.empty()) {
    const std::optional<double> v = plainNumber(tags.replacementValue);
    if (v && *v >= 0.0 && *v <= 1e12) {
      out.replacementValueUsd = static_cast<float>(*v);
    } else {
      warn("replacement value not a number", names != nullptr ? names->valueProperty : "replacement_value",
           tags.replacementValue, "is not an amount in USD; inferred from floor area and use instead");
    }
  }
  // The use follows from the same facility value the category does (normalizeFacility).
  out.facility = normalizeFacility(tags.amenity, tags.emergency, tags.healthcare, tags.socialFacility, tags.power,
                                   tags.shop, tags.industrial);
  out.use = feature.kind == FeatureKind::Building ? normalizeUse(tags.building, out.facility)
                                                  : normalizeUse(tags.buildingPart, out.facility);
}

/// Cleans and parses one feature (its points already projected in `table`).
void prepareFeature(RawFeature& feature, const std::vector<glm::dvec2>& table, Prepared& out, WorkerOutput& worker) {
  std::uint32_t ring = 0;
  for (const std::uint32_t polygonEnd : feature.polygonEnds) {
    Polygon polygon;
    const std::uint32_t first = ring == 0 ? 0 : feature.ringEnds[ring - 1];
    const std::uint32_t last = polygonEnd == 0 ? 0 : feature.ringEnds[polygonEnd - 1];
    polygon.points.resize(last - first);
    for (std::uint32_t i = first; i < last; ++i) polygon.points[i - first] = table[feature.points[i]];
    for (std::uint32_t r = ring; r < polygonEnd; ++r) polygon.ringEnds.push_back(feature.ringEnds[r] - first);
    ring = polygonEnd;
    if (const std::string reason = cleanPolygon(polygon.points, polygon.ringEnds, &worker.drops); !reason.empty()) {
      worker.drops.add(reason);
      continue;
    }
    polygon.areaM2 = polygonArea(polygon.points, polygon.ringEnds);
    polygon.centroid = polygonCentroid(polygon.points, polygon.ringEnds);
    for (std::uint32_t i = 0; i < polygon.ringEnds[0]; ++i) out.box.add(polygon.points[i]);
    out.polygons.push_back(std::move(polygon));
  }
  feature.points = {};  // the polygons hold the geometry from here on
  if (out.polygons.empty()) return;
  glm::dvec2 moment{0.0, 0.0};
  for (const Polygon& polygon : out.polygons) {
    out.areaM2 += polygon.areaM2;
    moment += polygon.centroid * polygon.areaM2;
  }
  out.centroid = out.areaM2 > 0.0 ? moment / out.areaM2 : out.polygons[0].centroid;
  parseTags(feature, out, worker.warnings);
}

/// Runs work(t, chunks) for t in [0, chunks) on up to `maxThreads` threads, the calling thread
/// included; chunks = min(maxThreads, max(1, wanted)). Returns chunks. If the system refuses a
/// thread, the calling thread runs that chunk itself. An exception thrown by a chunk (bad_alloc)
/// is rethrown here after every thread has joined.
template <typename Work>
unsigned parallelChunks(unsigned maxThreads, std::size_t wanted, const Work& work) {
  const auto chunks = static_cast<unsigned>(std::clamp<std::size_t>(wanted, 1, std::max(1u, maxThreads)));
  std::vector<std::exception_ptr> errors(chunks);
  auto guarded = [&](unsigned t) {
    try {
      work(t, chunks);
    } catch (...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  unsigned started = 1;
  try {
    for (unsigned t = 1; t < chunks; ++t) {
      pool.emplace_back(guarded, t);
      ++started;
    }
  } catch (const std::system_error&) {
    // No more threads: this thread does the remaining chunks.
  }
  guarded(0u);
  for (std::thread& thread : pool) thread.join();
  for (unsigned t = started; t < chunks; ++t) guarded(t);
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return chunks;
}

/// Outlines indexed by the grid cells their bounds cover.
class OutlineGrid {
 public:
  void insert(std::uint32_t feature, const Bounds& box) {
    const auto [x0, y0] = cell({box.minX, box.minY});
    const auto [x1, y1] = cell({box.maxX, box.maxY});
    for (std::int64_t y = y0; y <= y1; ++y) {
      for (std::int64_t x = x0; x <= x1; ++x) cells_[key(x, y)].push_back(feature);
    }
  }
  [[nodiscard]] const std::vector<std::uint32_t>* at(glm::dvec2 p) const {
    const auto [x, y] = cell(p);
    const auto it = cells_.find(key(x, y));
    return it == cells_.end() ? nullptr : &it->second;
  }

 private:
  static std::pair<std::int64_t, std::int64_t> cell(glm::dvec2 p) {
    return {static_cast<std::int64_t>(std::floor(p.x / kGridCellM)),
            static_cast<std::int64_t>(std::floor(p.y / kGridCellM))};
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffULL);
  }
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

std::uint16_t clampStoreys(double storeys) {
  return static_cast<std::uint16_t>(std::clamp(std::round(storeys), 1.0, 999.0));
}

/// The BuildingAttributes fields that come straight from the kept tags.
void fillIdentity(const RawFeature& feature, const Prepared& prepared, BuildingAttributes& a) {
  const detail::RawTags& tags = feature.tags;
  a.id = feature.id;
  a.name = tags.name;
  a.use = prepared.use;
  a.address = formatAddress(tags.houseNumber, tags.street, tags.postcode, tags.city);
  a.material = tags.material;
  a.structure = tags.structure;
  a.amenity = prepared.facility;
  a.startYear = static_cast<std::int16_t>(prepared.startYear);
  a.occupants = prepared.occupants;
  a.replacementValueUsd = prepared.replacementValueUsd;
  a.lod = 1;
  a.footprintAreaM2 = static_cast<float>(prepared.areaM2);
  a.centroidX = prepared.centroid.x;
  a.centroidY = prepared.centroid.y;
}

void addParts(Prepared& prepared, const RawFeature& feature, const ResolvedHeights& heights,
              const std::string& sourceId, Building& building) {
  for (Polygon& polygon : prepared.polygons) {
    BuildingPart part;
    part.points = std::move(polygon.points);
    part.ringEnds = std::move(polygon.ringEnds);
    part.minHeightM = heights.minHeightM;
    part.heightM = heights.heightM;
    part.roofShape = feature.tags.roofShape;
    part.roofHeightM = prepared.roofHeightM;
    part.sourceId = sourceId;
    building.parts.push_back(std::move(part));
  }
}

/// A building drawn from its own footprint (a plain outline, or a part without an outline).
Building makeSimpleBuilding(const RawFeature& feature, Prepared& prepared, WarningLog& warnings) {
  Building building;
  BuildingAttributes& a = building.attributes;
  fillIdentity(feature, prepared, a);
  const ResolvedHeights h = resolveHeights(prepared.heights, a.use);
  a.heightM = h.heightM;
  a.minHeightM = h.minHeightM;
  a.storeys = h.storeys;
  a.heightSource = h.heightSource;
  a.storeysSource = h.storeysSource;
  if (prepared.zeroHeight) a.notes |= kNoteZeroHeight;
  addParts(prepared, feature, h, feature.kind == FeatureKind::Part ? feature.id : std::string(), building);
  StoreyEvidence evidence;
  if (prepared.roofHeightTagged && prepared.heights.heightM) {
    evidence.mainBodyHeightM = *prepared.heights.heightM - static_cast<double>(prepared.roofHeightM);
  }
  for (const std::string& message : applyStoreyRules(a, evidence)) {
    warnings.add("height and levels in conflict", a.id + ": " + message);
  }
  inferSeismicAttributes(a, false);
  return building;
}

/// A part that is a spire, mast or antenna on top of a building, not storeys (docs/attributes.md,
/// "roof appendage"): man_made=mast|antenna|flagpole, man_made=tower with tower:type=communication,
/// building:part=spire|antenna|mast, or a part raised above the ground that is all roof with a
/// pointed shape (roof:shape pyramidal, cone, onion or spire, roof:height its whole height: the
/// Empire State Building's mast). One World Trade Center's spire is man_made=tower,
/// tower:type=communication.
bool isRoofAppendage(const detail::RawTags& tags, const ResolvedHeights& h, const Prepared& part) {
  const std::string_view manMade = tags.manMade;
  if (manMade == "mast" || manMade == "antenna" || manMade == "flagpole") return true;
  if (manMade == "tower" && tags.towerType == "communication") return true;
  const std::string_view partKind = tags.buildingPart;
  if (partKind == "spire" || partKind == "antenna" || partKind == "mast") return true;
  const std::string_view shape = tags.roofShape;
  const bool pointed = shape == "pyramidal" || shape == "cone" || shape == "onion" || shape == "spire";
  return pointed && part.roofHeightTagged && h.minHeightM > 0.0f &&
         part.roofHeightM >= (h.heightM - h.minHeightM) - 0.5f;
}

/// A building whose geometry is its parts (Simple 3D Buildings): the outline gives identity,
/// footprint and defaults; heights are the parts'. The structural height stops at the roof: parts
/// that are spires, masts or antennas (isRoofAppendage) are drawn but add no height or storeys.
Building makeBuildingWithParts(const RawFeature& outline, Prepared& prepared, const std::vector<std::uint32_t>& partIds,
                               std::deque<RawFeature>& features, std::vector<Prepared>& preparedParts,
                               WarningLog& warnings) {
  Building building;
  BuildingAttributes& a = building.attributes;
  fillIdentity(outline, prepared, a);
  float top = 0.0f;
  float appendageTop = 0.0f;  // the highest spire, mast or antenna part
  float bottom = std::numeric_limits<float>::infinity();
  ValueSource topSource = ValueSource::Inferred;
  std::optional<double> maxLevels = prepared.heights.levels;
  std::string tallestMaterial;
  std::string tallestStructure;
  double largestPartAreaM2 = -1.0;
  float largestPartHeightM = 0.0f;
  // An outline tagged building:part as well is one of its own parts (Simple 3D Buildings; 437
  // buildings of Lower Manhattan): a cathedral's nave under its spires, the lower storeys under a
  // rooftop addition. Without it the building would float on its rooftop part.
  const std::string_view outlinePart = outline.tags.buildingPart;
  if (!outlinePart.empty() && outlinePart != "no") {
    const ResolvedHeights h = resolveHeights(prepared.heights, a.use);
    top = h.heightM;
    topSource = h.heightSource;
    bottom = h.minHeightM;
    largestPartAreaM2 = prepared.areaM2;
    largestPartHeightM = h.heightM;
    addParts(prepared, outline, h, outline.id, building);
  }
  for (const std::uint32_t p : partIds) {
    Prepared& part = preparedParts[p];
    const std::string& partUse = part.use == "unknown" ? a.use : part.use;
    const ResolvedHeights h = resolveHeights(part.heights, partUse, prepared.heights.heightM);
    if (isRoofAppendage(features[p].tags, h, part)) {
      appendageTop = std::max(appendageTop, h.heightM);
      addParts(part, features[p], h, features[p].id, building);
      continue;
    }
    if (part.areaM2 > largestPartAreaM2) {
      largestPartAreaM2 = part.areaM2;
      largestPartHeightM = h.heightM;
    }
    if (h.heightM > top) {
      top = h.heightM;
      topSource = h.heightSource;
      tallestMaterial = features[p].tags.material;
      tallestStructure = features[p].tags.structure;
    }
    bottom = std::min(bottom, h.minHeightM);
    if (h.storeysSource == ValueSource::Tagged && part.heights.levels)
      maxLevels = std::max(maxLevels.value_or(0.0), *part.heights.levels);
    addParts(part, features[p], h, features[p].id, building);
  }
  if (top <= 0.0f) top = appendageTop;  // only such parts: they are the building
  if (appendageTop > top) a.notes |= kNoteRoofAppendage;
  a.heightM = top;
  a.minHeightM = std::isfinite(bottom) ? bottom : 0.0f;
  a.heightSource =
      topSource == ValueSource::Tagged || prepared.heights.heightM ? ValueSource::Tagged : ValueSource::Inferred;
  const double storeyM = storeyHeightForUse(a.use);
  if (maxLevels && *maxLevels > 0.0) {
    // Levels count from the ground (S3DB); a building floating above it starts that many higher.
    const double levelsBelow = std::round(a.minHeightM / storeyM);
    a.storeys = clampStoreys(*maxLevels - levelsBelow);
    a.storeysSource = ValueSource::Tagged;
  } else {
    a.storeys = clampStoreys((a.heightM - a.minHeightM) / storeyM);
    a.storeysSource = ValueSource::Inferred;
  }
  if (a.material.empty()) a.material = tallestMaterial;
  if (a.structure.empty()) a.structure = tallestStructure;
  if (prepared.zeroHeight) a.notes |= kNoteZeroHeight;
  // The main body: the outline's own height under taller parts (a cathedral's nave under its
  // spires), else the largest part's.
  StoreyEvidence evidence;
  evidence.mainBodyHeightM = prepared.heights.heightM ? *prepared.heights.heightM : double{largestPartHeightM};
  for (const std::string& message : applyStoreyRules(a, evidence)) {
    warnings.add("height and levels in conflict", a.id + ": " + message);
  }
  inferSeismicAttributes(a, true);
  return building;
}

std::string describeDrops(const DropCounts& drops) {
  std::string text;
  for (const auto& [reason, n] : drops.byReason) {
    if (!text.empty()) text += ", ";
    text += reason + " " + std::to_string(n);
  }
  return text.empty() ? "none" : text;
}

std::string joinPaths(const std::vector<std::string>& paths) {
  std::string text;
  for (const std::string& p : paths) {
    if (!text.empty()) text += ", ";
    text += p;
  }
  return text;
}

/// Projects the ground features read (degrees) into `out` (city frame) with the buildings'
/// projection: through `grid` inside its box, exactly elsewhere. A shape with a point farther
/// than kMaxSpanDegrees from the origin (where the projection is not the city's any more) or not
/// a longitude/latitude is skipped as "outside-projection".
void projectGround(const detail::RawGround& raw, const CityProjection& projection,
                   const std::optional<ProjectionGrid>& grid, const Bounds& gridBox, GroundFeatures& out) {
  out.skipped = raw.skipped;
  std::vector<glm::dvec2> xy(raw.points.size());
  std::vector<bool> valid(raw.points.size());
  const double lon0 = projection.originLon();
  const double lat0 = projection.originLat();
  auto usable = [&](glm::dvec2 p) {
    return validLonLat(p.x, p.y) && std::abs(p.y) < 90.0 && std::abs(p.x - lon0) <= kMaxSpanDegrees &&
           std::abs(p.y - lat0) <= kMaxSpanDegrees;
  };
  auto project = [&](glm::dvec2 p) {
    return grid && gridBox.contains(p) ? grid->forward(p.x, p.y) : projection.forward(p.x, p.y);
  };
  for (std::size_t i = 0; i < raw.points.size(); ++i) {
    valid[i] = usable(raw.points[i]);
    if (valid[i]) xy[i] = project(raw.points[i]);
  }
  auto allValid = [&](std::uint32_t begin, std::uint32_t end) {
    for (std::uint32_t i = begin; i < end; ++i) {
      if (!valid[i]) {
        ++out.skipped["outside-projection"];
        return false;
      }
    }
    return true;
  };
  auto range = [&](std::uint32_t begin, std::uint32_t end) {
    return std::vector<glm::dvec2>(xy.begin() + begin, xy.begin() + end);
  };
  out.lines.reserve(out.lines.size() + raw.lines.size());
  for (const detail::RawGround::Line& line : raw.lines) {
    if (!allValid(line.begin, line.end)) continue;
    out.lines.push_back({line.groundClass, range(line.begin, line.end), line.widthM, line.name, line.rank});
  }
  out.areas.reserve(out.areas.size() + raw.areas.size());
  for (const detail::RawGround::Area& area : raw.areas) {
    if (area.ringEnds.empty() || !allValid(area.begin, area.ringEnds.back())) continue;
    GroundArea a;
    a.groundClass = area.groundClass;
    a.name = area.name;
    a.rank = area.rank;
    std::uint32_t begin = area.begin;
    for (const std::uint32_t end : area.ringEnds) {
      a.rings.push_back(range(begin, end));
      begin = end;
    }
    out.areas.push_back(std::move(a));
  }
  for (const detail::RawGround::Place& place : raw.places) {
    if (!usable(place.lonLat)) {
      ++out.skipped["outside-projection"];
      continue;
    }
    out.places.push_back({place.kind, project(place.lonLat), place.name, place.rank});
  }
  for (const auto& [begin, end] : raw.coastlines) {
    if (allValid(begin, end)) out.coastlines.push_back(range(begin, end));
  }
  for (const detail::RawGround::Boundary& b : raw.boundaries) {
    if (b.ringEnds.empty() || !allValid(b.begin, b.ringEnds.back())) continue;
    GroundBoundary boundary{b.name, b.source, b.fineness, {}};
    std::uint32_t begin = b.begin;
    for (const std::uint32_t end : b.ringEnds) {
      boundary.rings.push_back(range(begin, end));
      begin = end;
    }
    out.boundaries.push_back(std::move(boundary));
  }
}

Result<CityModel> readCityOrThrow(const std::vector<std::string>& inputPaths, const IngestOptions& options,
                                  IngestStats* statsOut) {
  using Clock = std::chrono::steady_clock;
  const auto started = Clock::now();
  IngestStats stats;
  if (inputPaths.empty()) return fail("no input files");
  const std::optional<LengthUnit> plainUnit = parseLengthUnit(options.heightUnit);
  if (!plainUnit) return fail("height unit \"" + options.heightUnit + "\" is neither \"m\" nor \"ft\"");
  if (options.originLonLat) {
    const auto [lon, lat] = *options.originLonLat;
    if (!validLonLat(lon, lat) || std::abs(lat) >= 90.0)
      return fail("origin " + std::to_string(lon) + "," + std::to_string(lat) +
                  " is not a longitude,latitude in degrees");
  }

  // ---- Read every input into raw features.
  RawCity raw;
  std::size_t geojsonOrdinal = 0;
  for (const std::string& path : inputPaths) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) return fail(path + ": no such file");
    if (std::filesystem::is_directory(status)) return fail(path + ": is a directory, not a file");
    Status read;
    switch (inputKind(path)) {
      case InputKind::Osm:
        read = detail::readOsmFile(path, options, raw, stats);
        break;
      case InputKind::GeoJson:
        read = detail::readGeoJsonFile(path, options, *plainUnit, geojsonOrdinal++, raw, stats);
        break;
      case InputKind::Unknown:
        return fail(path + ": unknown input format (expected .osm, .osm.bz2, .osm.gz, .osm.pbf, .geojson or .json)");
    }
    if (!read) return fail(read.error());
  }
  const auto readDone = Clock::now();
  stats.readSeconds = std::chrono::duration<double>(readDone - started).count();

  std::deque<RawFeature>& features = raw.features;
  if (features.empty()) {
    return fail("no buildings in " + joinPaths(inputPaths) + " (read " + std::to_string(stats.osmWays) +
                " building ways, " + std::to_string(stats.osmRelations) + " building relations, " +
                std::to_string(stats.geojsonFeatures) + " GeoJSON features; dropped: " + describeDrops(raw.drops) +
                ")");
  }

  // ---- Bounds in degrees, sanity of the coordinates, the projection.
  std::vector<glm::dvec2>& points = raw.points.points;
  Bounds lonLat;
  for (const glm::dvec2& p : points) lonLat.add(p);
  if (lonLat.empty()) return fail("no building geometry in " + joinPaths(inputPaths));
  if (lonLat.maxX - lonLat.minX > kMaxSpanDegrees || lonLat.maxY - lonLat.minY > kMaxSpanDegrees) {
    std::size_t west = 0;
    std::size_t east = 0;
    std::size_t south = 0;
    std::size_t north = 0;
    for (std::size_t i = 0; i < features.size(); ++i) {
      for (const std::uint32_t index : features[i].points) {
        const glm::dvec2 p = points[index];
        if (p.x == lonLat.minX) west = i;
        if (p.x == lonLat.maxX) east = i;
        if (p.y == lonLat.minY) south = i;
        if (p.y == lonLat.maxY) north = i;
      }
    }
    return fail("the buildings of " + joinPaths(inputPaths) + " span " + std::to_string(lonLat.maxX - lonLat.minX) +
                " degrees of longitude and " + std::to_string(lonLat.maxY - lonLat.minY) +
                " of latitude (more than a city's 10): absurd coordinates in the extreme buildings " +
                features[west].id + " (west), " + features[east].id + " (east), " + features[south].id + " (south), " +
                features[north].id + " (north)");
  }
  const double originLon = options.originLonLat ? (*options.originLonLat)[0] : 0.5 * (lonLat.minX + lonLat.maxX);
  const double originLat = options.originLonLat ? (*options.originLonLat)[1] : 0.5 * (lonLat.minY + lonLat.maxY);
  if (std::abs(originLon - lonLat.minX) > kMaxSpanDegrees || std::abs(originLon - lonLat.maxX) > kMaxSpanDegrees ||
      std::abs(originLat - lonLat.minY) > kMaxSpanDegrees || std::abs(originLat - lonLat.maxY) > kMaxSpanDegrees) {
    return fail("origin " + std::to_string(originLon) + "," + std::to_string(originLat) +
                " is more than 10 degrees from the buildings of " + joinPaths(inputPaths));
  }
  const CityProjection projection(originLon, originLat);

  // ---- Project every point once, then clean and parse every feature (independent: a few threads).
  const unsigned maxThreads = options.threads > 0 ? options.threads : std::min(4u, usableCores());
  // Through a grid of exact values when the points outnumber its nodes (ProjectionGrid: under a
  // millimetre from the exact projection, measured), else one by one.
  const std::optional<ProjectionGrid> projectionGrid = ProjectionGrid::make(
      projection, lonLat.minX, lonLat.minY, lonLat.maxX, lonLat.maxY, points.size() / 8, maxThreads);
  parallelChunks(maxThreads, points.size() / kPointsPerThreadMin, [&](unsigned t, unsigned chunks) {
    const std::size_t end = points.size() * (t + 1) / chunks;
    for (std::size_t i = points.size() * t / chunks; i < end; ++i) {
      points[i] = projectionGrid ? projectionGrid->forward(points[i].x, points[i].y)
                                 : projection.forward(points[i].x, points[i].y);
    }
  });
  stats.points = points.size();
  std::vector<Prepared> prepared(features.size());
  std::vector<WorkerOutput> workers(maxThreads);
  const unsigned featureChunks =
      parallelChunks(maxThreads, features.size() / kFeaturesPerThreadMin, [&](unsigned t, unsigned chunks) {
        const std::size_t end = features.size() * (t + 1) / chunks;
        for (std::size_t i = features.size() * t / chunks; i < end; ++i)
          prepareFeature(features[i], points, prepared[i], workers[t]);
      });
  workers.resize(featureChunks);
  CityModel model;
  model.originLon = originLon;
  model.originLat = originLat;
  model.sources = inputPaths;
  model.drops = raw.drops;
  WarningLog warnings = raw.warnings;
  for (const WorkerOutput& w : workers) {
    for (const auto& [reason, n] : w.drops.byReason) model.drops.add(reason, n);
    warnings.append(w.warnings);
  }

  // ---- Ids: the first building of an id wins (an object in two merged extracts is one building).
  std::unordered_map<std::string_view, std::uint32_t> byId;
  byId.reserve(features.size());
  for (std::uint32_t i = 0; i < features.size(); ++i) {
    if (prepared[i].polygons.empty()) continue;
    if (!byId.emplace(features[i].id, i).second) {
      model.drops.add("duplicate-id");
      prepared[i].polygons.clear();
    }
  }

  // ---- Parts to outlines: type=building relations first, then containment of an interior point.
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> owner(features.size(), kNone);
  std::vector<std::vector<std::uint32_t>> partsOf(features.size());
  auto kept = [&](std::uint32_t i, FeatureKind kind) {
    return features[i].kind == kind && !prepared[i].polygons.empty();
  };
  auto findKept = [&](const std::string& id, FeatureKind kind) -> std::uint32_t {
    const auto it = byId.find(id);
    return it != byId.end() && kept(it->second, kind) ? it->second : kNone;
  };
  auto underground = [&](std::uint32_t i) { return !prepared[i].undergroundReason.empty(); };
  for (const detail::BuildingGroup& group : raw.groups) {
    const std::uint32_t outline = findKept(group.outlineId, FeatureKind::Building);
    if (outline == kNone) continue;
    for (const std::string& partId : group.partIds) {
      const std::uint32_t part = findKept(partId, FeatureKind::Part);
      if (part == kNone || owner[part] != kNone || underground(part)) continue;
      owner[part] = outline;
      ++stats.partsAttachedByRelation;
    }
  }
  OutlineGrid grid;
  bool anyPart = false;
  for (std::uint32_t i = 0; i < features.size(); ++i) {
    // An underground outline owns no part by containment (Penn Station lies under Madison Square
    // Garden's parts).
    if (kept(i, FeatureKind::Building) && !underground(i)) grid.insert(i, prepared[i].box);
    anyPart = anyPart || kept(i, FeatureKind::Part);
  }
  for (std::uint32_t i = 0; anyPart && i < features.size(); ++i) {
    if (!kept(i, FeatureKind::Part) || owner[i] != kNone || underground(i)) continue;
    const auto largest = std::max_element(prepared[i].polygons.begin(), prepared[i].polygons.end(),
                                          [](const Polygon& a, const Polygon& b) { return a.areaM2 < b.areaM2; });
    const std::optional<glm::dvec2> inside = interiorPoint(largest->points, largest->ringEnds);
    if (!inside) continue;
    const std::vector<std::uint32_t>* candidates = grid.at(*inside);
    if (candidates == nullptr) continue;
    double bestArea = std::numeric_limits<double>::infinity();
    for (const std::uint32_t c : *candidates) {
      if (!prepared[c].box.contains(*inside) || prepared[c].areaM2 >= bestArea) continue;
      for (const Polygon& polygon : prepared[c].polygons) {
        if (pointInPolygon(*inside, polygon.points, polygon.ringEnds)) {
          owner[i] = c;
          bestArea = prepared[c].areaM2;
          break;
        }
      }
    }
  }
  for (std::uint32_t i = 0; i < features.size(); ++i) {
    if (owner[i] != kNone) partsOf[owner[i]].push_back(i);
  }

  // ---- Buildings, in input order.
  model.buildings.reserve(byId.size());
  for (std::uint32_t i = 0; i < features.size(); ++i) {
    if (prepared[i].polygons.empty()) continue;
    if (underground(i) && (features[i].kind == FeatureKind::Building || owner[i] == kNone)) {
      // Not drawn above ground and not analysed; counted (summary, manifest, `info`) and named.
      model.excluded["underground"] += 1;
      warnings.add("underground",
                   features[i].id + ": " + prepared[i].undergroundReason + ": underground, neither drawn nor analysed");
      continue;
    }
    if (features[i].kind == FeatureKind::Building) {
      if (partsOf[i].empty()) {
        model.buildings.push_back(makeSimpleBuilding(features[i], prepared[i], warnings));
      } else {
        stats.partsAttached += partsOf[i].size();
        model.buildings.push_back(
            makeBuildingWithParts(features[i], prepared[i], partsOf[i], features, prepared, warnings));
      }
    } else if (owner[i] == kNone) {
      ++stats.partsStandalone;
      model.buildings.push_back(makeSimpleBuilding(features[i], prepared[i], warnings));
    }
  }
  // ---- The ground, with the buildings' projection (its points never moved the origin).
  if (options.ground) {
    projectGround(raw.ground, projection, projectionGrid, lonLat, model.ground);
    raw.ground = {};
    stats.groundLines = model.ground.lines.size();
    stats.groundAreas = model.ground.areas.size();
    stats.groundPlaces = model.ground.places.size();
    stats.groundCoastlines = model.ground.coastlines.size();
    for (const auto& [reason, n] : model.ground.skipped) stats.groundSkipped += n;
  }
  model.warnings = std::move(warnings.messages);
  model.warningCounts = std::move(warnings.counts);
  stats.buildings = model.buildings.size();
  stats.buildSeconds = std::chrono::duration<double>(Clock::now() - readDone).count();
  if (statsOut != nullptr) *statsOut = stats;
  if (model.buildings.empty()) {
    return fail("no building left in " + joinPaths(inputPaths) +
                " after cleaning (dropped: " + describeDrops(model.drops) + ")");
  }
  return model;
}

}  // namespace

Result<CityModel> readCity(const std::vector<std::string>& inputPaths, const IngestOptions& options,
                           IngestStats* stats) {
  // The readers catch libosmium's and the file system's exceptions with their file and position;
  // what is left (out of memory in the standard library) must not escape either.
  try {
    return readCityOrThrow(inputPaths, options, stats);
  } catch (const std::bad_alloc&) {
    return fail("out of memory reading the city (" + joinPaths(inputPaths) + ")");
  } catch (const std::exception& e) {
    return fail("reading the city failed (" + joinPaths(inputPaths) + "): " + e.what());
  }
}

}  // namespace qv::prep
