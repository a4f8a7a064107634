// The plane geometry of the ground tiler (internal to prep::ground): clipping to a cell, the
// simplification of clipped shapes, street ribbons, the even-odd triangulation of clipped rings,
// label stretches and label text. Every coordinate is in the city frame (metres, double) unless a
// name says otherwise; a cell is an axis-aligned box.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

namespace qv::prep::ground {

using Ring = std::vector<glm::dvec2>;      ///< closed implicitly (the last point is not the first again)
using Polyline = std::vector<glm::dvec2>;  ///< open, at least 2 points

struct Box2 {
  double minX = 0.0, minY = 0.0, maxX = 0.0, maxY = 0.0;
  [[nodiscard]] Box2 expanded(double by) const { return {minX - by, minY - by, maxX + by, maxY + by}; }
  [[nodiscard]] bool contains(glm::dvec2 p) const { return p.x >= minX && p.x <= maxX && p.y >= minY && p.y <= maxY; }
  [[nodiscard]] bool intersects(const Box2& b) const {
    return !(b.minX > maxX || b.maxX < minX || b.minY > maxY || b.maxY < minY);
  }
};

/// Bounds of the points (an inverted box when there are none).
Box2 boundsOf(std::span<const glm::dvec2> points);

/// Triangles in the city frame: 3 indices per triangle, counter-clockwise.
struct Mesh {
  std::vector<glm::dvec2> vertices;
  std::vector<std::uint32_t> triangles;
  [[nodiscard]] bool empty() const { return triangles.empty(); }
};

/// Liang–Barsky clipping of each segment of `line` to `box` (closed); consecutive kept segments
/// are joined, so `out` receives one polyline per stretch of the line inside the box (each of at
/// least 2 distinct points). Exact where the line does not cross the box's sides.
void clipPolyline(std::span<const glm::dvec2> line, const Box2& box, std::vector<Polyline>& out);

/// Sutherland–Hodgman clipping of a closed ring to `box`. A ring entering and leaving the box more
/// than once comes back as one ring joined by zero-width "bridges" along the box's sides: its
/// even-odd inside is exactly ring ∩ box. Points on a side have exactly that side's coordinate
/// (triangulateEvenOdd relies on it). Empty when fewer than 3 points remain. Consecutive duplicate
/// points are removed.
Ring clipRing(std::span<const glm::dvec2> ring, const Box2& box);

/// Douglas–Peucker simplification of an open polyline, keeping both ends (iterative, any length).
Polyline simplifyPolyline(std::span<const glm::dvec2> line, double toleranceM);

/// Douglas–Peucker simplification of a ring clipped to `box`: every point on a side of the box is
/// kept (neighbouring cells meet exactly there), the chains between them are simplified. Empty when
/// fewer than 3 points remain. qv/prep/Simplify.h's simplifyRing does not fit: it has no fixed points.
Ring simplifyClippedRing(std::span<const glm::dvec2> ring, const Box2& box, double toleranceM);

/// Appends the ribbon of `line` (`halfWidthM` either side, consecutive duplicate points allowed):
/// one quad per segment, a fan of up to 4 triangles on the outer side of every bend (no crack at
/// bends) and a half-disc of 4 triangles at both ends (streets split into several ways meet
/// without a notch).
void appendRibbon(std::span<const glm::dvec2> line, double halfWidthM, Mesh& out);

/// Appends the parts of `mesh`'s triangles inside `box` (Sutherland–Hodgman per triangle, re-fanned)
/// to `out`; triangles wholly inside keep their vertices, slivers below 1e-9 m² are dropped.
void clipMesh(const Mesh& mesh, const Box2& box, Mesh& out);

/// Triangulates the even-odd inside of `rings` (any winding; they may touch, cross themselves or
/// each other) with CGAL's constrained Delaunay triangulation and qv/prep/CdtDomains.h. Edges lying
/// on a side of `box` are summed modulo 2 along that side first, so the bridges of clipRing and
/// rings that share the box's sides cancel out; `addBoxSides` adds the box's own boundary (the
/// inside is then box minus the rings: the sea outside land rings). Vertices are in the city frame.
/// Returns false when CGAL throws (the caller counts the failure).
bool triangulateEvenOdd(std::span<const Ring> rings, const Box2& box, bool addBoxSides, Mesh& out);

/// Signed area of a ring (positive counter-clockwise), square metres.
double signedArea(std::span<const glm::dvec2> ring);

/// True when `p` is inside the rings by the even-odd rule.
bool insideEvenOdd(glm::dvec2 p, std::span<const Ring> rings);

/// The longest straight-ish stretch of a set of polylines: consecutive segments within 20° of the
/// stretch's first segment. Angle is the direction of its chord in (-pi/2, pi/2] as a float.
struct Stretch {
  glm::dvec2 middle{0.0};  ///< the point halfway along the stretch
  float angleRad = 0.0f;
  double lengthM = 0.0;
};
std::optional<Stretch> longestStretch(std::span<const Polyline> pieces);

/// The direction of (dx, dy) as a text angle: counter-clockwise from east, in (-pi/2, pi/2] in float
/// (text never reads upside down; GroundLabel::angleRad).
float textAngle(double dx, double dy);

/// `text` as a ground label may hold it: valid UTF-8 (invalid sequences become U+FFFD), tabs and
/// line breaks as spaces, other control characters (C0, DEL, C1) removed, outer spaces trimmed, cut
/// to 255 bytes at a character boundary. Empty when nothing is left.
std::string cleanLabelText(std::string_view text);

}  // namespace qv::prep::ground
