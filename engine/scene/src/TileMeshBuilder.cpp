#include "qv/scene/TileMeshBuilder.h"

#include <algorithm>

namespace qv {
namespace {

// The LOD2 model of one building (the far mesh in coarse tiles), marked kKindModel. Its vertices
// lie on the floor planes it was re-meshed at: the vertex shader blends the displacements of the
// floors below and above each vertex by height (qv/anim/FloorBlend.h), so tiles store no skin.
void appendModel(MeshData& mesh, const TileMesh& model, float groundZ, std::uint32_t slot) {
  const std::size_t first = mesh.vertices.size();
  const std::size_t firstTriangle = mesh.triangleCount();
  TriangleMeshInput in;
  in.offset = glm::vec3(0.0f, 0.0f, groundZ);
  in.slot = slot;
  std::vector<std::uint8_t> kinds;
  constexpr std::uint8_t kKinds[kMeshSurfaceKinds] = {kWall, kRoof, kGround, kKindFromNormal};
  for (std::size_t k = 0; k < kMeshSurfaceKinds; ++k) kinds.insert(kinds.end(), model.trianglesPerKind[k], kKinds[k]);
  in.positions = model.positions;
  in.triangles = model.triangles;
  in.kinds = kinds;
  appendTriangleMesh(mesh, in);
  for (std::size_t v = first; v < mesh.vertices.size(); ++v) mesh.vertices[v].kind |= kKindModel;
  mesh.modelTriangles += mesh.triangleCount() - firstTriangle;
}

// The LOD1 extrusion of one building: its parts as prisms, with a vertex ring at every floor
// level inside each part when `floorRings`.
void appendExtrusions(MeshData& mesh, const CityTile& d, const TileBuilding& tb, std::uint32_t slot, bool floorRings) {
  const BuildingAttributes& a = tb.attributes;
  const FloorGrid floors{a.minHeightM, std::max(a.storeyHeightM(), 0.5f), a.storeys};
  std::vector<float> levels;
  std::vector<std::uint32_t> ringEnds, roof;
  for (std::uint32_t pi = tb.firstPart; pi < tb.firstPart + tb.partCount; ++pi) {
    const TilePart& part = d.parts[pi];
    levels.clear();
    if (floorRings) floorLevelsBetween(floors, part.minHeightM, part.heightM, 0.01f, levels);
    ringEnds.clear();
    std::uint32_t end = 0;
    for (std::uint32_t r = part.firstRing; r < part.firstRing + part.ringCount; ++r) {
      end += d.ringVertexCounts[r];
      ringEnds.push_back(end);
    }
    roof.assign(d.roofTriangles.begin() + static_cast<std::ptrdiff_t>(part.firstTriangle) * 3,
                d.roofTriangles.begin() + static_cast<std::ptrdiff_t>(part.firstTriangle + part.triangleCount) * 3);
    ExtrusionInput in;
    in.points = std::span<const glm::vec2>(d.vertices).subspan(part.firstVertex, part.vertexCount);
    in.ringEnds = ringEnds;
    in.roofTriangles = roof;
    in.baseZ = part.minHeightM;
    in.topZ = part.heightM;
    in.levels = levels;
    in.slot = slot;
    appendExtrusion(mesh, in);
  }
}

}  // namespace

Box buildingBox(const TileContent& tile, std::uint32_t b) {
  const CityTile& d = tile.data;
  const TileBuilding& tb = d.buildings[b];
  Box box;
  for (std::uint32_t p = tb.firstPart; p < tb.firstPart + tb.partCount; ++p) {
    const TilePart& part = d.parts[p];
    for (std::uint32_t v = part.firstVertex; v < part.firstVertex + part.vertexCount; ++v) {
      box.expand(d.vertices[v].x + tile.origin.x, d.vertices[v].y + tile.origin.y, part.minHeightM);
      box.expand(d.vertices[v].x + tile.origin.x, d.vertices[v].y + tile.origin.y, part.heightM);
    }
  }
  if (const TileMesh* m = tile.drawnModelOf(b)) {
    const float ground = tb.attributes.minHeightM;
    for (const glm::vec3& q : m->positions) box.expand(q.x + tile.origin.x, q.y + tile.origin.y, q.z + ground);
  }
  return box;
}

TileContent indexTile(CityTile data) {
  TileContent tile;
  tile.data = std::move(data);
  const CityTile& d = tile.data;
  tile.origin = glm::vec3(static_cast<float>(d.originX), static_cast<float>(d.originY), 0.0f);
  // LOD2 models (MESH section), by building: drawn instead of the building's prisms, the skinned
  // mesh in leaves and the simplified far mesh in coarse tiles.
  tile.meshIndex.assign(d.buildings.size(), -1);
  for (std::size_t k = 0; k < d.meshes.size(); ++k) {
    if (d.meshes[k].building < d.buildings.size()) tile.meshIndex[d.meshes[k].building] = static_cast<std::int32_t>(k);
  }
  // Boxes per building in the city frame, then the BoxTree's Morton order for slots and mesh.
  std::vector<Box> boxes(d.buildings.size());
  for (std::uint32_t b = 0; b < d.buildings.size(); ++b) boxes[b] = buildingBox(tile, b);
  tile.tree.build(boxes);
  const auto& order = tile.tree.order();
  tile.idIndex.reserve(d.buildings.size());
  for (std::uint32_t b = 0; b < d.buildings.size(); ++b) tile.idIndex.emplace(d.buildings[b].attributes.id, b);
  tile.positionOf.resize(order.size());
  for (std::uint32_t p = 0; p < order.size(); ++p) tile.positionOf[order[p]] = p;
  return tile;
}

MeshData buildTileMesh(const TileContent& tile, std::uint32_t slotBase, TileIndexRuns* runs,
                       std::span<const std::uint32_t> appendOrder, TileWalls walls) {
  const bool floorRings = walls == TileWalls::Storeys && !tile.data.coarse;
  MeshData mesh;
  const CityTile& d = tile.data;
  const auto& order = tile.tree.order();
  const auto count = static_cast<std::uint32_t>(appendOrder.empty() ? order.size() : appendOrder.size());
  if (runs != nullptr) {
    runs->firstIndex.assign(count + 1, 0);
    runs->modelTriangles.assign(count + 1, 0);
    runs->fallbackTriangles.assign(count + 1, 0);
  }
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t p = appendOrder.empty() ? k : appendOrder[k];
    if (runs != nullptr) {
      runs->firstIndex[k] = static_cast<std::uint32_t>(mesh.indices.size());
      runs->modelTriangles[k] = static_cast<std::uint32_t>(mesh.modelTriangles);
      runs->fallbackTriangles[k] = static_cast<std::uint32_t>(mesh.fallbackTriangles);
    }
    const TileBuilding& tb = d.buildings[order[p]];
    const TileMesh* model = tile.drawnModelOf(order[p]);
    if (model != nullptr) appendModel(mesh, *model, tb.attributes.minHeightM, slotBase + p);
    // The LOD1 extrusion; after a model, marked as the fallback the shader draws instead when LOD2
    // is switched off.
    const std::size_t firstExtruded = mesh.vertices.size();
    const std::size_t firstExtrudedTriangle = mesh.triangleCount();
    appendExtrusions(mesh, d, tb, slotBase + p, floorRings);
    if (model != nullptr) {
      for (std::size_t v = firstExtruded; v < mesh.vertices.size(); ++v) mesh.vertices[v].kind |= kKindFallback;
      mesh.fallbackTriangles += mesh.triangleCount() - firstExtrudedTriangle;
    }
  }
  if (runs != nullptr) {
    runs->firstIndex[count] = static_cast<std::uint32_t>(mesh.indices.size());
    runs->modelTriangles[count] = static_cast<std::uint32_t>(mesh.modelTriangles);
    runs->fallbackTriangles[count] = static_cast<std::uint32_t>(mesh.fallbackTriangles);
  }
  return mesh;
}

void visibleIndexSpans(const TileIndexRuns& runs, std::span<const IndexRange> visible, std::uint32_t mergeGapIndices,
                       std::uint32_t maxSpans, std::vector<IndexSpan>& out) {
  out.clear();
  const std::size_t positions = runs.firstIndex.empty() ? 0 : runs.firstIndex.size() - 1;
  // Spans as [begin, end) of positions first; indices and counts once merged.
  struct Run {
    std::uint32_t begin, end;
  };
  std::vector<Run> spans;
  for (const IndexRange& r : visible) {
    const std::uint32_t begin = std::min<std::uint32_t>(r.begin, static_cast<std::uint32_t>(positions));
    const std::uint32_t end = std::min<std::uint32_t>(r.end, static_cast<std::uint32_t>(positions));
    if (end <= begin || runs.firstIndex[end] == runs.firstIndex[begin]) continue;
    if (!spans.empty() && runs.firstIndex[begin] - runs.firstIndex[spans.back().end] <= mergeGapIndices) {
      spans.back().end = end;
    } else {
      spans.push_back({begin, end});
    }
  }
  maxSpans = std::max<std::uint32_t>(maxSpans, 1);
  if (spans.size() > maxSpans) {
    // Keep the maxSpans - 1 largest gaps; merge across the rest.
    std::vector<std::uint32_t> gaps(spans.size() - 1);
    for (std::size_t k = 0; k + 1 < spans.size(); ++k) {
      gaps[k] = runs.firstIndex[spans[k + 1].begin] - runs.firstIndex[spans[k].end];
    }
    std::vector<std::uint32_t> sorted = gaps;
    const std::size_t keep = maxSpans - 1;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() - keep - 1),
                     sorted.end());
    const std::uint32_t cut = sorted[sorted.size() - keep - 1];
    // Gaps above the cut stay; of the gaps equal to it, as many as the cap leaves room for.
    std::size_t ties = keep - static_cast<std::size_t>(
                                  std::count_if(gaps.begin(), gaps.end(), [cut](std::uint32_t g) { return g > cut; }));
    std::vector<Run> merged{spans[0]};
    for (std::size_t k = 0; k + 1 < spans.size(); ++k) {
      bool split = gaps[k] > cut;
      if (!split && gaps[k] == cut && ties > 0) {
        split = true;
        --ties;
      }
      if (split) {
        merged.push_back(spans[k + 1]);
      } else {
        merged.back().end = spans[k + 1].end;
      }
    }
    spans.swap(merged);
  }
  out.reserve(spans.size());
  for (const Run& s : spans) {
    out.push_back(IndexSpan{runs.firstIndex[s.begin], runs.firstIndex[s.end] - runs.firstIndex[s.begin],
                            runs.modelTriangles[s.end] - runs.modelTriangles[s.begin],
                            runs.fallbackTriangles[s.end] - runs.fallbackTriangles[s.begin]});
  }
}

void initialBuildingRows(const TileContent& tile, bool resultsPending, std::span<BuildingGpuRecord> rows) {
  const auto& order = tile.tree.order();
  for (std::uint32_t p = 0; p < order.size() && p < rows.size(); ++p) {
    const BuildingAttributes& a = tile.data.buildings[order[p]].attributes;
    BuildingGpuRecord& row = rows[p];
    row = BuildingGpuRecord{};
    row.storeyHeightMeters = std::max(a.storeyHeightM(), 0.5f);
    row.storeys = static_cast<float>(a.storeys);
    row.baseZ = a.minHeightM;
    // Results on their way: plain (not hatched as "no result") until the summary arrives.
    if (resultsPending) row.damageState = kDamagePending;
  }
}

std::uint64_t tileCpuBytes(const TileContent& tile) {
  const CityTile& d = tile.data;
  std::uint64_t bytes = d.vertices.size() * sizeof(glm::vec2) + d.roofTriangles.size() * 2 +
                        d.ringVertexCounts.size() * 2 + d.parts.size() * sizeof(TilePart) +
                        d.buildings.size() * (sizeof(TileBuilding) + 64) + d.buildings.size() * (sizeof(Box) * 2 + 12) +
                        tile.meshIndex.size() * 4;
  for (const TileMesh& m : d.meshes) {
    bytes += sizeof(TileMesh) + m.positions.size() * sizeof(glm::vec3) + m.triangles.size() * 4 +
             m.farPositions.size() * sizeof(glm::vec3) + m.farTriangles.size() * 2;
  }
  return bytes;
}

std::uint64_t meshGpuBytes(const MeshData& mesh) {
  return mesh.vertices.size() * sizeof(BuildingVertex) + mesh.indices.size() * sizeof(std::uint32_t);
}

}  // namespace qv
