// The ground pyramid of a city (docs/formats.md "Ground tile"): the readers' GroundFeatures cut
// into square cells, triangulated (areas: CGAL constrained Delaunay; lines: ribbons of their
// width), simplified per level, labelled, and written as ground/<level>-<x>-<y>.qvg files.
//
// Screen-bounded detail, like the city tiles: leaves (cells of about `leafCellM`) hold every
// feature at full detail; an inner cell holds the features that matter at the distance it is drawn
// from (motorways, major roads, railways, rivers and areas larger than a few of its pixels),
// simplified to its geometric error, and the names of its rank. The viewer replaces a cell by its
// four children as it comes closer (REPLACE refinement).
#pragma once

#include <cstdint>
#include <string>

#include "qv/core/Result.h"
#include "qv/format/Tileset.h"
#include "qv/geometry/Bounds.h"
#include "qv/prep/GroundFeatures.h"

namespace qv::prep {

/// Detail per level (s: the cell's side): leaves hold every feature as read. An inner cell keeps
/// motorways, major roads, railways, rivers, and areas (and holes, islands) of at least (s / 128)²,
/// simplified to s / 256 (Douglas–Peucker; points on the cell's sides stay, so cells meet exactly)
/// with lines at least 1.5 × s / 256 wide; streets and paths at the two finest levels only. Names:
/// places and the names of drawn water and park areas at every level, streets and paths at the two
/// finest levels, major roads, motorways and rivers at the three finest.
struct GroundTilerOptions {
  double leafCellM = 600.0;  ///< leaves are the first level whose cells are at most this wide
  unsigned threads = 0;      ///< 0: all cores; the files do not depend on it
};

struct GroundTilerReport {
  GroundLayer layer;            ///< for the manifest (Tileset::ground): nodes, counts, bytes
  std::uint64_t triangles = 0;  ///< over every file
  std::uint64_t leafTriangles = 0;
  std::uint64_t labels = 0;
  double areaKm2 = 0.0;  ///< the level-0 cell's area covered by leaves with a file
};

/// Writes the ground files of `features` into `<cityDir>/ground/` (`cityDir` must exist and is the
/// staging city directory of the caller; `ground/` is created in it and files are written with
/// their final names there) over a pyramid whose level-0 cell is a square around `cityBounds`
/// united with the features' bounds (clamped to 4 × the city's size, at least `leafCellM`, around
/// its centre, so one far-away feature does not blow the pyramid up; the features' bounds alone
/// when `cityBounds` is empty). Features outside that square are clipped away. With no usable
/// feature nothing is written and the layer has no nodes. Returns the layer for the
/// manifest. Broken geometry (fewer than 2 points, rings of fewer than 3, self-intersections CGAL
/// cannot triangulate, coastlines that do not close) is skipped and counted in layer.skipped,
/// added to features.skipped; an error only for I/O (or Ctrl-C).
/// A cell whose subtree draws nothing has no file; an inner cell that draws nothing itself over
/// cells that do gets an empty tile, so the pyramid with files is connected from level 0. With a
/// closed coastline every cell is land or sea, and the whole pyramid has files.
Result<GroundTilerReport> writeGroundTiles(const GroundFeatures& features, const Rect& cityBounds,
                                           const std::string& cityDir, const GroundTilerOptions& options = {});

/// "ground/<level>-<x>-<y>.qvg"
std::string groundFileName(int level, std::uint32_t x, std::uint32_t y);

}  // namespace qv::prep
