// Cuts a CityModel into the quadtree of binary city tiles the viewer streams, and writes the
// city directory: tiles/<level>-<x>-<y>.qvt and tileset.json (written last: the manifest is the
// commit point), search.qvi (the city-wide building table, docs/formats.md) and the map under the
// city, ground/<level>-<x>-<y>.qvg (qv/prep/GroundTiler.h). Leaves hold a
// bounded number of buildings at full detail; every inner tile holds a coarse prism of the largest
// buildings below it (all of them up to maxCoarseBuildings), so the far city draws from a few inner
// tiles (hierarchical LOD, as in 3D Tiles' REPLACE refinement) and no tile grows with the city.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "qv/core/Result.h"
#include "qv/format/Tileset.h"
#include "qv/prep/CityModel.h"
#include "qv/prep/GroundTiler.h"

namespace qv::prep {

struct TilerOptions {
  std::uint32_t maxBuildingsPerLeaf = 1000;  ///< split a node holding more
  std::size_t maxLeafBytes = 150 * 1024;     ///< split a node whose leaf tile would be larger
  /// An inner tile draws at most this many buildings of its subtree (the largest by footprint area
  /// times height); its geometric error covers the largest one left out.
  std::size_t maxCoarseBuildings = 100000;
  unsigned threads = 0;  ///< 0: all cores
  std::string generator = "quakeview-prep";
  std::string name;  ///< the manifest's `name` (the city's own name)
  std::uint64_t buildingsRevision = 1;
  bool showProgress = true;
  /// Written into the manifest as is. A tool that changes the buildings of a city with a response
  /// passes the old record (its buildingsRevision older than `buildingsRevision`), so the city
  /// reports its response as out of date; no tile refers to the old response files.
  std::optional<ResponseInfo> response;
  /// Writes the ground pyramid of model.ground and the manifest's `ground` layer (present with no
  /// cells when the model has no ground features). Off (--no-ground): neither, and no `ground`.
  bool ground = true;
  /// A city rewritten from its own tiles (lod2) has no ground features in its model: the ground
  /// layer of the city it replaces, kept as it is: its files are linked or copied from the city
  /// directory `keptGroundDir` and the layer goes into the manifest unchanged. Used instead of
  /// model.ground when set (and `ground` is on).
  std::optional<GroundLayer> keptGround;
  std::string keptGroundDir;
  /// With keptGround: the districts of the city it replaces, kept the same way (their file in
  /// keptGroundDir).
  std::optional<DistrictsInfo> keptDistricts;
  /// The input the ground came from, named in the districts' source ("OpenStreetMap", "synth-city").
  std::string districtsOrigin = "the input's";
};

struct TilerReport {
  std::uint64_t buildings = 0;
  std::uint64_t tiles = 0;
  std::uint64_t leaves = 0;
  std::uint64_t bytes = 0;      ///< all tile files
  std::uint64_t leafBytes = 0;  ///< leaf tiles only
  std::uint64_t largestLeafBytes = 0;
  std::uint64_t smallestLeafBytes = 0;
  int depth = 0;
  std::uint64_t triangulationDrops = 0;
  /// What writeGroundTiles reported, when the ground was written from model.ground (not with
  /// --no-ground, not when a kept ground was copied).
  std::optional<GroundTilerReport> ground;
  std::uint64_t districts = 0;  ///< districts written (districts.geojson), 0 when the input offers none
  Tileset tileset;              ///< the manifest as written
};

/// Writes the city into a new directory `outDir` (staged beside it and swapped in at the end;
/// a failure or Ctrl-C leaves any previous city there untouched). Buildings whose roof cannot be
/// triangulated are dropped and counted in `model.drops` ("triangulation-failed").
Result<TilerReport> writeCityTiles(CityModel& model, const std::string& outDir, const TilerOptions& options);

/// Tile file name of a node: "tiles/<level>-<x>-<y>.qvt".
std::string tileFileName(int level, std::uint32_t x, std::uint32_t y);

}  // namespace qv::prep
