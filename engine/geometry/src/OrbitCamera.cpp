#include "qv/geometry/OrbitCamera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

namespace qv {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

double clampOr(double value, double lo, double hi, double fallback, bool& changed) {
  if (!std::isfinite(value)) {
    changed = true;
    return std::clamp(fallback, lo, hi);
  }
  const double c = std::clamp(value, lo, hi);
  if (c != value) changed = true;
  return c;
}

}  // namespace

bool sanitizeCamera(CameraState& s, const CameraState& f, const CameraLimits& l) {
  bool changed = false;
  s.x = clampOr(s.x, -l.maxAbsCoordinate, l.maxAbsCoordinate, f.x, changed);
  s.y = clampOr(s.y, -l.maxAbsCoordinate, l.maxAbsCoordinate, f.y, changed);
  s.distance = clampOr(s.distance, l.minDistance, l.maxDistance, f.distance, changed);
  s.pitchDeg = clampOr(s.pitchDeg, l.minPitchDeg, l.maxPitchDeg, f.pitchDeg, changed);
  s.fovDeg = clampOr(s.fovDeg, l.minFovDeg, l.maxFovDeg, f.fovDeg, changed);
  if (!std::isfinite(s.headingDeg)) {
    s.headingDeg = f.headingDeg;
    changed = true;
  }
  double h = std::fmod(s.headingDeg, 360.0);
  if (h < 0.0) h += 360.0;
  s.headingDeg = h;
  return !changed;
}

CameraView::CameraView(const CameraState& s, int viewportWidth, int viewportHeight, float shiftNdcX)
    : width_(std::max(1, viewportWidth)), height_(std::max(1, viewportHeight)) {
  const double heading = s.headingDeg * kDegToRad;
  const double pitch = s.pitchDeg * kDegToRad;
  // Direction from the eye towards the looked-at point.
  const glm::dvec3 forward(std::sin(heading) * std::cos(pitch), std::cos(heading) * std::cos(pitch), -std::sin(pitch));
  const glm::dvec3 target(s.x, s.y, 0.0);
  const glm::dvec3 eye = target - forward * s.distance;
  const glm::dvec3 right(std::cos(heading), -std::sin(heading), 0.0);
  const glm::dvec3 up = glm::cross(right, forward);

  eye_ = glm::vec3(eye);
  forward_ = glm::vec3(forward);
  view_ = glm::mat4(glm::lookAt(eye, target, up));

  // Clipping planes from street level to a whole city: the near plane scales with the eye's height
  // above the ground and with the distance (buildings up to ~550 m can stand between eye and
  // target), the far plane reaches the horizon of a large city.
  const double eyeHeight = std::max(1.0, eye.z);
  near_ = static_cast<float>(std::clamp(std::min(eyeHeight, s.distance) * 0.05, 0.5, 2000.0));
  far_ = static_cast<float>(std::max(s.distance * 4.0 + 60000.0, static_cast<double>(near_) * 10.0));
  const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
  const float fov = static_cast<float>(s.fovDeg * kDegToRad);
  projection_ = glm::perspective(fov, aspect, near_, far_);
  if (std::isfinite(shiftNdcX) && shiftNdcX != 0.0f) {
    projection_ =
        glm::translate(glm::mat4(1.0f), glm::vec3(std::clamp(shiftNdcX, -1.0f, 1.0f), 0.0f, 0.0f)) * projection_;
  }
  viewProjection_ = projection_ * view_;
  inverseViewProjection_ = glm::inverse(viewProjection_);
  frustum_ = Frustum(viewProjection_);
  projectionScale_ = static_cast<float>(height_) / (2.0f * std::tan(fov * 0.5f));
}

void CameraView::ray(double px, double py, glm::vec3& origin, glm::vec3& direction) const {
  const float ndcX = static_cast<float>(2.0 * px / width_ - 1.0);
  const float ndcY = static_cast<float>(1.0 - 2.0 * py / height_);
  glm::vec4 nearPoint = inverseViewProjection_ * glm::vec4(ndcX, ndcY, -1.0f, 1.0f);
  glm::vec4 farPoint = inverseViewProjection_ * glm::vec4(ndcX, ndcY, 1.0f, 1.0f);
  nearPoint /= nearPoint.w;
  farPoint /= farPoint.w;
  origin = eye_;
  direction = glm::normalize(glm::vec3(farPoint) - glm::vec3(nearPoint));
}

std::optional<glm::dvec2> CameraView::groundPoint(double px, double py, double groundZ) const {
  glm::vec3 origin;
  glm::vec3 direction;
  ray(px, py, origin, direction);
  if (direction.z > -1e-6f) return std::nullopt;  // parallel to or away from the ground
  const double t = (groundZ - static_cast<double>(origin.z)) / static_cast<double>(direction.z);
  if (t < 0.0) return std::nullopt;
  return glm::dvec2(static_cast<double>(origin.x) + t * static_cast<double>(direction.x),
                    static_cast<double>(origin.y) + t * static_cast<double>(direction.y));
}

std::optional<glm::vec2> CameraView::project(const glm::vec3& world) const {
  const glm::vec4 clip = viewProjection_ * glm::vec4(world, 1.0f);
  if (clip.w <= 1e-6f) return std::nullopt;
  const float ndcX = clip.x / clip.w;
  const float ndcY = clip.y / clip.w;
  return glm::vec2((ndcX + 1.0f) * 0.5f * static_cast<float>(width_),
                   (1.0f - ndcY) * 0.5f * static_cast<float>(height_));
}

float CameraView::pixelsPerMeterAt(float distanceMeters) const {
  return projectionScale_ / std::max(distanceMeters, 1e-3f);
}

namespace camera_gestures {

void pan(CameraState& state, const CameraView& view, glm::dvec2 from, glm::dvec2 to) {
  const auto a = view.groundPoint(from.x, from.y);
  const auto b = view.groundPoint(to.x, to.y);
  if (a && b) {
    // Limit one gesture's travel near the horizon, where a pixel spans kilometres.
    glm::dvec2 delta = *a - *b;
    const double maxStep = state.distance * 2.0;
    const double len = std::hypot(delta.x, delta.y);
    if (len > maxStep) delta *= maxStep / len;
    state.x += delta.x;
    state.y += delta.y;
  }
}

void orbit(CameraState& state, double dxPixels, double dyPixels, const CameraLimits& limits) {
  state.headingDeg = std::fmod(state.headingDeg + dxPixels * 0.25 + 360.0, 360.0);
  state.pitchDeg = std::clamp(state.pitchDeg + dyPixels * 0.25, limits.minPitchDeg, limits.maxPitchDeg);
}

void zoomAt(CameraState& state, const CameraView& view, glm::dvec2 at, double factor, const CameraLimits& limits) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  const double newDistance = std::clamp(state.distance * factor, limits.minDistance, limits.maxDistance);
  const double applied = newDistance / state.distance;
  // Scaling the whole camera about the ground point P keeps P at the same pixel.
  if (const auto p = view.groundPoint(at.x, at.y)) {
    const glm::dvec2 target(state.x, state.y);
    glm::dvec2 moved = *p + (target - *p) * applied;
    const glm::dvec2 shift = moved - target;
    const double maxShift = state.distance * 2.0;  // the horizon guard again
    const double len = std::hypot(shift.x, shift.y);
    if (len > maxShift) moved = target + shift * (maxShift / len);
    state.x = moved.x;
    state.y = moved.y;
  }
  state.distance = newDistance;
}

}  // namespace camera_gestures
}  // namespace qv
