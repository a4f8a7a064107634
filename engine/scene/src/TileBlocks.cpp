#include "qv/scene/TileBlocks.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace qv {
namespace {

// Sutherland–Hodgman clipping of a ring against one side of an axis-aligned rectangle, keeping
// the points with (axis coordinate) × sign <= limit × sign.
void clipSide(const std::vector<glm::vec2>& in, int axis, float limit, float sign, std::vector<glm::vec2>& out) {
  out.clear();
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec2& a = in[i];
    const glm::vec2& b = in[(i + 1) % n];
    const float da = (a[axis] - limit) * sign;
    const float db = (b[axis] - limit) * sign;
    if (da <= 0.0f) out.push_back(a);
    if ((da < 0.0f && db > 0.0f) || (da > 0.0f && db < 0.0f)) {
      const float t = da / (da - db);
      out.push_back(a + (b - a) * t);
    }
  }
}

struct CellKey {
  std::int32_t x, y;
  bool operator==(const CellKey&) const = default;
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return std::hash<std::uint64_t>()((static_cast<std::uint64_t>(static_cast<std::uint32_t>(k.x)) << 32) |
                                      static_cast<std::uint32_t>(k.y));
  }
};

struct Accumulator {
  Box box;
  std::vector<std::uint32_t> members;  // positions, ascending (buildings are visited in order)
  std::uint64_t code = 0;              // Morton code of the cell
  std::uint32_t region = 0;
  glm::ivec2 cell{0};
};

// Morton code of a grid cell (cells within ±2^31 of the origin).
std::uint64_t mortonOf(std::int32_t x, std::int32_t y) {
  auto spread = [](std::uint64_t v) {
    v &= 0xffffffffull;
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
  };
  const auto ux = static_cast<std::uint64_t>(static_cast<std::int64_t>(x) + (1ll << 31));
  const auto uy = static_cast<std::uint64_t>(static_cast<std::int64_t>(y) + (1ll << 31));
  return spread(ux) | (spread(uy) << 1);
}

std::int32_t cellIndex(float v, float inverseSide) {
  return static_cast<std::int32_t>(std::floor(v * inverseSide));
}

}  // namespace

int regionLevelFor(float widthM, float heightM) {
  const float side = std::max(widthM, heightM);
  int level = kBlockRegionLevel;
  while (level + 1 < kBlockLevels && !(side <= kMaxRegionsAcross * blockCellM(level))) ++level;
  return level;
}

std::uint32_t TileRegions::regionOf(float x, float y) const {
  const float inverse = 1.0f / blockCellM(level);
  const std::uint64_t code = mortonOf(cellIndex(x, inverse), cellIndex(y, inverse));
  const auto it = std::lower_bound(codes.begin(), codes.end(), code);
  return it != codes.end() && *it == code ? static_cast<std::uint32_t>(it - codes.begin()) : UINT32_MAX;
}

TileRegions buildTileRegions(const TileContent& tile, int level) {
  TileRegions regions;
  const auto& order = tile.tree.order();
  const Box& all = tile.tree.bounds();
  regions.level = std::clamp(level, kBlockRegionLevel, kBlockLevels - 1);
  const float side = blockCellM(regions.level);
  const float inverse = 1.0f / side;
  // Every region a building's box reaches into (a block of its parts may lie there), with its
  // grid cell; each building's home region (its box's centre).
  std::vector<std::pair<std::uint64_t, glm::ivec2>> cells;
  std::vector<std::uint64_t> home(order.size());
  for (std::uint32_t p = 0; p < order.size(); ++p) {
    const Box box = buildingBox(tile, order[p]);
    for (std::int32_t y = cellIndex(box.minY, inverse); y <= cellIndex(box.maxY, inverse); ++y) {
      for (std::int32_t x = cellIndex(box.minX, inverse); x <= cellIndex(box.maxX, inverse); ++x)
        cells.emplace_back(mortonOf(x, y), glm::ivec2(x, y));
    }
    home[p] =
        mortonOf(cellIndex(0.5f * (box.minX + box.maxX), inverse), cellIndex(0.5f * (box.minY + box.maxY), inverse));
  }
  std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  cells.erase(std::unique(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
              cells.end());
  std::vector<std::uint64_t>& codes = regions.codes;
  codes.reserve(cells.size());
  regions.boxes.resize(cells.size());
  for (std::size_t r = 0; r < cells.size(); ++r) {
    codes.push_back(cells[r].first);
    const glm::ivec2 c = cells[r].second;
    Box& b = regions.boxes[r];
    b.expand(static_cast<float>(c.x) * side, static_cast<float>(c.y) * side, all.empty() ? 0.0f : all.minZ);
    b.expand(static_cast<float>(c.x + 1) * side, static_cast<float>(c.y + 1) * side, all.empty() ? 0.0f : all.maxZ);
  }
  // Buildings region by region.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> byRegion(order.size());
  for (std::uint32_t p = 0; p < order.size(); ++p) {
    const auto r = static_cast<std::uint32_t>(std::lower_bound(codes.begin(), codes.end(), home[p]) - codes.begin());
    byRegion[p] = {r, p};
  }
  std::sort(byRegion.begin(), byRegion.end());
  regions.appendOrder.resize(order.size());
  regions.positionStart.assign(codes.size() + 1, 0);
  regions.regionOfPosition.resize(order.size());
  for (std::size_t k = 0; k < byRegion.size(); ++k) {
    regions.appendOrder[k] = byRegion[k].second;
    regions.regionOfPosition[byRegion[k].second] = byRegion[k].first;
    ++regions.positionStart[byRegion[k].first + 1];
  }
  for (std::size_t r = 0; r < codes.size(); ++r) regions.positionStart[r + 1] += regions.positionStart[r];
  return regions;
}

TileBlockLevel buildBlockLevel(const TileContent& tile, float cellM, const TileRegions& regions) {
  TileBlockLevel level;
  level.cellM = cellM;
  const CityTile& d = tile.data;
  const auto& order = tile.tree.order();
  std::unordered_map<CellKey, std::uint32_t, CellHash> cellOf;
  std::vector<Accumulator> cells;
  std::vector<glm::vec2> ring, clipped, scratch;
  const float inverse = 1.0f / cellM;
  auto add = [&](CellKey key, float minX, float minY, float maxX, float maxY, const TilePart& part,
                 std::uint32_t position) {
    auto [it, inserted] = cellOf.try_emplace(key, static_cast<std::uint32_t>(cells.size()));
    if (inserted) cells.emplace_back();
    Accumulator& c = cells[it->second];
    c.box.expand(minX, minY, part.minHeightM);
    c.box.expand(maxX, maxY, part.heightM);
    if (c.members.empty() || c.members.back() != position) c.members.push_back(position);
  };
  for (std::uint32_t p = 0; p < order.size(); ++p) {
    const TileBuilding& tb = d.buildings[order[p]];
    for (std::uint32_t pi = tb.firstPart; pi < tb.firstPart + tb.partCount; ++pi) {
      const TilePart& part = d.parts[pi];
      if (part.ringCount == 0 || part.heightM <= part.minHeightM) continue;
      const std::uint32_t outer = std::min<std::uint32_t>(d.ringVertexCounts[part.firstRing], part.vertexCount);
      if (outer < 3) continue;
      ring.clear();
      float minX = INFINITY, minY = INFINITY, maxX = -INFINITY, maxY = -INFINITY;
      for (std::uint32_t v = part.firstVertex; v < part.firstVertex + outer; ++v) {
        const glm::vec2 q(d.vertices[v].x + tile.origin.x, d.vertices[v].y + tile.origin.y);
        ring.push_back(q);
        minX = std::min(minX, q.x);
        minY = std::min(minY, q.y);
        maxX = std::max(maxX, q.x);
        maxY = std::max(maxY, q.y);
      }
      const auto x0 = static_cast<std::int32_t>(std::floor(minX * inverse));
      const auto x1 = static_cast<std::int32_t>(std::floor(maxX * inverse));
      const auto y0 = static_cast<std::int32_t>(std::floor(minY * inverse));
      const auto y1 = static_cast<std::int32_t>(std::floor(maxY * inverse));
      if (x0 == x1 && y0 == y1) {
        add(CellKey{x0, y0}, minX, minY, maxX, maxY, part, p);
        continue;
      }
      // The part reaches into several cells: each gets the bounds of what of it lies inside.
      for (std::int32_t cy = y0; cy <= y1; ++cy) {
        for (std::int32_t cx = x0; cx <= x1; ++cx) {
          const float left = static_cast<float>(cx) * cellM, right = static_cast<float>(cx + 1) * cellM;
          const float bottom = static_cast<float>(cy) * cellM, top = static_cast<float>(cy + 1) * cellM;
          clipSide(ring, 0, right, 1.0f, clipped);
          clipSide(clipped, 0, left, -1.0f, scratch);
          clipSide(scratch, 1, top, 1.0f, clipped);
          clipSide(clipped, 1, bottom, -1.0f, scratch);
          if (scratch.size() < 3) continue;
          float a = INFINITY, b = INFINITY, c = -INFINITY, e = -INFINITY;
          for (const glm::vec2& q : scratch) {
            a = std::min(a, q.x);
            b = std::min(b, q.y);
            c = std::max(c, q.x);
            e = std::max(e, q.y);
          }
          if (c - a <= 1e-3f || e - b <= 1e-3f) continue;  // touches the cell's edge only
          add(CellKey{cx, cy}, a, b, c, e, part, p);
        }
      }
    }
  }
  // Blocks region by region, in Morton order within a region (a block's cell lies in one region).
  for (const auto& [key, index] : cellOf) {
    Accumulator& c = cells[index];
    c.code = mortonOf(key.x, key.y);
    c.cell = glm::ivec2(key.x, key.y);
    const float centreX = (static_cast<float>(key.x) + 0.5f) * cellM,
                centreY = (static_cast<float>(key.y) + 0.5f) * cellM;
    c.region = regions.regionOf(centreX, centreY);
  }
  std::vector<std::uint32_t> sorted(cells.size());
  for (std::uint32_t k = 0; k < sorted.size(); ++k) sorted[k] = k;
  std::sort(sorted.begin(), sorted.end(), [&](std::uint32_t a, std::uint32_t b) {
    return cells[a].region != cells[b].region ? cells[a].region < cells[b].region : cells[a].code < cells[b].code;
  });
  while (!sorted.empty() && cells[sorted.back()].region == UINT32_MAX) sorted.pop_back();  // none: not expected
  const std::size_t n = sorted.size();
  level.boxes.resize(n);
  level.cells.resize(n);
  level.memberStart.assign(n + 1, 0);
  level.regionStart.assign(regions.boxes.size() + 1, 0);
  std::size_t memberCount = 0;
  for (const Accumulator& c : cells) memberCount += c.members.size();
  level.members.reserve(memberCount);
  for (std::size_t k = 0; k < n; ++k) {
    const Accumulator& c = cells[sorted[k]];
    level.boxes[k] = c.box;
    level.cells[k] = c.cell;
    level.memberStart[k] = static_cast<std::uint32_t>(level.members.size());
    level.members.insert(level.members.end(), c.members.begin(), c.members.end());
    ++level.regionStart[c.region + 1];
  }
  level.memberStart[n] = static_cast<std::uint32_t>(level.members.size());
  for (std::size_t r = 0; r < regions.boxes.size(); ++r) level.regionStart[r + 1] += level.regionStart[r];
  level.tree.build(level.boxes);
  return level;
}

MeshData buildBlockMesh(const TileBlockLevel& level, const glm::vec3& origin, std::uint32_t slotBase,
                        TileIndexRuns* runs) {
  MeshData mesh;
  const std::size_t n = level.boxes.size();
  mesh.vertices.reserve(n * 20);
  mesh.indices.reserve(n * 30);
  if (runs != nullptr) {
    runs->firstIndex.assign(n + 1, 0);
    runs->modelTriangles.assign(n + 1, 0);
    runs->fallbackTriangles.assign(n + 1, 0);
  }
  std::unordered_map<CellKey, std::uint32_t, CellHash> blockAt;
  blockAt.reserve(n);
  for (std::uint32_t p = 0; p < n; ++p) blockAt.emplace(CellKey{level.cells[p].x, level.cells[p].y}, p);
  const float cell = level.cellM;
  constexpr float kEdge = 1e-3f;
  // Whether block p's wall on side (dx, dy) is inside the neighbouring block q: both on the
  // shared cell edge, q spanning p's extent along it, from below p's base to above its top.
  auto hidden = [&](std::uint32_t p, int dx, int dy) {
    const auto it = blockAt.find(CellKey{level.cells[p].x + dx, level.cells[p].y + dy});
    if (it == blockAt.end()) return false;
    const Box& a = level.boxes[p];
    const Box& b = level.boxes[it->second];
    if (b.maxZ < a.maxZ || b.minZ > a.minZ) return false;
    const glm::ivec2 c = level.cells[p];
    if (dx != 0) {
      const float edge = static_cast<float>(dx > 0 ? c.x + 1 : c.x) * cell;
      const float mine = dx > 0 ? a.maxX : a.minX, theirs = dx > 0 ? b.minX : b.maxX;
      return std::abs(mine - edge) < kEdge && std::abs(theirs - edge) < kEdge && b.minY <= a.minY + kEdge &&
             b.maxY >= a.maxY - kEdge;
    }
    const float edge = static_cast<float>(dy > 0 ? c.y + 1 : c.y) * cell;
    const float mine = dy > 0 ? a.maxY : a.minY, theirs = dy > 0 ? b.minY : b.maxY;
    return std::abs(mine - edge) < kEdge && std::abs(theirs - edge) < kEdge && b.minX <= a.minX + kEdge &&
           b.maxX >= a.maxX - kEdge;
  };
  for (std::uint32_t p = 0; p < n; ++p) {
    if (runs != nullptr) runs->firstIndex[p] = static_cast<std::uint32_t>(mesh.indices.size());
    const Box& b = level.boxes[p];
    const std::uint32_t slot = slotBase + p;
    const float x0 = b.minX - origin.x, x1 = b.maxX - origin.x, y0 = b.minY - origin.y, y1 = b.maxY - origin.y;
    const float z0 = b.minZ, z1 = std::max(b.maxZ, b.minZ + 0.01f);
    // Counter-clockwise corners; wall k runs from corner k to k + 1 with its outward normal.
    const glm::vec2 corners[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    constexpr int kSide[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    for (int k = 0; k < 4; ++k) {
      if (hidden(p, kSide[k][0], kSide[k][1])) continue;
      const glm::vec2 a = corners[k], c = corners[(k + 1) % 4];
      const auto nx = static_cast<std::int8_t>(127 * kSide[k][0]), ny = static_cast<std::int8_t>(127 * kSide[k][1]);
      const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.push_back({a.x, a.y, z0, nx, ny, 0, kWall, slot});
      mesh.vertices.push_back({c.x, c.y, z0, nx, ny, 0, kWall, slot});
      mesh.vertices.push_back({a.x, a.y, z1, nx, ny, 0, kWall, slot});
      mesh.vertices.push_back({c.x, c.y, z1, nx, ny, 0, kWall, slot});
      // As appendExtrusion: both triangles end on a bottom vertex (the provoking one).
      mesh.indices.insert(mesh.indices.end(), {first + 3, first, first + 1, first + 3, first + 2, first});
    }
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    for (const glm::vec2& q : corners) mesh.vertices.push_back({q.x, q.y, z1, 0, 0, 127, kRoof, slot});
    mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
  }
  if (runs != nullptr) runs->firstIndex[n] = static_cast<std::uint32_t>(mesh.indices.size());
  return mesh;
}

void aggregateBlockRows(const TileBlockLevel& level, std::span<const BuildingGpuRecord> buildingRows,
                        std::span<BuildingGpuRecord> out) {
  const std::size_t n = std::min(level.boxes.size(), out.size());
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint32_t* first = level.members.data() + level.memberStart[p];
    const std::uint32_t* last = level.members.data() + level.memberStart[p + 1];
    // Flags over every member; the colour over the members a filter keeps, when it keeps any.
    bool anySelected = false, allDimmed = true, allHidden = true;
    for (const std::uint32_t* m = first; m != last; ++m) {
      if (*m >= buildingRows.size()) continue;
      const auto flags = static_cast<unsigned>(buildingRows[*m].flags);
      anySelected = anySelected || (flags & kFlagSelected) != 0;
      allDimmed = allDimmed && (flags & kFlagDimmed) != 0;
      allHidden = allHidden && (flags & kFlagHidden) != 0;
    }
    BuildingGpuRecord row;
    row.floorBase = -1.0f;
    row.peakValue = 0.0f;
    row.lossCode = -1.0f;
    row.baseZ = level.boxes[p].minZ;
    bool anyPending = false, anyResult = false;
    float tallest = -INFINITY, damage = -INFINITY;
    for (const std::uint32_t* m = first; m != last; ++m) {
      if (*m >= buildingRows.size()) continue;
      const BuildingGpuRecord& r = buildingRows[*m];
      if (!allDimmed && (static_cast<unsigned>(r.flags) & kFlagDimmed) != 0) continue;
      if (r.damageState >= 0.0f) {
        anyResult = true;
        damage = std::max(damage, r.damageState);
      } else if (r.damageState == kDamagePending) {
        anyPending = true;
      }
      row.peakValue = std::max(row.peakValue, r.peakValue);
      row.lossCode = std::max(row.lossCode, r.lossCode);
      const float height = r.storeyHeightMeters * r.storeys;
      if (height > tallest) {
        tallest = height;
        row.storeyHeightMeters = r.storeyHeightMeters;
        row.storeys = r.storeys;
      }
    }
    row.damageState = anyResult ? damage : (anyPending ? kDamagePending : kDamageNoResult);
    unsigned flags = 0;
    if (anySelected) flags |= kFlagSelected;
    if (allDimmed) flags |= kFlagDimmed;
    if (allHidden) flags |= kFlagHidden;
    row.flags = static_cast<float>(flags);
    out[p] = row;
  }
}

std::uint64_t blockLevelCpuBytes(const TileBlockLevel& level) {
  return level.boxes.size() * (sizeof(Box) * 2 + sizeof(std::uint32_t) * 2) +
         level.members.size() * sizeof(std::uint32_t);
}

}  // namespace qv
