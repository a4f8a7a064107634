// CityJSON 1.0, 1.1 and 2.0 (https://www.cityjson.org/specs/) through simdjson's DOM API with error
// codes only. Reads the Buildings of a file, each with its BuildingParts merged into one triangle
// mesh in the file's own coordinates (the `transform` applied, no georeferencing yet), semantic
// surfaces kept, faces with holes triangulated in their plane. Everything else (roads, vegetation,
// land use, water, bridges, installations, ...) is skipped and counted by CityObject type.
//
// Errors never escape as exceptions: malformed JSON gives "file:line:column: malformed JSON: ...",
// structural problems name the CityObject and the JSON path (`geometry[0].boundaries[2][0]`).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "qv/core/Result.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

struct CityJsonOptions {
  /// The level of detail to take when an object has several geometries, e.g. "2.2" or "1.2"
  /// (compared as numbers: "2" = "2.0"). Empty: the highest present. A Building without a geometry
  /// of the requested LOD (in itself or its parts) is skipped and counted as "no LOD <lod>".
  std::string lod;
};

/// One CityJSON Building with its parts, in the file's coordinates.
struct CityJsonBuilding {
  std::string objectId;  ///< the CityObjects key
  /// Positions of the vertices its faces use, in the file's CRS units (transform applied), in order
  /// of first use. positions.size() is the model's vertex count before re-meshing.
  std::vector<glm::dvec3> positions;
  std::vector<std::uint32_t> triangles;  ///< indices into positions, orientation as in the file
  std::vector<SurfaceKind> kinds;        ///< per triangle: semantics, else by normal
  std::string lod;                       ///< the LOD taken, as written ("2.2", "2")
  std::uint32_t parts = 0;               ///< BuildingParts merged into it
  std::uint32_t geometries = 0;          ///< geometry objects used (Solids, MultiSurfaces, ...)
  // Attributes the product uses (CityGML names, and the 3D BAG's construction year).
  std::string name;                          ///< "name"
  std::string function;                      ///< "function", else "usage" (text values only)
  std::optional<double> storeysAboveGround;  ///< "storeysAboveGround"
  std::optional<double> measuredHeightM;     ///< "measuredHeight" (kept for reference)
  int startYear = 0;                         ///< "yearOfConstruction", "oorspronkelijk_bouwjaar"
};

struct CityJsonFile {
  std::string version;                              ///< "1.0", "1.1", "2.0" as written
  std::string referenceSystem;                      ///< metadata.referenceSystem as written (empty when absent)
  std::string crs;                                  ///< "EPSG:<code>" when the reference system names one, else empty
  std::vector<CityJsonBuilding> buildings;          ///< in document order of the Buildings
  std::map<std::string, std::uint64_t> skipped;     ///< by CityObject type ("Road" -> 143) or reason
  std::map<std::string, std::uint64_t> geometries;  ///< geometries used, by type ("Solid" -> 9)
  std::map<std::string, std::uint64_t> lods;        ///< Buildings by the LOD taken ("2.2" -> 10)
  std::uint64_t partsMerged = 0;                    ///< BuildingParts merged into Buildings
  std::uint64_t facesSkipped = 0;                   ///< degenerate faces (no area, fewer than 3 distinct points)
  std::vector<std::string> warnings;                ///< the first 100 messages
};

/// Reads a CityJSON file (see the file comment). Fails for unreadable files, malformed JSON, a
/// document that is not CityJSON, an unsupported version (message lists the supported ones),
/// vertex indices out of range and other structural errors.
Result<CityJsonFile> readCityJson(const std::string& path, const CityJsonOptions& options = {});

/// The same on a text in memory; `name` is used in messages in place of the path.
Result<CityJsonFile> parseCityJson(std::string_view text, const std::string& name, const CityJsonOptions& options = {});

}  // namespace qv::prep
