#include "qv/scene/FlyToPose.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace qv {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// The eye of an orbit camera (qv::CameraView's construction: it looks at (x, y, 0)).
glm::dvec3 eyeOf(const CameraState& s) {
  const double heading = s.headingDeg * kDegToRad;
  const double pitch = s.pitchDeg * kDegToRad;
  const glm::dvec3 forward(std::sin(heading) * std::cos(pitch), std::cos(heading) * std::cos(pitch), -std::sin(pitch));
  return glm::dvec3(s.x, s.y, 0.0) - forward * s.distance;
}

// Slab test of the segment from + t (to - from), t in [0, 1], against a box.
bool segmentMeetsBox(const glm::dvec3& from, const glm::dvec3& to, const Box& box) {
  if (box.empty()) return false;
  const double lo[3] = {box.minX, box.minY, box.minZ};
  const double hi[3] = {box.maxX, box.maxY, box.maxZ};
  double t0 = 0.0, t1 = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double o = from[a];
    const double d = to[a] - from[a];
    if (std::abs(d) < 1e-12) {
      if (o < lo[a] || o > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o) / d, tb = (hi[a] - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

double flyToDistance(double heightM, double footprintAreaM2) {
  return std::max({heightM * 2.5, std::sqrt(std::max(0.0, footprintAreaM2)) * 6.0, 150.0});
}

bool segmentBlocked(const glm::dvec3& from, const glm::dvec3& to, std::span<const Box> boxes) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const Box& b) { return segmentMeetsBox(from, to, b); });
}

FlyToPose chooseFlyToPose(const CameraState& current, const FlyToTarget& target, std::span<const Box> occluders) {
  CameraState base = current;
  base.x = target.x;
  base.y = target.y;
  base.distance = flyToDistance(target.topZ, target.footprintAreaM2);
  const glm::dvec3 centre(target.x, target.y, 0.5 * (target.baseZ + target.topZ));
  const glm::dvec3 roof(target.x, target.y, target.topZ);

  // Only occluders that could stand between an eye at the framing distance and the building.
  std::vector<Box> near;
  const double reach = base.distance + 1.0;
  for (const Box& b : occluders) {
    if (b.empty()) continue;
    const double dx = std::max({0.0, static_cast<double>(b.minX) - target.x, target.x - static_cast<double>(b.maxX)});
    const double dy = std::max({0.0, static_cast<double>(b.minY) - target.y, target.y - static_cast<double>(b.maxY)});
    if (dx * dx + dy * dy <= reach * reach) near.push_back(b);
  }

  std::vector<double> pitches{std::clamp(std::isfinite(current.pitchDeg) ? current.pitchDeg : 45.0, 30.0, 60.0)};
  for (double p = std::floor(pitches[0] / 10.0) * 10.0 + 10.0; p <= 80.0; p += 10.0) pitches.push_back(p);
  pitches.push_back(89.0);
  std::vector<double> headings{current.headingDeg};
  for (int k = 1; k <= 8; ++k) {
    headings.push_back(current.headingDeg + 22.5 * k);
    if (k < 8) headings.push_back(current.headingDeg - 22.5 * k);
  }

  std::optional<FlyToPose> centreOnly;
  for (double pitch : pitches) {
    for (double heading : headings) {
      FlyToPose pose;
      pose.camera = base;
      pose.camera.pitchDeg = pitch;
      pose.camera.headingDeg = std::fmod(heading + 360.0, 360.0);
      const glm::dvec3 eye = eyeOf(pose.camera);
      pose.centreVisible = !segmentBlocked(eye, centre, near);
      if (!pose.centreVisible) continue;
      pose.roofVisible = !segmentBlocked(eye, roof, near);
      if (pose.roofVisible) return pose;
      if (!centreOnly) centreOnly = pose;
    }
  }
  if (centreOnly) return *centreOnly;
  FlyToPose down;
  down.camera = base;
  down.camera.pitchDeg = 89.0;
  const glm::dvec3 eye = eyeOf(down.camera);
  down.centreVisible = !segmentBlocked(eye, centre, near);
  down.roofVisible = !segmentBlocked(eye, roof, near);
  return down;
}

}  // namespace qv
