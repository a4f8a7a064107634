// The in-memory city that preprocess builds from its inputs (OSM, GeoJSON, synthetic) before it is
// cut into tiles: buildings with attributes and geometry in the city frame (double precision,
// metres east and north of the origin, transverse Mercator centred on the data).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "qv/format/BuildingAttributes.h"
#include "qv/format/CityTile.h"
#include "qv/prep/GroundFeatures.h"

namespace qv::prep {

/// One extruded piece of a building: a polygon with holes between two heights. A plain building
/// has one part (its outline from the ground to its roof); an OSM building with building:part
/// members has one per part (setbacks, towers on podiums) and its outline is not drawn again.
struct BuildingPart {
  /// All rings' points, outer ring first (counter-clockwise), then holes (clockwise); rings do
  /// not repeat their first point. Metres in the city frame.
  std::vector<glm::dvec2> points;
  /// ring i = points[ringEnds[i-1] (or 0), ringEnds[i]).
  std::vector<std::uint32_t> ringEnds;
  float minHeightM = 0.0f;   ///< bottom of this part above ground
  float heightM = 0.0f;      ///< top of this part above ground
  std::string roofShape;     ///< roof:shape, kept for later (flat roofs are drawn for now)
  float roofHeightM = 0.0f;  ///< roof:height, 0 when not tagged
  std::string sourceId;      ///< the part's own id (w…/r…) when it came from a building:part

  [[nodiscard]] std::size_t ringCount() const { return ringEnds.size(); }
};

/// A LOD2 model of a building as the tiles store it (docs/formats.md, "MESH"): a mesh re-meshed at
/// the building's floor levels (the viewer skins it by height) and a simplified far mesh. Positions
/// are in the city frame (metres east and north of the origin) with z in metres above the
/// building's ground.
struct BuildingMesh {
  MeshSource source = MeshSource::Other;
  std::uint32_t verticesBefore = 0;  ///< as imported, before re-meshing
  std::vector<glm::dvec3> positions;
  /// 3 indices per triangle, grouped by kind (wall, roof, ground, other) as counted below.
  std::vector<std::uint32_t> triangles;
  std::array<std::uint32_t, kMeshSurfaceKinds> trianglesPerKind{};
  std::vector<glm::dvec3> farPositions;     ///< at most 65535
  std::vector<std::uint16_t> farTriangles;  ///< 3 indices per triangle into farPositions
};

struct Building {
  BuildingAttributes attributes;
  std::vector<BuildingPart> parts;  ///< at least one (a LOD2 building: its footprint, the LOD1 fallback)
  /// LOD2 model (attributes.lod == 2), written to the tiles' MESH section; animated by the floors
  /// of attributes.storeys.
  std::optional<BuildingMesh> mesh;
};

/// Why a footprint or building was dropped, counted and printed in the summary.
struct DropCounts {
  std::map<std::string, std::uint64_t> byReason;  ///< "self-intersecting" -> 12, ...
  void add(const std::string& reason, std::uint64_t n = 1) { byReason[reason] += n; }
  [[nodiscard]] std::uint64_t total() const {
    std::uint64_t t = 0;
    for (const auto& [reason, n] : byReason) t += n;
    return t;
  }
};

struct CityModel {
  double originLon = 0.0;  ///< degrees, the centre of the projection (x = y = 0 here)
  double originLat = 0.0;
  std::string projection = "transverse-mercator";  ///< GeographicLib TM on WGS84, k0 = 1
  std::vector<Building> buildings;
  DropCounts drops;
  std::vector<std::string> warnings;                   ///< what was inferred instead of a garbage tag, etc.
  std::map<std::string, std::uint64_t> warningCounts;  ///< "building:levels not a number" -> 1
  std::vector<std::string> sources;                    ///< input files, for the manifest
  /// Buildings read but neither drawn nor analysed, by reason ("underground" -> 1); they are not in
  /// `buildings`. Written to the manifest (Tileset::excluded) and shown by `info`.
  std::map<std::string, std::uint64_t> excluded;
  /// The map under the buildings (streets, water, parks, names) as read from the input; the
  /// tiler writes it as the ground pyramid (qv/prep/GroundTiler.h) unless told not to.
  GroundFeatures ground;
};

}  // namespace qv::prep
