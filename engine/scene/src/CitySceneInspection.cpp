// CityScene's inspection: selection, filter and visibility flags in the building table, lookup
// and picking of buildings, what the panel shows of one, and the city index's side (search, lists).
#include <algorithm>
#include <cmath>

#include "CitySceneState.h"
#include "qv/scene/Palette.h"
#include "qv/spatial/RayIntersection.h"

namespace qv {

void CityScene::applyFlags(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded) return;
  const LoadedTile& tile = *t.loaded;
  const bool filtering = filters_.active();
  for (std::uint32_t b = 0; b < tile.data.buildings.size(); ++b) {
    BuildingGpuRecord& row = table_.row(tile.slotBase + tile.positionOf[b]);
    const BuildingAttributes& a = tile.data.buildings[b].attributes;
    const BuildingResponse* r = t.summary && b < t.summary->buildings.size() ? &t.summary->buildings[b] : nullptr;
    const BuildingDamageOdds* odds =
        r != nullptr && r->source != ResponseSource::None && b < t.summary->odds.size() ? &t.summary->odds[b] : nullptr;
    BuildingTable::setFlag(row, kFlagSelected, !selected_.empty() && a.id == selected_);
    BuildingTable::setFlag(row, kFlagDimmed, filtering && !filters_.passes(a, r, odds));
    BuildingTable::setFlag(row, kFlagHidden, hiddenByLod(a.lod));
  }
  table_.changed(tile.slotBase, tile.buildingCount());
  refreshBlockRows(node);
}

void CityScene::applyFlagsEverywhere() {
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    if (tiles_[i]->loaded) applyFlags(i);
  }
}

bool CityScene::hiddenByLod(std::uint8_t lod) const {
  // A LOD2 building with models switched off is drawn as its LOD1 extrusion, like the LOD1 ones.
  return lod == 2 && showLod2_ ? false : !showLod1_;
}

void CityScene::setLodVisibility(bool lod1, bool lod2) {
  if (lod1 == showLod1_ && lod2 == showLod2_) return;
  showLod1_ = lod1;
  showLod2_ = lod2;
  applyFlagsEverywhere();
}

void CityScene::setFilters(const BuildingFilters& filters) {
  if (filters == filters_) return;
  filters_ = filters;
  applyFlagsEverywhere();
}

std::optional<BuildingRef> CityScene::find(std::string_view id) const {
  std::optional<BuildingRef> coarse;
  const std::string key(id);
  for (std::uint32_t i = 0; i < tiles_.size(); ++i) {
    const TileRuntime& t = *tiles_[i];
    if (!t.loaded) continue;
    const auto it = t.loaded->idIndex.find(key);
    if (it == t.loaded->idIndex.end()) continue;
    if (!t.loaded->data.coarse) return BuildingRef{i, it->second};
    // Of the coarse copies, the deepest (the most detailed) wins.
    if (!coarse || tileset_->nodes[i].level > tileset_->nodes[coarse->node].level) coarse = BuildingRef{i, it->second};
  }
  return coarse;
}

std::optional<BuildingInfo> CityScene::info(BuildingRef ref) const {
  if (ref.node >= tiles_.size() || !tiles_[ref.node]->loaded) return std::nullopt;
  const TileRuntime& t = *tiles_[ref.node];
  const CityTile& d = t.loaded->data;
  if (ref.index >= d.buildings.size()) return std::nullopt;
  BuildingInfo info;
  info.attributes = d.buildings[ref.index].attributes;
  info.attributes.centroidX += d.originX;
  info.attributes.centroidY += d.originY;
  info.detailed = !d.coarse;
  // Far-view tiles carry no descriptive strings: the city index has the name and address while
  // the building's leaf is on its way.
  if (d.coarse) {
    if (const SearchEntry* e = index_.entry(info.attributes.id)) {
      if (info.attributes.name.empty()) info.attributes.name = e->name;
      if (info.attributes.address.empty()) info.attributes.address = e->address;
    }
  }
  info.tile = tileset_->nodes[ref.node].key();
  if (const TileMesh* m = t.loaded->meshOf(ref.index)) {
    info.modelSource = meshSourceName(m->source);
    info.modelTriangles = static_cast<std::uint32_t>(m->triangles.size() / 3);
  }
  // Its results: from this tile's summary, or, while that is on its way (a leaf just loaded for
  // the selection), from another loaded copy's (the coarse tiles above carry the same results).
  const TileRuntime* source = &t;
  std::uint32_t index = ref.index;
  if (!t.summary && tileset_->nodes[ref.node].response) {
    const std::string& id = d.buildings[ref.index].attributes.id;
    for (const auto& other : tiles_) {
      if (!other->loaded || !other->summary) continue;
      const auto it = other->loaded->idIndex.find(id);
      if (it == other->loaded->idIndex.end()) continue;
      source = other.get();
      index = it->second;
      break;
    }
  }
  if (source->summary && index < source->summary->buildings.size()) {
    info.hasResponse = true;
    info.response = source->summary->buildings[index];
    const auto first =
        source->summary->storeyPeakDrift.begin() + static_cast<std::ptrdiff_t>(info.response.firstStorey);
    info.storeyPeakDrift.assign(first, first + static_cast<std::ptrdiff_t>(info.response.storeys));
    const ResponseSummaryTile& summary = *source->summary;
    if (index < summary.scaling.size()) info.scaling = summary.scaling[index];
    if (index < summary.sites.size() && summary.sites[index].given()) info.site = summary.sites[index];
    if (index < summary.spread.size()) info.spread = summary.spread[index];
    if (index < summary.losses.size()) info.loss = summary.losses[index];
  }
  // What tile summaries leave out when the city has its index (docs/formats.md, DPRB): the
  // building's site, suite spread and losses from the summary in the index's order.
  if (info.hasResponse && (!info.site || !info.spread || !info.loss)) {
    const ResponseSummaryTile* all = index_.summary();
    const auto at = all != nullptr ? index_.position(info.attributes.id) : std::nullopt;
    if (at) {
      const bool result = info.response.source != ResponseSource::None;
      if (!info.site && *at < all->sites.size() && all->sites[*at].given()) info.site = all->sites[*at];
      if (!info.spread && result && *at < all->spread.size()) info.spread = all->spread[*at];
      if (!info.loss && result && *at < all->losses.size()) info.loss = all->losses[*at];
    }
  }
  return info;
}

bool CityScene::select(const std::string& id) {
  if (id == selected_) return true;
  const auto ref = id.empty() || !tileset_ ? std::nullopt : find(id);
  const SearchEntry* entry = id.empty() || ref ? nullptr : index_.entry(id);
  if (!id.empty() && !ref && entry == nullptr) return false;
  selected_ = id;
  series_.reset();
  seriesFor_.clear();
  detailWanted_.clear();
  applyFlagsEverywhere();
  if (id.empty() || !tileset_) return true;
  if (entry != nullptr) {
    // In no loaded tile (a large city's coarse tiles hold only its largest buildings): its leaf,
    // from the index.
    detailWanted_.push_back(entry->leaf);
  } else if (tiles_[ref->node]->loaded->data.coarse) {
    // Its leaf (full attributes and history): the leaves whose bounds hold its centroid.
    const auto info = this->info(*ref);
    for (std::uint32_t i = 0; i < tileset_->nodes.size(); ++i) {
      const TileNode& n = tileset_->nodes[i];
      if (n.children.empty() && n.bounds.contains(static_cast<float>(info->attributes.centroidX),
                                                  static_cast<float>(info->attributes.centroidY))) {
        detailWanted_.push_back(i);
      }
    }
  }
  return true;
}

std::optional<BuildingSeries> CityScene::selectionSeries(std::size_t samples) {
  if (selected_.empty() || samples < 2) return std::nullopt;
  if (series_ && seriesFor_ == selected_ && series_->roofDisplacementM.size() == samples) return series_;
  const auto ref = find(selected_);
  if (!ref) return std::nullopt;
  TileRuntime& t = *tiles_[ref->node];
  if (t.loaded->data.coarse) return std::nullopt;  // the leaf is on its way
  requestHistory(ref->node);                       // when not loaded or loading (and any backoff has passed)
  t.historyUsed = frame_;
  if (t.historyLoad.state != TileState::Loaded || ref->index >= t.history->buildings.size()) return std::nullopt;
  const BuildingHistory& h = t.history->buildings[ref->index];
  const BuildingAttributes& a = t.loaded->data.buildings[ref->index].attributes;
  if (h.floors == 0) return std::nullopt;
  BuildingSeries s;
  s.durationSeconds = duration();
  std::vector<float> x(h.floors + 1u), y(h.floors + 1u);
  const float storeyHeight = std::max(a.storeyHeightM(), 0.1f);
  for (std::size_t i = 0; i < samples; ++i) {
    const double time = s.durationSeconds * static_cast<double>(i) / static_cast<double>(samples - 1);
    sampleHistory(h, time, x, y);
    s.roofDisplacementM.push_back(std::hypot(x[h.floors], y[h.floors]));
    float drift = 0.0f;
    for (std::size_t k = 0; k < h.floors; ++k) {
      drift = std::max(drift, std::hypot(x[k + 1] - x[k], y[k + 1] - y[k]) / storeyHeight);
    }
    s.maxDriftRatio.push_back(drift);
  }
  series_ = std::move(s);
  seriesFor_ = selected_;
  return series_;
}

std::vector<Box> CityScene::buildingBoxesNear(double x, double y, double radiusM, std::string_view exceptId) const {
  std::vector<Box> out;
  auto near = [&](const Box& b) {
    const double dx = std::max({0.0, static_cast<double>(b.minX) - x, x - static_cast<double>(b.maxX)});
    const double dy = std::max({0.0, static_cast<double>(b.minY) - y, y - static_cast<double>(b.maxY)});
    return dx * dx + dy * dy <= radiusM * radiusM;
  };
  for (const auto& t : tiles_) {
    if (!t->loaded) continue;
    const LoadedTile& tile = *t->loaded;
    if (tile.tree.size() == 0 || !near(tile.tree.bounds())) continue;
    for (std::uint32_t b = 0; b < tile.buildingCount(); ++b) {
      const TileBuilding& tb = tile.data.buildings[b];
      if (hiddenByLod(tb.attributes.lod) || tb.attributes.id == exceptId) continue;
      const Box box = buildingBox(tile, b);
      if (near(box)) out.push_back(box);
    }
  }
  return out;
}

namespace {

// Where a ray (origin o, direction dir) first meets a building's prisms, if it does.
std::optional<float> rayPrisms(const TileContent& tile, const TileBuilding& tb, const float o[3], const float dir[3]) {
  std::optional<float> nearest;
  for (std::uint32_t p = tb.firstPart; p < tb.firstPart + tb.partCount; ++p) {
    const TilePart& part = tile.data.parts[p];
    PrismView prism;
    prism.xy = &tile.data.vertices[part.firstVertex].x;
    prism.ringCounts = &tile.data.ringVertexCounts[part.firstRing];
    prism.ringCount = part.ringCount;
    prism.offsetX = tile.origin.x;
    prism.offsetY = tile.origin.y;
    prism.minZ = part.minHeightM;
    prism.maxZ = part.heightM;
    if (const auto tHit = rayPrism(o, dir, prism); tHit && (!nearest || *tHit < *nearest)) nearest = tHit;
  }
  return nearest;
}

}  // namespace

std::optional<std::uint32_t> CityScene::pickInBlocks(const TileRuntime& t, int level, const glm::vec3& origin,
                                                     const glm::vec3& direction, float& best) const {
  // The block's box is what is drawn, so the ray's entry into it is where it meets the picture.
  // Of its members, the one whose prisms the ray meets first, else the one nearest that point.
  const LoadedTile& tile = *t.loaded;
  const TileBlockLevel& blocks = tile.blocks[level]->level;
  std::vector<std::pair<float, std::uint32_t>> candidates;
  blocks.tree.raycast(origin, direction, best == INFINITY ? 1.0e7f : best, candidates);
  const float o[3] = {origin.x, origin.y, origin.z};
  const float dir[3] = {direction.x, direction.y, direction.z};
  for (const auto& [entry, position] : candidates) {
    if (entry > best) break;
    const std::uint32_t block = blocks.tree.order()[position];
    // Only where this level is drawn this frame.
    const auto region = static_cast<std::size_t>(
        std::upper_bound(blocks.regionStart.begin(), blocks.regionStart.end(), block) - blocks.regionStart.begin() - 1);
    if (region >= t.regionForm.size() || t.regionForm[region] != level) continue;
    const glm::vec3 at = origin + direction * entry;
    float nearestHit = INFINITY, nearestDistance = INFINITY;
    std::optional<std::uint32_t> chosen;
    bool chosenByRay = false;
    for (std::uint32_t m = blocks.memberStart[block]; m < blocks.memberStart[block + 1]; ++m) {
      const std::uint32_t b = tile.tree.order()[blocks.members[m]];
      const TileBuilding& tb = tile.data.buildings[b];
      if (hiddenByLod(tb.attributes.lod)) continue;
      if (const auto tHit = rayPrisms(tile, tb, o, dir); tHit && *tHit < nearestHit) {
        nearestHit = *tHit;
        chosen = b;
        chosenByRay = true;
      }
      if (chosenByRay) continue;
      const Box box = buildingBox(tile, b);
      const float dx = std::max({box.minX - at.x, 0.0f, at.x - box.maxX});
      const float dy = std::max({box.minY - at.y, 0.0f, at.y - box.maxY});
      const float dz = std::max({box.minZ - at.z, 0.0f, at.z - box.maxZ});
      const float distance = dx * dx + dy * dy + dz * dz;
      if (distance < nearestDistance) {
        nearestDistance = distance;
        chosen = b;
      }
    }
    if (chosen) {
      best = entry;
      return chosen;
    }
  }
  return std::nullopt;
}

std::optional<BuildingRef> CityScene::pick(const glm::vec3& origin, const glm::vec3& direction) const {
  float best = INFINITY;
  std::optional<BuildingRef> hit;
  std::vector<std::pair<float, std::uint32_t>> candidates;
  const float o[3] = {origin.x, origin.y, origin.z};
  const float dir[3] = {direction.x, direction.y, direction.z};
  for (std::uint32_t node : selection_.draw) {
    const TileRuntime& t = *tiles_[node];
    if (!t.loaded) continue;
    const LoadedTile& tile = *t.loaded;
    // Regions drawn as blocks: the first block the ray enters answers with one of its buildings.
    bool levelDrawn[kBlockLevels] = {};
    for (const std::int8_t form : t.regionForm) {
      if (form >= 0) levelDrawn[form] = true;
    }
    for (int level = 0; level < kBlockLevels; ++level) {
      if (!levelDrawn[level] || !tile.blocks[level]) continue;
      if (const auto b = pickInBlocks(t, level, origin, direction, best)) hit = BuildingRef{node, *b};
    }
    candidates.clear();
    tile.tree.raycast(origin, direction, best == INFINITY ? 1.0e7f : best, candidates);
    for (const auto& [entry, position] : candidates) {
      if (entry > best) break;  // boxes come nearest first: nothing further can be nearer
      const std::uint32_t b = tile.tree.order()[position];
      const TileBuilding& tb = tile.data.buildings[b];
      if (hiddenByLod(tb.attributes.lod)) continue;  // hidden: not pickable
      // A far-view tile's building is picked on its prisms only where they are drawn.
      const TileRegions& grid = t.farGrid ? *tile.farRegions : tile.regions;
      if (!t.regionForm.empty() &&
          (position >= grid.regionOfPosition.size() || t.regionForm[grid.regionOfPosition[position]] != -1))
        continue;
      if (const TileMesh* m = showLod2_ ? tile.drawnModelOf(b) : nullptr) {
        // A LOD2 model is picked on its own triangles (in coarse tiles it is drawn, and picked, as
        // its extrusion).
        const glm::vec3 offset(tile.origin.x, tile.origin.y, tb.attributes.minHeightM);
        const auto tHit = rayTriangles<std::uint32_t>(o, dir, m->positions, m->triangles, offset);
        if (tHit && *tHit < best) {
          best = *tHit;
          hit = BuildingRef{node, b};
        }
        continue;
      }
      if (const auto tHit = rayPrisms(tile, tb, o, dir); tHit && *tHit < best) {
        best = *tHit;
        hit = BuildingRef{node, b};
      }
    }
  }
  return hit;
}

const SearchEntry* CityScene::indexEntry(std::string_view id) const {
  return index_.entry(id);
}

std::vector<BuildingListEntry> CityScene::search(std::string_view query, std::size_t limit) {
  index_.request();
  return index_.search(query, limit);
}

std::vector<BuildingListEntry> CityScene::filteredList(std::size_t limit, std::size_t* total) {
  index_.request();
  return index_.filteredList(filters_, limit, total);
}

const std::vector<BuildingListEntry>& CityScene::markedBuildings() {
  const std::uint64_t indexBytes = index_.loaded() ? index_.bytes() : 0;
  if (filters_ == markedFilters_ && indexBytes == markedIndexBytes_) return marked_;
  markedFilters_ = filters_;
  markedIndexBytes_ = indexBytes;
  marked_.clear();
  if (filters_.categoryMask() != 0) marked_ = filteredList(kMaxMarkedBuildings);
  return marked_;
}

const std::optional<BuildingListEntry>& CityScene::selectedListEntry() {
  // Looked up again when the selection or what the index holds changes (a scan of the index).
  const std::uint64_t indexBytes = index_.loaded() ? index_.bytes() : 0;
  if (selected_ != markedSelection_ || indexBytes != markedSelectionIndexBytes_) {
    markedSelection_ = selected_;
    markedSelectionIndexBytes_ = indexBytes;
    markedSelectionEntry_.reset();
    if (!selected_.empty()) markedSelectionEntry_ = index_.listEntryOf(selected_);
  }
  return markedSelectionEntry_;
}

void CityScene::mapMarkers(float pixelRatio, std::vector<MapMarker>& out) {
  auto colourOf = [](const BuildingListEntry& e) {
    Rgb c = kNoResultColor;
    if (e.loss) {
      c = paletteRamp(e.loss->structuralAtLeast(2));
    } else if (e.damage != DamageState::NoResult) {
      c = paletteRamp(static_cast<float>(e.damage) / kDamageComplete);
    }
    return glm::vec3(c.r, c.g, c.b);
  };
  for (const BuildingListEntry& e : markedBuildings()) {
    out.push_back({glm::vec3(e.x, e.y, e.heightM), 7.0f * pixelRatio, colourOf(e), false});
  }
  if (const std::optional<BuildingListEntry>& selected = selectedListEntry()) {
    const BuildingListEntry& e = *selected;
    out.push_back({glm::vec3(e.x, e.y, e.heightM), 10.0f * pixelRatio, colourOf(e), true});
  }
}

bool CityScene::searchIndexSettled() const {
  return tileset_ ? index_.settled() : manifestFailed_;
}

}  // namespace qv
