// CityScene's response files, tile by tile: each drawn tile's summary (peaks, damage state, HAZUS
// probabilities, written into the building table) and, for the tiles whose buildings animate, its
// history.
#include <algorithm>
#include <array>

#include "CitySceneState.h"
#include "qv/anim/SeriesSampling.h"

namespace qv {

static_assert(kSeriesFullScale == kDriftSeriesFullScale, "the shader's series scale is the writer's");

FileSpec CityScene::summarySpec(std::uint32_t node) const {
  const TileResponseFiles& r = *tileset_->nodes[node].response;
  return FileSpec{
      FileKind::ResponseSummary, resolveUrl(manifestUrl_, r.summaryFile), r.summaryBytes, r.summaryCrc32, {}};
}

FileSpec CityScene::historySpec(std::uint32_t node) const {
  const TileResponseFiles& r = *tileset_->nodes[node].response;
  return FileSpec{
      FileKind::ResponseHistory, resolveUrl(manifestUrl_, r.historyFile), r.historyBytes, r.historyCrc32, {}};
}

void CityScene::requestSummary(std::uint32_t node) {
  if (!tileset_->nodes[node].response) return;
  const FileSpec spec = summarySpec(node);
  loader_.start(
      tiles_[node]->summaryLoad, spec,
      [this, node, url = spec.url](std::vector<std::uint8_t>& bytes) {
        auto decoded = decodeResponseSummary(bytes, url);
        if (!decoded.ok()) return Verdict::rejected(decoded.error(), false);
        if (decoded->buildings.size() != tileset_->nodes[node].buildings) {
          return Verdict::rejected(url + ": building count differs from the city tile", false);
        }
        tiles_[node]->summary = std::make_unique<ResponseSummaryTile>(std::move(decoded).value());
        float maxRoof = 0.0f;
        for (const BuildingResponse& b : tiles_[node]->summary->buildings)
          maxRoof = std::max(maxRoof, b.peakRoofDisplacementM);
        tiles_[node]->maxRoofM = maxRoof;
        applySummary(node);
        return Verdict::loaded();
      },
      [this, node] { markNoResult(node); });  // its buildings are hatched: no result
}

void CityScene::markNoResult(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded) return;
  const LoadedTile& tile = *t.loaded;
  for (BuildingGpuRecord& row : table_.edit(tile.slotBase, tile.buildingCount())) row.damageState = -1.0f;
  refreshBlockRows(node);
}

void CityScene::applySummary(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded || !t.summary) return;
  const LoadedTile& tile = *t.loaded;
  for (std::size_t b = 0; b < t.summary->buildings.size() && b < tile.positionOf.size(); ++b) {
    const BuildingResponse& r = t.summary->buildings[b];
    BuildingGpuRecord& row = table_.row(tile.slotBase + tile.positionOf[b]);
    row.peakValue = r.peakDriftRatio;
    // Its sway from its drift series where its floors are not moved one by one (seriesSwayAt).
    row.swayGainM = r.source == ResponseSource::None ? 0.0f
                                                     : swayGainMeters(r.peakRoofDisplacementM, r.peakDriftRatio,
                                                                      row.storeys * row.storeyHeightMeters);
    const bool hasPeriods = b < t.summary->scaling.size() && t.summary->scaling[b].periodS[0] > 0.0f;
    row.swayPeriodXS = hasPeriods ? t.summary->scaling[b].periodS[0] : estimatedPeriodS(row.storeys);
    row.swayPeriodYS =
        hasPeriods && t.summary->scaling[b].periodS[1] > 0.0f ? t.summary->scaling[b].periodS[1] : row.swayPeriodXS;
    row.damageState = r.damage == DamageState::NoResult ? -1.0f : static_cast<float>(r.damage);
    row.lossCode = -1.0f;
    if (b < t.summary->odds.size() && r.source != ResponseSource::None) {
      const BuildingDamageOdds& o = t.summary->odds[b];
      row.lossCode =
          packLossCode(o.structuralAtLeast(static_cast<int>(DamageState::Moderate)), o.expectedState(), o.likelyTag());
    }
  }
  table_.changed(tile.slotBase, tile.buildingCount());
  applySeries(node);
  applyFlags(node);  // damage filters need the summary (and the blocks' rows and series follow)
}

void CityScene::applySeries(std::uint32_t node) {
  TileRuntime& t = *tiles_[node];
  if (!t.loaded || !t.summary) return;
  LoadedTile& tile = *t.loaded;
  DriftSeries& d = t.summary->driftSeries;
  if (tile.seriesCount > 0 || d.empty() || d.codes.empty() || d.spans.size() != tile.buildingCount()) return;
  const auto count = static_cast<std::uint32_t>(d.codes.size());
  const auto base = table_.reserveSeries(count);
  if (!base) return;  // the series table is full: these buildings show their peak in grey
  tile.seriesBase = *base;
  tile.seriesCount = count;
  // The table's codes are on kSeriesFullScale; another file scale is mapped code by code.
  std::array<std::uint8_t, 256> map{};
  for (int c = 0; c < 256; ++c) {
    map[static_cast<std::size_t>(c)] =
        d.fullScale == kSeriesFullScale
            ? static_cast<std::uint8_t>(c)
            : driftSeriesCode(driftSeriesValue(static_cast<std::uint8_t>(c), d.fullScale), kSeriesFullScale);
  }
  const std::span<std::uint8_t> into = table_.editSeries(*base, count);
  std::transform(d.codes.begin(), d.codes.end(), into.begin(), [&map](std::uint8_t c) { return map[c]; });
  tile.seriesBefore.assign(tile.positionOf.size() + 1, 0);
  std::vector<std::uint8_t> has(tile.positionOf.size(), 0);
  for (std::size_t b = 0; b < d.spans.size() && b < tile.positionOf.size(); ++b) {
    const DriftSpan& span = d.spans[b];
    BuildingGpuRecord& row = table_.row(tile.slotBase + tile.positionOf[b]);
    const bool valid = span.count > 0 && std::uint64_t{span.first} + span.count <= count;
    row.seriesBase = valid ? static_cast<float>(*base + span.first) : -1.0f;
    row.seriesStart = span.startSeconds;
    row.seriesCount = valid ? static_cast<float>(span.count) : 0.0f;
    row.seriesRateHz = d.rateHz;
    if (valid) has[tile.positionOf[b]] = 1;
  }
  for (std::size_t p = 0; p < has.size(); ++p) tile.seriesBefore[p + 1] = tile.seriesBefore[p] + has[p];
  // When the shaking arrives: the earliest window reaching a tenth of the tile's largest drift
  // (codes are on a square-root scale: a tenth of the drift is 0.316 of the code).
  const std::uint8_t top = *std::max_element(d.codes.begin(), d.codes.end());
  const auto threshold = static_cast<std::uint8_t>(std::max(1.0, std::ceil(top * 0.316)));
  for (const DriftSpan& span : d.spans) {
    for (std::uint32_t i = 0; i < span.count && std::uint64_t{span.first} + i < d.codes.size(); ++i) {
      if (d.codes[span.first + i] < threshold) continue;
      const double at = static_cast<double>(span.startSeconds) + static_cast<double>(i) / d.rateHz;
      if (!firstShaking_ || at < *firstShaking_) firstShaking_ = at;
      break;
    }
  }
  table_.changed(tile.slotBase, tile.buildingCount());
  // The table holds them now.
  d.codes.clear();
  d.codes.shrink_to_fit();
}

void CityScene::refreshBlockSeries(BlockLevelRuntime& blocks, std::span<const BuildingGpuRecord> buildingRows) {
  const TileBlockLevel& level = blocks.level;
  const std::span<const std::uint8_t> codes = table_.series();
  std::vector<std::uint8_t> merged;
  std::vector<SeriesRef> refs(level.boxes.size());
  std::vector<SeriesRef> members;
  for (std::size_t p = 0; p < level.boxes.size(); ++p) {
    members.clear();
    float rate = 0.0f;
    // The members a filter keeps, when it keeps any (as the block's colour: aggregateBlockRows).
    bool allDimmed = true;
    for (std::uint32_t k = level.memberStart[p]; k < level.memberStart[p + 1]; ++k) {
      const std::uint32_t m = level.members[k];
      if (m < buildingRows.size() && (static_cast<unsigned>(buildingRows[m].flags) & kFlagDimmed) == 0)
        allDimmed = false;
    }
    for (std::uint32_t k = level.memberStart[p]; k < level.memberStart[p + 1]; ++k) {
      const std::uint32_t m = level.members[k];
      if (m >= buildingRows.size()) continue;
      const BuildingGpuRecord& r = buildingRows[m];
      if (r.seriesBase < 0.0f || r.seriesCount < 0.5f) continue;
      if (!allDimmed && (static_cast<unsigned>(r.flags) & kFlagDimmed) != 0) continue;
      members.push_back({static_cast<std::int64_t>(r.seriesBase), r.seriesStart,
                         static_cast<std::uint32_t>(r.seriesCount), r.seriesRateHz});
      rate = std::max(rate, r.seriesRateHz);
    }
    refs[p] = mergeSeries(codes, members, rate, merged);
  }
  const auto count = static_cast<std::uint32_t>(merged.size());
  if (count != blocks.seriesCount) {
    table_.releaseSeries(blocks.seriesBase, blocks.seriesCount);
    blocks.seriesBase = blocks.seriesCount = 0;
    if (count > 0) {
      const auto base = table_.reserveSeries(count);
      if (base) {
        blocks.seriesBase = *base;
        blocks.seriesCount = count;
      }
    }
  }
  const bool stored = blocks.seriesCount == count && count > 0;
  if (stored) std::copy(merged.begin(), merged.end(), table_.editSeries(blocks.seriesBase, count).begin());
  const std::span<BuildingGpuRecord> rows =
      table_.edit(blocks.slotBase, static_cast<std::uint32_t>(level.boxes.size()));
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const SeriesRef& r = refs[p];
    const bool has = stored && r.count > 0;
    rows[p].seriesBase = has ? static_cast<float>(blocks.seriesBase + static_cast<std::uint32_t>(r.base)) : -1.0f;
    rows[p].seriesStart = r.startSeconds;
    rows[p].seriesCount = has ? static_cast<float>(r.count) : 0.0f;
    rows[p].seriesRateHz = r.rateHz;
  }
}

bool CityScene::hasDriftSeries() const {
  return std::any_of(tiles_.begin(), tiles_.end(),
                     [](const auto& t) { return t->loaded && t->loaded->seriesCount > 0; });
}

void CityScene::releaseSeries(LoadedTile& tile) {
  table_.releaseSeries(tile.seriesBase, tile.seriesCount);
  tile.seriesBase = tile.seriesCount = 0;
  tile.seriesBefore.clear();
  for (const auto& blocks : tile.blocks) {
    if (!blocks) continue;
    table_.releaseSeries(blocks->seriesBase, blocks->seriesCount);
    blocks->seriesBase = blocks->seriesCount = 0;
  }
}

void CityScene::requestHistory(std::uint32_t node) {
  const TileNode& n = tileset_->nodes[node];
  if (!n.response || n.response->historyFile.empty()) return;
  const FileSpec spec = historySpec(node);
  loader_.start(tiles_[node]->historyLoad, spec, [this, node, url = spec.url](std::vector<std::uint8_t>& bytes) {
    auto decoded = decodeResponseHistory(bytes, url);
    if (!decoded.ok()) return Verdict::rejected(decoded.error(), false);
    if (decoded->buildings.size() != tileset_->nodes[node].buildings) {
      return Verdict::rejected(url + ": building count differs from the city tile", false);
    }
    TileRuntime& t = *tiles_[node];
    t.history = std::make_unique<ResponseHistoryTile>(std::move(decoded).value());
    std::uint64_t historyBytes = 0;
    for (const BuildingHistory& h : t.history->buildings) {
      historyBytes += sizeof(BuildingHistory) + (h.x.coordinates.size() + h.y.coordinates.size()) * 2 +
                      (h.x.shapes.size() + h.y.shapes.size()) * 4;
    }
    t.historyBytes = historyBytes;
    ++residencyGeneration_;
    return Verdict::loaded();
  });
}

}  // namespace qv
