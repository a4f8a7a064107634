// The tileset manifest (tileset.json): what a city directory holds and how its tiles nest. It is
// the commit point of every tool that changes a city: tools write new tile files first and replace
// the manifest last, so a reader always sees a consistent city. Specification: docs/formats.md.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"
#include "qv/geometry/Bounds.h"

namespace qv {

inline constexpr int kTilesetVersion = 1;
inline constexpr std::string_view kTilesetFormat = "quakeview-tileset";

/// Per-tile files of the response step (absent until `quakeview-prep response` ran).
struct TileResponseFiles {
  std::string summaryFile;  ///< relative to the manifest; every tile has one
  std::uint64_t summaryBytes = 0;
  std::uint32_t summaryCrc32 = 0;
  std::string historyFile;  ///< leaves only (empty for inner tiles)
  std::uint64_t historyBytes = 0;
  std::uint32_t historyCrc32 = 0;
};

struct TileNode {
  std::uint8_t level = 0;              ///< quadtree depth, 0 = root
  std::uint32_t x = 0, y = 0;          ///< quadtree cell at that level
  Rect bounds;                         ///< metres, the footprints of every building in the subtree
  float maxHeightM = 0.0f;             ///< tallest building in the subtree
  bool coarse = false;                 ///< an inner node: simplified prisms of everything below
  float geometricErrorM = 0;           ///< how far the tile's shapes may stray from the full detail (0 for leaves)
  std::uint32_t buildings = 0;         ///< buildings in this tile's own file
  std::uint64_t subtreeBuildings = 0;  ///< distinct buildings in this subtree
  std::string file;                    ///< relative to the manifest
  std::uint64_t bytes = 0;
  std::uint32_t crc32 = 0;              ///< CRC-32 of the whole file
  std::vector<std::uint32_t> children;  ///< indices into Tileset::nodes
  std::optional<TileResponseFiles> response;

  [[nodiscard]] std::string key() const;  ///< "level/x/y"
};

/// A file of the city other than tiles, with its size and checksum.
struct CityFile {
  std::string file;  ///< relative to the manifest
  std::uint64_t bytes = 0;
  std::uint32_t crc32 = 0;
};

struct ResponseInfo {
  std::string motion;    ///< e.g. "synthetic Kanai-Tajimi seed 7, PGA 0.35 g" or a file name
  std::string scenario;  ///< e.g. "M6.8 at -74.02,40.68, depth 10 km" or "" (one record for all)
  double durationSeconds = 0;
  double sampleRateHz = 0;              ///< history tier display rate
  std::uint64_t buildingsRevision = 0;  ///< the city revision the response was computed for
  std::string method;                   ///< "MDOF shear building, Bouc-Wen" or "imported"
  /// Counts per damage state: none, slight, moderate, extensive, complete, no_result.
  std::uint64_t damageStates[6] = {0, 0, 0, 0, 0, 0};
  /// The input record's X component for plotting: the sample of largest |a| in each window of
  /// 1 / motionPreviewRateHz seconds, in g (empty when unknown).
  std::vector<float> motionPreviewG;
  double motionPreviewRateHz = 0.0;
  /// Every building's summary in the search index's order (the city-wide list, filters and
  /// exports); absent in cities without a search index.
  std::optional<CityFile> summaryIndex;
  /// The response's notes (JSON, docs/formats.md "Response notes"): why each building without a
  /// result has none, in detail, and the buildings whose result is approximate.
  std::optional<CityFile> notes;
  /// Whether the shaking is a SCENARIO (computed, or a ShakeMap of a scenario) or an ACTUAL event (a
  /// ShakeMap of a recorded earthquake): "SCENARIO", "ACTUAL", or empty when not stated (imported
  /// results, responses written before this field).
  std::string eventType;
  /// Where each building's shaking came from: "record" (the record(s) for every building),
  /// "scenario" (--epicentre: BSSA14 at each building), "shakemap" (a ShakeMap grid); empty: older.
  std::string shakingField;
  /// "sa" (each record scaled to the target Sa at the building's first-mode period, per direction),
  /// "pga" (to the target PGA), or empty (records used as given / older responses).
  std::string scaling;
  /// The ShakeMap the shaking came from (shakingField "shakemap").
  struct ShakeMap {
    std::string eventId, version, processTimestamp, eventTimestamp, description, source;
    double magnitude = 0.0, depthKm = 0.0, latitudeDeg = 0.0, longitudeDeg = 0.0;
    bool operator==(const ShakeMap&) const = default;
  };
  std::optional<ShakeMap> shakemap;
  /// The record suite, one description per record (file name and header title, or synthetic seed).
  std::vector<std::string> records;
  /// The time of day the consequences assume ("night", "day", "commute"); empty without losses.
  std::string timeOfDay;
  /// Totals of the consequences (JSON, docs/losses.md): the city, and each district when given.
  std::optional<CityFile> consequences;
};

/// One cell of the ground pyramid that has a file (docs/formats.md "Ground tile").
struct GroundNode {
  std::uint8_t level = 0;      ///< 0 = the one cell over the whole ground
  std::uint32_t x = 0, y = 0;  ///< the cell at that level, from the pyramid's south-west corner
  float geometricErrorM = 0;   ///< how far its shapes may stray from full detail (0 for leaves)
  std::string file;            ///< relative to the manifest: "ground/<level>-<x>-<y>.qvg"
  std::uint64_t bytes = 0;
  std::uint32_t crc32 = 0;
};

/// The map under the city (streets, water, parks, names), made from the city's own input.
struct GroundLayer {
  double minX = 0.0, minY = 0.0;  ///< the level-0 cell's south-west corner, metres
  double size = 0.0;              ///< the level-0 cell's side, metres (a level-L cell: size / 2^L)
  std::uint8_t levels = 0;        ///< levels of the pyramid (leaves at levels - 1)
  std::vector<GroundNode> nodes;  ///< the cells with a file; empty when the input had no ground features
  /// Features read from the input by class name (groundClassName, plus "labels"); features
  /// skipped as broken by reason ("unclosed-coastline" -> 2); written only when not empty.
  std::map<std::string, std::uint64_t> features;
  std::map<std::string, std::uint64_t> skipped;
  std::uint64_t bytes = 0;  ///< all ground files
};

/// The districts `quakeview-prep response` totals the consequences by when given no --districts:
/// made by `city` and `synth-city` from the input's own boundaries or named places
/// (docs/losses.md "Districts by default"), a GeoJSON FeatureCollection like --districts takes.
struct DistrictsInfo {
  CityFile file;            ///< "districts.geojson"
  std::uint64_t count = 0;  ///< districts in the file
  std::string source;       ///< what they were made from, e.g. "OpenStreetMap boundary=administrative admin_level=8"
  bool inferred = false;  ///< true when no boundary was drawn by the source (each building to its nearest named place)
  double coverage = 0.0;  ///< share of the city's buildings inside a district, 0 to 1
};

struct Tileset {
  int version = kTilesetVersion;
  std::string generator;
  /// The city's own name, shown by the viewer beside where its files came from ("midtown",
  /// "Synthetic city, 100000 buildings"): `--name` of the tool that made it, by default the output
  /// folder's name. Empty in manifests written before it existed.
  std::string name;
  double originLon = 0.0, originLat = 0.0;  ///< degrees, WGS84; the city frame's (0, 0)
  std::string projection = "transverse-mercator";
  Rect bounds;  ///< metres
  float maxHeightM = 0.0f;
  std::uint64_t buildings = 0;
  std::uint64_t buildingsRevision = 1;  ///< bumped by every tool that adds or changes buildings
  std::vector<std::string> sources;     ///< input files the city came from
  /// Buildings read from the sources but neither drawn nor analysed, by reason ("underground" -> 3);
  /// written as "excluded" only when not empty.
  std::map<std::string, std::uint64_t> excluded;
  std::optional<CityFile> search;  ///< the search index (search.qvi): the city-wide building table
  std::vector<TileNode> nodes;     ///< nodes[0] is the root
  std::optional<ResponseInfo> response;
  /// The ground layer; absent when the city was made with --no-ground or before ground existed.
  /// Present with no nodes when the input had no streets, water or open land.
  std::optional<GroundLayer> ground;
  /// The city's own districts; absent when its input named none (or before they existed).
  std::optional<DistrictsInfo> districts;

  /// True when a response exists but was computed for an older revision of the buildings.
  [[nodiscard]] bool responseOutOfDate() const { return response && response->buildingsRevision != buildingsRevision; }
};

/// Serializes the manifest (pretty enough to read: one tile per line).
std::string tilesetToJson(const Tileset& tileset);

/// Parses and validates a manifest; `name` prefixes error messages. Checks the format name and
/// version, the tree's shape (indices in range, no cycles, every node reached once) and values.
Result<Tileset> parseTileset(std::string_view json, std::string_view name);

}  // namespace qv
