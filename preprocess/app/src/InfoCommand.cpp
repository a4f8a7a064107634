// quakeview-prep info DIR [--json] [--building ID] [--verify]
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "CityFiles.h"
#include "Commands.h"
#include "Summary.h"
#include "qv/core/JsonWriter.h"
#include "qv/format/FacilityCategory.h"
#include "qv/format/GroundTile.h"
#include "qv/format/ResponseTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/prep/Cli.h"
#include "qv/prep/Consequences.h"
#include "qv/prep/Files.h"
#include "qv/prep/ResponseWriter.h"
#include "qv/seismic/TypeMixture.h"

namespace qv::prep {
namespace {

const char* const kUsage =
    "usage: quakeview-prep info DIR [--json] [--building ID] [--verify]\n"
    "  Summarizes a city directory: buildings, storeys, tagged and inferred heights, structural\n"
    "  types, tiles and bytes; after `response` or `import-response`, the motion used, buildings per\n"
    "  damage state (none, slight, moderate, extensive, complete, no_result) and whether the response\n"
    "  is older than the buildings (run `response` again after adding buildings), buildings without\n"
    "  a result counted by reason, and the buildings whose result is approximate with their residuals.\n"
    "  --json          print the same as one JSON object\n"
    "  --building ID   print one building (w123, r45, s7, g:12, cj:abc), with its response: damage\n"
    "                  state, peak drift ratio per storey, peak roof displacement, PGA; without a\n"
    "                  result, why; an approximate result (solver steps accepted unconverged), how far\n"
    "  The ground (the map under the city): its files, bytes, bytes per km2 and features by class.\n"
    "  --verify        decode and check every tile (and ground tile); exit 1 naming each bad one\n";

// Upper bounds (exclusive) of the storey histogram's buckets: 1, 2, 3, 4-5, 6-9, 10-19, 20-39, 40+.
constexpr std::array<int, 8> kStoreyBuckets = {2, 3, 4, 6, 10, 20, 40, 1 << 30};

std::string bucketName(std::size_t i) {
  const int lo = i == 0 ? 1 : kStoreyBuckets[i - 1];
  const int hi = kStoreyBuckets[i] - 1;
  if (i + 1 == kStoreyBuckets.size()) return std::to_string(lo) + "+";
  if (lo == hi) return std::to_string(lo);
  return std::to_string(lo) + "-" + std::to_string(hi);
}

constexpr std::uint64_t kMaxLod2Ids = 1000;

struct CitySummary {
  std::uint64_t buildings = 0;
  std::array<std::uint64_t, kStoreyBuckets.size()> storeys{};
  std::uint64_t heightTagged = 0, heightInferred = 0, storeysTagged = 0, storeysInferred = 0;
  std::uint64_t critical = 0, lod2 = 0;  // critical: facility category Essential or SchoolShelter
  std::array<std::uint64_t, static_cast<std::size_t>(FacilityCategory::Count)> facilities{};
  std::vector<std::string> lod2Ids;  // the first kMaxLod2Ids, in tile order
  double totalStoreys = 0;
  std::map<std::string, std::uint64_t> types, eras, uses;
  std::uint64_t typeMixtures = 0;  // types guessed from use and height: damage as Hazus type mixtures
};

// The building's attributes as fields of the object `w` is writing.
void writeBuildingJson(JsonWriter& w, const BuildingAttributes& a, const TileNode& node, const CityTile& tile) {
  w.field("id", a.id).field("name", a.name).field("use", a.use).field("address", a.address);
  w.field("height_m", a.heightM).field("height_source", valueSourceName(a.heightSource));
  w.field("storeys", static_cast<unsigned>(a.storeys)).field("storeys_source", valueSourceName(a.storeysSource));
  w.field("min_height_m", a.minHeightM).field("footprint_area_m2", a.footprintAreaM2);
  w.field("structural_type", structuralTypeCode(a.structuralType));
  w.field("structural_type_description", structuralTypeDescription(a.structuralType));
  // Where the type is a guess, the Hazus types its damage is the mixture of (TypeMixture.h).
  if (const seismic::TypeMixtureInfo m = seismic::buildingTypeMixture(a); !m.shares.empty()) {
    w.key("type_mixture").beginObject().field("source", seismic::kTypeMixtureSource);
    w.field("height_class", m.heightClass).field("substituted", m.substituted);
    w.key("shares").beginObject();
    for (const seismic::TypeShare& t : m.shares) w.field(t.code, t.share);
    w.endObject().endObject();
  } else {
    w.key("type_mixture").null();
  }
  w.field("code_era", codeEraName(a.codeEra)).field("importance", importanceName(a.importance));
  w.key("importance_reasons").beginArray();
  for (const std::string_view name : importanceReasonNames(a.importanceReasons)) w.value(name);
  w.endArray();
  const FacilityClass facility = classifyFacility(a);
  w.field("facility", facilityCategoryName(facility.category)).field("facility_kind", facility.kind);
  w.field("lod", static_cast<unsigned>(a.lod));
  w.field("start_year", static_cast<int>(a.startYear)).field("material", a.material).field("structure", a.structure);
  w.field("amenity", a.amenity);
  w.key("attribute_notes").beginArray();  // why values were inferred (docs/attributes.md)
  for (const std::string_view name : attributeNoteNames(a.notes)) w.value(name);
  w.endArray();
  w.field("x_m", a.centroidX + tile.originX).field("y_m", a.centroidY + tile.originY);
  w.field("tile", node.key());
}

// A LOD2 building's model as the tile's MESH section stores it: "lod2": {source, vertex and
// triangle counts}, or null.
void writeMeshJson(JsonWriter& w, const CityTile& tile, std::size_t buildingIndex) {
  for (const TileMesh& m : tile.meshes) {
    if (m.building != buildingIndex) continue;
    w.key("lod2").beginObject();
    w.field("source", meshSourceName(m.source));
    w.field("vertices_before", std::uint64_t{m.verticesBefore});
    w.field("vertices", static_cast<std::uint64_t>(m.positions.size()));
    w.field("triangles", static_cast<std::uint64_t>(m.triangles.size() / 3));
    w.field("far_triangles", static_cast<std::uint64_t>(m.farTriangles.size() / 3));
    w.endObject();
    return;
  }
  w.key("lod2").null();
}

// The ground layer's figures: the area its leaf cells with a file cover and its bytes per km² of it.
struct GroundFigures {
  double areaKm2 = 0.0;
  double bytesPerKm2 = 0.0;
};

GroundFigures groundFigures(const GroundLayer& g) {
  GroundFigures f;
  if (g.levels == 0 || g.size <= 0.0) return f;
  const double leafSideM = g.size / std::ldexp(1.0, g.levels - 1);
  std::uint64_t leaves = 0;
  for (const GroundNode& n : g.nodes) leaves += n.level + 1 == g.levels ? 1 : 0;
  f.areaKm2 = static_cast<double>(leaves) * leafSideM * leafSideM / 1e6;
  if (f.areaKm2 > 0.0) f.bytesPerKm2 = static_cast<double>(g.bytes) / f.areaKm2;
  return f;
}

// "ground": {...}, or null when the city has no ground layer (--no-ground, or made before it).
void writeGroundJson(JsonWriter& w, const std::optional<GroundLayer>& ground) {
  if (!ground) {
    w.key("ground").null();
    return;
  }
  const GroundLayer& g = *ground;
  const GroundFigures f = groundFigures(g);
  w.key("ground").beginObject();
  w.field("files", static_cast<std::uint64_t>(g.nodes.size())).field("bytes", g.bytes);
  w.field("levels", static_cast<unsigned>(g.levels)).field("size_m", g.size);
  w.field("area_km2", f.areaKm2).field("bytes_per_km2", f.bytesPerKm2);
  w.key("features").beginObject();  // by class name, and "labels"
  for (const auto& [k, n] : g.features) w.field(k, n);
  w.endObject();
  w.key("skipped").beginObject();  // left out of the input, by reason
  for (const auto& [k, n] : g.skipped) w.field(k, n);
  w.endObject();
  w.endObject();
}

void printGround(const std::optional<GroundLayer>& ground) {
  if (!ground) {
    std::printf("ground      none (made with --no-ground, or before cities had one)\n");
    return;
  }
  const GroundLayer& g = *ground;
  if (g.nodes.empty()) {
    std::printf("ground      empty: the input has no streets, water or open land\n");
  } else {
    const GroundFigures f = groundFigures(g);
    std::printf("ground      %zu files in %u levels, %s, %s per km2 (%.2f km2 of leaf cells)\n", g.nodes.size(),
                static_cast<unsigned>(g.levels), humanBytes(g.bytes).c_str(),
                humanBytes(static_cast<std::uint64_t>(std::llround(f.bytesPerKm2))).c_str(), f.areaKm2);
  }
  if (!g.features.empty()) {
    std::printf("           ");
    for (const auto& [k, n] : g.features) std::printf(" %s: %llu;", k.c_str(), static_cast<unsigned long long>(n));
    std::printf("\n");
  }
  if (!g.skipped.empty()) {
    std::printf("            left out:");
    for (const auto& [k, n] : g.skipped) std::printf(" %s %llu;", k.c_str(), static_cast<unsigned long long>(n));
    std::printf("\n");
  }
}

constexpr const char* kDamageKeys[6] = {"none", "slight", "moderate", "extensive", "complete", "no_result"};

// Buildings per damage state as the response recorded them; buildings the response does not know
// (added since, or no response at all) count as no_result, so the counts sum to `buildings`.
std::array<std::uint64_t, 6> damageCounts(const Tileset& t, std::uint64_t buildings) {
  std::array<std::uint64_t, 6> counts{};
  if (t.response) {
    for (std::size_t k = 0; k < 6; ++k) counts[k] = t.response->damageStates[k];
  }
  std::uint64_t sum = 0;
  for (std::uint64_t c : counts) sum += c;
  if (sum < buildings) counts[5] += buildings - sum;
  return counts;
}

// One building's response from its tile's summary (nullopt: no response for that tile).
struct BuildingResponseView {
  BuildingResponse summary;
  std::vector<float> storeyPeakDrift;
  std::vector<StoreySpread> storeySpread;  ///< empty when the summary has none
  std::optional<BuildingScaling> scaling;
  std::optional<BuildingSite> site;  ///< the shaking field at the site (with or without a result)
  std::optional<BuildingSpread> spread;
  std::optional<BuildingLoss> loss;
};

// "site_shaking": the field's values at the building (null where the field gives none).
void writeSiteJson(JsonWriter& w, const std::optional<BuildingSite>& site) {
  if (!site || !site->given()) {
    w.key("site_shaking").null();
    return;
  }
  w.key("site_shaking").beginObject().field("source", siteSourceName(site->source));
  w.field("pga_g", site->pgaG).field("pgv_cms", site->pgvCmS);
  w.field("psa03_g", site->psa03G).field("psa10_g", site->psa10G).field("psa30_g", site->psa30G);
  w.field("mmi", site->mmi).field("vs30_mps", site->vs30Mps).endObject();
}

// "  shaking at the site (ShakeMap): PGA 0.304 g, PGV 6.9 cm/s, ..." (what the field gives).
void printSite(const std::optional<BuildingSite>& site) {
  if (!site || !site->given()) return;
  std::printf("  shaking at the site (%s): %s\n", std::string(siteSourceLabel(site->source)).c_str(),
              siteShakingText(*site).c_str());
}

void printBuildingLoss(const BuildingResponseView& r);

constexpr const char* kStateNames[5] = {"none", "slight", "moderate", "extensive", "complete"};

void writeProbabilities(JsonWriter& w, std::string_view key, const float (&p)[5]) {
  w.key(key).beginObject();
  for (std::size_t k = 0; k < 5; ++k) w.field(kStateNames[k], p[k]);
  w.endObject();
}

// The building's spectral scaling, suite spread, HAZUS probabilities and consequences (when the
// response has them).
void writeBuildingLossJson(JsonWriter& w, const BuildingResponseView& r) {
  if (r.scaling) {
    w.key("spectral_scaling").beginObject();
    for (int d = 0; d < 2; ++d) {
      w.key(d == 0 ? "x" : "y").beginObject();
      w.field("period_s", r.scaling->periodS[d]).field("target_sa_g", r.scaling->targetSaG[d]);
      w.field("record_sa_g", r.scaling->recordSaG[d]).field("scale", r.scaling->scale[d]);
      w.endObject();
    }
    w.endObject();
  }
  if (r.spread) {
    w.key("suite").beginObject();
    w.field("records", static_cast<unsigned>(r.spread->records));
    w.field("shown_record", static_cast<unsigned>(r.spread->shownRecord));
    w.field("peak_drift_ratio_beta", r.spread->driftBeta);
    w.field("peak_floor_acceleration_beta", r.spread->accelerationBeta);
    w.endObject();
  }
  if (!r.storeySpread.empty()) {
    w.key("peak_drift_ratio_beta").beginArray();
    for (const StoreySpread& s : r.storeySpread) w.value(s.driftBeta);
    w.endArray();
    w.key("peak_floor_acceleration_per_floor_mps2").beginArray();
    for (const StoreySpread& s : r.storeySpread) w.value(s.accelerationMedianMs2);
    w.endArray();
  }
  if (!r.loss) return;
  const BuildingLoss& l = *r.loss;
  writeProbabilities(w, "damage_probabilities", l.structural);
  w.field("collapse_probability", l.collapse);
  w.field("expected_damage_state", l.expectedState());
  std::size_t likely = 0;
  for (std::size_t k = 1; k < 5; ++k) {
    if (l.structural[k] > l.structural[likely]) likely = k;
  }
  w.field("most_likely_damage_state", kStateNames[likely]);
  writeProbabilities(w, "non_structural_drift_probabilities", l.nonStructuralDrift);
  writeProbabilities(w, "non_structural_acceleration_probabilities", l.nonStructuralAcceleration);
  w.key("consequences").beginObject();
  w.field("occupants", l.occupants).field("occupants_inferred", (l.flags & kLossOccupantsInferred) != 0);
  w.key("injuries").beginObject();
  for (std::size_t k = 0; k < 4; ++k) w.field("severity_" + std::to_string(k + 1), l.injuries[k]);
  w.endObject();
  w.field("deaths", l.injuries[3]);
  w.field("replacement_value_usd", l.replacementValueUsd).field("value_inferred", (l.flags & kLossValueInferred) != 0);
  w.field("repair_cost_usd", l.repairCostUsd).field("repair_time_days", l.repairTimeDays);
  w.key("tags").beginObject().field("green", l.tag[0]).field("yellow", l.tag[1]).field("red", l.tag[2]).endObject();
  w.endObject();
}
// The values tile summaries leave out when the city has its index (SITE, SUIT, SSPR, LOSS;
// docs/formats.md, DPRB), from the summary in the search index's order.
Status addIndexValues(const std::string& dir, const Tileset& tileset, const std::string& id, BuildingResponseView& v) {
  if (!tileset.search || !tileset.response || !tileset.response->summaryIndex || tileset.responseOutOfDate()) return {};
  auto searchBytes = readFile(dir + "/" + tileset.search->file);
  if (!searchBytes.ok()) return Error{searchBytes.error()};
  auto entries = decodeSearchIndex(*searchBytes, dir + "/" + tileset.search->file);
  if (!entries.ok()) return Error{entries.error()};
  std::size_t at = entries->size();
  for (std::size_t i = 0; i < entries->size(); ++i) {
    if ((*entries)[i].id == id) {
      at = i;
      break;
    }
  }
  if (at == entries->size()) return {};
  const std::string path = dir + "/" + tileset.response->summaryIndex->file;
  auto bytes = readFile(path);
  if (!bytes.ok()) return Error{bytes.error()};
  auto all = decodeResponseSummary(*bytes, path);
  if (!all.ok()) return Error{all.error()};
  if (at >= all->buildings.size()) return Error{path + ": fewer buildings than the search index"};
  const BuildingResponse& r = all->buildings[at];
  if (!v.site && at < all->sites.size()) v.site = all->sites[at];
  if (!v.spread && at < all->spread.size()) v.spread = all->spread[at];
  if (!v.loss && at < all->losses.size()) v.loss = all->losses[at];
  if (v.storeySpread.empty() && !all->storeySpread.empty() && r.storeys == v.summary.storeys &&
      r.firstStorey + r.storeys <= all->storeySpread.size()) {
    const auto first = all->storeySpread.begin() + static_cast<std::ptrdiff_t>(r.firstStorey);
    v.storeySpread.assign(first, first + static_cast<std::ptrdiff_t>(r.storeys));
  }
  return {};
}

Result<std::optional<BuildingResponseView>> loadBuildingResponse(const std::string& dir, const Tileset& tileset,
                                                                 const TileNode& node, const std::string& id,
                                                                 std::size_t index, std::size_t tileBuildings) {
  if (!node.response) return std::optional<BuildingResponseView>();
  auto bytes = readFile(dir + "/" + node.response->summaryFile);
  if (!bytes.ok()) return Error{bytes.error()};
  auto tile = decodeResponseSummary(*bytes, dir + "/" + node.response->summaryFile);
  if (!tile.ok()) return Error{tile.error()};
  if (tile->buildings.size() != tileBuildings || index >= tile->buildings.size()) {
    return std::optional<BuildingResponseView>();  // out of date: the tile changed since
  }
  BuildingResponseView v;
  v.summary = tile->buildings[index];
  const auto first = tile->storeyPeakDrift.begin() + static_cast<std::ptrdiff_t>(v.summary.firstStorey);
  v.storeyPeakDrift.assign(first, first + static_cast<std::ptrdiff_t>(v.summary.storeys));
  if (!tile->storeySpread.empty()) {
    const auto spread = tile->storeySpread.begin() + static_cast<std::ptrdiff_t>(v.summary.firstStorey);
    v.storeySpread.assign(spread, spread + static_cast<std::ptrdiff_t>(v.summary.storeys));
  }
  if (!tile->scaling.empty()) v.scaling = tile->scaling[index];
  if (!tile->sites.empty()) v.site = tile->sites[index];
  if (!tile->spread.empty()) v.spread = tile->spread[index];
  if (!tile->losses.empty()) v.loss = tile->losses[index];
  if (!v.loss || !v.site) {
    if (Status s = addIndexValues(dir, tileset, id, v); !s.ok()) return Error{s.error()};
  }
  return std::optional<BuildingResponseView>(std::move(v));
}

void printBuildingLoss(const BuildingResponseView& r) {
  if (r.scaling && r.scaling->periodS[0] > 0.0f) {
    for (int d = 0; d < 2; ++d) {
      const BuildingScaling& s = *r.scaling;
      if (s.scale[d] <= 0.0f) continue;
      std::printf("  %s: T1 %.2f s, target Sa(T1) %.3f g, record Sa(T1) %.3f g, scale %.3f\n", d == 0 ? "X" : "Y",
                  static_cast<double>(s.periodS[d]), static_cast<double>(s.targetSaG[d]),
                  static_cast<double>(s.recordSaG[d]), static_cast<double>(s.scale[d]));
    }
  }
  if (r.spread && r.spread->records > 1) {
    std::printf("  suite: %u records (history of record %u), peak drift beta %.2f, floor acceleration beta %.2f\n",
                r.spread->records, r.spread->shownRecord + 1, static_cast<double>(r.spread->driftBeta),
                static_cast<double>(r.spread->accelerationBeta));
  }
  if (!r.loss) return;
  const BuildingLoss& l = *r.loss;
  std::printf(
      "  P(damage state): none %.3f, slight %.3f, moderate %.3f, extensive %.3f, complete %.3f; collapse %.4f\n",
      static_cast<double>(l.structural[0]), static_cast<double>(l.structural[1]), static_cast<double>(l.structural[2]),
      static_cast<double>(l.structural[3]), static_cast<double>(l.structural[4]), static_cast<double>(l.collapse));
  std::printf("  occupants %.1f%s, injuries %.3f / %.3f / %.3f, deaths %.4f\n", static_cast<double>(l.occupants),
              (l.flags & kLossOccupantsInferred) != 0 ? " (inferred from floor area and use)" : "",
              static_cast<double>(l.injuries[0]), static_cast<double>(l.injuries[1]),
              static_cast<double>(l.injuries[2]), static_cast<double>(l.injuries[3]));
  std::printf("  repair cost %.0f USD of %.0f USD%s, repair time %.0f days; tags green %.2f, yellow %.2f, red %.2f\n",
              static_cast<double>(l.repairCostUsd), static_cast<double>(l.replacementValueUsd),
              (l.flags & kLossValueInferred) != 0 ? " (value inferred from floor area and use)" : "",
              static_cast<double>(l.repairTimeDays), static_cast<double>(l.tag[0]), static_cast<double>(l.tag[1]),
              static_cast<double>(l.tag[2]));
}

}  // namespace

int runInfo(const CommandArgs& argv) {
  std::string error;
  const auto args = Args::parse(argv, {{"json", false}, {"building"}, {"verify", false}, {"help", false}}, error);
  if (!args || args->has("help")) {
    if (!args) std::fprintf(stderr, "info: %s\n", error.c_str());
    std::fputs(kUsage, args ? stdout : stderr);
    return args ? kExitOk : kExitUsage;
  }
  if (args->positional().size() != 1) {
    std::fprintf(stderr, "info: give exactly one city directory\n%s", kUsage);
    return kExitUsage;
  }
  const std::string dir = args->positional()[0];
  const bool json = args->has("json");
  const auto tileset = loadTileset(dir);
  if (!tileset.ok()) {
    std::fprintf(stderr, "info: %s\n", tileset.error().c_str());
    return kExitDataError;
  }
  const Tileset& t = *tileset;

  if (args->has("verify")) {
    std::uint64_t bad = 0, checked = 0;
    for (const TileNode& node : t.nodes) {
      ++checked;
      const auto tile = loadCityTile(dir, node);
      if (!tile.ok()) {
        ++bad;
        std::fprintf(stderr, "BAD %s: %s\n", node.key().c_str(), tile.error().c_str());
      } else if (tile->buildings.size() != node.buildings) {
        ++bad;
        std::fprintf(stderr, "BAD %s: %zu buildings, the manifest says %u\n", node.key().c_str(),
                     tile->buildings.size(), node.buildings);
      }
    }
    if (t.ground) {
      for (const GroundNode& node : t.ground->nodes) {
        ++checked;
        auto bytes = loadCityFile(dir, CityFile{node.file, node.bytes, node.crc32});
        if (!bytes.ok()) {
          ++bad;
          std::fprintf(stderr, "BAD %s: %s\n", node.file.c_str(), bytes.error().c_str());
          continue;
        }
        const auto tile = decodeGroundTile(*bytes, dir + "/" + node.file);
        if (!tile.ok()) {
          ++bad;
          std::fprintf(stderr, "BAD %s: %s\n", node.file.c_str(), tile.error().c_str());
        }
      }
    }
    if (t.districts) {
      // The city's own districts: as listed (size, CRC) and as the response reads them.
      ++checked;
      const std::string& file = t.districts->file.file;
      auto bytes = loadCityFile(dir, t.districts->file);
      auto districts =
          bytes.ok() ? parseDistricts(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()),
                                      dir + "/" + file)
                     : Result<Districts>(Error{bytes.error()});
      if (!districts.ok()) {
        ++bad;
        std::fprintf(stderr, "BAD %s: %s\n", file.c_str(), districts.error().c_str());
      } else if (districts->names.size() != t.districts->count) {
        ++bad;
        std::fprintf(stderr, "BAD %s: %zu districts, the manifest says %llu\n", file.c_str(), districts->names.size(),
                     static_cast<unsigned long long>(t.districts->count));
      }
    }
    if (bad > 0) {
      std::fprintf(stderr, "info: %llu of %llu tiles are bad\n", static_cast<unsigned long long>(bad),
                   static_cast<unsigned long long>(checked));
      return kExitDataError;
    }
    std::printf("ok: %llu tiles verified\n", static_cast<unsigned long long>(checked));
    return kExitOk;
  }

  if (const auto id = args->value("building")) {
    for (const TileNode& node : t.nodes) {
      if (node.coarse) continue;
      const auto tile = loadCityTile(dir, node);
      if (!tile.ok()) {
        std::fprintf(stderr, "info: %s\n", tile.error().c_str());
        return kExitDataError;
      }
      for (std::size_t index = 0; index < tile->buildings.size(); ++index) {
        const TileBuilding& b = tile->buildings[index];
        if (b.attributes.id != *id) continue;
        const BuildingAttributes& a = b.attributes;
        auto response = loadBuildingResponse(dir, t, node, *id, index, tile->buildings.size());
        if (!response.ok()) {
          std::fprintf(stderr, "info: %s\n", response.error().c_str());
          return kExitDataError;
        }
        const std::optional<BuildingResponseView>& r = *response;
        const bool hasResult = r && r->summary.source != ResponseSource::None;
        auto notes = loadResponseNotes(dir, t);
        if (!notes.ok()) {
          std::fprintf(stderr, "info: %s\n", notes.error().c_str());
          return kExitDataError;
        }
        // Why there is no result: the summary's reason, the notes' details.
        NoResultReason reason = r ? r->summary.noResultReason : NoResultReason::Unknown;
        std::string detail;
        for (const ResponseNotes::NoResult& n : notes->noResult) {
          if (n.id != a.id) continue;
          if (reason == NoResultReason::Unknown || reason == NoResultReason::None) reason = n.reason;
          detail = n.detail;
        }
        if (!t.response) detail = "no response yet";
        const bool approximate = hasResult && r->summary.approximate;
        const std::string damage(damageStateName(hasResult ? r->summary.damage : DamageState::NoResult));
        if (json) {
          JsonWriter w;
          w.beginObject();
          writeBuildingJson(w, a, node, *tile);
          writeMeshJson(w, *tile, index);
          w.field("damage_state", damage);
          w.field("response_source", responseSourceName(hasResult ? r->summary.source : ResponseSource::None));
          w.key("peak_drift_ratio").beginArray();
          if (hasResult) {
            for (float v : r->storeyPeakDrift) w.value(v);
          }
          w.endArray();
          if (hasResult) {
            w.field("peak_roof_displacement_m", r->summary.peakRoofDisplacementM);
            // pga_g (kept for scripts) is the record's: its peak after scaling, as record_pga_g says.
            w.field("pga_g", r->summary.pgaG).field("record_pga_g", r->summary.pgaG);
            w.field("peak_floor_acceleration_mps2", r->summary.peakFloorAccelerationMs2);
            w.field("residual_drift_ratio", r->summary.residualDriftRatio);
          } else {
            w.key("peak_roof_displacement_m").null();
            w.key("pga_g").null().key("record_pga_g").null();
          }
          writeSiteJson(w, r ? r->site : std::nullopt);
          if (hasResult) {
            w.key("no_result_reason").null();
            w.key("no_result_detail").null();
          } else {
            w.field("no_result_reason", noResultReasonName(reason));
            w.field("no_result_detail", detail.empty() ? std::string(noResultReasonDescription(reason)) : detail);
          }
          w.field("approximate", approximate);
          w.field("unconverged_steps", std::uint64_t{hasResult ? r->summary.unconvergedSteps : 0u});
          w.field("worst_residual_ratio", hasResult ? r->summary.worstResidualRatio : 0.0f);
          if (hasResult) writeBuildingLossJson(w, *r);
          w.field("response_out_of_date", t.responseOutOfDate());
          w.endObject();
          std::printf("%s\n", w.str().c_str());
        } else {
          std::printf("%s  %s\n", a.id.c_str(), a.name.empty() ? "(no name)" : a.name.c_str());
          std::printf("  use %s%s%s\n", a.use.c_str(), a.address.empty() ? "" : ", ", a.address.c_str());
          std::printf("  height %.1f m (%s), %u storeys (%s), base %.1f m, footprint %.0f m²\n",
                      static_cast<double>(a.heightM), std::string(valueSourceName(a.heightSource)).c_str(), a.storeys,
                      std::string(valueSourceName(a.storeysSource)).c_str(), static_cast<double>(a.minHeightM),
                      static_cast<double>(a.footprintAreaM2));
          std::printf("  %s (%s), %s, %s, LOD %u, tile %s\n", std::string(structuralTypeCode(a.structuralType)).c_str(),
                      std::string(structuralTypeDescription(a.structuralType)).c_str(),
                      std::string(codeEraName(a.codeEra)).c_str(), std::string(importanceName(a.importance)).c_str(),
                      a.lod, node.key().c_str());
          for (unsigned bit = 1; bit < 256; bit <<= 1) {
            if ((a.notes & bit) != 0) std::printf("  note: %s\n", std::string(attributeNoteText(bit)).c_str());
          }
          if (const seismic::TypeMixtureInfo m = seismic::buildingTypeMixture(a); !m.shares.empty()) {
            std::printf("  damage over Hazus types (%s, %s):", std::string(m.heightClass).c_str(),
                        std::string(seismic::kTypeMixtureSource).c_str());
            for (const seismic::TypeShare& share : m.shares) {
              std::printf(" %s %.0f %%", std::string(share.code).c_str(), 100 * share.share);
            }
            std::printf("\n");
          }
          if (r) printSite(r->site);
          if (hasResult) {
            std::printf("  damage %s (%s), peak drift %.4f, peak roof displacement %.3f m, record's PGA %.3f g\n",
                        damage.c_str(), std::string(responseSourceName(r->summary.source)).c_str(),
                        static_cast<double>(r->summary.peakDriftRatio),
                        static_cast<double>(r->summary.peakRoofDisplacementM), static_cast<double>(r->summary.pgaG));
            std::printf("  peak drift per storey (ground up):");
            for (float v : r->storeyPeakDrift) std::printf(" %.4f", static_cast<double>(v));
            std::printf("\n");
            if (approximate) {
              std::printf(
                  "  approximate: the solver did not converge at %u steps (accepted after splitting them), largest "
                  "relative residual %.2g\n",
                  r->summary.unconvergedSteps, static_cast<double>(r->summary.worstResidualRatio));
            }
            printBuildingLoss(*r);
          } else if (!t.response) {
            std::printf("  damage no_result (no response yet)\n");
          } else {
            std::printf("  damage no_result, reason %s: %s%s%s\n", std::string(noResultReasonName(reason)).c_str(),
                        std::string(noResultReasonDescription(reason)).c_str(), detail.empty() ? "" : "; ",
                        detail.c_str());
          }
          if (t.responseOutOfDate()) std::printf("  note: the response is older than the buildings\n");
        }
        return kExitOk;
      }
    }
    std::fprintf(stderr, "info: no building with id '%s' in %s\n", id->c_str(), dir.c_str());
    return kExitDataError;
  }

  CitySummary s;
  std::uint64_t leaves = 0, bytes = 0;
  int depth = 0;
  for (const TileNode& node : t.nodes) {
    bytes += node.bytes;
    depth = std::max(depth, static_cast<int>(node.level));
    if (node.coarse) continue;
    ++leaves;
    const auto tile = loadCityTile(dir, node);
    if (!tile.ok()) {
      std::fprintf(stderr, "info: %s\n", tile.error().c_str());
      return kExitDataError;
    }
    for (const TileBuilding& b : tile->buildings) {
      const BuildingAttributes& a = b.attributes;
      ++s.buildings;
      std::size_t bucket = 0;
      while (a.storeys >= kStoreyBuckets[bucket]) ++bucket;
      ++s.storeys[bucket];
      s.totalStoreys += a.storeys;
      (a.heightSource == ValueSource::Tagged ? s.heightTagged : s.heightInferred)++;
      (a.storeysSource == ValueSource::Tagged ? s.storeysTagged : s.storeysInferred)++;
      // Critical by facility category (never height or parts, which older tiles stored as critical).
      const FacilityCategory facility = classifyFacility(a).category;
      ++s.facilities[static_cast<std::size_t>(facility)];
      if ((facilityCategoryBit(facility) & kCriticalCategories) != 0) ++s.critical;
      if (a.lod == 2 && ++s.lod2 <= kMaxLod2Ids) s.lod2Ids.push_back(a.id);
      ++s.types[std::string(structuralTypeCode(a.structuralType))];
      if ((a.notes & kNoteTypeFromUse) != 0) ++s.typeMixtures;
      ++s.eras[std::string(codeEraName(a.codeEra))];
      ++s.uses[a.use.empty() ? "unknown" : a.use];
    }
  }
  const double meanStoreys = s.buildings > 0 ? s.totalStoreys / static_cast<double>(s.buildings) : 0.0;
  const std::array<std::uint64_t, 6> damage = damageCounts(t, s.buildings);
  auto notesResult = loadResponseNotes(dir, t);
  if (!notesResult.ok()) {
    std::fprintf(stderr, "info: %s\n", notesResult.error().c_str());
    return kExitDataError;
  }
  const ResponseNotes& notes = *notesResult;
  // Buildings without a result by reason; those the notes do not explain (responses written before
  // the notes existed, buildings added since) count as unknown.
  std::map<std::string, std::uint64_t> reasons;
  for (const ResponseNotes::NoResult& n : notes.noResult) ++reasons[std::string(noResultReasonName(n.reason))];
  if (notes.noResult.size() < damage[5]) reasons["unknown"] += damage[5] - notes.noResult.size();
  std::uint64_t unconvergedSteps = 0;
  for (const ResponseNotes::Approximate& n : notes.approximate) unconvergedSteps += n.unconvergedSteps;
  // The consequences' totals (responses with HAZUS losses).
  std::optional<seismic::ConsequenceTotals> consequences;
  if (t.response && t.response->consequences) {
    const std::string path = dir + "/" + t.response->consequences->file;
    auto text = readTextFile(path, 64ull << 20);
    if (!text.ok()) {
      std::fprintf(stderr, "info: %s\n", text.error().c_str());
      return kExitDataError;
    }
    auto parsedTotals = seismic::parseConsequences(*text, path);
    if (!parsedTotals.ok()) {
      std::fprintf(stderr, "info: %s\n", parsedTotals.error().c_str());
      return kExitDataError;
    }
    consequences = std::move(parsedTotals).value();
  }

  if (json) {
    JsonWriter w;
    w.beginObject();
    w.field("buildings", s.buildings).field("tiles", static_cast<std::uint64_t>(t.nodes.size()));
    w.field("leaf_tiles", leaves).field("depth", depth).field("bytes", bytes);
    w.key("origin").beginArray().value(t.originLon).value(t.originLat).endArray();
    w.field("projection", t.projection);
    w.key("bounds_m")
        .beginArray()
        .value(t.bounds.minX)
        .value(t.bounds.minY)
        .value(t.bounds.maxX)
        .value(t.bounds.maxY)
        .endArray();
    w.field("max_height_m", t.maxHeightM).field("mean_storeys", meanStoreys);
    w.key("storeys_histogram").beginObject();
    for (std::size_t i = 0; i < kStoreyBuckets.size(); ++i) w.field(bucketName(i), s.storeys[i]);
    w.endObject();
    w.key("height_source")
        .beginObject()
        .field("tagged", s.heightTagged)
        .field("inferred", s.heightInferred)
        .endObject();
    w.key("storeys_source")
        .beginObject()
        .field("tagged", s.storeysTagged)
        .field("inferred", s.storeysInferred)
        .endObject();
    w.key("structural_types").beginObject();
    for (const auto& [k, v] : s.types) w.field(k, v);
    w.endObject();
    w.field("type_mixture_buildings", s.typeMixtures);
    w.key("code_eras").beginObject();
    for (const auto& [k, v] : s.eras) w.field(k, v);
    w.endObject();
    w.key("uses").beginObject();
    for (const auto& [k, v] : s.uses) w.field(k, v);
    w.endObject();
    w.field("critical", s.critical).field("lod2", s.lod2);
    w.key("facility_categories").beginObject();  // buildings by FacilityCategory name
    for (std::size_t i = 0; i < s.facilities.size(); ++i) {
      w.field(facilityCategoryName(static_cast<FacilityCategory>(i)), s.facilities[i]);
    }
    w.endObject();
    w.key("lod2_ids").beginArray();  // which buildings have a detailed model (the first 1000)
    for (const std::string& id : s.lod2Ids) w.value(id);
    w.endArray();
    w.key("excluded").beginObject();  // read but neither drawn nor analysed, by reason
    for (const auto& [reason, n] : t.excluded) w.field(reason, n);
    w.endObject();
    w.field("buildings_revision", t.buildingsRevision);
    w.key("sources").beginArray();
    for (const std::string& src : t.sources) w.value(src);
    w.endArray();
    writeGroundJson(w, t.ground);
    // The city's own districts (made from its input; the response uses them without --districts).
    if (t.districts) {
      const DistrictsInfo& d = *t.districts;
      w.key("districts").beginObject();
      w.field("file", d.file.file).field("count", d.count).field("source", d.source).field("inferred", d.inferred);
      w.field("coverage", d.coverage).endObject();
    } else {
      w.key("districts").null();
    }
    w.key("damage_states").beginObject();
    for (std::size_t k = 0; k < 6; ++k) w.field(kDamageKeys[k], damage[k]);
    w.endObject();
    if (t.response) {
      w.field("motion", t.response->motion).field("scenario", t.response->scenario);
      const ResponseInfo& ri = *t.response;
      if (!ri.eventType.empty()) {
        w.field("event_type", ri.eventType);
      } else {
        w.key("event_type").null();
      }
      w.field("shaking_field", ri.shakingField).field("scaling", ri.scaling).field("time_of_day", ri.timeOfDay);
      w.key("records").beginArray();
      for (const std::string& rec : ri.records) w.value(rec);
      w.endArray();
      if (ri.shakemap) {
        const ResponseInfo::ShakeMap& m = *ri.shakemap;
        w.key("shakemap").beginObject();
        w.field("event_id", m.eventId).field("version", m.version).field("process_timestamp", m.processTimestamp);
        w.field("event_timestamp", m.eventTimestamp).field("description", m.description).field("source", m.source);
        w.field("magnitude", m.magnitude).field("depth_km", m.depthKm).field("latitude", m.latitudeDeg);
        w.field("longitude", m.longitudeDeg).endObject();
      }
      if (consequences) {
        w.key("expected_damage_states").beginObject();
        for (std::size_t k = 0; k < 5; ++k) w.field(kStateNames[k], consequences->city.damageStates[k].expected);
        w.endObject();
        w.key("consequences").beginObject();
        w.field("time_of_day", consequences->timeOfDay);
        if (consequences->population.given()) {
          const seismic::PopulationFigures& p = consequences->population;
          w.key("population").beginObject();
          if (p.night >= 0) w.field("night", p.night);
          if (p.day >= 0) w.field("day", p.day);
          w.field("source", p.source).endObject();
        }
        seismic::writeLossTotals(w, consequences->city);
        w.key("districts").beginArray();
        for (const seismic::ConsequenceTotals::District& d : consequences->districts) {
          w.beginObject().field("name", d.name);
          seismic::writeLossTotals(w, d.totals);
          w.endObject();
        }
        w.endArray();
        if (!consequences->districtsSource.empty()) {
          w.field("districts_source", consequences->districtsSource);
          w.field("districts_inferred", consequences->districtsInferred);
        }
        w.endObject();
      }
      w.key("response")
          .beginObject()
          .field("method", t.response->method)
          .field("duration_s", t.response->durationSeconds)
          .field("sample_rate_hz", t.response->sampleRateHz)
          .field("buildings_revision", t.response->buildingsRevision)
          .endObject();
    } else {
      w.key("motion").null();
      w.key("response").null();
    }
    w.key("no_result_reasons").beginObject();
    for (const auto& [k, v] : reasons) w.field(k, v);
    w.endObject();
    w.field("approximate_buildings", static_cast<std::uint64_t>(notes.approximate.size()));
    w.field("unconverged_steps", unconvergedSteps);
    w.key("approximate").beginArray();  // worst residual first
    for (const ResponseNotes::Approximate& n : notes.approximate) {
      w.beginObject().field("id", n.id).field("unconverged_steps", std::uint64_t{n.unconvergedSteps});
      w.field("worst_residual_ratio", n.worstResidualRatio).endObject();
    }
    w.endArray();
    w.field("response_out_of_date", t.responseOutOfDate());
    w.endObject();
    std::printf("%s\n", w.str().c_str());
    return kExitOk;
  }

  std::printf("city        %s\n", dir.c_str());
  std::printf("origin      %.6f, %.6f (lon, lat), %s projection\n", t.originLon, t.originLat, t.projection.c_str());
  std::printf("extent      %.0f m x %.0f m, tallest %.1f m\n", static_cast<double>(t.bounds.width()),
              static_cast<double>(t.bounds.height()), static_cast<double>(t.maxHeightM));
  std::printf("buildings   %llu (%llu critical, %llu LOD2), mean %.2f storeys\n",
              static_cast<unsigned long long>(s.buildings), static_cast<unsigned long long>(s.critical),
              static_cast<unsigned long long>(s.lod2), meanStoreys);
  auto facilities = [&s](FacilityCategory c) {
    return static_cast<unsigned long long>(s.facilities[static_cast<std::size_t>(c)]);
  };
  std::printf("facilities  %llu essential, %llu school or shelter, %llu high occupancy, %llu hazardous\n",
              facilities(FacilityCategory::Essential), facilities(FacilityCategory::SchoolShelter),
              facilities(FacilityCategory::HighOccupancy), facilities(FacilityCategory::Hazardous));
  if (!t.excluded.empty()) {
    std::printf("excluded   ");
    for (const auto& [reason, n] : t.excluded)
      std::printf(" %s %llu;", reason.c_str(), static_cast<unsigned long long>(n));
    std::printf(" (neither drawn nor analysed)\n");
  }
  std::printf("storeys    ");
  for (std::size_t i = 0; i < kStoreyBuckets.size(); ++i) {
    std::printf(" %s: %llu;", bucketName(i).c_str(), static_cast<unsigned long long>(s.storeys[i]));
  }
  std::printf("\nheights     %llu tagged, %llu inferred; storeys %llu tagged, %llu inferred\n",
              static_cast<unsigned long long>(s.heightTagged), static_cast<unsigned long long>(s.heightInferred),
              static_cast<unsigned long long>(s.storeysTagged), static_cast<unsigned long long>(s.storeysInferred));
  std::printf("types      ");
  for (const auto& [k, v] : s.types) std::printf(" %s: %llu;", k.c_str(), static_cast<unsigned long long>(v));
  std::printf(
      "\n           %llu guessed from use and height: their damage is the Hazus type mixture of their "
      "occupancy and height",
      static_cast<unsigned long long>(s.typeMixtures));
  std::printf("\ncode eras  ");
  for (const auto& [k, v] : s.eras) std::printf(" %s: %llu;", k.c_str(), static_cast<unsigned long long>(v));
  std::printf("\ntiles       %zu (%llu leaves, depth %d), %s\n", t.nodes.size(),
              static_cast<unsigned long long>(leaves), depth, humanBytes(bytes).c_str());
  printGround(t.ground);
  std::printf("%s\n", districtsSummaryLine(t).c_str());
  if (t.response) {
    std::printf("response    %s\n", t.response->method.c_str());
    std::printf("motion      %s\n", t.response->motion.c_str());
    if (!t.response->scenario.empty()) std::printf("scenario    %s\n", t.response->scenario.c_str());
    std::printf("damage     ");
    for (std::size_t k = 0; k < 6; ++k) {
      std::printf(" %s: %llu;", kDamageKeys[k], static_cast<unsigned long long>(damage[k]));
    }
    std::printf("\n");
    if (!reasons.empty()) {
      std::printf("no result  ");
      for (const auto& [k, v] : reasons) std::printf(" %s: %llu;", k.c_str(), static_cast<unsigned long long>(v));
      std::printf("\n");
    }
    if (!notes.approximate.empty()) {
      std::printf("approximate %zu buildings (%llu solver steps accepted without convergence); worst residuals:\n",
                  notes.approximate.size(), static_cast<unsigned long long>(unconvergedSteps));
      constexpr std::size_t kListed = 20;
      for (std::size_t i = 0; i < std::min(kListed, notes.approximate.size()); ++i) {
        const ResponseNotes::Approximate& n = notes.approximate[i];
        std::printf("            %s: %u steps, residual %.2g\n", n.id.c_str(), n.unconvergedSteps,
                    static_cast<double>(n.worstResidualRatio));
      }
      if (notes.approximate.size() > kListed) std::printf("            ... (`--json` lists every one)\n");
    }
    if (t.responseOutOfDate()) {
      std::printf(
          "note        the response is out of date: it was computed for buildings revision %llu, the city "
          "is at %llu; run `quakeview-prep response` again\n",
          static_cast<unsigned long long>(t.response->buildingsRevision),
          static_cast<unsigned long long>(t.buildingsRevision));
    }
  } else {
    std::printf("response    none (run `quakeview-prep response` or `import-response`)\n");
  }
  return kExitOk;
}

}  // namespace qv::prep
