// The LOD2 import in one call: reads a model file (CityJSON or OBJ, by extension), georeferences it
// into the city frame (its CRS through PROJ, or a placement), matches the models to the city's
// buildings when given, and finishes them (re-meshing, skinning, far mesh). docs/lod2.md.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/geometry/Bounds.h"
#include "qv/prep/Lod2CityJson.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Georeference.h"
#include "qv/prep/Lod2Match.h"
#include "qv/prep/Lod2Model.h"
#include "qv/prep/Lod2Obj.h"

namespace qv::prep {

struct Lod2ImportOptions {
  double originLon = 0.0;  ///< the city's projection origin (CityModel::originLon/originLat), degrees
  double originLat = 0.0;
  /// The city's extent in its frame (metres). Without a placement, a model whose footprint centre
  /// falls outside it is refused (or skipped, see skipOutsideExtent). An empty Rect (the default)
  /// disables the check.
  Rect extent;
  /// Puts the model set's footprint centre at a point, rotated (CityJSON: instead of its CRS, which
  /// may then be missing; OBJ: required, the model's origin or footprint centre goes there).
  std::optional<Placement> placement;
  std::string lod;  ///< CityJSON LOD to take ("2.2"); empty: the highest present
  // OBJ only: the file's unit, scale, up axis and which point goes to the placement.
  ModelUnit objUnit = ModelUnit::Metre;
  double objScale = 1.0;
  UpAxis objUp = UpAxis::Y;
  bool objCentreOnAnchor = false;
  /// false: a model outside the extent fails the import; true: it is skipped and counted as
  /// "outside-extent".
  bool skipOutsideExtent = false;
  /// The city's buildings: when given, models are matched before they are finished.
  const std::vector<ExistingBuilding>* existing = nullptr;
  MatchOptions match;
  FinishOptions finish;
};

struct Lod2ImportReport {
  std::string format;                               ///< "cityjson 1.1", "obj"
  std::string crs;                                  ///< "EPSG:7415", or "" (none, or a placement was used)
  std::uint64_t imported = 0;                       ///< models returned
  std::uint64_t replaced = 0;                       ///< of them replacing an existing building (filled by matching)
  std::uint64_t partsMerged = 0;                    ///< CityJSON BuildingParts merged into their Buildings
  std::map<std::string, std::uint64_t> geometries;  ///< geometries used by type ("Solid" -> 9)
  std::map<std::string, std::uint64_t> lods;        ///< models by the LOD taken ("2.2" -> 10)
  std::map<std::string, std::uint64_t> skipped;     ///< by CityObject type ("Road" -> 143) or reason
  std::uint64_t facesSkipped = 0;                   ///< degenerate faces
  std::uint64_t verticesBefore = 0;                 ///< sum over models, as imported
  std::uint64_t verticesAfter = 0;                  ///< sum over models, after re-meshing
  std::uint64_t originalTriangles = 0;              ///< sum over models, as imported (faces triangulated)
  std::uint64_t trianglesAfter = 0;                 ///< sum over models, after re-meshing
  std::uint64_t farTriangles = 0;                   ///< sum over the far meshes
  std::vector<std::string> warnings;                ///< skipped faces, orphan parts, models left out
  double seconds = 0.0;                             ///< wall time of the whole import
};

struct Lod2Import {
  std::vector<Lod2Model> models;
  Lod2ImportReport report;
};

/// Imports `path`: ".json" / ".city.json" as CityJSON, ".obj" as OBJ (any case). Fails, with a
/// message naming the file, for unreadable or malformed files, unsupported CityJSON versions, a
/// missing or unknown CRS without a placement, an OBJ without a placement, or a model outside the
/// city's extent without a placement (unless skipOutsideExtent). A model that cannot be finished
/// (finishModel fails) is left out, counted as skipped "cannot-finish" and named in the warnings.
Result<Lod2Import> importModels(const std::string& path, const Lod2ImportOptions& options);

/// Georeferences a CityJSON file already read (the middle of importModels, for callers that read
/// several files): models in the city frame with new-building attributes, not yet matched or
/// finished; `report` (may be null) receives the counts and warnings. Buildings without height are
/// skipped as "flat-model", taller than kMaxModelHeightM as "too-tall", wider or deeper than
/// kMaxModelExtentM as "too-large" (with a warning naming them).
Result<std::vector<Lod2Model>> georeferenceCityJson(const CityJsonFile& file, const std::string& fileName,
                                                    const Lod2ImportOptions& options, Lod2ImportReport* report);

}  // namespace qv::prep
