#include "qv/scene/MapLabels.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include <glm/vec4.hpp>

namespace qv {
namespace {

std::optional<glm::vec2> toScreen(const glm::mat4& viewProjection, glm::vec2 viewport, double x, double y,
                                  float z = 0.0f) {
  const glm::vec4 clip = viewProjection * glm::vec4(static_cast<float>(x), static_cast<float>(y), z, 1.0f);
  if (clip.w <= 1e-4f) return std::nullopt;
  const float nx = clip.x / clip.w;
  const float ny = clip.y / clip.w;
  if (!std::isfinite(nx) || !std::isfinite(ny)) return std::nullopt;
  return glm::vec2((nx * 0.5f + 0.5f) * viewport.x, (0.5f - ny * 0.5f) * viewport.y);
}

// The screen box around a w × h rectangle centred on c and turned by a.
Rect boundsOf(glm::vec2 c, glm::vec2 size, float a, float pad) {
  const float cs = std::abs(std::cos(a));
  const float sn = std::abs(std::sin(a));
  const float hw = 0.5f * (size.x * cs + size.y * sn) + pad;
  const float hh = 0.5f * (size.x * sn + size.y * cs) + pad;
  return Rect{c.x - hw, c.y - hh, c.x + hw, c.y + hh};
}

bool overlaps(const Rect& a, const Rect& b) {
  return a.minX < b.maxX && b.minX < a.maxX && a.minY < b.maxY && b.minY < a.maxY;
}

}  // namespace

std::vector<PlacedLabel> placeMapLabels(std::span<const MapLabel> labels, const glm::mat4& viewProjection,
                                        glm::vec2 viewport, const MeasureLabel& measure,
                                        std::span<const Rect> obstacles, const LabelPlacementOptions& options) {
  std::vector<PlacedLabel> placed;
  std::vector<Rect> boxes;
  const Rect screen{0.0f, 0.0f, viewport.x, viewport.y};
  for (const MapLabel& label : labels) {
    if (placed.size() >= options.maxLabels) break;
    if (label.text == nullptr || label.text->empty()) continue;
    std::optional<glm::vec2> at = toScreen(viewProjection, viewport, label.position.x, label.position.y, label.z);
    if (!at) continue;
    const glm::vec2 size = measure(*label.text, label.kind);
    at->y -= label.liftPx > 0.0f ? label.liftPx + 0.5f * size.y : 0.0f;
    if (!(size.x > 0.0f) || !(size.y > 0.0f)) continue;
    float angle = 0.0f;
    if (label.kind == GroundLabelKind::Street && label.lengthM > 0.0f) {
      // Along the street: its stretch's ends on screen give the direction and the room there is.
      const double half = 0.5 * label.lengthM;
      const double dx = std::cos(label.angleRad) * half;
      const double dy = std::sin(label.angleRad) * half;
      const auto a = toScreen(viewProjection, viewport, label.position.x - dx, label.position.y - dy);
      const auto b = toScreen(viewProjection, viewport, label.position.x + dx, label.position.y + dy);
      if (!a || !b) continue;
      const glm::vec2 d = *b - *a;
      const float room = std::sqrt(d.x * d.x + d.y * d.y);
      if (room < size.x + options.streetMarginPx) continue;
      angle = std::atan2(d.y, d.x);
      // Upright: never upside down.
      if (angle > 0.5f * std::numbers::pi_v<float>) angle -= std::numbers::pi_v<float>;
      if (angle < -0.5f * std::numbers::pi_v<float>) angle += std::numbers::pi_v<float>;
    }
    const Rect box = boundsOf(*at, size, angle, options.paddingPx);
    if (box.minX < screen.minX || box.minY < screen.minY || box.maxX > screen.maxX || box.maxY > screen.maxY) continue;
    bool free = true;
    for (const Rect& o : obstacles) free = free && !overlaps(box, o);
    for (std::size_t i = 0; free && i < boxes.size(); ++i) {
      if (overlaps(box, boxes[i])) free = false;
    }
    if (!free) continue;
    bool repeated = false;
    for (const PlacedLabel& p : placed) {
      if (p.text != *label.text) continue;
      const glm::vec2 d = p.center - *at;
      if (d.x * d.x + d.y * d.y < options.repeatDistancePx * options.repeatDistancePx) repeated = true;
    }
    if (repeated) continue;
    placed.push_back(PlacedLabel{*label.text, label.kind, *at, size, angle, label.facility});
    boxes.push_back(box);
  }
  return placed;
}

}  // namespace qv
