// CityScene::map2d: the 2D city's shapes (qv/scene/Map2d.h) from the tiles and buildings the last
// frame culled in view.
#include <algorithm>
#include <cmath>

#include "CitySceneState.h"
#include "qv/scene/CityScene.h"
#include "qv/scene/Map2d.h"

namespace qv {

void CityScene::map2d(const CameraView& view, double cssPerPixel, ColorMode mode, double t, Map2dFrame& out) const {
  const std::size_t lastSize = out.data.size();
  out.clear();
  out.data.reserve(lastSize);
  if (!tileset_) return;
  const glm::mat4& vp = view.viewProjection();
  const auto width = static_cast<float>(view.width());
  const auto height = static_cast<float>(view.height());
  const auto scale = static_cast<float>(cssPerPixel);
  // Ground point (x, y) of the city frame to CSS pixels; false behind the camera.
  const auto project = [&](double x, double y, float& px, float& py) {
    const glm::vec4 clip = vp * glm::vec4(static_cast<float>(x), static_cast<float>(y), 0.0f, 1.0f);
    if (clip.w <= 1e-6f) return false;
    px = (clip.x / clip.w + 1.0f) * 0.5f * width * scale;
    py = (1.0f - clip.y / clip.w) * 0.5f * height * scale;
    return true;
  };
  const std::span<const std::uint8_t> series = table_.series();
  // CSS pixels per metre on the ground (seen from above, about the same everywhere in view): a
  // building whose footprint is under about two pixels across is one dot at its centre, found
  // with one projection instead of its ring's.
  const float cssPerMetre = view.pixelsPerMeterAt(std::max(std::abs(view.eye().z), 1.0f)) * scale;
  std::vector<float> ring;
  for (const std::uint32_t i : selection_.draw) {
    const TileRuntime& tr = *tiles_[i];
    if (!tr.loaded) continue;
    const LoadedTile& tile = *tr.loaded;
    const CityTile& data = tile.data;
    if (tile.mapPoints.size() != tile.tree.order().size()) {
      tile.mapPoints.resize(tile.tree.order().size());
      for (std::size_t p = 0; p < tile.mapPoints.size(); ++p) {
        const std::uint32_t b = tile.tree.order()[p];
        if (b >= data.buildings.size()) continue;
        const BuildingAttributes& a = data.buildings[b].attributes;
        tile.mapPoints[p] = {static_cast<float>(data.originX + a.centroidX),
                             static_cast<float>(data.originY + a.centroidY),
                             std::sqrt(std::max(a.footprintAreaM2, 0.0f))};
      }
    }
    for (const IndexRange& range : tr.inView) {
      for (std::uint32_t p = range.begin; p < range.end; ++p) {
        const std::uint32_t b = tile.tree.order()[p];
        if (b >= data.buildings.size()) continue;
        const BuildingGpuRecord& row = table_.row(tile.slotBase + tile.positionOf[b]);
        if ((static_cast<unsigned>(row.flags + 0.5f) & kFlagHidden) != 0u) continue;
        std::span<const FloorGpuRecord> floors;
        if (b < tr.animatedIndex.size() && tr.animatedIndex[b] != kNotAnimated && row.floorBase >= 0.0f) {
          const Animated& a = *animated_[tr.animatedIndex[b]];
          floors = table_.floors(a.floorBase, a.rows);
        }
        const auto color = static_cast<float>(packRgb(buildingRowColor(row, mode, t, series, floors)));
        const TileBuilding& building = data.buildings[b];
        const LoadedTile::MapPoint& point = tile.mapPoints[p];
        if (point.side * cssPerMetre < 1.5f) {
          float px = 0, py = 0;
          if (!project(point.x, point.y, px, py)) continue;
          if (px < 0 || py < 0 || px > width * scale || py > height * scale) continue;
          out.data.push_back(color);
          out.data.push_back(1.0f);
          out.data.push_back(px);
          out.data.push_back(py);
          ++out.shapes;
          ++out.points;
          continue;
        }
        // Each part's outer ring; a building under two pixels across is one dot.
        for (std::uint32_t k = 0; k < building.partCount; ++k) {
          const TilePart& part = data.parts[building.firstPart + k];
          if (part.ringCount == 0 || part.firstRing >= data.ringVertexCounts.size()) continue;
          const std::uint32_t n = std::min<std::uint32_t>(data.ringVertexCounts[part.firstRing], part.vertexCount);
          if (n < 3 || part.firstVertex + n > data.vertices.size()) continue;
          ring.clear();
          float minX = 1e30f, minY = 1e30f, maxX = -1e30f, maxY = -1e30f;
          bool behind = false;
          for (std::uint32_t v = 0; v < n; ++v) {
            const glm::vec2& q = data.vertices[part.firstVertex + v];
            float px = 0, py = 0;
            if (!project(data.originX + q.x, data.originY + q.y, px, py)) {
              behind = true;
              break;
            }
            ring.push_back(px);
            ring.push_back(py);
            minX = std::min(minX, px);
            maxX = std::max(maxX, px);
            minY = std::min(minY, py);
            maxY = std::max(maxY, py);
          }
          if (behind || maxX < 0 || maxY < 0 || minX > width * scale || minY > height * scale) continue;
          out.data.push_back(color);
          ++out.shapes;
          if (maxX - minX < 2.0f && maxY - minY < 2.0f) {
            out.data.push_back(1.0f);
            out.data.push_back(0.5f * (minX + maxX));
            out.data.push_back(0.5f * (minY + maxY));
            ++out.points;
            break;  // one dot for the whole building
          }
          out.data.push_back(static_cast<float>(n));
          out.data.insert(out.data.end(), ring.begin(), ring.end());
          out.points += n;
        }
      }
    }
  }
}

}  // namespace qv
