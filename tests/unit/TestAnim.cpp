#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <vector>

#include "qv/anim/FloorBlend.h"
#include "qv/anim/FloorDisplacements.h"
#include "qv/anim/HistorySampling.h"
#include "qv/anim/SeriesSampling.h"

using namespace qv;

namespace {

// A floor row as the scene's floor table has it: the displacements and something else.
struct Row {
  float dxMeters = 0.0f;
  float dyMeters = 0.0f;
  float other = 7.0f;
};

// A history of `samples` samples at `rateHz` from `startSeconds`, `modes` per sample, whose mode
// k at sample i is base + slope * i + k (a straight line in time per mode).
struct RampHistory {
  std::vector<std::int16_t> coordinates;
  std::vector<float> scales;
  float startSeconds, rateHz;
  std::uint32_t samples;
  std::size_t modes;
  RampHistory(float start, float rate, std::uint32_t n, std::size_t m, int base, int slope)
      : startSeconds(start), rateHz(rate), samples(n), modes(m) {
    for (std::uint32_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < m; ++k)
        coordinates.push_back(static_cast<std::int16_t>(base + slope * static_cast<int>(i) + static_cast<int>(k)));
    }
    for (std::size_t k = 0; k < m; ++k) scales.push_back(0.5f + 0.25f * static_cast<float>(k));
  }
};

}  // namespace

TEST_CASE("A history is read exactly at its samples and held before its start and after its end", "[anim]") {
  const float start = 2.0f, rate = 8.0f;  // samples at times exact in binary
  const std::uint32_t count = 50;
  for (std::uint32_t i = 0; i < count; ++i) {
    CAPTURE(i);
    const HistoryTap tap = historyTap(start, rate, count, start + i / 8.0);
    CHECK(tap.i1 == i);
    CHECK(tap.w1 == Approx(1.0f).margin(1e-5));
    CHECK(tap.w0 == Approx(0.0f).margin(1e-5));
    CHECK(tap.w2 == Approx(0.0f).margin(1e-5));
    CHECK(tap.w3 == Approx(0.0f).margin(1e-5));
  }
  for (double t : {-5.0, 0.0, 1.99}) {
    const HistoryTap tap = historyTap(start, rate, count, t);
    CHECK(tap.i1 == 0);
    CHECK(tap.w1 == 1.0f);
  }
  for (double t : {start + 49.0 / 8.0, 100.0, 1.0e9}) {
    const HistoryTap tap = historyTap(start, rate, count, t);
    CHECK(tap.i1 == count - 1);
    CHECK(tap.i2 == count - 1);
    CHECK(tap.i3 == count - 1);
  }
}

TEST_CASE("Between samples a straight-line history stays on its line, in every mode", "[anim]") {
  const RampHistory h(1.0f, 8.0f, 40, 5, -300, 15);
  for (double t = 1.2; t < 5.5; t += 0.037) {
    CAPTURE(t);
    const HistoryTap tap = historyTap(h.startSeconds, h.rateHz, h.samples, t);
    float out[kMaxHistoryModes] = {};
    modalCoordinates(h.coordinates.data(), h.modes, h.scales.data(), tap, out);
    const double position = (t - h.startSeconds) * h.rateHz;
    for (std::size_t k = 0; k < h.modes; ++k) {
      const double expected = (-300.0 + 15.0 * position + static_cast<double>(k)) * h.scales[k];
      CHECK(out[k] == Approx(expected).margin(1e-3));
    }
  }
}

TEST_CASE("A building's sample window gives what the whole history gives, forward, backward and after jumps",
          "[anim]") {
  const RampHistory hx(0.5f, 20.0f, 300, 3, 100, -7);
  RampHistory hy(0.5f, 20.0f, 300, 6, -900, 11);
  for (std::size_t i = 0; i < hy.coordinates.size(); ++i) {
    hy.coordinates[i] = static_cast<std::int16_t>(hy.coordinates[i] * ((i % 3) == 0 ? -1 : 1));  // not a line
  }
  HistoryStream stream;
  stream.x = hx.coordinates.data();
  stream.y = hy.coordinates.data();
  stream.scalesX = hx.scales.data();
  stream.scalesY = hy.scales.data();
  stream.startSeconds = hx.startSeconds;
  stream.sampleRateHz = hx.rateHz;
  stream.sampleCount = hx.samples;
  stream.modesX = static_cast<std::uint8_t>(hx.modes);
  stream.modesY = static_cast<std::uint8_t>(hy.modes);
  SampleWindow window;
  std::vector<double> times;
  for (double t = 0.0; t < 4.0; t += 1.0 / 60.0) times.push_back(t);       // playing at 60 frames a second
  for (double t = 4.0; t > 2.0; t -= 1.0 / 30.0) times.push_back(t);       // scrubbing back
  for (double t : {12.0, 0.7, 15.9, 16.0, 3.3, 3.31}) times.push_back(t);  // jumps and the end
  for (double t : times) {
    CAPTURE(t);
    float windowed[2 * kMaxHistoryModes] = {};
    windowedModalCoordinates(stream, t, window, windowed);
    const HistoryTap tap = historyTap(stream.startSeconds, stream.sampleRateHz, stream.sampleCount, t);
    float x[kMaxHistoryModes] = {}, y[kMaxHistoryModes] = {};
    modalCoordinates(hx.coordinates.data(), hx.modes, hx.scales.data(), tap, x);
    modalCoordinates(hy.coordinates.data(), hy.modes, hy.scales.data(), tap, y);
    for (std::size_t k = 0; k < hx.modes; ++k) CHECK(windowed[k] == x[k]);
    for (std::size_t k = 0; k < hy.modes; ++k) CHECK(windowed[kMaxHistoryModes + k] == y[k]);
  }
}

TEST_CASE("Floor displacements from modal coordinates equal the plain dot products for every mode count", "[anim]") {
  // Shapes and coordinates with distinct values, for 0 … 8 modes in each direction (the unrolled
  // kernels up to 6, the general loop beyond).
  constexpr std::size_t kFloors = 7;
  std::vector<float> shapesX(kFloors * 8), shapesY(kFloors * 8), cx(8), cy(8);
  for (std::size_t i = 0; i < shapesX.size(); ++i) {
    shapesX[i] = 0.01f * static_cast<float>(i % 13) - 0.05f;
    shapesY[i] = 0.02f * static_cast<float>(i % 7) + 0.01f;
  }
  for (std::size_t k = 0; k < 8; ++k) {
    cx[k] = 1.5f - 0.4f * static_cast<float>(k);
    cy[k] = 0.3f * static_cast<float>(k) - 0.7f;
  }
  for (std::size_t mx = 0; mx <= 8; ++mx) {
    for (std::size_t my = 0; my <= 8; ++my) {
      CAPTURE(mx, my);
      std::vector<Row> rows(kFloors + 1);
      rows[kFloors].dxMeters = 42.0f;  // beyond the floors: untouched
      floorDisplacements(shapesX.data(), cx.data(), mx, shapesY.data(), cy.data(), my, kFloors, rows.data());
      for (std::size_t f = 0; f < kFloors; ++f) {
        double x = 0.0, y = 0.0;
        for (std::size_t k = 0; k < mx; ++k) x += static_cast<double>(shapesX[f * mx + k]) * cx[k];
        for (std::size_t k = 0; k < my; ++k) y += static_cast<double>(shapesY[f * my + k]) * cy[k];
        CHECK(rows[f].dxMeters == Approx(x).margin(1e-6));
        CHECK(rows[f].dyMeters == Approx(y).margin(1e-6));
      }
      CHECK(rows[kFloors].dxMeters == 42.0f);
      for (const Row& row : rows) CHECK(row.other == 7.0f);  // only dx and dy are written
    }
  }
}

TEST_CASE("Skinning by height: a vertex follows the floors below and above it by its height", "[anim][skin]") {
  // Levels 2, 5, 8, 11, 14 m (base 2 m, 3 m storeys, 4 storeys); displacements not linear in the
  // level, so a wrong pair of floors or a wrong weight shows.
  const float baseZ = 2.0f, storeyHeight = 3.0f;
  const int storeys = 4;
  const std::array<float, 5> dx = {0.0f, 0.01f, 0.04f, 0.09f, 0.16f};
  struct Row {
    float z;
    int lower, upper;
    float weight;
  };
  const Row rows[] = {{-1.0f, 0, 1, 0.0f}, {2.0f, 0, 1, 0.0f},   {3.5f, 0, 1, 0.5f},
                      {5.0f, 1, 2, 0.0f},  {7.25f, 1, 2, 0.75f}, {8.0f, 2, 3, 0.0f},
                      {13.7f, 3, 4, 0.9f}, {14.0f, 4, 4, 0.0f},  {20.0f, 4, 4, 0.0f}};
  for (const Row& row : rows) {
    INFO("z = " << row.z);
    const FloorBlend b = floorBlendAt(row.z, baseZ, storeyHeight, storeys);
    CHECK(b.lower == row.lower);
    CHECK(b.upper == row.upper);
    CHECK(b.upperWeight == Approx(row.weight).margin(1e-6));
  }

  SECTION("a vertex midway between two floors moves by half of each") {
    const FloorBlend b = floorBlendAt(6.5f, baseZ, storeyHeight, storeys);  // between 5 m and 8 m
    CHECK(blendedDisplacement(b, dx) == Approx(0.5f * dx[1] + 0.5f * dx[2]));
    CHECK(blendedDisplacement(b, dx) != Approx(dx[1]));
    CHECK(blendedDisplacement(b, dx) != Approx(dx[2]));
  }
  SECTION("a vertex on a floor follows that floor alone") {
    for (int k = 0; k <= storeys; ++k) {
      const float z = baseZ + static_cast<float>(k) * storeyHeight;
      CHECK(blendedDisplacement(floorBlendAt(z, baseZ, storeyHeight, storeys), dx) == dx[static_cast<std::size_t>(k)]);
    }
  }
  SECTION("below the ground it follows the ground, above the roof the roof") {
    CHECK(blendedDisplacement(floorBlendAt(0.0f, baseZ, storeyHeight, storeys), dx) == dx[0]);
    CHECK(blendedDisplacement(floorBlendAt(30.0f, baseZ, storeyHeight, storeys), dx) == dx[4]);
  }
  SECTION("the motion is continuous across a floor") {
    const float below = blendedDisplacement(floorBlendAt(8.0f - 1e-3f, baseZ, storeyHeight, storeys), dx);
    const float above = blendedDisplacement(floorBlendAt(8.0f + 1e-3f, baseZ, storeyHeight, storeys), dx);
    CHECK(std::fabs(below - dx[2]) < 1e-4f);
    CHECK(std::fabs(above - dx[2]) < 1e-4f);
  }
}

TEST_CASE("A drift series is read at its windows' centres, linear between, at rest before it starts",
          "[anim][series]") {
  // Codes 0, 255, 51 (drifts 0, full scale, full scale / 25) at 4 windows a second from 2 s.
  const std::vector<std::uint8_t> codes = {9, 0, 255, 51};
  const qv::SeriesRef s{1, 2.0f, 3, 4.0f};
  const float full = 0.05f;
  CHECK(qv::seriesDriftAt(codes, s, full, 1.99) == 0.0f);                                 // before the shaking
  CHECK(qv::seriesDriftAt(codes, s, full, 2.0) == 0.0f);                                  // first window
  CHECK(qv::seriesDriftAt(codes, s, full, 2.375) == Approx(0.05f));                       // window 1's centre
  CHECK(qv::seriesDriftAt(codes, s, full, 2.25) == Approx(0.025f));                       // halfway
  CHECK(qv::seriesDriftAt(codes, s, full, 2.625) == Approx(0.05f * 0.04f).margin(1e-4));  // window 2
  CHECK(qv::seriesDriftAt(codes, s, full, 60.0) == Approx(0.05f * 0.04f).margin(1e-4));   // holds the last
  CHECK(qv::seriesDriftAt(codes, qv::SeriesRef{}, full, 2.0) == -1.0f);                   // no series
  CHECK(qv::seriesDriftAt(codes, qv::SeriesRef{2, 0.0f, 5, 4.0f}, full, 2.0) == -1.0f);   // beyond the codes
}

TEST_CASE("Merged series take the largest member code at each moment, over all members' times", "[anim][series]") {
  // Member a from 0 s: 10, 20, 30, 40; member b from 0.5 s (two windows later): 50, 5, 5.
  const std::vector<std::uint8_t> codes = {10, 20, 30, 40, 50, 5, 5};
  const std::vector<qv::SeriesRef> members = {{0, 0.0f, 4, 4.0f}, {4, 0.5f, 3, 4.0f}, qv::SeriesRef{}};
  std::vector<std::uint8_t> out = {77};
  const qv::SeriesRef merged = qv::mergeSeries(codes, members, 4.0f, out);
  CHECK(merged.base == 1);
  CHECK(merged.startSeconds == 0.0f);
  REQUIRE(merged.count == 5);  // 0 .. 1.25 s
  CHECK(std::vector<std::uint8_t>(out.begin() + 1, out.end()) == std::vector<std::uint8_t>{10, 20, 50, 40, 5});
  CHECK(out[0] == 77);
  // No member with a series: none.
  std::vector<std::uint8_t> none;
  CHECK(qv::mergeSeries(codes, std::vector<qv::SeriesRef>{qv::SeriesRef{}}, 4.0f, none).count == 0);
  CHECK(none.empty());
}

TEST_CASE("A building not moved floor by floor sways from its drift series at its own periods", "[anim][series]") {
  // Gain 40 m per unit drift, drift 0.005 now: the roof moves 0.2 m in all, 0.2/√2 on each axis at
  // their peaks; X at 0.8 s, Y at 1.2 s, from a start at 3 s.
  const float gain = 40.0f, drift = 0.005f, tx = 0.8f, ty = 1.2f, start = 3.0f;
  const double roofAxis = 0.2 / std::sqrt(2.0);
  // At rest before the shaking arrives and at the start itself.
  CHECK(qv::seriesSwayAt(drift, gain, tx, ty, start, 2.9, 1.0f).dxMeters == 0.0f);
  CHECK(std::fabs(qv::seriesSwayAt(drift, gain, tx, ty, start, 3.0, 1.0f).dxMeters) < 1e-6f);
  // A quarter of each period later each axis is at its peak, the roof by the full amount.
  CHECK(qv::seriesSwayAt(drift, gain, tx, ty, start, 3.2, 1.0f).dxMeters == Approx(roofAxis).epsilon(1e-4));
  CHECK(qv::seriesSwayAt(drift, gain, tx, ty, start, 3.3, 1.0f).dyMeters == Approx(roofAxis).epsilon(1e-4));
  // Half a period later the other way: it oscillates, it does not lean.
  CHECK(qv::seriesSwayAt(drift, gain, tx, ty, start, 3.6, 1.0f).dxMeters == Approx(-roofAxis).epsilon(1e-4));
  // Never more than gain × drift, and a point moves its height's share of the roof's (ground: 0).
  for (double t = 3.0; t < 13.0; t += 0.037) {
    const qv::Sway roof = qv::seriesSwayAt(drift, gain, tx, ty, start, t, 1.0f);
    const qv::Sway middle = qv::seriesSwayAt(drift, gain, tx, ty, start, t, 0.5f);
    CHECK(std::hypot(roof.dxMeters, roof.dyMeters) <= 0.2f + 1e-5f);
    CHECK(middle.dxMeters == Approx(roof.dxMeters * 0.5f).margin(1e-6));
    CHECK(qv::seriesSwayAt(drift, gain, tx, ty, start, t, 0.0f).dxMeters == 0.0f);
    CHECK(qv::seriesSwayAt(drift, gain, tx, ty, start, t, 2.0f).dxMeters == roof.dxMeters);  // clamped to the roof
  }
  // No series (drift -1), no gain (a block, no result) or no period: still.
  CHECK(qv::seriesSwayAt(-1.0f, gain, tx, ty, start, 3.2, 1.0f).dxMeters == 0.0f);
  CHECK(qv::seriesSwayAt(drift, 0.0f, tx, ty, start, 3.2, 1.0f).dxMeters == 0.0f);
  CHECK(qv::seriesSwayAt(drift, gain, 0.0f, ty, start, 3.2, 1.0f).dxMeters == 0.0f);
}

TEST_CASE("Sway gains and estimated periods follow the building's peaks and storeys", "[anim][series]") {
  // 0.12 m of roof at 0.4 % drift: 30 m of roof per unit drift; capped at 1.5 × the height.
  CHECK(qv::swayGainMeters(0.12f, 0.004f, 30.0f) == Approx(30.0f));
  CHECK(qv::swayGainMeters(1.0f, 0.001f, 30.0f) == Approx(45.0f));
  CHECK(qv::swayGainMeters(0.12f, 0.0f, 30.0f) == 0.0f);
  CHECK(qv::swayGainMeters(0.0f, 0.004f, 30.0f) == 0.0f);
  CHECK(qv::estimatedPeriodS(10.0f) == Approx(1.0f));
  CHECK(qv::estimatedPeriodS(0.0f) == Approx(0.1f));
}
