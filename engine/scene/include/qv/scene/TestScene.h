// The built-in test scene (`?scene=test`): a few extruded prisms (rectangles, an L-shape, a
// courtyard with a hole, an octagon, a tower) that sway floor by floor with analytic motion. It
// exercises the whole drawing path (extrusion, per-floor displacement, drift colours, lighting,
// camera) without any data, and is what the first-light browser test looks at.
#pragma once

#include <vector>

#include "qv/geometry/Bounds.h"
#include "qv/geometry/BuildingMesh.h"
#include "qv/scene/RenderDevice.h"

namespace qv {

struct TestPrism {
  MeshData mesh;
  Box bounds;
  int storeys = 1;
  float storeyHeight = 3.0f;
  float periodSeconds = 1.0f;
  float swayRatio = 0.01f;  ///< roof displacement / height at peak
};

/// Builds the prisms around the origin (within ±100 m). Slot i belongs to prism i.
std::vector<TestPrism> makeTestPrisms();

/// Floor displacements of prism `p` at time t (linear first-mode shape), storeys + 1 records.
void testPrismFloors(const TestPrism& p, double timeSeconds, std::vector<FloorGpuRecord>& out);

}  // namespace qv
