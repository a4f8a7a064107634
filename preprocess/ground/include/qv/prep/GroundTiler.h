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

struct GroundTilerOptions {
  double leafCellM = 600.0;  ///< leaves are the first level whose cells are at most this wide
  /// An inner cell of side s keeps lines and areas simplified to s / 256 and drops areas smaller
  /// than (s / 128)², unless that leaves nothing of the class.
  unsigned threads = 0;  ///< 0: all cores
};

struct GroundTilerReport {
  GroundLayer layer;              ///< for the manifest (Tileset::ground): nodes, counts, bytes
  std::uint64_t triangles = 0;    ///< over every file
  std::uint64_t leafTriangles = 0;
  std::uint64_t labels = 0;
  double areaKm2 = 0.0;           ///< the level-0 cell's area covered by leaves with a file
};

/// Writes the ground files of `features` into `<cityDir>/ground/` (the directory must exist and
/// is the staging city directory of the caller; files are written with their final names there)
/// over a pyramid whose level-0 cell is a square around `cityBounds` united with the features'
/// bounds (clamped to 4 × the city's size around it, so one far-away feature does not blow the
/// pyramid up). Features outside that square are clipped away. Returns the layer for the
/// manifest. Broken geometry (fewer than 2 points, rings of fewer than 3, self-intersections CGAL
/// cannot triangulate, coastlines that do not close) is skipped and counted in layer.skipped,
/// added to features.skipped; an error only for I/O.
Result<GroundTilerReport> writeGroundTiles(const GroundFeatures& features, const Rect& cityBounds,
                                           const std::string& cityDir, const GroundTilerOptions& options = {});

/// "ground/<level>-<x>-<y>.qvg"
std::string groundFileName(int level, std::uint32_t x, std::uint32_t y);

}  // namespace qv::prep
