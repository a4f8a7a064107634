#include "qv/prep/Tiler.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <functional>
#include <mutex>
#include <span>
#include <thread>
#include <unordered_map>

#include "qv/core/Crc32.h"
#include "qv/format/CityTile.h"
#include "qv/format/SearchIndex.h"
#include "qv/prep/Cli.h"
#include "qv/prep/DefaultDistricts.h"
#include "qv/prep/Files.h"
#include "qv/prep/Simplify.h"
#include "qv/prep/Triangulate.h"

namespace qv::prep {
namespace {

// The top of what is drawn of a building (metres above ground): its height, or a taller part's (a
// spire, mast or antenna above the roof is drawn but not in the structural height).
float drawnTopM(const Building& b) {
  float top = b.attributes.heightM;
  for (const BuildingPart& p : b.parts) top = std::max(top, p.heightM);
  return top;
}

constexpr int kMaxDepth = 16;
constexpr double kMinCellSize = 20.0;          // metres: never split finer than a building
constexpr std::uint16_t kMaxCoarseParts = 32;  // parts of one building in a coarse tile

struct BuildingInfo {
  double minX, minY, maxX, maxY;                  // footprint bounds
  double cx, cy;                                  // centroid (assignment to quadtree cells)
  std::size_t leafBytes;                          // estimated size in a leaf tile
  std::vector<std::vector<std::uint32_t>> roofs;  // per part
  bool valid = true;
};

// Coarse outlines that needed the constrained triangulation, per building: a building is drawn in
// the coarse tiles of several levels, whose tolerances often simplify it to the same ring. Shared
// by the threads that write tiles (one lock per stripe of buildings).
class CoarseTriangulations {
 public:
  explicit CoarseTriangulations(std::size_t buildings) : entries_(buildings) {}
  /// The triangles of `ring` as building `b` triangulated them before, or false.
  bool find(std::uint32_t b, std::span<const glm::dvec2> ring, std::vector<std::uint32_t>& triangles) {
    const std::lock_guard lock(stripes_[b % kStripes]);
    for (const Entry& e : entries_[b]) {
      if (std::equal(e.ring.begin(), e.ring.end(), ring.begin(), ring.end())) {
        triangles = e.triangles;
        return true;
      }
    }
    return false;
  }
  void add(std::uint32_t b, std::span<const glm::dvec2> ring, const std::vector<std::uint32_t>& triangles) {
    const std::lock_guard lock(stripes_[b % kStripes]);
    entries_[b].push_back(Entry{std::vector<glm::dvec2>(ring.begin(), ring.end()), triangles});
  }

 private:
  struct Entry {
    std::vector<glm::dvec2> ring;
    std::vector<std::uint32_t> triangles;
  };
  static constexpr std::size_t kStripes = 64;
  std::mutex stripes_[kStripes];
  std::vector<std::vector<Entry>> entries_;
};

struct Node {
  int level = 0;
  std::uint32_t x = 0, y = 0;
  double cellMinX = 0, cellMinY = 0, cellSize = 0;
  std::vector<std::uint32_t> buildings;  // subtree members
  std::vector<std::uint32_t> coarse;     // inner nodes: the members drawn in the coarse tile
  double omittedErrorM = 0.0;            // inner nodes: the largest member left out of the coarse tile
  std::vector<std::size_t> children;     // indices into the node list
  bool leaf() const { return children.empty(); }
  // Results.
  std::string file;
  std::uint64_t bytes = 0;
  std::uint32_t crc = 0;
  std::uint32_t tileBuildings = 0;  // buildings in the tile file
  float geometricError = 0.0f;
  Rect bounds;
  float maxHeight = 0.0f;
};

std::size_t stringsBytes(const BuildingAttributes& a) {
  return 7 + a.id.size() + a.name.size() + a.use.size() + a.address.size() + a.material.size() + a.structure.size() +
         a.amenity.size();
}

// The footprints' bounds of a set of buildings (metres, city frame).
struct Extent {
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
};
Extent extentOf(const std::vector<BuildingInfo>& info, const std::vector<std::uint32_t>& members) {
  Extent e;
  for (std::uint32_t b : members) {
    e.minX = std::min(e.minX, info[b].minX);
    e.minY = std::min(e.minY, info[b].minY);
    e.maxX = std::max(e.maxX, info[b].maxX);
    e.maxY = std::max(e.maxY, info[b].maxY);
  }
  return e;
}

Rect toRect(const Extent& e) {
  return Rect{static_cast<float>(e.minX), static_cast<float>(e.minY), static_cast<float>(e.maxX),
              static_cast<float>(e.maxY)};
}

// Tile origin and quantization extent covering a set of buildings.
void frame(const Extent& e, CityTile& tile) {
  tile.originX = std::floor(e.minX);
  tile.originY = std::floor(e.minY);
  tile.extent = static_cast<float>(std::max(e.maxX - tile.originX, e.maxY - tile.originY) + 0.01);
}

// An inner node's coarse tile holds at most `limit` buildings of its subtree: the largest (footprint
// area times height; ties by index), in subtree order. The largest of those left out (its height
// or footprint size, whichever is more) becomes part of the tile's geometric error, so the viewer
// refines to the children before the gap would show.
void chooseCoarse(const CityModel& model, const std::vector<float>& size, Node& node, std::size_t limit) {
  node.omittedErrorM = 0.0;
  if (node.buildings.size() <= limit) {
    node.coarse = node.buildings;
    return;
  }
  std::vector<std::uint32_t> order = node.buildings;
  const auto larger = [&](std::uint32_t a, std::uint32_t b) { return size[a] != size[b] ? size[a] > size[b] : a < b; };
  std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(limit), order.end(), larger);
  for (auto it = order.begin() + static_cast<std::ptrdiff_t>(limit); it != order.end(); ++it) {
    const BuildingAttributes& a = model.buildings[*it].attributes;
    node.omittedErrorM = std::max({node.omittedErrorM, static_cast<double>(drawnTopM(model.buildings[*it])),
                                   std::sqrt(std::max(0.0, static_cast<double>(a.footprintAreaM2)))});
  }
  order.resize(limit);
  std::sort(order.begin(), order.end());
  node.coarse.clear();
  node.coarse.reserve(limit);
  // Subtree order (the quadrant order the split gave), kept for the tile's locality.
  for (std::uint32_t b : node.buildings) {
    if (std::binary_search(order.begin(), order.end(), b)) node.coarse.push_back(b);
  }
}

void addAttributes(CityTile& tile, const Building& b, std::uint16_t partCount, bool coarse) {
  TileBuilding tb;
  const BuildingAttributes& a = b.attributes;
  tb.attributes = a;
  if (coarse) {
    // Far-view tiles carry what drawing and picking need; the leaf has the rest. Everything is
    // copied and only the descriptive strings are dropped, so a field added to BuildingAttributes
    // reaches coarse tiles without anyone remembering to list it here.
    BuildingAttributes& c = tb.attributes;
    c.name.clear();
    c.address.clear();
    c.material.clear();
    c.structure.clear();
    c.amenity.clear();
  }
  tb.attributes.centroidX = a.centroidX - tile.originX;
  tb.attributes.centroidY = a.centroidY - tile.originY;
  tb.firstPart = static_cast<std::uint32_t>(tile.parts.size()) - partCount;
  tb.partCount = partCount;
  tile.buildings.push_back(std::move(tb));
}

// The building just added to `tile` gets its LOD2 model: the full mesh in leaves, only the far mesh
// in coarse tiles. Models of buildings with more storeys than a tile holds are not written (the
// building keeps its LOD1 prism).
void addMesh(CityTile& tile, const Building& b, bool coarse) {
  if (!b.mesh || b.attributes.storeys == 0 || b.attributes.storeys > kMaxMeshStoreys) return;
  const BuildingMesh& m = *b.mesh;
  if (m.farPositions.size() > 65535) return;
  TileMesh tm;
  tm.building = static_cast<std::uint32_t>(tile.buildings.size() - 1);
  tm.source = m.source;
  tm.storeys = b.attributes.storeys;
  tm.verticesBefore = m.verticesBefore;
  double top = 0.0;
  for (const auto* points : {&m.positions, &m.farPositions}) {
    for (const glm::dvec3& p : *points) top = std::max(top, p.z);
  }
  tm.topM = static_cast<float>(std::clamp(top, 0.01, 10000.0));
  auto local = [&](const glm::dvec3& p) {
    return glm::vec3(static_cast<float>(p.x - tile.originX), static_cast<float>(p.y - tile.originY),
                     static_cast<float>(p.z));
  };
  if (!coarse) {
    tm.positions.reserve(m.positions.size());
    for (const glm::dvec3& p : m.positions) tm.positions.push_back(local(p));
    tm.triangles = m.triangles;
    tm.trianglesPerKind = m.trianglesPerKind;
  }
  tm.farPositions.reserve(m.farPositions.size());
  for (const glm::dvec3& p : m.farPositions) tm.farPositions.push_back(local(p));
  tm.farTriangles = m.farTriangles;
  tile.meshes.push_back(std::move(tm));
}

CityTile leafTile(const CityModel& model, const std::vector<BuildingInfo>& info, const Node& node, Rect& bounds) {
  CityTile tile;
  const Extent e = extentOf(info, node.buildings);
  frame(e, tile);
  bounds = toRect(e);
  for (std::uint32_t bi : node.buildings) {
    const Building& b = model.buildings[bi];
    std::uint16_t parts = 0;
    for (std::size_t pi = 0; pi < b.parts.size(); ++pi) {
      const BuildingPart& part = b.parts[pi];
      const auto& roof = info[bi].roofs[pi];
      if (roof.empty()) continue;
      TilePart tp;
      tp.ringCount = static_cast<std::uint16_t>(part.ringEnds.size());
      tp.triangleCount = static_cast<std::uint32_t>(roof.size() / 3);
      tp.minHeightM = part.minHeightM;
      tp.heightM = part.heightM;
      tp.roofHeightM = part.roofHeightM;
      tp.roofShape = parseRoofShape(part.roofShape);
      std::uint32_t begin = 0;
      for (std::uint32_t end : part.ringEnds) {
        tile.ringVertexCounts.push_back(static_cast<std::uint16_t>(end - begin));
        begin = end;
      }
      for (const glm::dvec2& p : part.points) {
        tile.vertices.emplace_back(static_cast<float>(p.x - tile.originX), static_cast<float>(p.y - tile.originY));
      }
      for (std::uint32_t i : roof) tile.roofTriangles.push_back(static_cast<std::uint16_t>(i));
      tile.parts.push_back(tp);
      ++parts;
    }
    addAttributes(tile, b, parts, false);
    addMesh(tile, b, false);
  }
  return tile;
}

CityTile coarseTile(const CityModel& model, const std::vector<BuildingInfo>& info, const Node& node, Rect& bounds,
                    float& geometricError, CoarseTriangulations& cache) {
  CityTile tile;
  tile.coarse = true;
  bounds = toRect(extentOf(info, node.buildings));  // the subtree's, for the viewer's culling
  frame(extentOf(info, node.coarse), tile);
  // Simplify to about 1/400 of the cell: at the distance where the tile is drawn, that is well
  // under a pixel of the screen-space error budget.
  const double tolerance = node.cellSize / 400.0;
  double worst = 0.0;
  tile.buildings.reserve(node.coarse.size());
  tile.parts.reserve(node.coarse.size());
  tile.ringVertexCounts.reserve(node.coarse.size());
  tile.vertices.reserve(node.coarse.size() * 6);
  tile.roofTriangles.reserve(node.coarse.size() * 12);
  std::vector<std::pair<double, std::size_t>> byArea;
  std::vector<std::uint32_t> triangles;
  for (std::uint32_t bi : node.coarse) {
    const Building& b = model.buildings[bi];
    // Far away a building is the prisms of its parts, each part's outer ring simplified, at its
    // own heights: vertical walls and flat roofs, setbacks kept. Parts smaller than the tolerance
    // are left out, except the largest and the highest (the building keeps its size and height).
    byArea.clear();
    std::size_t highest = b.parts.size();
    for (std::size_t pi = 0; pi < b.parts.size(); ++pi) {
      const BuildingPart& p = b.parts[pi];
      if (info[bi].roofs[pi].empty() || p.ringEnds.empty()) continue;
      const double area = std::abs(signedArea(std::span(p.points).first(p.ringEnds[0])));
      byArea.emplace_back(area, pi);
      if (highest == b.parts.size() || p.heightM > b.parts[highest].heightM) highest = pi;
    }
    if (byArea.empty()) continue;
    std::sort(byArea.begin(), byArea.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    std::uint16_t written = 0;
    for (std::size_t k = 0; k < byArea.size() && written < kMaxCoarseParts; ++k) {
      const std::size_t pi = byArea[k].second;
      if (k > 0 && pi != highest && byArea[k].first < tolerance * tolerance) continue;
      const BuildingPart& p = b.parts[pi];
      double error = 0.0;
      const std::span<const glm::dvec2> outer = std::span(p.points).first(p.ringEnds[0]);
      std::vector<glm::dvec2> ring = coarseOutline(outer, tolerance, error);
      if (ring.size() < 3) continue;
      triangles.clear();
      if (p.ringEnds.size() == 1 && std::equal(ring.begin(), ring.end(), outer.begin(), outer.end())) {
        triangles = info[bi].roofs[pi];  // nothing simplified away: the roof's triangulation holds
      } else if (!cache.find(bi, ring, triangles)) {
        const std::uint32_t end = static_cast<std::uint32_t>(ring.size());
        bool constrained = false;
        if (!triangulatePolygon(ring, std::span(&end, 1), triangles, &constrained)) continue;
        if (constrained) cache.add(bi, ring, triangles);
      }
      worst = std::max(worst, error);
      TilePart tp;
      tp.ringCount = 1;
      tp.triangleCount = static_cast<std::uint32_t>(triangles.size() / 3);
      tp.minHeightM = p.minHeightM;
      tp.heightM = p.heightM;
      tile.ringVertexCounts.push_back(static_cast<std::uint16_t>(ring.size()));
      for (const glm::dvec2& q : ring) {
        tile.vertices.emplace_back(static_cast<float>(q.x - tile.originX), static_cast<float>(q.y - tile.originY));
      }
      for (std::uint32_t i : triangles) tile.roofTriangles.push_back(static_cast<std::uint16_t>(i));
      tile.parts.push_back(tp);
      ++written;
    }
    if (written == 0) continue;
    addAttributes(tile, b, written, true);
    addMesh(tile, b, true);
  }
  geometricError = static_cast<float>(std::max(std::min(worst, node.cellSize / 8.0), node.omittedErrorM));
  return tile;
}

}  // namespace

std::string tileFileName(int level, std::uint32_t x, std::uint32_t y) {
  return "tiles/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvt";
}

Result<TilerReport> writeCityTiles(CityModel& model, const std::string& outDir, const TilerOptions& options) {
  const unsigned threads = options.threads > 0 ? options.threads : usableCores();
  if (model.buildings.empty()) return Error{"no buildings to write"};

  auto staging = StagingDirectory::create(outDir);
  if (!staging.ok()) return Error{staging.error()};
  if (auto s = makeDirectories(staging->path() + "/tiles"); !s.ok()) return Error{s.error()};

  // 1. Per-building bounds, size estimates and roof triangulations (in parallel).
  const std::size_t n = model.buildings.size();
  std::vector<BuildingInfo> info(n);
  {
    Progress progress("triangulating roofs", n);
    std::atomic<std::size_t> done{0};
    parallelFor(n, threads, [&](std::size_t i) {
      const Building& b = model.buildings[i];
      BuildingInfo& bi = info[i];
      bi.minX = bi.minY = 1e300;
      bi.maxX = bi.maxY = -1e300;
      bi.leafBytes = 40 + stringsBytes(b.attributes);
      bi.roofs.resize(b.parts.size());
      bool anyPart = false;
      for (std::size_t pi = 0; pi < b.parts.size(); ++pi) {
        const BuildingPart& p = b.parts[pi];
        for (const glm::dvec2& q : p.points) {
          bi.minX = std::min(bi.minX, q.x);
          bi.minY = std::min(bi.minY, q.y);
          bi.maxX = std::max(bi.maxX, q.x);
          bi.maxY = std::max(bi.maxY, q.y);
        }
        if (p.points.size() > 65535 || p.ringEnds.size() > 65535) continue;
        if (triangulatePolygon(p.points, p.ringEnds, bi.roofs[pi])) anyPart = true;
        bi.leafBytes += 20 + p.ringEnds.size() * 2 + p.points.size() * 4 + bi.roofs[pi].size() * 2;
      }
      if (b.mesh) {
        // The tile's quantization frame must hold the mesh too (overhangs, pieces beside the
        // footprint's largest polygon).
        for (const auto* points : {&b.mesh->positions, &b.mesh->farPositions}) {
          for (const glm::dvec3& q : *points) {
            bi.minX = std::min(bi.minX, q.x);
            bi.minY = std::min(bi.minY, q.y);
            bi.maxX = std::max(bi.maxX, q.x);
            bi.maxY = std::max(bi.maxY, q.y);
          }
        }
        bi.leafBytes += 44 + b.mesh->positions.size() * 8 + b.mesh->triangles.size() * 4 +
                        b.mesh->farPositions.size() * 6 + b.mesh->farTriangles.size() * 2;
      }
      bi.valid = anyPart && bi.minX <= bi.maxX;
      bi.cx = b.attributes.centroidX;
      bi.cy = b.attributes.centroidY;
      if (!std::isfinite(bi.cx) || !std::isfinite(bi.cy)) {
        bi.cx = 0.5 * (bi.minX + bi.maxX);
        bi.cy = 0.5 * (bi.minY + bi.maxY);
      }
      const std::size_t d = ++done;
      if (d % 1024 == 0) progress.update(d);
    });
  }
  if (interrupted()) return Error{"interrupted; nothing was written"};
  TilerReport report;
  std::vector<std::uint32_t> kept;
  kept.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (info[i].valid)
      kept.push_back(i);
    else
      ++report.triangulationDrops;
  }
  if (report.triangulationDrops > 0) model.drops.add("triangulation-failed", report.triangulationDrops);
  if (kept.empty()) return Error{"no building could be triangulated"};

  // 2. The quadtree over the centroids: a square root cell around all footprints.
  double minX = 1e300, minY = 1e300, maxX = -1e300, maxY = -1e300;
  for (std::uint32_t i : kept) {
    minX = std::min(minX, info[i].minX);
    minY = std::min(minY, info[i].minY);
    maxX = std::max(maxX, info[i].maxX);
    maxY = std::max(maxY, info[i].maxY);
  }
  std::vector<Node> nodes(1);
  nodes[0].cellSize = std::max({maxX - minX, maxY - minY, kMinCellSize}) * 1.0001;
  nodes[0].cellMinX = 0.5 * (minX + maxX) - 0.5 * nodes[0].cellSize;
  nodes[0].cellMinY = 0.5 * (minY + maxY) - 0.5 * nodes[0].cellSize;
  nodes[0].buildings = kept;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    std::size_t bytes = 0;
    for (std::uint32_t b : nodes[i].buildings) bytes += info[b].leafBytes;
    const bool split = (nodes[i].buildings.size() > options.maxBuildingsPerLeaf || bytes > options.maxLeafBytes) &&
                       nodes[i].level < kMaxDepth && nodes[i].cellSize / 2 >= kMinCellSize;
    if (!split) continue;
    const Node parent = nodes[i];
    std::vector<std::uint32_t> quadrant[4];
    const double half = parent.cellSize / 2;
    for (std::uint32_t b : parent.buildings) {
      const int qx = info[b].cx >= parent.cellMinX + half ? 1 : 0;
      const int qy = info[b].cy >= parent.cellMinY + half ? 1 : 0;
      quadrant[qy * 2 + qx].push_back(b);
    }
    for (int q = 0; q < 4; ++q) {
      if (quadrant[q].empty()) continue;
      Node child;
      child.level = parent.level + 1;
      child.x = parent.x * 2 + static_cast<std::uint32_t>(q % 2);
      child.y = parent.y * 2 + static_cast<std::uint32_t>(q / 2);
      child.cellSize = half;
      child.cellMinX = parent.cellMinX + half * (q % 2);
      child.cellMinY = parent.cellMinY + half * (q / 2);
      child.buildings = std::move(quadrant[q]);
      nodes[i].children.push_back(nodes.size());
      nodes.push_back(std::move(child));
    }
  }

  // 3. What each inner node's coarse tile draws; the city-wide index, leaf by leaf.
  {
    std::vector<float> size(n, 0.0f);
    for (std::uint32_t b : kept) {
      const BuildingAttributes& a = model.buildings[b].attributes;
      size[b] = std::max(a.footprintAreaM2, 1.0f) * std::max(a.heightM, 1.0f);
    }
    // The root, drawn alone from far away, holds up to the limit; every other inner tile up to a
    // quarter of it. A refinement step then draws about as many buildings as the tile it replaces
    // (four children of a quarter each), and a viewer can refine the view near the camera down to
    // the leaves within a memory budget: a chain of tiles as large as the root would not fit.
    const std::size_t rootLimit = std::max<std::size_t>(options.maxCoarseBuildings, 1);
    for (Node& node : nodes) {
      if (!node.leaf())
        chooseCoarse(model, size, node, node.level == 0 ? rootLimit : std::max<std::size_t>(rootLimit / 4, 1));
    }
  }
  // Leaves are numbered as readers of the manifest number tiles: depth first, children in order.
  std::vector<std::size_t> preorder;
  preorder.reserve(nodes.size());
  for (std::vector<std::size_t> stack{0}; !stack.empty();) {
    const std::size_t i = stack.back();
    stack.pop_back();
    preorder.push_back(i);
    for (auto c = nodes[i].children.rbegin(); c != nodes[i].children.rend(); ++c) stack.push_back(*c);
  }
  std::vector<SearchEntry> search;
  search.reserve(kept.size());
  for (std::size_t k = 0; k < preorder.size(); ++k) {
    const std::size_t i = preorder[k];
    if (!nodes[i].leaf()) continue;
    for (std::uint32_t b : nodes[i].buildings) {
      const BuildingAttributes& a = model.buildings[b].attributes;
      SearchEntry e;
      e.id = a.id;
      e.name = a.name;
      e.address = a.address;
      e.use = a.use;
      e.x = static_cast<float>(info[b].cx);
      e.y = static_cast<float>(info[b].cy);
      e.heightM = a.heightM;
      e.storeys = a.storeys;
      e.importance = a.importance;
      const FacilityClass facility = classifyFacility(a);
      e.facility = facility.category;
      e.facilityKind = std::string(facility.kind);
      e.lod = a.lod;
      e.leaf = static_cast<std::uint32_t>(k);
      search.push_back(std::move(e));
    }
  }

  // 4. Build, encode and write every tile (in parallel).
  CoarseTriangulations coarseTriangulations(n);
  std::mutex errorMutex;
  std::string firstError;
  {
    Progress progress("writing tiles", nodes.size());
    std::atomic<std::size_t> done{0};
    parallelFor(nodes.size(), threads, [&](std::size_t i) {
      Node& node = nodes[i];
      CityTile tile = node.leaf()
                          ? leafTile(model, info, node, node.bounds)
                          : coarseTile(model, info, node, node.bounds, node.geometricError, coarseTriangulations);
      auto stored = compressStoredFile(encodeCityTile(tile));
      if (!stored.ok()) {
        const std::lock_guard lock(errorMutex);
        if (firstError.empty()) firstError = stored.error();
        return;
      }
      const std::vector<std::uint8_t>& bytes = *stored;
      node.file = tileFileName(node.level, node.x, node.y);
      node.bytes = bytes.size();
      node.crc = crc32(bytes);
      node.tileBuildings = static_cast<std::uint32_t>(tile.buildings.size());
      for (std::uint32_t b : node.buildings) node.maxHeight = std::max(node.maxHeight, drawnTopM(model.buildings[b]));
      if (const Status s = writeStagedFile(staging->path() + "/" + node.file, bytes); !s.ok()) {
        const std::lock_guard lock(errorMutex);
        if (firstError.empty()) firstError = s.error();
      }
      progress.update(++done);
    });
  }
  if (interrupted()) return Error{"interrupted; the previous output (if any) is unchanged"};
  if (!firstError.empty()) return Error{firstError};

  // 5. The search index, then the manifest, last.
  Tileset& t = report.tileset;
  {
    auto stored = compressStoredFile(encodeSearchIndex(search));
    if (!stored.ok()) return Error{stored.error()};
    const std::vector<std::uint8_t>& bytes = *stored;
    if (const Status s = writeStagedFile(staging->path() + "/search.qvi", bytes); !s.ok()) return Error{s.error()};
    t.search = CityFile{"search.qvi", bytes.size(), crc32(bytes)};
  }
  // 6. The ground (the map under the city), before the manifest that lists it.
  if (options.ground && options.keptGround) {
    // Files of the city being replaced, which goes when this one is committed: links (or copies)
    // of them stay.
    if (!options.keptGround->nodes.empty()) {
      if (auto s = makeDirectories(staging->path() + "/ground"); !s.ok()) return Error{s.error()};
    }
    for (const GroundNode& node : options.keptGround->nodes) {
      const Status s = linkOrCopyFile(options.keptGroundDir + "/" + node.file, staging->path() + "/" + node.file);
      if (!s.ok()) return Error{"cannot keep the city's ground: " + s.error()};
    }
    t.ground = options.keptGround;
  } else if (options.ground) {
    if (!model.ground.empty()) {
      if (auto s = makeDirectories(staging->path() + "/ground"); !s.ok()) return Error{s.error()};
    }
    GroundTilerOptions groundOptions;
    groundOptions.threads = threads;
    auto ground = writeGroundTiles(model.ground, nodes[0].bounds, staging->path(), groundOptions);
    if (!ground.ok()) return Error{ground.error()};
    t.ground = ground->layer;
    if (t.ground->nodes.empty() && !(t.ground->size > 0.0)) {
      // Nothing to draw: the layer still has a square (the manifest requires one), the city's.
      const Rect& b = nodes[0].bounds;
      const double side = std::max({double{b.width()}, double{b.height()}, 1.0});
      t.ground->minX = double{b.centerX()} - 0.5 * side;
      t.ground->minY = double{b.centerY()} - 0.5 * side;
      t.ground->size = side;
      t.ground->levels = 1;
    }
    report.ground = std::move(ground).value();
  }
  // 7. The districts the consequences are totalled by without --districts (DefaultDistricts.h).
  if (options.ground && options.keptGround) {
    if (options.keptDistricts) {
      const std::string& file = options.keptDistricts->file.file;
      const Status s = linkOrCopyFile(options.keptGroundDir + "/" + file, staging->path() + "/" + file);
      if (!s.ok()) return Error{"cannot keep the city's districts: " + s.error()};
      t.districts = options.keptDistricts;
    }
  } else if (options.ground) {
    std::vector<glm::dvec2> centres;
    centres.reserve(kept.size());
    for (const std::uint32_t i : kept) {
      const BuildingAttributes& a = model.buildings[i].attributes;
      centres.emplace_back(a.centroidX, a.centroidY);
    }
    if (const auto districts = chooseDistricts(model.ground, centres, options.districtsOrigin)) {
      const std::string text = districtsGeoJson(*districts, GeoFrame(model.originLon, model.originLat));
      const std::vector<std::uint8_t> bytes(text.begin(), text.end());
      if (const Status s = writeStagedFile(staging->path() + "/districts.geojson", bytes); !s.ok()) {
        return Error{s.error()};
      }
      t.districts =
          DistrictsInfo{CityFile{"districts.geojson", bytes.size(), crc32(bytes)}, districts->districts.size(),
                        districts->source, districts->inferred, districts->coverage};
      report.districts = districts->districts.size();
    }
  }
  if (interrupted()) return Error{"interrupted; the previous output (if any) is unchanged"};

  t.generator = options.generator;
  t.name = options.name;
  t.originLon = model.originLon;
  t.originLat = model.originLat;
  t.projection = model.projection;
  t.buildings = kept.size();
  t.buildingsRevision = options.buildingsRevision;
  t.response = options.response;
  // An older response's city-wide summary follows the old index's order, and its notes and
  // consequence totals are of the old buildings: none is this city's (nor are their files written
  // into it).
  if (t.response) {
    t.response->summaryIndex.reset();
    t.response->notes.reset();
    t.response->consequences.reset();
  }
  // The inputs by file name only: a manifest does not carry the directories of the machine that
  // prepared it.
  t.sources.clear();
  for (const std::string& source : model.sources) {
    const std::string name = std::filesystem::path(source).filename().string();
    t.sources.push_back(name.empty() ? source : name);
  }
  t.excluded = model.excluded;
  t.bounds = nodes[0].bounds;
  t.maxHeightM = nodes[0].maxHeight;
  t.nodes.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& node = nodes[i];
    TileNode& tn = t.nodes[i];
    tn.level = static_cast<std::uint8_t>(node.level);
    tn.x = node.x;
    tn.y = node.y;
    tn.bounds = node.bounds;
    tn.maxHeightM = node.maxHeight;
    tn.coarse = !node.leaf();
    tn.geometricErrorM = node.geometricError;
    tn.buildings = node.tileBuildings;
    tn.subtreeBuildings = node.buildings.size();
    tn.file = node.file;
    tn.bytes = node.bytes;
    tn.crc32 = node.crc;
    for (std::size_t c : node.children) tn.children.push_back(static_cast<std::uint32_t>(c));
    report.bytes += node.bytes;
    report.depth = std::max(report.depth, node.level);
    if (node.leaf()) {
      ++report.leaves;
      report.leafBytes += node.bytes;
      report.largestLeafBytes = std::max(report.largestLeafBytes, node.bytes);
      report.smallestLeafBytes =
          report.smallestLeafBytes == 0 ? node.bytes : std::min(report.smallestLeafBytes, node.bytes);
    }
  }
  report.tiles = nodes.size();
  report.buildings = kept.size();
  if (const Status s = writeStagedFile(staging->path() + "/tileset.json", tilesetToJson(t)); !s.ok()) {
    return Error{s.error()};
  }
  if (interrupted()) return Error{"interrupted; the previous output (if any) is unchanged"};
  if (const Status s = staging->commit(); !s.ok()) return Error{s.error()};
  return report;
}

}  // namespace qv::prep
