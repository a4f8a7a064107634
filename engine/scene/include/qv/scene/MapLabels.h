// Placement of the map's names (qv/scene/GroundScene.h MapLabel) on the screen: most important
// first, none overlapping another or a panel, upright, street names along their street where the
// street is long enough on screen to carry them. Pure: the UI layer measures and draws the text.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "qv/format/GroundTile.h"
#include "qv/geometry/Bounds.h"
#include "qv/scene/GroundScene.h"

namespace qv {

/// A label where it is drawn: its text's box (width × height, screen pixels) centred on `center`,
/// turned by `angleRad` (screen space, y down: positive turns clockwise), in [-pi/2, pi/2] so it
/// reads left to right.
struct PlacedLabel {
  std::string_view text;  ///< points into the MapLabel's text
  GroundLabelKind kind = GroundLabelKind::Street;
  glm::vec2 center{0.0f};
  glm::vec2 size{0.0f};
  float angleRad = 0.0f;
  bool facility = false;  ///< MapLabel::facility
};

struct LabelPlacementOptions {
  std::size_t maxLabels = 150;  ///< placed at most
  float paddingPx = 3.0f;       ///< kept free around each label
  /// The same name is placed again only this far (pixels) from where it already is (a long
  /// street crossing many cells, a river).
  float repeatDistancePx = 300.0f;
  /// A street's name needs this much more of its street on screen than its own width.
  float streetMarginPx = 10.0f;
};

/// Text size in screen pixels of a label of this kind (the UI's font).
using MeasureLabel = std::function<glm::vec2(std::string_view text, GroundLabelKind kind)>;

/// Places `labels` (in rank order) seen through `viewProjection` on a `viewport` of pixels (origin
/// top-left), keeping clear of `obstacles` (screen rectangles: the panels). Labels behind the eye,
/// off screen, or whose street is too short on screen to carry them are left out.
std::vector<PlacedLabel> placeMapLabels(std::span<const MapLabel> labels, const glm::mat4& viewProjection,
                                        glm::vec2 viewport, const MeasureLabel& measure,
                                        std::span<const Rect> obstacles, const LabelPlacementOptions& options = {});

}  // namespace qv
