#include "qv/scene/TestScene.h"

#include <cmath>

namespace qv {
namespace {

constexpr float kPi = 3.14159265358979f;

TestPrism makePrism(std::uint32_t slot, std::vector<glm::vec2> points, std::vector<std::uint32_t> ringEnds,
                    std::vector<std::uint32_t> roof, int storeys, float storeyHeight, float period, float sway) {
  TestPrism p;
  p.storeys = storeys;
  p.storeyHeight = storeyHeight;
  p.periodSeconds = period;
  p.swayRatio = sway;
  const float top = static_cast<float>(storeys) * storeyHeight;
  std::vector<float> levels;
  floorLevelsBetween(0.0f, top, storeyHeight, levels);
  ExtrusionInput in;
  in.points = points;
  in.ringEnds = ringEnds;
  in.roofTriangles = roof;
  in.baseZ = 0.0f;
  in.topZ = top;
  in.levels = levels;
  in.slot = slot;
  appendExtrusion(p.mesh, in);
  for (const glm::vec2& q : points) {
    p.bounds.expand(q.x, q.y, 0.0f);
    p.bounds.expand(q.x, q.y, top);
  }
  // Room for the sway itself.
  const float margin = sway * top * 3.0f;
  p.bounds.minX -= margin;
  p.bounds.minY -= margin;
  p.bounds.maxX += margin;
  p.bounds.maxY += margin;
  return p;
}

std::vector<glm::vec2> rectangle(float cx, float cy, float w, float h) {
  return {{cx - w / 2, cy - h / 2}, {cx + w / 2, cy - h / 2}, {cx + w / 2, cy + h / 2}, {cx - w / 2, cy + h / 2}};
}

std::vector<std::uint32_t> fan(std::uint32_t n) {
  std::vector<std::uint32_t> t;
  triangulateConvexRing(0, n, t);
  return t;
}

}  // namespace

std::vector<TestPrism> makeTestPrisms() {
  std::vector<TestPrism> prisms;
  // A 40-storey tower in the middle.
  prisms.push_back(makePrism(0, rectangle(0, 0, 24, 24), {4}, fan(4), 40, 3.5f, 4.0f, 0.006f));
  // A 10-storey slab to the north-west and a 4-storey block to the north-east.
  prisms.push_back(makePrism(1, rectangle(-60, 45, 30, 30), {4}, fan(4), 10, 3.5f, 1.3f, 0.009f));
  prisms.push_back(makePrism(2, rectangle(45, 60, 44, 22), {4}, fan(4), 4, 3.2f, 0.5f, 0.004f));
  // An L-shape (not convex) to the south-east: outer ring counter-clockwise.
  prisms.push_back(makePrism(3, {{40, -70}, {90, -70}, {90, -50}, {60, -50}, {60, -20}, {40, -20}}, {6},
                             {0, 1, 2, 0, 2, 3, 0, 3, 5, 3, 4, 5}, 6, 3.3f, 0.8f, 0.012f));
  // A courtyard block to the south-west: outer ring CCW, the courtyard (hole) clockwise.
  {
    std::vector<glm::vec2> pts = rectangle(-65, -60, 50, 50);
    const std::vector<glm::vec2> hole = {{-75, -70}, {-75, -50}, {-55, -50}, {-55, -70}};
    pts.insert(pts.end(), hole.begin(), hole.end());
    // Outer 0..3 (SW, SE, NE, NW), hole 4..7 (SW, NW, NE, SE): four trapezoids between them.
    const std::vector<std::uint32_t> roof = {0, 1, 7, 0, 7, 4, 1, 2, 6, 1, 6, 7, 2, 3, 5, 2, 5, 6, 3, 0, 4, 3, 4, 5};
    prisms.push_back(makePrism(4, pts, {4, 8}, roof, 3, 3.2f, 0.6f, 0.016f));
  }
  // An octagon to the east.
  {
    std::vector<glm::vec2> pts;
    for (int i = 0; i < 8; ++i) {
      const float a = (static_cast<float>(i) + 0.5f) * kPi / 4.0f;
      pts.emplace_back(95.0f + 14.0f * std::cos(a), 5.0f + 14.0f * std::sin(a));
    }
    prisms.push_back(makePrism(5, pts, {8}, fan(8), 8, 3.4f, 1.0f, 0.008f));
  }
  return prisms;
}

void testPrismFloors(const TestPrism& p, double t, std::vector<FloorGpuRecord>& out) {
  const double height = p.storeys * static_cast<double>(p.storeyHeight);
  const double phase = 2.0 * 3.14159265358979 * t / p.periodSeconds;
  const double roofX = p.swayRatio * height * std::sin(phase);
  const double roofY = 0.4 * p.swayRatio * height * std::sin(phase * 0.73 + 1.0);
  for (int k = 0; k <= p.storeys; ++k) {
    const double shape = static_cast<double>(k) / p.storeys;
    FloorGpuRecord r;
    r.dxMeters = static_cast<float>(roofX * shape);
    r.dyMeters = static_cast<float>(roofY * shape);
    r.peakDriftAbove = k < p.storeys ? p.swayRatio : 0.0f;
    out.push_back(r);
  }
}

}  // namespace qv
