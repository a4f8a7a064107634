#include <algorithm>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <vector>

#include "qv/core/Crc32.h"
#include "qv/format/ResponseTile.h"

using namespace qv;

namespace {

// Two buildings: a 2-storey result that the solver could not converge everywhere, and a rooftop
// part without a result.
ResponseSummaryTile tinySummary() {
  ResponseSummaryTile t;
  BuildingResponse a;
  a.damage = DamageState::Moderate;
  a.source = ResponseSource::Model;
  a.storeys = 2;
  a.peakDriftRatio = 0.0125f;
  a.peakRoofDisplacementM = 0.25f;
  a.pgaG = 0.5f;
  a.peakFloorAccelerationMs2 = 4.0f;
  a.residualDriftRatio = 0.001953125f;
  a.approximate = true;
  a.unconvergedSteps = 3;
  a.worstResidualRatio = 0.0625f;
  t.buildings.push_back(a);
  BuildingResponse none;
  none.noResultReason = NoResultReason::BaseAboveGround;
  t.buildings.push_back(none);
  t.storeyPeakDrift = {0.0125f, 0.0078125f};
  return t;
}

}  // namespace

TEST_CASE("Response summary version 2 is pinned by golden bytes", "[format][response]") {
  const std::vector<std::uint8_t> golden = {
      0x51, 0x56, 0x52, 0x53, 0x02, 0x00, 0x00, 0x00, 0x84, 0x00, 0x00, 0x00, 0xba, 0x33, 0xb1, 0xee,  //
      0x02, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x52, 0x53, 0x55, 0x4d,  //
      0x34, 0x00, 0x00, 0x00, 0x48, 0x00, 0x00, 0x00, 0x53, 0x44, 0x52, 0x46, 0x7c, 0x00, 0x00, 0x00,  //
      0x08, 0x00, 0x00, 0x00, 0x02, 0x01, 0x02, 0x00, 0xcd, 0xcc, 0x4c, 0x3c, 0x00, 0x00, 0x80, 0x3e,  //
      0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0x00, 0x3b, 0x00, 0x01, 0x00, 0x00,  //
      0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3d, 0xff, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //
      0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xcd, 0xcc, 0x4c, 0x3c,  //
      0x00, 0x00, 0x00, 0x3c};
  CHECK(encodeResponseSummary(tinySummary()) == golden);
  const auto decoded = decodeResponseSummary(golden, "golden.qvs");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->buildings.size() == 2);
  const BuildingResponse& a = decoded->buildings[0];
  CHECK(a.damage == DamageState::Moderate);
  CHECK(a.noResultReason == NoResultReason::None);
  CHECK(a.approximate);
  CHECK(a.unconvergedSteps == 3);
  CHECK(a.worstResidualRatio == 0.0625f);
  const BuildingResponse& b = decoded->buildings[1];
  CHECK(b.damage == DamageState::NoResult);
  CHECK(b.noResultReason == NoResultReason::BaseAboveGround);
  CHECK_FALSE(b.approximate);
  CHECK(decoded->storeyPeakDrift == std::vector<float>{0.0125f, 0.0078125f});
}

TEST_CASE("Response history version 1 is pinned by golden bytes written from docs/formats.md", "[format][response]") {
  // Built field by field from the layout in docs/formats.md (CRC by zlib), not by the encoder: a
  // 2-storey building with 3 samples at 10 Hz from 0.5 s, one X basis vector in 8 bits and no Y
  // motion, and a building without a history.
  const std::vector<std::uint8_t> golden = {0x51, 0x56, 0x52, 0x48, 0x01, 0x00, 0x00, 0x00,
                                            0x5c, 0x00, 0x00, 0x00, 0xfa, 0xf4, 0x6c, 0x3a,  // header
                                            0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                                            0x02, 0x00, 0x00, 0x00, 0x48, 0x4d, 0x45, 0x54,  // B, 0, S, HMET
                                            0x34, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00,
                                            0x48, 0x49, 0x53, 0x54, 0x38, 0x00, 0x00, 0x00,  // HIST at 56
                                            0x23, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x40,
                                            0x02, 0x00, 0x08, 0x00, 0x00, 0x00, 0x20, 0x41,  // 4 s; 2 floors, 8 bits
                                            0x00, 0x00, 0x00, 0x3f, 0x03, 0x00, 0x00, 0x00,
                                            0x01, 0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80,  // start, N, X: 1 mode
                                            0x3f, 0x00, 0x00, 0x80, 0x3e, 0x01, 0xfe, 0x7f,
                                            0x00, 0x00, 0x00, 0x00};  // scale, 1 -2 127, Y: 0; floors 0; pad
  ResponseHistoryTile tile;
  tile.durationSeconds = 4.0f;
  BuildingHistory a;
  a.floors = 2;
  a.bits = 8;
  a.sampleRateHz = 10.0f;
  a.startSeconds = 0.5f;
  a.sampleCount = 3;
  a.x.modes = 1;
  a.x.shapes = {0.5f, 1.0f};
  a.x.scales = {0.25f};
  a.x.coordinates = {1, -2, 127};
  tile.buildings.push_back(a);
  tile.buildings.push_back(BuildingHistory{});
  CHECK(encodeResponseHistory(tile) == golden);

  const auto decoded = decodeResponseHistory(golden, "golden.qvh");
  REQUIRE(decoded.ok());
  CHECK(decoded->durationSeconds == 4.0f);
  REQUIRE(decoded->buildings.size() == 2);
  const BuildingHistory& d = decoded->buildings[0];
  CHECK(d.floors == 2);
  CHECK(d.bits == 8);
  CHECK(d.sampleRateHz == 10.0f);
  CHECK(d.startSeconds == 0.5f);
  CHECK(d.sampleCount == 3);
  CHECK(d.x.modes == 1);
  CHECK(d.x.shapes == std::vector<float>{0.5f, 1.0f});
  CHECK(d.x.coordinates == std::vector<std::int16_t>{1, -2, 127});
  CHECK(d.y.modes == 0);
  CHECK(decoded->buildings[1].floors == 0);
  // At the second sample (t = 0.6 s) the roof is at shape 1.0 x scale 0.25 x -2 = -0.5 m.
  std::vector<float> fx(3), fy(3);
  sampleHistory(*decoded->buildings.data(), 0.6, fx, fy);
  CHECK(fx[2] == Approx(-0.5f));
  CHECK(fx[1] == Approx(-0.25f));
  CHECK(fy[2] == 0.0f);
}

TEST_CASE("Response summary version 1 files are still read, without status", "[format][response]") {
  // Written by the version 1 encoder: the same two buildings (28-byte records, reserved bytes).
  const std::vector<std::uint8_t> version1 = {
      0x51, 0x56, 0x52, 0x53, 0x01, 0x00, 0x00, 0x00, 0x74, 0x00, 0x00, 0x00, 0xdc, 0xa2, 0x4e, 0xbb,  //
      0x02, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x52, 0x53, 0x55, 0x4d,  //
      0x34, 0x00, 0x00, 0x00, 0x38, 0x00, 0x00, 0x00, 0x53, 0x44, 0x52, 0x46, 0x6c, 0x00, 0x00, 0x00,  //
      0x08, 0x00, 0x00, 0x00, 0x02, 0x01, 0x02, 0x00, 0xcd, 0xcc, 0x4c, 0x3c, 0x00, 0x00, 0x80, 0x3e,  //
      0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0x00, 0x3b, 0x00, 0x00, 0x00, 0x00,  //
      0xff, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xcd, 0xcc, 0x4c, 0x3c,  //
      0x00, 0x00, 0x00, 0x3c};
  const auto decoded = decodeResponseSummary(version1, "old.qvs");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->buildings.size() == 2);
  CHECK(decoded->buildings[0].damage == DamageState::Moderate);
  CHECK(decoded->buildings[0].peakRoofDisplacementM == 0.25f);
  CHECK(decoded->buildings[0].noResultReason == NoResultReason::None);
  CHECK_FALSE(decoded->buildings[0].approximate);
  CHECK(decoded->buildings[1].noResultReason == NoResultReason::Unknown);
  CHECK(decoded->storeyPeakDrift.size() == 2);
}

TEST_CASE("No-result reasons have stable names, and unknown values read as unknown", "[format][response]") {
  CHECK(noResultReasonName(NoResultReason::None) == "none");
  CHECK(noResultReasonName(NoResultReason::ModelInvalid) == "model_invalid");
  CHECK(noResultReasonName(NoResultReason::OutsideField) == "outside_field");
  CHECK(noResultReasonName(NoResultReason::SkippedByOption) == "skipped_by_option");
  CHECK(noResultReasonName(NoResultReason::BaseAboveGround) == "base_above_ground");
  CHECK(noResultReasonName(NoResultReason::NotInImport) == "not_in_import");
  CHECK(noResultReasonName(NoResultReason::Unknown) == "unknown");
  CHECK(noResultReasonDescription(NoResultReason::BaseAboveGround).find("rooftop") != std::string_view::npos);
  ResponseSummaryTile t = tinySummary();
  t.buildings[1].noResultReason = static_cast<NoResultReason>(77);  // a reason of a later version
  const auto decoded = decodeResponseSummary(encodeResponseSummary(t), "later.qvs");
  REQUIRE(decoded.ok());
  CHECK(decoded->buildings[1].noResultReason == NoResultReason::Unknown);
}

TEST_CASE("A summary of an unknown version is refused with both versions named", "[format][response]") {
  std::vector<std::uint8_t> bytes = encodeResponseSummary(tinySummary());
  bytes[4] = 3;
  const auto decoded = decodeResponseSummary(bytes, "new.qvs");
  REQUIRE_FALSE(decoded.ok());
  CHECK(decoded.error().find("version 3") != std::string::npos);
  CHECK(decoded.error().find("versions 1 to 2") != std::string::npos);
}

TEST_CASE("The optional summary sections (scaling, suite spread, losses) round-trip and are checked",
          "[format][response]") {
  ResponseSummaryTile t = tinySummary();
  BuildingScaling scaled;
  scaled.periodS[0] = 0.5f;
  scaled.periodS[1] = 0.55f;
  scaled.targetSaG[0] = 0.75f;
  scaled.targetSaG[1] = 0.7f;
  scaled.recordSaG[0] = 1.5f;
  scaled.recordSaG[1] = 1.25f;
  scaled.scale[0] = 0.5f;
  scaled.scale[1] = 0.56f;
  t.scaling = {scaled, BuildingScaling{}};
  t.spread = {BuildingSpread{7, 3, 0.375f, 0.25f}, BuildingSpread{}};
  t.storeySpread = {StoreySpread{0.375f, 5.5f, 0.25f}, StoreySpread{0.3f, 6.5f, 0.2f}};
  BuildingLoss loss;
  const float p[5] = {0.25f, 0.25f, 0.25f, 0.125f, 0.125f};
  for (int k = 0; k < 5; ++k)
    loss.structural[k] = loss.nonStructuralDrift[k] = loss.nonStructuralAcceleration[k] = p[k];
  loss.collapse = 0.01f;
  loss.occupants = 12.5f;
  loss.injuries[0] = 0.5f;
  loss.injuries[3] = 0.01f;
  loss.replacementValueUsd = 2.5e6f;
  loss.repairCostUsd = 3.0e5f;
  loss.repairTimeDays = 40.0f;
  loss.tag[0] = 0.5f;
  loss.tag[1] = 0.25f;
  loss.tag[2] = 0.25f;
  loss.repairCostStdUsd = 4.5e5f;
  loss.injuriesStd[0] = 1.25f;
  loss.injuriesStd[3] = 0.1f;
  loss.flags = kLossOccupantsInferred | kLossValueInferred;
  t.losses = {loss, BuildingLoss{}};
  const auto bytes = encodeResponseSummary(t);
  // Four more section table entries and the documented record sizes.
  CHECK(bytes.size() == encodeResponseSummary(tinySummary()).size() + 4 * 12 + 2 * 32 + 2 * 12 + 2 * 12 + 2 * 132);
  const auto decoded = decodeResponseSummary(bytes, "optional.qvs");
  REQUIRE(decoded.ok());
  CHECK(decoded->scaling == t.scaling);
  CHECK(decoded->spread == t.spread);
  CHECK(decoded->storeySpread == t.storeySpread);
  CHECK(decoded->losses == t.losses);
  CHECK(decoded->losses[0].expectedState() == Approx(0.25 + 0.5 + 0.375 + 0.5));
  // A summary without them still reads, with the optional vectors empty.
  const auto plain = decodeResponseSummary(encodeResponseSummary(tinySummary()), "plain.qvs");
  REQUIRE(plain.ok());
  CHECK(plain->losses.empty());
  CHECK(plain->scaling.empty());

  SECTION("a probability above 1 is refused, naming the section") {
    t.losses[0].structural[4] = 1.5f;
    const auto bad = decodeResponseSummary(encodeResponseSummary(t), "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("bad.qvs") && Catch::Contains("LOSS"));
  }
  SECTION("a shown record beyond the suite is refused") {
    t.spread[0].shownRecord = 7;
    const auto bad = decodeResponseSummary(encodeResponseSummary(t), "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("SUIT"));
  }
  SECTION("a negative scale is refused") {
    t.scaling[0].scale[1] = -1.0f;
    const auto bad = decodeResponseSummary(encodeResponseSummary(t), "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("SPEC"));
  }
}

TEST_CASE("The drift series section round-trips, keeps small drifts and is checked", "[format][response]") {
  ResponseSummaryTile t = tinySummary();
  REQUIRE(t.buildings.size() == 2);
  // Building 0: four windows from 2.5 s; building 1 (no history): none.
  t.driftSeries.rateHz = kDriftSeriesRateHz;
  t.driftSeries.fullScale = kDriftSeriesFullScale;
  for (const float drift : {0.0f, 0.001f, 0.02f, 0.2f}) {
    t.driftSeries.codes.push_back(driftSeriesCode(drift, kDriftSeriesFullScale));
  }
  t.driftSeries.spans = {DriftSpan{2.5f, 0, 4}, DriftSpan{0.0f, 4, 0}};
  const auto bytes = encodeResponseSummary(t);
  // One more section table entry, its 12-byte header, 8 bytes a building and a byte a sample.
  CHECK(bytes.size() == encodeResponseSummary(tinySummary()).size() + 12 + 12 + 2 * 8 + 4);
  const auto decoded = decodeResponseSummary(bytes, "series.qvs");
  REQUIRE(decoded.ok());
  CHECK(decoded->driftSeries == t.driftSeries);
  // Quantization: 0 stays 0; 0.1 % drift within 3 % of itself; above the full scale clips to it.
  const DriftSeries& d = decoded->driftSeries;
  CHECK(driftSeriesValue(d.codes[0], d.fullScale) == 0.0f);
  CHECK(driftSeriesValue(d.codes[1], d.fullScale) == Approx(0.001f).epsilon(0.03));
  CHECK(driftSeriesValue(d.codes[2], d.fullScale) == Approx(0.02f).epsilon(0.01));
  CHECK(d.codes[3] == 255);
  CHECK(driftSeriesValue(255, d.fullScale) == Approx(kDriftSeriesFullScale));
  // Codes grow with the drift.
  for (int q = 1; q < 256; ++q) {
    CHECK(driftSeriesValue(static_cast<std::uint8_t>(q), 0.05f) >
          driftSeriesValue(static_cast<std::uint8_t>(q - 1), 0.05f));
  }
  // Without the section, no series.
  const auto plain = decodeResponseSummary(encodeResponseSummary(tinySummary()), "plain.qvs");
  REQUIRE(plain.ok());
  CHECK(plain->driftSeries.empty());

  SECTION("a rate of zero is refused, naming the section") {
    t.driftSeries.rateHz = 0.0f;
    const auto bad = decodeResponseSummary(encodeResponseSummary(t), "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("bad.qvs") && Catch::Contains("DSER") && Catch::Contains("rate"));
  }
  SECTION("a non-finite start time is refused") {
    t.driftSeries.spans[0].startSeconds = std::numeric_limits<float>::infinity();
    const auto bad = decodeResponseSummary(encodeResponseSummary(t), "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("DSER") && Catch::Contains("start"));
  }
}

TEST_CASE("A history's drift series is the largest storey drift in each window", "[format][response]") {
  // Two storeys of 4 m, one X mode: floor 1 moves q, floor 2 moves 3q (drifts q / 4 and 2q / 4);
  // q ramps up by one step a sample at 20 samples a second for 2 s, from t = 1.5 s.
  BuildingHistory h;
  h.floors = 2;
  h.sampleRateHz = 20.0f;
  h.startSeconds = 1.5f;
  h.sampleCount = 41;
  h.x.modes = 1;
  h.x.shapes = {1.0f, 3.0f};
  h.x.scales = {0.001f};  // metres a step
  for (std::uint32_t i = 0; i < h.sampleCount; ++i) h.x.coordinates.push_back(static_cast<std::int16_t>(i));
  DriftSeries series;
  series.rateHz = 4.0f;
  series.fullScale = kDriftSeriesFullScale;
  series.codes = {7};  // codes already there stay
  const DriftSpan span = appendDriftSeries(h, 4.0f, series);
  CHECK(span.first == 1);
  CHECK(span.startSeconds == 1.5f);
  REQUIRE(span.count == 9);  // 2 s at 4 windows a second, and the window holding the last sample
  REQUIRE(series.codes.size() == 10);
  CHECK(series.codes[0] == 7);
  for (std::uint32_t w = 0; w < span.count; ++w) {
    // Window w holds samples 5w .. 5w + 4; its largest q is the last of them (the last window: 40).
    const double q = std::min(5.0 * w + 4.0, 40.0);
    const double drift = 2.0 * q * 0.001 / 4.0;
    CAPTURE(w);
    CHECK(driftSeriesValue(series.codes[span.first + w], series.fullScale) ==
          Approx(drift).epsilon(0.025).margin(1e-6));
  }
  // No history, no series.
  const DriftSpan none = appendDriftSeries(BuildingHistory{}, 3.0f, series);
  CHECK(none.count == 0);
  CHECK(series.codes.size() == 10);
}

TEST_CASE("The site section keeps the field's values, 'not given' as NaN, with or without a result",
          "[format][response]") {
  ResponseSummaryTile t = tinySummary();
  BuildingSite shakemap;  // a ShakeMap without MMI
  shakemap.source = SiteSource::ShakeMap;
  shakemap.pgaG = 0.304f;
  shakemap.pgvCmS = 6.9f;
  shakemap.psa03G = 0.281f;
  shakemap.psa10G = 0.076f;
  shakemap.psa30G = 0.015f;
  shakemap.vs30Mps = 446.0f;
  t.sites = {shakemap, BuildingSite{}};
  const auto bytes = encodeResponseSummary(t);
  CHECK(bytes.size() == encodeResponseSummary(tinySummary()).size() + 12 + 2 * 32);
  const auto decoded = decodeResponseSummary(bytes, "site.qvs");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->sites.size() == 2);
  const BuildingSite& s = decoded->sites[0];
  CHECK(s.source == SiteSource::ShakeMap);
  CHECK(s.pgaG == 0.304f);
  CHECK(s.psa10G == 0.076f);
  CHECK(s.vs30Mps == 446.0f);
  CHECK(std::isnan(s.mmi));
  CHECK_FALSE(decoded->sites[1].given());
  CHECK(std::isnan(decoded->sites[1].pgaG));
  CHECK(siteShakingText(s) ==
        "PGA 0.304 g, PGV 6.9 cm/s, PSA 0.3 s 0.281 g, PSA 1.0 s 0.076 g, PSA 3.0 s 0.015 g, "
        "Vs30 446 m/s");
  CHECK(siteShakingText(decoded->sites[1]).empty());
  CHECK(siteSourceName(SiteSource::Scenario) == "scenario");

  // A hostile file: a negative PGA, or an infinite one, is refused naming the section; an unknown
  // source reads as no site.
  auto patched = [&](std::size_t recordByte, auto write) {
    std::vector<std::uint8_t> b = bytes;
    std::uint32_t offset = 0;
    for (std::size_t at = 28;  // the header, then the section table (docs/formats.md)
         at + 12 <= b.size(); at += 12) {
      if (std::memcmp(b.data() + at, "SITE", 4) == 0) {
        std::memcpy(&offset, b.data() + at + 4, 4);
        break;
      }
    }
    REQUIRE(offset > 0);
    write(b.data() + offset + recordByte);
    const std::uint32_t crc = crc32(std::span<const std::uint8_t>(b).subspan(16));
    std::memcpy(b.data() + 12, &crc, 4);
    return b;
  };
  for (const float v : {-0.5f, std::numeric_limits<float>::infinity()}) {
    const auto bad = decodeResponseSummary(patched(4, [&](std::uint8_t* p) { std::memcpy(p, &v, 4); }), "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("bad.qvs") && Catch::Contains("SITE"));
  }
  const auto unknown = decodeResponseSummary(patched(0, [](std::uint8_t* p) { *p = 9; }), "future.qvs");
  REQUIRE(unknown.ok());
  CHECK_FALSE(unknown->sites[0].given());
}

TEST_CASE("The drawing probabilities (DPRB) round-trip to 1/65535, come from LOSS where a file has it, and are checked",
          "[format][response]") {
  ResponseSummaryTile t = tinySummary();
  BuildingDamageOdds o;
  const float atLeast[4] = {0.75f, 0.5f, 0.25f, 0.125f};
  const float tags[3] = {0.5f, 0.3f, 0.2f};
  std::copy(std::begin(atLeast), std::end(atLeast), o.atLeast);
  std::copy(std::begin(tags), std::end(tags), o.tag);
  t.odds = {o, BuildingDamageOdds{}};
  std::vector<std::uint8_t> bytes = encodeResponseSummary(t);
  // One more section table entry and two records of 14 bytes (28: already on a 4-byte boundary).
  CHECK(bytes.size() == encodeResponseSummary(tinySummary()).size() + 12 + 2 * 14);
  const auto decoded = decodeResponseSummary(bytes, "slim.qvs");
  REQUIRE(decoded.ok());
  REQUIRE(decoded->odds.size() == 2);
  CHECK(decoded->losses.empty());
  for (int k = 0; k < 4; ++k) CHECK(decoded->odds[0].atLeast[k] == Approx(atLeast[k]).margin(1.0 / 131070.0));
  for (int k = 0; k < 3; ++k) CHECK(decoded->odds[0].tag[k] == Approx(tags[k]).margin(1.0 / 131070.0));
  CHECK(decoded->odds[0].expectedState() == Approx(1.625).margin(1e-4));
  CHECK(decoded->odds[0].likelyTag() == 0);
  CHECK(decoded->odds[0].structuralAtLeast(0) == 1.0f);
  CHECK(decoded->odds[0].structuralAtLeast(5) == 0.0f);

  // The record as docs/formats.md lays it out: u16 round(65535 p), P(>= slight) first.
  std::size_t at = 0;
  const std::uint16_t sections = static_cast<std::uint16_t>(bytes[24] | (bytes[25] << 8));
  for (std::uint16_t s = 0; s < sections; ++s) {
    const std::size_t entry = 28 + 12 * static_cast<std::size_t>(s);
    if (std::memcmp(&bytes[entry], "DPRB", 4) == 0) std::memcpy(&at, &bytes[entry + 4], 4);
  }
  REQUIRE(at > 0);
  CHECK(bytes[at] == 0xFF);  // 0.75 x 65535 = 49151.25 -> 49151 = 0xBFFF
  CHECK(bytes[at + 1] == 0xBF);
  CHECK(bytes[at + 2] == 0x00);  // 0.5 -> 32768 (rounded half up) = 0x8000
  CHECK(bytes[at + 3] == 0x80);

  SECTION("a file with LOSS gives the exact probabilities; the encoder never writes both sections") {
    BuildingLoss loss;
    const float p[5] = {0.25f, 0.25f, 0.25f, 0.125f, 0.125f};
    for (int k = 0; k < 5; ++k)
      loss.structural[k] = loss.nonStructuralDrift[k] = loss.nonStructuralAcceleration[k] = p[k];
    loss.tag[0] = 0.25f;
    loss.tag[1] = 0.5f;
    loss.tag[2] = 0.25f;
    t.losses = {loss, BuildingLoss{}};
    const auto both = decodeResponseSummary(encodeResponseSummary(t), "full.qvs");
    REQUIRE(both.ok());
    REQUIRE(both->odds.size() == 2);
    CHECK(both->odds[0] == BuildingDamageOdds::of(loss));
    CHECK(both->odds[0].atLeast[1] == 0.5f);
    CHECK(both->odds[0].likelyTag() == 1);
  }
  SECTION("P(DS >= k) growing with k is refused") {
    bytes[at + 2] = 0xFF;
    bytes[at + 3] = 0xFF;  // P(>= moderate) = 1 > P(>= slight)
    const std::uint32_t crc = crc32(std::span<const std::uint8_t>(bytes).subspan(16));
    std::memcpy(&bytes[12], &crc, 4);
    const auto bad = decodeResponseSummary(bytes, "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("bad.qvs") && Catch::Contains("DPRB") && Catch::Contains("grows"));
  }
  SECTION("tag probabilities over 1 are refused") {
    for (int k = 0; k < 6; ++k) bytes[at + 8 + static_cast<std::size_t>(k)] = 0xFF;
    const std::uint32_t crc = crc32(std::span<const std::uint8_t>(bytes).subspan(16));
    std::memcpy(&bytes[12], &crc, 4);
    const auto bad = decodeResponseSummary(bytes, "bad.qvs");
    REQUIRE_FALSE(bad.ok());
    CHECK_THAT(bad.error(), Catch::Contains("DPRB") && Catch::Contains("tag"));
  }
}
