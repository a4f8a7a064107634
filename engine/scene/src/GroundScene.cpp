#include "qv/scene/GroundScene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "qv/geometry/Bounds.h"
#include "qv/scene/Fetcher.h"

namespace qv {

struct GroundScene::Cell {
  GroundNode node;
  FileSpec spec;
  FileLoad load;
  std::uint32_t children[4] = {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX};
  Box box;  // the cell, z in [0, 1]
  glm::vec3 origin{0.0f};
  MeshHandle mesh;
  std::uint64_t meshBytes = 0;
  std::uint64_t triangles = 0;
  std::vector<GroundLabel> labels;
  std::uint64_t lastUsed = 0;
};

void groundMesh(const GroundTile& tile, std::vector<GroundVertex>& vertices, std::vector<std::uint32_t>& indices) {
  vertices.clear();
  indices.clear();
  // A vertex shared by runs of two classes is copied once per run: each vertex carries its class.
  std::vector<std::uint32_t> remap(tile.vertices.size(), UINT32_MAX);
  std::vector<std::uint32_t> stamp(tile.vertices.size(), UINT32_MAX);
  for (std::uint32_t r = 0; r < tile.runs.size(); ++r) {
    const GroundRun& run = tile.runs[r];
    const auto cls = static_cast<std::uint8_t>(run.groundClass);
    const std::size_t first = std::size_t{run.firstTriangle} * 3;
    const std::size_t end = first + std::size_t{run.triangleCount} * 3;
    for (std::size_t i = first; i < end && i < tile.triangles.size(); ++i) {
      const std::uint32_t v = tile.triangles[i];
      if (v >= tile.vertices.size()) continue;  // the decoder refuses these; a hand-made tile may not
      if (stamp[v] != r) {
        stamp[v] = r;
        remap[v] = static_cast<std::uint32_t>(vertices.size());
        GroundVertex gv;
        gv.x = tile.vertices[v].x;
        gv.y = tile.vertices[v].y;
        gv.groundClass = cls;
        vertices.push_back(gv);
      }
      indices.push_back(remap[v]);
    }
  }
  indices.resize(indices.size() / 3 * 3);
}

GroundScene::GroundScene(RenderDevice& device, FileLoader& loader, std::string manifestUrl, const GroundLayer& layer,
                         GroundSceneOptions options)
    : device_(device), loader_(loader), manifestUrl_(std::move(manifestUrl)), layer_(layer), options_(options) {
  std::map<std::tuple<int, std::uint32_t, std::uint32_t>, std::uint32_t> byCell;
  cells_.reserve(layer_.nodes.size());
  for (const GroundNode& n : layer_.nodes) {
    auto cell = std::make_unique<Cell>();
    cell->node = n;
    cell->spec = FileSpec{FileKind::Ground, resolveUrl(manifestUrl_, n.file), n.bytes, n.crc32, {}};
    const double side = layer_.size / std::ldexp(1.0, n.level);
    const double x0 = layer_.minX + side * n.x;
    const double y0 = layer_.minY + side * n.y;
    cell->box = Box{static_cast<float>(x0),        static_cast<float>(y0),        0.0f,
                    static_cast<float>(x0 + side), static_cast<float>(y0 + side), 1.0f};
    cell->origin = glm::vec3(static_cast<float>(x0), static_cast<float>(y0), 0.0f);
    byCell[{n.level, n.x, n.y}] = static_cast<std::uint32_t>(cells_.size());
    cells_.push_back(std::move(cell));
  }
  for (std::uint32_t i = 0; i < cells_.size(); ++i) {
    const GroundNode& n = cells_[i]->node;
    if (n.level == 0) root_ = i;
    for (std::uint32_t q = 0; q < 4; ++q) {
      const auto it = byCell.find({n.level + 1, n.x * 2 + (q % 2), n.y * 2 + (q / 2)});
      if (it != byCell.end()) cells_[i]->children[q] = it->second;
    }
  }
}

GroundScene::~GroundScene() {
  for (auto& cell : cells_) {
    loader_.cancel(cell->load);
    if (cell->mesh) device_.destroyMesh(cell->mesh);
  }
}

bool GroundScene::usable(const Cell& cell) const {
  return cell.load.state == TileState::Loaded || cell.load.state == TileState::Failed;
}

void GroundScene::request(Cell& cell) {
  cell.lastUsed = frame_;
  if (cell.load.state == TileState::Loaded) return;
  if (cell.load.state != TileState::Failed) ++pending_;
  if (!loader_.hasRoom() || !loader_.due(cell.load)) return;
  Cell* c = &cell;
  loader_.start(cell.load, cell.spec, [this, c](std::vector<std::uint8_t>& bytes) {
    Result<GroundTile> tile = decodeGroundTile(bytes, c->spec.url);
    if (!tile) return Verdict::rejected(tile.error(), false);
    std::vector<GroundVertex> vertices;
    std::vector<std::uint32_t> indices;
    groundMesh(*tile, vertices, indices);
    if (c->mesh) device_.destroyMesh(c->mesh);
    c->mesh = indices.empty() ? MeshHandle{} : device_.createGroundMesh(GroundMeshData{vertices, indices});
    if (!indices.empty() && !c->mesh) return Verdict::rejected("Ground tile " + c->spec.url + ": no GPU memory", true);
    c->meshBytes = vertices.size() * sizeof(GroundVertex) + indices.size() * sizeof(std::uint32_t);
    c->triangles = indices.size() / 3;
    c->labels = std::move(tile->labels);
    return Verdict::loaded();
  });
}

void GroundScene::evict(Cell& cell) {
  if (cell.load.state != TileState::Loaded) return;
  if (cell.mesh) device_.destroyMesh(cell.mesh);
  cell.mesh = {};
  cell.meshBytes = 0;
  cell.triangles = 0;
  cell.labels.clear();
  cell.labels.shrink_to_fit();
  cell.load.state = TileState::Unloaded;
}

namespace {

constexpr float kCellPixelsPerError = 48.0f;

}  // namespace

void GroundScene::visit(std::uint32_t index, const CameraView& view, std::vector<std::uint32_t>& drawn) {
  Cell& cell = *cells_[index];
  if (!view.frustum().intersects(cell.box)) return;
  cell.lastUsed = frame_;
  bool hasChildren = false;
  for (std::uint32_t c : cell.children) hasChildren = hasChildren || c != UINT32_MAX;
  const float distance = std::max(distanceToBox(view.eye(), cell.box), view.nearPlane());
  // An inner cell leaves out the streets, paths and small parks of its subtree, which its
  // geometric error (its shapes' simplification) does not count: it is refined once it spans more
  // than kCellPixelsPerError times the error limit on screen (576 pixels at the default 12), so the
  // streets show from about a kilometre and a half on a laptop's screen.
  const float side = cell.box.maxX - cell.box.minX;
  const float error = std::max(cell.node.geometricErrorM, side / kCellPixelsPerError);
  const float sse = error * view.pixelsPerMeterAt(distance);
  if (hasChildren && sse > options_.maxScreenSpaceError && drawn.size() + 4 <= options_.maxDrawCells) {
    bool ready = true;
    for (std::uint32_t c : cell.children) {
      if (c == UINT32_MAX || !view.frustum().intersects(cells_[c]->box)) continue;
      if (!usable(*cells_[c])) {
        ready = false;
        request(*cells_[c]);
      }
    }
    if (ready) {
      for (std::uint32_t c : cell.children) {
        if (c != UINT32_MAX) visit(c, view, drawn);
      }
      return;
    }
  }
  request(cell);
  if (cell.load.state == TileState::Loaded) drawn.push_back(index);
}

void GroundScene::update(const CameraView& view) {
  ++frame_;
  items_.clear();
  labels_.clear();
  trianglesDrawn_ = 0;
  pending_ = 0;
  std::vector<std::uint32_t> drawn;
  if (root_ != UINT32_MAX) visit(root_, view, drawn);
  for (std::uint32_t i : drawn) {
    const Cell& cell = *cells_[i];
    if (cell.mesh) {
      items_.push_back(GroundDrawItem{cell.mesh, cell.origin});
      trianglesDrawn_ += cell.triangles;
    }
    for (const GroundLabel& l : cell.labels) {
      labels_.push_back(
          MapLabel{l.kind, l.rank, glm::dvec2(cell.origin) + glm::dvec2(l.position), l.angleRad, l.lengthM, &l.text});
    }
  }
  std::stable_sort(labels_.begin(), labels_.end(),
                   [](const MapLabel& a, const MapLabel& b) { return a.rank < b.rank; });

  // Eviction: cells not used this frame, least recently used first, beyond the budget.
  std::uint64_t bytes = memoryBytes();
  if (bytes > options_.memoryBudgetBytes) {
    std::vector<Cell*> idle;
    for (auto& c : cells_) {
      if (c->load.state == TileState::Loaded && c->lastUsed != frame_) idle.push_back(c.get());
    }
    std::sort(idle.begin(), idle.end(), [](const Cell* a, const Cell* b) { return a->lastUsed < b->lastUsed; });
    for (Cell* c : idle) {
      if (bytes <= options_.memoryBudgetBytes) break;
      const std::uint64_t held = c->meshBytes + c->labels.size() * sizeof(GroundLabel);
      evict(*c);
      bytes -= std::min(bytes, held);
    }
  }
}

std::uint32_t GroundScene::cellsLoaded() const {
  std::uint32_t n = 0;
  for (const auto& c : cells_) n += c->load.state == TileState::Loaded ? 1u : 0u;
  return n;
}

std::uint32_t GroundScene::cellsFailed() const {
  std::uint32_t n = 0;
  for (const auto& c : cells_) n += c->load.state == TileState::Failed ? 1u : 0u;
  return n;
}

std::uint64_t GroundScene::memoryBytes() const {
  std::uint64_t n = 0;
  for (const auto& c : cells_) {
    n += c->meshBytes + c->labels.size() * sizeof(GroundLabel);
    for (const GroundLabel& l : c->labels) n += l.text.capacity() > 15 ? l.text.capacity() : 0;
  }
  return n;
}

}  // namespace qv
