// Axis-aligned boxes in the city frame: metres east (x), north (y) and up (z) of the tileset
// origin. Float precision is ample for a city (±50 km at < 4 mm).
#pragma once

#include <algorithm>
#include <limits>

namespace qv {

struct Rect {
  float minX = std::numeric_limits<float>::max();
  float minY = std::numeric_limits<float>::max();
  float maxX = std::numeric_limits<float>::lowest();
  float maxY = std::numeric_limits<float>::lowest();

  [[nodiscard]] bool empty() const { return minX > maxX || minY > maxY; }
  [[nodiscard]] float width() const { return maxX - minX; }
  [[nodiscard]] float height() const { return maxY - minY; }
  [[nodiscard]] float centerX() const { return 0.5f * (minX + maxX); }
  [[nodiscard]] float centerY() const { return 0.5f * (minY + maxY); }
  void expand(float x, float y) {
    minX = std::min(minX, x);
    minY = std::min(minY, y);
    maxX = std::max(maxX, x);
    maxY = std::max(maxY, y);
  }
  void expand(const Rect& r) {
    if (r.empty()) return;
    expand(r.minX, r.minY);
    expand(r.maxX, r.maxY);
  }
  [[nodiscard]] bool contains(float x, float y) const { return x >= minX && x <= maxX && y >= minY && y <= maxY; }
  [[nodiscard]] bool intersects(const Rect& r) const {
    return !(r.minX > maxX || r.maxX < minX || r.minY > maxY || r.maxY < minY);
  }
};

struct Box {
  float minX = std::numeric_limits<float>::max();
  float minY = std::numeric_limits<float>::max();
  float minZ = std::numeric_limits<float>::max();
  float maxX = std::numeric_limits<float>::lowest();
  float maxY = std::numeric_limits<float>::lowest();
  float maxZ = std::numeric_limits<float>::lowest();

  [[nodiscard]] bool empty() const { return minX > maxX || minY > maxY || minZ > maxZ; }
  void expand(float x, float y, float z) {
    minX = std::min(minX, x);
    minY = std::min(minY, y);
    minZ = std::min(minZ, z);
    maxX = std::max(maxX, x);
    maxY = std::max(maxY, y);
    maxZ = std::max(maxZ, z);
  }
  void expand(const Box& b) {
    if (b.empty()) return;
    expand(b.minX, b.minY, b.minZ);
    expand(b.maxX, b.maxY, b.maxZ);
  }
  [[nodiscard]] Rect rect() const { return Rect{minX, minY, maxX, maxY}; }
};

}  // namespace qv
