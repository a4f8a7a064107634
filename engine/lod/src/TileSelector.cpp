#include "qv/lod/TileSelector.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace qv {

float distanceToBox(const glm::vec3& p, const Box& b) {
  const float dx = std::max({b.minX - p.x, 0.0f, p.x - b.maxX});
  const float dy = std::max({b.minY - p.y, 0.0f, p.y - b.maxY});
  const float dz = std::max({b.minZ - p.z, 0.0f, p.z - b.maxZ});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

Box nodeBox(const TileNode& n) {
  return Box{n.bounds.minX, n.bounds.minY, 0.0f, n.bounds.maxX, n.bounds.maxY, std::max(n.maxHeightM, 1.0f)};
}

float screenSpaceError(const TileNode& node, const CameraView& view) {
  if (node.children.empty()) return 0.0f;
  const float d = distanceToBox(view.eye(), nodeBox(node));
  return node.geometricErrorM * view.pixelsPerMeterAt(std::max(d, view.nearPlane()));
}

void selectTiles(const Tileset& t, std::span<const TileState> states, const CameraView& view,
                 const TileSelectorOptions& options, TileSelection& out) {
  out.draw.clear();
  out.wanted.clear();
  out.used.clear();
  out.replaced.clear();
  out.budgetLimited = false;
  out.memoryLimited = false;
  out.bytes = 0;
  if (t.nodes.empty() || states.size() != t.nodes.size()) return;
  const Frustum& frustum = view.frustum();
  const bool limitMemory = options.memoryBudgetBytes > 0 && options.nodeBytes.size() == t.nodes.size();
  auto visible = [&](std::uint32_t i) { return frustum.intersects(nodeBox(t.nodes[i])); };
  auto state = [&](std::uint32_t i) { return states[i]; };
  auto loaded = [&](std::uint32_t i) { return state(i) == TileState::Loaded; };
  auto ready = [&](std::uint32_t i) { return state(i) == TileState::Loaded || state(i) == TileState::Failed; };
  auto cost = [&](std::uint32_t i) -> std::uint64_t { return limitMemory ? options.nodeBytes[i] : 0; };

  struct Item {
    float priority;
    std::uint32_t node;
    bool operator<(const Item& o) const { return priority < o.priority; }
  };
  auto priorityOf = [&](std::uint32_t i) {
    const TileNode& n = t.nodes[i];
    float p = screenSpaceError(n, view);
    const float distance = distanceToBox(view.eye(), nodeBox(n));
    // Tiles in the detail radius refine before anything else, nearest first.
    if (options.detailRadiusM > 0.0f && !n.children.empty() && distance <= options.detailRadiusM) p = 1.0e6f - distance;
    return p;
  };

  if (!visible(0)) return;
  std::priority_queue<Item> queue;
  std::vector<Item> wanted;
  std::vector<std::uint32_t> cut;
  std::vector<std::uint32_t> children;
  // Bytes of the nodes in the cut, in the queue and wanted (drawn or about to be).
  std::uint64_t spent = cost(0);
  auto fits = [&](std::uint64_t more, std::uint64_t less) {
    return !limitMemory || spent - std::min(spent, less) + more <= options.memoryBudgetBytes;
  };
  queue.push({priorityOf(0), 0});
  out.used.push_back(0);

  while (!queue.empty()) {
    const Item item = queue.top();
    queue.pop();
    const std::uint32_t i = item.node;
    const TileNode& n = t.nodes[i];
    children.clear();
    for (std::uint32_t c : n.children) {
      if (visible(c)) children.push_back(c);
    }
    const bool wantsRefine = !n.children.empty() && item.priority > options.maxScreenSpaceError;
    const bool allReady = std::all_of(children.begin(), children.end(), ready);
    if (!ready(i)) {
      // Not loaded. Evicted after its children replaced it: pass through to the children (the
      // missing ones are wanted). Never loaded: it is wanted first (coarse first), unless its
      // children can already replace it; its loaded children stand in for it meanwhile.
      const bool evicted = i < options.wasLoaded.size() && options.wasLoaded[i];
      if (!(wantsRefine && !children.empty() && (allReady || evicted))) {
        wanted.push_back({i == 0 ? 1.0e9f : item.priority, i});
        cut.push_back(i);
        for (std::uint32_t c : children) {
          if (!loaded(c)) continue;
          cut.push_back(c);
          out.used.push_back(c);
          spent += cost(c);
        }
        continue;
      }
    } else {
      if (!wantsRefine) {
        cut.push_back(i);
        continue;
      }
      // Keep drawing this node until its children can replace it (a failed node cannot be drawn:
      // go on to its children, which are then wanted).
      if (!allReady && loaded(i)) {
        cut.push_back(i);
        std::uint64_t more = 0;
        for (std::uint32_t c : children) more += cost(c);
        if (!fits(more, 0)) {
          out.memoryLimited = true;
          continue;
        }
        spent += more;
        for (std::uint32_t c : children) {
          if (ready(c)) {
            // The children that have arrived are kept (not evicted) until their siblings join them.
            out.used.push_back(c);
          } else {
            wanted.push_back({item.priority, c});
          }
        }
        continue;
      }
      if (cut.size() + queue.size() + children.size() > options.maxDrawTiles) {
        cut.push_back(i);
        out.budgetLimited = true;
        // Its children stay resident: evicting them (they are ready, so nothing else keeps them) only
        // to fetch them again once the budget allows would reload tiles every frame at the limit.
        for (std::uint32_t c : children) out.used.push_back(c);
        continue;
      }
      std::uint64_t more = 0;
      for (std::uint32_t c : children) more += cost(c);
      if (loaded(i) && !fits(more, cost(i))) {
        cut.push_back(i);
        out.memoryLimited = true;
        continue;
      }
    }
    // Replaced by its visible children.
    for (std::uint32_t c : children) {
      spent += cost(c);
      out.used.push_back(c);
      queue.push({priorityOf(c), c});
    }
    spent -= std::min(spent, cost(i));
    if (loaded(i)) out.replaced.push_back(i);
  }
  for (std::uint32_t i : cut) {
    if (loaded(i)) out.draw.push_back(i);
  }
  out.bytes = spent;
  std::stable_sort(wanted.begin(), wanted.end(), [](const Item& a, const Item& b) { return a.priority > b.priority; });
  for (const Item& w : wanted) {
    if (state(w.node) == TileState::Unloaded || state(w.node) == TileState::Loading) out.wanted.push_back(w.node);
  }
}

}  // namespace qv
