#include "qv/format/ResponseTile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include "qv/anim/HistorySampling.h"
#include "qv/core/ByteIO.h"
#include "qv/core/Crc32.h"
#include "qv/format/StoredFile.h"

namespace qv {
namespace {

constexpr std::size_t kHeaderSize = 28;
constexpr std::size_t kSummaryRecordSizeV1 = 28;
constexpr std::size_t kSummaryRecordSize = 36;
constexpr std::uint8_t kFlagApproximate = 1;
constexpr std::uint32_t kMaxBuildings = 1u << 20;
constexpr std::uint32_t kMaxFloors = 500;
constexpr std::uint8_t kMaxModes = 8;
static_assert(kMaxModes == kMaxHistoryModes);
constexpr std::uint32_t kMaxSamples = 1u << 20;

std::uint32_t tag(const char (&t)[5]) {
  return static_cast<std::uint32_t>(t[0]) | static_cast<std::uint32_t>(t[1]) << 8 |
         static_cast<std::uint32_t>(t[2]) << 16 | static_cast<std::uint32_t>(t[3]) << 24;
}

struct Section {
  std::uint32_t id;
  const ByteWriter* data;
};

// Header + section table + sections; CRC over [16, end).
std::vector<std::uint8_t> assemble(const char (&magic)[5], std::uint16_t version, std::uint32_t count,
                                   std::uint32_t extra, std::span<const Section> sections) {
  ByteWriter out;
  out.fourcc(magic);
  out.u16(version);
  out.u16(0);
  out.u32(0);
  out.u32(0);
  out.u32(count);
  out.u32(extra);
  out.u16(static_cast<std::uint16_t>(sections.size()));
  out.u16(0);
  std::size_t offset = kHeaderSize + sections.size() * 12;
  for (const Section& s : sections) {
    out.u32(s.id);
    out.u32(static_cast<std::uint32_t>(offset));
    out.u32(static_cast<std::uint32_t>(s.data->size()));
    offset += (s.data->size() + 3) / 4 * 4;
  }
  for (const Section& s : sections) {
    out.bytes(s.data->data());
    out.align(4);
  }
  out.patchU32(8, static_cast<std::uint32_t>(out.size()));
  out.patchU32(12, crc32(std::span(out.data()).subspan(16)));
  return out.take();
}

struct Parsed {
  std::uint16_t version = 0;
  std::uint32_t count = 0;
  std::uint32_t extra = 0;
  std::vector<std::pair<std::uint32_t, std::pair<std::size_t, std::size_t>>> sections;  // id -> offset, size
};

// Checks magic, version, size and CRC and reads the section table.
// Reads versions 1 .. `newest`.
Result<Parsed> parseHeader(std::span<const std::uint8_t> bytes, const char (&magic)[5], std::uint16_t newest,
                           const char* kind, const std::string& prefix) {
  if (bytes.size() < kHeaderSize) {
    return Error{prefix + "not a " + kind + ": " + std::to_string(bytes.size()) + " bytes is shorter than the header"};
  }
  if (std::memcmp(bytes.data(), magic, 4) != 0) {
    return Error{prefix + "not a " + kind + ": the file does not start with \"" + magic + "\""};
  }
  ByteReader h(bytes.subspan(4, kHeaderSize - 4), 4);
  const std::uint16_t version = h.u16("version");
  if (version < 1 || version > newest) {
    return Error{prefix + "unsupported " + kind + " version " + std::to_string(version) + " (this build reads " +
                 (newest == 1 ? "version 1" : "versions 1 to " + std::to_string(newest)) + ")"};
  }
  h.u16("flags");
  const std::uint32_t size = h.u32("file size");
  const std::uint32_t stored = h.u32("checksum");
  Parsed p;
  p.version = version;
  p.count = h.u32("count");
  p.extra = h.u32("extra");
  const std::uint16_t sections = h.u16("section count");
  if (size != bytes.size()) {
    return Error{prefix + "truncated or padded: the header says " + std::to_string(size) + " bytes, the file has " +
                 std::to_string(bytes.size())};
  }
  if (const std::uint32_t crc = crc32(bytes.subspan(16)); crc != stored) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "checksum mismatch: stored %08x, computed %08x (corrupt file)", stored, crc);
    return Error{prefix + buffer};
  }
  if (p.count > kMaxBuildings) {
    return Error{prefix + std::to_string(p.count) + " buildings exceeds the limit of " + std::to_string(kMaxBuildings)};
  }
  ByteReader table(bytes.subspan(kHeaderSize), kHeaderSize);
  for (std::uint16_t i = 0; i < sections; ++i) {
    const std::uint32_t id = table.u32("section id");
    const std::uint32_t offset = table.u32("section offset");
    const std::uint32_t length = table.u32("section size");
    if (!table.ok()) return Error{prefix + "section table: " + table.error()};
    if (offset < kHeaderSize || offset > bytes.size() || length > bytes.size() - offset) {
      return Error{prefix + "a section at byte " + std::to_string(offset) + " lies outside the file"};
    }
    p.sections.push_back({id, {offset, length}});
  }
  return p;
}

std::optional<std::pair<std::size_t, std::size_t>> findSection(const Parsed& p, std::uint32_t id) {
  for (const auto& [sid, range] : p.sections) {
    if (sid == id) return range;
  }
  return std::nullopt;
}

constexpr std::size_t kScalingRecordSize = 32;
constexpr std::size_t kSpreadRecordSize = 12;
constexpr std::size_t kStoreySpreadRecordSize = 12;
constexpr std::size_t kLossRecordSize = 132;
constexpr std::size_t kSiteRecordSize = 32;
constexpr std::size_t kOddsRecordSize = 14;
constexpr float kOddsLevels = 65535.0f;

// The optional summary sections (SPEC, SITE, SUIT, SSPR, LOSS): sizes match the counts, values are finite,
// non-negative, and probabilities lie in [0, 1].
Status decodeOptionalSections(std::span<const std::uint8_t> bytes, const Parsed& header, const std::string& prefix,
                              ResponseSummaryTile& tile) {
  auto sized = [&](const char(&id)[5], std::size_t count, std::size_t recordSize) -> Result<std::optional<ByteReader>> {
    const auto range = findSection(header, tag(id));
    if (!range) return std::optional<ByteReader>();
    if (range->second != count * recordSize) {
      return Error{prefix + "section " + id + " at byte " + std::to_string(range->first) + " holds " +
                   std::to_string(range->second) + " bytes, expected " + std::to_string(count) + " records of " +
                   std::to_string(recordSize)};
    }
    return std::optional<ByteReader>(ByteReader(bytes.subspan(range->first, range->second), range->first));
  };
  auto bad = [&](const char* id, const ByteReader& r, const char* what) {
    return Error{prefix + "section " + id + " near byte " + std::to_string(r.offset()) + ": " + what};
  };
  auto value = [](float v) { return std::isfinite(v) && v >= 0.0f; };
  auto probability = [](float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0001f; };
  const std::size_t n = tile.buildings.size();
  auto spec = sized("SPEC", n, kScalingRecordSize);
  if (!spec.ok()) return Error{spec.error()};
  if (*spec) {
    ByteReader& r = **spec;
    tile.scaling.resize(n);
    for (BuildingScaling& b : tile.scaling) {
      for (int d = 0; d < 2; ++d) {
        b.periodS[d] = r.f32("period");
        b.targetSaG[d] = r.f32("target Sa");
        b.recordSaG[d] = r.f32("record Sa");
        b.scale[d] = r.f32("scale");
        if (!value(b.periodS[d]) || !value(b.targetSaG[d]) || !value(b.recordSaG[d]) || !value(b.scale[d]))
          return bad("SPEC", r, "invalid period, Sa or scale");
      }
    }
  }
  auto site = sized("SITE", n, kSiteRecordSize);
  if (!site.ok()) return Error{site.error()};
  if (*site) {
    ByteReader& r = **site;
    tile.sites.resize(n);
    for (BuildingSite& b : tile.sites) {
      const std::uint8_t source = r.u8("site source");
      r.skip(3, "reserved");
      b.source = source <= static_cast<std::uint8_t>(SiteSource::Scenario) ? static_cast<SiteSource>(source)
                                                                           : SiteSource::None;
      for (float* v : {&b.pgaG, &b.pgvCmS, &b.psa03G, &b.psa10G, &b.psa30G, &b.mmi, &b.vs30Mps}) {
        *v = r.f32("site value");
        // NaN: not given; otherwise finite and >= 0 (MMI 1 .. 12 is not enforced: a value is shown as written).
        if (!std::isnan(*v) && !value(*v)) return bad("SITE", r, "invalid site value");
      }
      if (b.source == SiteSource::None) b = BuildingSite{};
    }
  }
  auto suit = sized("SUIT", n, kSpreadRecordSize);
  if (!suit.ok()) return Error{suit.error()};
  if (*suit) {
    ByteReader& r = **suit;
    tile.spread.resize(n);
    for (BuildingSpread& b : tile.spread) {
      b.records = r.u16("records");
      b.shownRecord = r.u16("shown record");
      b.driftBeta = r.f32("drift beta");
      b.accelerationBeta = r.f32("acceleration beta");
      if (!value(b.driftBeta) || !value(b.accelerationBeta)) return bad("SUIT", r, "invalid dispersion");
      if (b.records > 0 && b.shownRecord >= b.records) return bad("SUIT", r, "shown record beyond the records");
    }
  }
  auto sspr = sized("SSPR", tile.storeyPeakDrift.size(), kStoreySpreadRecordSize);
  if (!sspr.ok()) return Error{sspr.error()};
  if (*sspr) {
    ByteReader& r = **sspr;
    tile.storeySpread.resize(tile.storeyPeakDrift.size());
    for (StoreySpread& s : tile.storeySpread) {
      s.driftBeta = r.f32("drift beta");
      s.accelerationMedianMs2 = r.f32("acceleration median");
      s.accelerationBeta = r.f32("acceleration beta");
      if (!value(s.driftBeta) || !value(s.accelerationMedianMs2) || !value(s.accelerationBeta))
        return bad("SSPR", r, "invalid storey spread");
    }
  }
  auto loss = sized("LOSS", n, kLossRecordSize);
  if (!loss.ok()) return Error{loss.error()};
  if (*loss) {
    ByteReader& r = **loss;
    tile.losses.resize(n);
    for (BuildingLoss& b : tile.losses) {
      for (float* set : {b.structural, b.nonStructuralDrift, b.nonStructuralAcceleration}) {
        float sum = 0.0f;
        for (int k = 0; k < 5; ++k) {
          set[k] = r.f32("damage state probability");
          if (!probability(set[k])) return bad("LOSS", r, "invalid probability");
          sum += set[k];
        }
        if (sum > 0.0f && std::abs(sum - 1.0f) > 1e-3f) return bad("LOSS", r, "probabilities do not sum to 1");
      }
      b.collapse = r.f32("collapse probability");
      b.occupants = r.f32("occupants");
      for (float& v : b.injuries) v = r.f32("injuries");
      b.replacementValueUsd = r.f32("replacement value");
      b.repairCostUsd = r.f32("repair cost");
      b.repairTimeDays = r.f32("repair time");
      for (float& v : b.tag) v = r.f32("tag probability");
      b.repairCostStdUsd = r.f32("repair cost deviation");
      for (float& v : b.injuriesStd) v = r.f32("injuries deviation");
      b.flags = r.u8("flags");
      r.skip(3, "reserved");
      if (!probability(b.collapse) || !probability(b.tag[0]) || !probability(b.tag[1]) || !probability(b.tag[2]))
        return bad("LOSS", r, "invalid probability");
      for (const float v : {b.occupants, b.injuries[0], b.injuries[1], b.injuries[2], b.injuries[3],
                            b.replacementValueUsd, b.repairCostUsd, b.repairTimeDays, b.repairCostStdUsd,
                            b.injuriesStd[0], b.injuriesStd[1], b.injuriesStd[2], b.injuriesStd[3]}) {
        if (!value(v)) return bad("LOSS", r, "invalid consequence value");
      }
    }
  }
  auto odds = sized("DPRB", n, kOddsRecordSize);
  if (!odds.ok()) return Error{odds.error()};
  if (*odds && !tile.losses.empty()) {
    return Error{prefix + "sections LOSS and DPRB are both present (a file has one or the other)"};
  }
  if (*odds) {
    ByteReader& r = **odds;
    tile.odds.resize(n);
    for (BuildingDamageOdds& o : tile.odds) {
      for (float& p : o.atLeast) p = static_cast<float>(r.u16("damage probability")) / kOddsLevels;
      for (float& p : o.tag) p = static_cast<float>(r.u16("tag probability")) / kOddsLevels;
      if (!r.ok()) return bad("DPRB", r, "truncated");
      for (int k = 1; k < 4; ++k) {
        if (o.atLeast[k] > o.atLeast[k - 1]) return bad("DPRB", r, "P(DS >= k) grows with k");
      }
      if (o.tag[0] + o.tag[1] + o.tag[2] > 1.0f + 4.0f / kOddsLevels) return bad("DPRB", r, "tag probabilities over 1");
    }
  } else if (!tile.losses.empty()) {
    tile.odds.reserve(n);
    for (const BuildingLoss& l : tile.losses) tile.odds.push_back(BuildingDamageOdds::of(l));
  }
  if (const auto dser = findSection(header, tag("DSER"))) {
    ByteReader r(bytes.subspan(dser->first, dser->second), dser->first);
    DriftSeries& d = tile.driftSeries;
    d.rateHz = r.f32("rate");
    d.fullScale = r.f32("full scale");
    const std::uint32_t total = r.u32("sample count");
    if (!r.ok()) return bad("DSER", r, "truncated header");
    if (!std::isfinite(d.rateHz) || d.rateHz <= 0.0f || d.rateHz > 1000.0f) return bad("DSER", r, "invalid rate");
    if (!std::isfinite(d.fullScale) || d.fullScale <= 0.0f || d.fullScale > 1.0f)
      return bad("DSER", r, "invalid full scale");
    if (dser->second != 12 + n * 8 + static_cast<std::size_t>(total)) {
      return Error{prefix + "section DSER at byte " + std::to_string(dser->first) + " holds " +
                   std::to_string(dser->second) + " bytes, expected " + std::to_string(12 + n * 8) + " for " +
                   std::to_string(n) + " buildings and " + std::to_string(total) + " samples"};
    }
    d.spans.resize(n);
    std::uint64_t next = 0;
    for (DriftSpan& span : d.spans) {
      span.startSeconds = r.f32("start");
      span.count = r.u32("count");
      if (!std::isfinite(span.startSeconds) || std::abs(span.startSeconds) > 1e6f)
        return bad("DSER", r, "invalid start time");
      if (span.count > kMaxSamples) return bad("DSER", r, "too many samples for one building");
      span.first = static_cast<std::uint32_t>(next);
      next += span.count;
      if (next > total) return bad("DSER", r, "the buildings' samples exceed the section's count");
    }
    if (next != total) return bad("DSER", r, "the buildings' samples do not add up to the section's count");
    const auto codes = r.bytes(total, "samples");
    if (!r.ok()) return bad("DSER", r, "truncated samples");
    d.codes.assign(codes.begin(), codes.end());
  }
  return Status{};
}

}  // namespace

std::uint8_t driftSeriesCode(float driftRatio, float fullScale) {
  if (!(driftRatio > 0.0f) || !(fullScale > 0.0f)) return 0;
  const float x = std::min(driftRatio / fullScale, 1.0f);
  return static_cast<std::uint8_t>(std::lround(255.0f * std::sqrt(x)));
}

float driftSeriesValue(std::uint8_t code, float fullScale) {
  const float x = static_cast<float>(code) / 255.0f;
  return fullScale * x * x;
}

std::string_view noResultReasonName(NoResultReason r) {
  switch (r) {
    case NoResultReason::None:
      return "none";
    case NoResultReason::ModelInvalid:
      return "model_invalid";
    case NoResultReason::OutsideField:
      return "outside_field";
    case NoResultReason::SkippedByOption:
      return "skipped_by_option";
    case NoResultReason::BaseAboveGround:
      return "base_above_ground";
    case NoResultReason::NotInImport:
      return "not_in_import";
    default:
      return "unknown";
  }
}

std::string_view noResultReasonDescription(NoResultReason r) {
  switch (r) {
    case NoResultReason::None:
      return "has a result";
    case NoResultReason::ModelInvalid:
      return "no structural model could be made from its attributes";
    case NoResultReason::OutsideField:
      return "outside the area where the shaking is defined";
    case NoResultReason::SkippedByOption:
      return "skipped by an option of the response command";
    case NoResultReason::BaseAboveGround:
      return "base above ground (rooftop structure resting on another building; not analysed)";
    case NoResultReason::NotInImport:
      return "not included in the imported results";
    default:
      return "no reason recorded";
  }
}

std::string_view siteSourceName(SiteSource s) {
  switch (s) {
    case SiteSource::ShakeMap:
      return "shakemap";
    case SiteSource::Scenario:
      return "scenario";
    case SiteSource::None:
      break;
  }
  return "none";
}

std::string_view siteSourceLabel(SiteSource s) {
  switch (s) {
    case SiteSource::ShakeMap:
      return "ShakeMap";
    case SiteSource::Scenario:
      return "scenario median (BSSA14)";
    case SiteSource::None:
      break;
  }
  return "";
}

std::string siteShakingText(const BuildingSite& site) {
  std::string text;
  if (!site.given()) return text;
  char buffer[48];
  auto add = [&](const char* format, float v) {
    if (std::isnan(v)) return;
    std::snprintf(buffer, sizeof buffer, format, static_cast<double>(v));
    text += text.empty() ? "" : ", ";
    text += buffer;
  };
  add("PGA %.3f g", site.pgaG);
  add("PGV %.1f cm/s", site.pgvCmS);
  add("PSA 0.3 s %.3f g", site.psa03G);
  add("PSA 1.0 s %.3f g", site.psa10G);
  add("PSA 3.0 s %.3f g", site.psa30G);
  add("MMI %.1f", site.mmi);
  add("Vs30 %.0f m/s", site.vs30Mps);
  return text;
}

std::string_view responseSourceName(ResponseSource s) {
  switch (s) {
    case ResponseSource::Model:
      return "model";
    case ResponseSource::Imported:
      return "imported";
    default:
      return "none";
  }
}

std::vector<std::uint8_t> encodeResponseSummary(const ResponseSummaryTile& tile) {
  ByteWriter rsum, sdrf;
  std::uint32_t storeyValues = 0;
  for (const BuildingResponse& b : tile.buildings) {
    rsum.u8(static_cast<std::uint8_t>(b.damage));
    rsum.u8(static_cast<std::uint8_t>(b.source));
    const std::uint16_t storeys = b.source == ResponseSource::None ? 0 : b.storeys;
    rsum.u16(storeys);
    rsum.f32(b.peakDriftRatio);
    rsum.f32(b.peakRoofDisplacementM);
    rsum.f32(b.pgaG);
    rsum.f32(b.peakFloorAccelerationMs2);
    rsum.f32(b.residualDriftRatio);
    const bool hasResult = b.source != ResponseSource::None;
    rsum.u8(static_cast<std::uint8_t>(hasResult ? NoResultReason::None : b.noResultReason));
    rsum.u8(hasResult && b.approximate ? kFlagApproximate : 0);
    rsum.u16(0);
    rsum.u32(hasResult ? b.unconvergedSteps : 0);
    rsum.f32(hasResult && std::isfinite(b.worstResidualRatio) && b.worstResidualRatio > 0.0f ? b.worstResidualRatio
                                                                                             : 0.0f);
    for (std::uint16_t s = 0; s < storeys; ++s) {
      const std::size_t i = b.firstStorey + s;
      sdrf.f32(i < tile.storeyPeakDrift.size() ? tile.storeyPeakDrift[i] : 0.0f);
    }
    storeyValues += storeys;
  }
  std::vector<Section> sections = {{tag("RSUM"), &rsum}, {tag("SDRF"), &sdrf}};
  ByteWriter spec, site, suit, sspr, loss;
  if (!tile.scaling.empty() && tile.scaling.size() == tile.buildings.size()) {
    for (const BuildingScaling& b : tile.scaling) {
      for (int d = 0; d < 2; ++d) {
        spec.f32(b.periodS[d]);
        spec.f32(b.targetSaG[d]);
        spec.f32(b.recordSaG[d]);
        spec.f32(b.scale[d]);
      }
    }
    sections.push_back({tag("SPEC"), &spec});
  }
  if (!tile.sites.empty() && tile.sites.size() == tile.buildings.size()) {
    for (const BuildingSite& b : tile.sites) {
      const bool given = b.source != SiteSource::None;
      site.u8(static_cast<std::uint8_t>(b.source));
      site.u8(0);
      site.u16(0);
      for (const float v : {b.pgaG, b.pgvCmS, b.psa03G, b.psa10G, b.psa30G, b.mmi, b.vs30Mps}) {
        // Anything not a valid value is written as "not given" (a reader refuses negatives and infinities).
        site.f32(given && std::isfinite(v) && v >= 0.0f ? v : BuildingSite::kNotGiven);
      }
    }
    sections.push_back({tag("SITE"), &site});
  }
  if (!tile.spread.empty() && tile.spread.size() == tile.buildings.size()) {
    for (const BuildingSpread& b : tile.spread) {
      suit.u16(b.records);
      suit.u16(b.shownRecord);
      suit.f32(b.driftBeta);
      suit.f32(b.accelerationBeta);
    }
    sections.push_back({tag("SUIT"), &suit});
  }
  if (!tile.storeySpread.empty() && tile.storeySpread.size() == storeyValues) {
    for (const StoreySpread& s : tile.storeySpread) {
      sspr.f32(s.driftBeta);
      sspr.f32(s.accelerationMedianMs2);
      sspr.f32(s.accelerationBeta);
    }
    sections.push_back({tag("SSPR"), &sspr});
  }
  if (!tile.losses.empty() && tile.losses.size() == tile.buildings.size()) {
    for (const BuildingLoss& b : tile.losses) {
      for (const float v : b.structural) loss.f32(v);
      for (const float v : b.nonStructuralDrift) loss.f32(v);
      for (const float v : b.nonStructuralAcceleration) loss.f32(v);
      loss.f32(b.collapse);
      loss.f32(b.occupants);
      for (const float v : b.injuries) loss.f32(v);
      loss.f32(b.replacementValueUsd);
      loss.f32(b.repairCostUsd);
      loss.f32(b.repairTimeDays);
      for (const float v : b.tag) loss.f32(v);
      loss.f32(b.repairCostStdUsd);
      for (const float v : b.injuriesStd) loss.f32(v);
      loss.u8(b.flags);
      loss.u8(0);
      loss.u16(0);
    }
    sections.push_back({tag("LOSS"), &loss});
  }
  ByteWriter dprb;
  if (tile.losses.empty() && !tile.odds.empty() && tile.odds.size() == tile.buildings.size()) {
    auto fraction = [](float p) {
      const float c = std::isfinite(p) ? std::clamp(p, 0.0f, 1.0f) : 0.0f;
      return static_cast<std::uint16_t>(std::lround(c * kOddsLevels));
    };
    for (const BuildingDamageOdds& o : tile.odds) {
      // Quantized from the largest state down, each no more than the one before (a reader checks).
      std::uint16_t previous = 65535;
      for (const float p : o.atLeast) {
        previous = std::min(previous, fraction(p));
        dprb.u16(previous);
      }
      for (const float p : o.tag) dprb.u16(fraction(p));
    }
    sections.push_back({tag("DPRB"), &dprb});
  }
  ByteWriter dser;
  const DriftSeries& d = tile.driftSeries;
  if (!d.empty() && d.spans.size() == tile.buildings.size()) {
    std::uint64_t total = 0;
    for (const DriftSpan& span : d.spans) total += span.count;
    dser.f32(d.rateHz);
    dser.f32(d.fullScale);
    dser.u32(static_cast<std::uint32_t>(total));
    for (const DriftSpan& span : d.spans) {
      dser.f32(span.startSeconds);
      dser.u32(span.count);
    }
    // In building order whatever `first` says (a tile's spans may come from several sources).
    for (const DriftSpan& span : d.spans) {
      for (std::uint32_t i = 0; i < span.count; ++i) {
        const std::size_t at = static_cast<std::size_t>(span.first) + i;
        dser.u8(at < d.codes.size() ? d.codes[at] : 0);
      }
    }
    sections.push_back({tag("DSER"), &dser});
  }
  return assemble("QVRS", kResponseSummaryVersion, static_cast<std::uint32_t>(tile.buildings.size()), storeyValues,
                  sections);
}

float BuildingLoss::structuralAtLeast(int k) const {
  if (k <= 0) return 1.0f;
  float sum = 0.0f;
  for (int j = std::min(k, 5); j < 5; ++j) sum += structural[j];
  return std::min(sum, 1.0f);
}

float BuildingDamageOdds::structuralAtLeast(int k) const {
  if (k <= 0) return 1.0f;
  if (k > 4) return 0.0f;
  return atLeast[k - 1];
}

float BuildingDamageOdds::expectedState() const {
  return atLeast[0] + atLeast[1] + atLeast[2] + atLeast[3];
}

int BuildingDamageOdds::likelyTag() const {
  int best = 0;
  for (int k = 1; k < 3; ++k) {
    if (tag[k] > tag[best]) best = k;
  }
  return best;
}

BuildingDamageOdds BuildingDamageOdds::of(const BuildingLoss& loss) {
  BuildingDamageOdds o;
  for (int k = 1; k <= 4; ++k) o.atLeast[k - 1] = loss.structuralAtLeast(k);
  for (int k = 0; k < 3; ++k) o.tag[k] = loss.tag[k];
  return o;
}

float BuildingLoss::expectedState() const {
  float sum = 0.0f;
  for (int k = 1; k < 5; ++k) sum += static_cast<float>(k) * structural[k];
  return sum;
}

namespace {
Result<ResponseSummaryTile> decodeSummaryFile(std::span<const std::uint8_t> bytes, std::string_view name) {
  const std::string prefix = std::string(name) + ": ";
  auto header = parseHeader(bytes, "QVRS", kResponseSummaryVersion, "response summary tile", prefix);
  if (!header.ok()) return Error{header.error()};
  const auto rsum = findSection(*header, tag("RSUM"));
  const auto sdrf = findSection(*header, tag("SDRF"));
  if (!rsum || !sdrf) return Error{prefix + "required section RSUM or SDRF is missing"};
  const std::size_t recordSize = header->version == 1 ? kSummaryRecordSizeV1 : kSummaryRecordSize;
  if (rsum->second != static_cast<std::size_t>(header->count) * recordSize) {
    return Error{prefix + "section RSUM at byte " + std::to_string(rsum->first) + " holds " +
                 std::to_string(rsum->second) + " bytes, expected " + std::to_string(header->count) + " records of " +
                 std::to_string(recordSize)};
  }
  if (sdrf->second != static_cast<std::size_t>(header->extra) * 4) {
    return Error{prefix + "section SDRF at byte " + std::to_string(sdrf->first) + " holds " +
                 std::to_string(sdrf->second) + " bytes, the header declares " + std::to_string(header->extra) +
                 " storey values"};
  }
  ResponseSummaryTile tile;
  tile.buildings.resize(header->count);
  ByteReader r(bytes.subspan(rsum->first, rsum->second), rsum->first);
  std::uint64_t storeyTotal = 0;
  for (BuildingResponse& b : tile.buildings) {
    const std::uint8_t damage = r.u8("damage state");
    const std::uint8_t source = r.u8("source");
    b.storeys = r.u16("storeys");
    b.peakDriftRatio = r.f32("peak drift");
    b.peakRoofDisplacementM = r.f32("peak roof displacement");
    b.pgaG = r.f32("pga");
    b.peakFloorAccelerationMs2 = r.f32("peak floor acceleration");
    b.residualDriftRatio = r.f32("residual drift");
    std::uint8_t reason = 255, flags = 0;
    if (header->version == 1) {
      r.skip(4, "reserved");
    } else {
      reason = r.u8("no-result reason");
      flags = r.u8("flags");
      r.skip(2, "reserved");
      b.unconvergedSteps = r.u32("unconverged steps");
      b.worstResidualRatio = r.f32("worst residual");
      if (!std::isfinite(b.worstResidualRatio) || b.worstResidualRatio < 0.0f)
        return Error{prefix + "section RSUM near byte " + std::to_string(r.offset()) + ": invalid residual"};
    }
    if (damage > 4 && damage != 255)
      return Error{prefix + "section RSUM near byte " + std::to_string(r.offset()) + ": damage state " +
                   std::to_string(damage)};
    if (source > 2)
      return Error{prefix + "section RSUM near byte " + std::to_string(r.offset()) + ": unknown source " +
                   std::to_string(source)};
    b.damage = static_cast<DamageState>(damage);
    b.source = static_cast<ResponseSource>(source);
    b.approximate = (flags & kFlagApproximate) != 0;
    if (b.source != ResponseSource::None) {
      b.noResultReason = NoResultReason::None;
    } else {
      b.noResultReason = reason >= 1 && reason <= 5 ? static_cast<NoResultReason>(reason) : NoResultReason::Unknown;
    }
    for (float v :
         {b.peakDriftRatio, b.peakRoofDisplacementM, b.pgaG, b.peakFloorAccelerationMs2, b.residualDriftRatio}) {
      if (!std::isfinite(v) || v < 0.0f)
        return Error{prefix + "section RSUM near byte " + std::to_string(r.offset()) + ": invalid peak value"};
    }
    if (b.source == ResponseSource::None && b.storeys != 0)
      return Error{prefix + "a building without a result has storeys"};
    b.firstStorey = static_cast<std::uint32_t>(storeyTotal);
    storeyTotal += b.storeys;
  }
  if (storeyTotal != header->extra) {
    return Error{prefix + "the buildings hold " + std::to_string(storeyTotal) + " storeys, the header declares " +
                 std::to_string(header->extra)};
  }
  tile.storeyPeakDrift.resize(header->extra);
  ByteReader s(bytes.subspan(sdrf->first, sdrf->second), sdrf->first);
  for (float& v : tile.storeyPeakDrift) {
    v = s.f32("storey peak drift");
    if (!std::isfinite(v) || v < 0.0f)
      return Error{prefix + "section SDRF near byte " + std::to_string(s.offset()) + ": invalid drift"};
  }
  if (Status optional = decodeOptionalSections(bytes, *header, prefix, tile); !optional.ok())
    return Error{optional.error()};
  return tile;
}
}  // namespace

Result<ResponseSummaryTile> decodeResponseSummary(std::span<const std::uint8_t> bytes, std::string_view name) {
  std::vector<std::uint8_t> storage;
  auto file = storedFileBytes(bytes, name, storage);
  if (!file.ok()) return Error{file.error()};
  return decodeSummaryFile(*file, name);
}

std::vector<std::uint8_t> encodeResponseHistory(const ResponseHistoryTile& tile) {
  ByteWriter hist;
  for (const BuildingHistory& b : tile.buildings) {
    hist.u16(b.floors);
    if (b.floors == 0) continue;
    const std::uint8_t bits = b.bits == 8 ? 8 : 16;
    hist.u8(bits);
    hist.u8(0);
    hist.f32(b.sampleRateHz);
    hist.f32(b.startSeconds);
    hist.u32(b.sampleCount);
    for (const HistoryDirection* d : {&b.x, &b.y}) {
      hist.u8(d->modes);
      for (std::size_t i = 0; i < static_cast<std::size_t>(b.floors) * d->modes; ++i) {
        hist.f32(i < d->shapes.size() ? d->shapes[i] : 0.0f);
      }
      for (std::size_t k = 0; k < d->modes; ++k) hist.f32(k < d->scales.size() ? d->scales[k] : 0.0f);
      // The file stores each mode's coordinates together (mode-major); memory is time-major.
      for (std::size_t k = 0; k < d->modes; ++k) {
        for (std::size_t s = 0; s < b.sampleCount; ++s) {
          const std::size_t i = s * d->modes + k;
          const std::int16_t v = i < d->coordinates.size() ? d->coordinates[i] : 0;
          if (bits == 8)
            hist.u8(static_cast<std::uint8_t>(static_cast<std::int8_t>(std::clamp<int>(v, -127, 127))));
          else
            hist.i16(v);
        }
      }
    }
  }
  ByteWriter meta;
  meta.f32(tile.durationSeconds);
  const std::array<Section, 2> sections = {{{tag("HMET"), &meta}, {tag("HIST"), &hist}}};
  return assemble("QVRH", kResponseHistoryVersion, static_cast<std::uint32_t>(tile.buildings.size()), 0, sections);
}

namespace {
Result<ResponseHistoryTile> decodeHistoryFile(std::span<const std::uint8_t> bytes, std::string_view name) {
  const std::string prefix = std::string(name) + ": ";
  auto header = parseHeader(bytes, "QVRH", kResponseHistoryVersion, "response history tile", prefix);
  if (!header.ok()) return Error{header.error()};
  const auto meta = findSection(*header, tag("HMET"));
  const auto hist = findSection(*header, tag("HIST"));
  if (!meta || !hist) return Error{prefix + "required section HMET or HIST is missing"};
  ResponseHistoryTile tile;
  ByteReader m(bytes.subspan(meta->first, meta->second), meta->first);
  tile.durationSeconds = m.f32("duration");
  if (!m.ok() || !std::isfinite(tile.durationSeconds) || tile.durationSeconds < 0.0f || tile.durationSeconds > 1.0e5f) {
    return Error{prefix + "section HMET: invalid duration"};
  }
  ByteReader r(bytes.subspan(hist->first, hist->second), hist->first);
  // Every building takes at least its two-byte floor count: check before allocating.
  if (header->count > hist->second / 2) {
    return Error{prefix + "section HIST at byte " + std::to_string(hist->first) + ": " + std::to_string(header->count) +
                 " buildings cannot fit in " + std::to_string(hist->second) + " bytes"};
  }
  tile.buildings.resize(header->count);
  for (BuildingHistory& b : tile.buildings) {
    b.floors = r.u16("floors");
    if (!r.ok()) break;
    if (b.floors == 0) continue;
    if (b.floors > kMaxFloors)
      return Error{prefix + "section HIST near byte " + std::to_string(r.offset()) + ": " + std::to_string(b.floors) +
                   " floors exceeds the limit"};
    b.bits = r.u8("bits");
    r.u8("reserved");
    b.sampleRateHz = r.f32("sample rate");
    b.startSeconds = r.f32("start time");
    b.sampleCount = r.u32("sample count");
    if (!r.ok()) break;
    if (b.bits != 8 && b.bits != 16)
      return Error{prefix + "section HIST near byte " + std::to_string(r.offset()) + ": sample width " +
                   std::to_string(b.bits)};
    if (!std::isfinite(b.sampleRateHz) || b.sampleRateHz <= 0.0f || b.sampleRateHz > 10000.0f || b.sampleCount == 0 ||
        b.sampleCount > kMaxSamples || !std::isfinite(b.startSeconds) || b.startSeconds < 0.0f ||
        b.startSeconds > 1.0e5f) {
      return Error{prefix + "section HIST near byte " + std::to_string(r.offset()) + ": invalid sampling"};
    }
    for (HistoryDirection* d : {&b.x, &b.y}) {
      d->modes = r.u8("modes");
      if (d->modes > kMaxModes)
        return Error{prefix + "section HIST near byte " + std::to_string(r.offset()) + ": " + std::to_string(d->modes) +
                     " modes exceeds the limit"};
      const std::size_t shapeCount = static_cast<std::size_t>(b.floors) * d->modes;
      const std::size_t sampleCount = static_cast<std::size_t>(d->modes) * b.sampleCount;
      // Check the bytes are there before allocating.
      const std::size_t need = shapeCount * 4 + d->modes * 4u + sampleCount * (b.bits / 8u);
      if (need > r.remaining()) {
        return Error{prefix + "section HIST near byte " + std::to_string(r.offset()) + ": truncated: a history needs " +
                     std::to_string(need) + " bytes, " + std::to_string(r.remaining()) + " left"};
      }
      d->shapes.resize(shapeCount);
      for (float& v : d->shapes) v = r.f32("shape");
      d->scales.resize(d->modes);
      for (float& v : d->scales) v = r.f32("scale");
      for (float v : d->shapes) {
        if (!std::isfinite(v)) return Error{prefix + "section HIST: non-finite mode shape"};
      }
      for (float v : d->scales) {
        if (!std::isfinite(v)) return Error{prefix + "section HIST: non-finite scale"};
      }
      // Mode-major in the file, time-major in memory: the viewer reads all modes of one instant
      // together (one cache line per building and frame instead of one per mode).
      d->coordinates.resize(sampleCount);
      const std::span<const std::uint8_t> raw = r.bytes(sampleCount * (b.bits / 8u), "coordinates");
      if (raw.size() == sampleCount * (b.bits / 8u)) {
        std::int16_t* out = d->coordinates.data();
        const std::size_t modes = d->modes;
        for (std::size_t k = 0; k < modes; ++k) {
          for (std::size_t s = 0; s < b.sampleCount; ++s) {
            const std::size_t at = k * b.sampleCount + s;
            out[s * modes + k] = b.bits == 8 ? static_cast<std::int16_t>(static_cast<std::int8_t>(raw[at]))
                                             : static_cast<std::int16_t>(static_cast<std::uint16_t>(
                                                   raw[2 * at] | (static_cast<unsigned>(raw[2 * at + 1]) << 8)));
          }
        }
      }
    }
  }
  if (!r.ok()) return Error{prefix + "section HIST: " + r.error()};
  return tile;
}
}  // namespace

Result<ResponseHistoryTile> decodeResponseHistory(std::span<const std::uint8_t> bytes, std::string_view name) {
  std::vector<std::uint8_t> storage;
  auto file = storedFileBytes(bytes, name, storage);
  if (!file.ok()) return Error{file.error()};
  return decodeHistoryFile(*file, name);
}

void sampleHistory(const BuildingHistory& h, double t, std::span<float> floorsX, std::span<float> floorsY) {
  // Level 0 (the ground) and any room beyond the building's floors stay at rest.
  const std::size_t room = std::min(floorsX.size(), floorsY.size());
  const std::size_t floors = h.sampleCount == 0 ? 0 : std::min<std::size_t>(h.floors, room > 0 ? room - 1 : 0);
  std::fill(floorsX.begin() + static_cast<std::ptrdiff_t>(std::min(floorsX.size(), floors + 1)), floorsX.end(), 0.0f);
  std::fill(floorsY.begin() + static_cast<std::ptrdiff_t>(std::min(floorsY.size(), floors + 1)), floorsY.end(), 0.0f);
  if (room > 0) floorsX[0] = floorsY[0] = 0.0f;
  if (floors == 0) return;
  const HistoryTap tap = historyTap(h.startSeconds, h.sampleRateHz, h.sampleCount, t);
  const std::pair<const HistoryDirection*, std::span<float>> directions[] = {{&h.x, floorsX}, {&h.y, floorsY}};
  for (const auto& [d, out] : directions) {
    // The modal coordinates at t first, then each floor as the sum of its shape row times them:
    // the shapes are read once, in order (floor-major).
    const std::size_t modes = std::min<std::size_t>(d->modes, kMaxModes);
    float coordinate[kMaxModes] = {};
    modalCoordinates(d->coordinates.data(), d->modes, d->scales.data(), tap, coordinate);
    const float* shape = d->shapes.data();
    for (std::size_t f = 0; f < floors; ++f, shape += d->modes) {
      float v = 0.0f;
      for (std::size_t k = 0; k < modes; ++k) v += shape[k] * coordinate[k];
      out[f + 1] = v;
    }
  }
}

DriftSpan appendDriftSeries(const BuildingHistory& h, float storeyHeightM, DriftSeries& series) {
  DriftSpan span;
  span.first = static_cast<std::uint32_t>(series.codes.size());
  span.startSeconds = h.startSeconds;
  if (h.sampleCount == 0 || h.floors == 0 || !(h.sampleRateHz > 0.0f) || !(series.rateHz > 0.0f) ||
      !(series.fullScale > 0.0f)) {
    return span;
  }
  // The largest storey drift at each stored sample (where the interpolated history equals the
  // samples), straight from the modes: floor f = sum over k of shape[f][k] scale[k] q_k.
  const std::size_t floors = h.floors;
  std::vector<float> drift(h.sampleCount, 0.0f);
  std::vector<float> x(floors + 1, 0.0f), y(floors + 1, 0.0f);
  const float height = std::max(storeyHeightM, 0.5f);
  for (std::uint32_t i = 0; i < h.sampleCount; ++i) {
    for (const auto& [d, out] : {std::pair{&h.x, &x}, std::pair{&h.y, &y}}) {
      const std::size_t modes = std::min<std::size_t>(d->modes, kMaxModes);
      const bool complete = d->shapes.size() >= floors * d->modes && d->scales.size() >= d->modes &&
                            d->coordinates.size() >= (std::size_t{i} + 1) * d->modes;
      for (std::size_t f = 0; f < floors; ++f) {
        float v = 0.0f;
        if (complete) {
          for (std::size_t k = 0; k < modes; ++k) {
            v += d->shapes[f * d->modes + k] * d->scales[k] *
                 static_cast<float>(d->coordinates[std::size_t{i} * d->modes + k]);
          }
        }
        (*out)[f + 1] = v;
      }
    }
    float worst = 0.0f;
    for (std::size_t f = 1; f <= floors; ++f) {
      worst = std::max({worst, std::abs(x[f] - x[f - 1]), std::abs(y[f] - y[f - 1])});
    }
    drift[i] = worst / height;
  }
  // Each window takes its samples' largest; a window between two samples (histories stored at
  // fewer samples a second than windows) the larger of its neighbours'.
  const double duration = static_cast<double>(h.sampleCount - 1) / static_cast<double>(h.sampleRateHz);
  const auto windows = static_cast<std::uint32_t>(
      std::min(std::floor(duration * static_cast<double>(series.rateHz)) + 1.0, double{kMaxSamples}));
  std::vector<float> window(windows, -1.0f);
  for (std::uint32_t i = 0; i < h.sampleCount; ++i) {
    const auto w = static_cast<std::uint32_t>(static_cast<double>(i) / h.sampleRateHz * series.rateHz);
    if (w < windows) window[w] = std::max(window[w], drift[i]);
  }
  for (std::uint32_t w = 0; w < windows; ++w) {
    float v = window[w];
    if (v < 0.0f) {
      const double t = static_cast<double>(w) / series.rateHz * h.sampleRateHz;  // in samples
      const auto before = static_cast<std::uint32_t>(std::min(std::floor(t), static_cast<double>(h.sampleCount - 1)));
      const std::uint32_t after = std::min(before + 1, h.sampleCount - 1);
      v = std::max(drift[before], drift[after]);
    }
    series.codes.push_back(driftSeriesCode(v, series.fullScale));
  }
  span.count = windows;
  return span;
}

}  // namespace qv
