// Where "Fly to" puts the camera so that the building it flies to is seen, not hidden behind
// taller neighbours: the orbit camera looks at the building's ground centre from a distance that
// frames it, from the side (heading) and height (pitch) nearest the current view along which the
// sight lines to the building's centre and roof pass no other building. Pure: the occluders are
// boxes the scene gathers (CityScene::buildingBoxesNear); native tests pin the choice.
#pragma once

#include <span>

#include <glm/vec3.hpp>

#include "qv/geometry/Bounds.h"
#include "qv/geometry/OrbitCamera.h"

namespace qv {

/// The building flown to, in the city frame (metres; z up from the ground at 0).
struct FlyToTarget {
  double x = 0.0, y = 0.0;       ///< footprint centre
  double baseZ = 0.0;            ///< bottom of the building (its minimum height)
  double topZ = 0.0;             ///< top of the building
  double footprintAreaM2 = 0.0;  ///< for the framing distance
};

/// The camera pose chosen and what was found along its sight lines.
struct FlyToPose {
  CameraState camera;
  bool centreVisible = false;  ///< no occluder between the eye and the building's centre
  bool roofVisible = false;    ///< nor between the eye and the middle of its roof
};

/// The distance that frames a building: 2.5 x its height, 6 x the side of a square of its
/// footprint area, at least 150 m.
double flyToDistance(double heightM, double footprintAreaM2);

/// True when the segment from `from` to `to` passes through any of `boxes` (a box containing
/// `to` itself counts as blocking; touching counts).
bool segmentBlocked(const glm::dvec3& from, const glm::dvec3& to, std::span<const Box> boxes);

/// The pose for flying to `target` from the current camera: the current field of view, the
/// framing distance, and the first heading and pitch, in this order of preference, from which the
/// building's centre and the middle of its roof are both unoccluded by `occluders` (the other
/// buildings; the target's own box must not be among them):
///   pitches: the current one clamped to [30°, 60°], then 10° steps up to 80°, then 89°;
///   headings (for each pitch): the current one, then ±22.5° steps alternating (right first) round
///   to the opposite side.
/// When no candidate sees both, the first that sees the centre; when none does, straight down
/// (89°, which sees any roof no neighbour overhangs) at the current heading.
FlyToPose chooseFlyToPose(const CameraState& current, const FlyToTarget& target, std::span<const Box> occluders);

}  // namespace qv
