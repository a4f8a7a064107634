// A map-style orbit camera over the city frame (x east, y north, z up, metres from the tileset
// origin). The state is exactly what `quakeview.getCamera()` reports.
#pragma once

#include <optional>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "qv/geometry/Frustum.h"

namespace qv {

struct CameraState {
  double x = 0.0;          ///< looked-at point, metres east of the origin
  double y = 0.0;          ///< looked-at point, metres north of the origin
  double distance = 1000;  ///< metres from the eye to the looked-at point
  double headingDeg = 0;   ///< 0 = looking north, clockwise (90 = looking east)
  double pitchDeg = 45;    ///< 0 = horizontal, 90 = straight down
  double fovDeg = 45;      ///< vertical field of view
};

/// Limits that keep the camera sane from street level to a whole city.
struct CameraLimits {
  double minDistance = 5.0;
  double maxDistance = 200000.0;
  double minPitchDeg = 2.0;
  double maxPitchDeg = 90.0;
  double minFovDeg = 10.0;
  double maxFovDeg = 100.0;
  double maxAbsCoordinate = 1.0e6;  ///< |x|, |y| beyond this are clamped (metres)
};

/// Clamps every field into its limits; non-finite fields take the fallback's value.
/// Returns true when the state was already valid.
bool sanitizeCamera(CameraState& state, const CameraState& fallback, const CameraLimits& limits = {});

/// Matrices and derived quantities of a camera state for a viewport of the given size (pixels).
class CameraView {
 public:
  /// `shiftNdcX`: the lens moved sideways, in normalized device units (the viewport is 2 wide):
  /// the looked-at point appears shiftNdcX × width / 2 pixels right of the viewport's centre (the
  /// centre of the canvas part the panels leave free; MapLibre's "padding"). Rays, projection and
  /// the frustum all follow it.
  CameraView(const CameraState& state, int viewportWidth, int viewportHeight, float shiftNdcX = 0.0f);

  [[nodiscard]] const glm::mat4& view() const { return view_; }
  [[nodiscard]] const glm::mat4& projection() const { return projection_; }
  [[nodiscard]] const glm::mat4& viewProjection() const { return viewProjection_; }
  [[nodiscard]] const Frustum& frustum() const { return frustum_; }
  [[nodiscard]] glm::vec3 eye() const { return eye_; }
  [[nodiscard]] glm::vec3 forward() const { return forward_; }
  [[nodiscard]] float nearPlane() const { return near_; }
  [[nodiscard]] float farPlane() const { return far_; }
  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

  /// World-space ray through a viewport point (pixels, origin top-left). Direction is unit length.
  void ray(double px, double py, glm::vec3& origin, glm::vec3& direction) const;
  /// Where the ray through a viewport point meets the plane z = groundZ, if it does (in front).
  [[nodiscard]] std::optional<glm::dvec2> groundPoint(double px, double py, double groundZ = 0.0) const;
  /// Projects a world point to viewport pixels (origin top-left); nullopt when behind the eye.
  [[nodiscard]] std::optional<glm::vec2> project(const glm::vec3& world) const;
  /// Metres per pixel at a given distance from the eye (for screen-space error).
  [[nodiscard]] float pixelsPerMeterAt(float distanceMeters) const;

 private:
  glm::mat4 view_{1.0f};
  glm::mat4 projection_{1.0f};
  glm::mat4 viewProjection_{1.0f};
  glm::mat4 inverseViewProjection_{1.0f};
  Frustum frustum_;
  glm::vec3 eye_{0.0f};
  glm::vec3 forward_{0.0f, 1.0f, 0.0f};
  float near_ = 1.0f;
  float far_ = 1000.0f;
  float projectionScale_ = 1.0f;  // viewport height / (2 tan(fov/2))
  int width_ = 1;
  int height_ = 1;
};

/// Map-style camera gestures. All take viewport pixels (origin top-left).
namespace camera_gestures {
/// Drags the ground so the point under `from` ends under `to`.
void pan(CameraState& state, const CameraView& view, glm::dvec2 from, glm::dvec2 to);
/// Rotates around the looked-at point: dx pixels change the heading, dy pixels the pitch.
void orbit(CameraState& state, double dxPixels, double dyPixels, const CameraLimits& limits = {});
/// Zooms by `factor` (< 1 zooms in) keeping the ground point under `at` fixed on screen.
void zoomAt(CameraState& state, const CameraView& view, glm::dvec2 at, double factor, const CameraLimits& limits = {});
}  // namespace camera_gestures

}  // namespace qv
