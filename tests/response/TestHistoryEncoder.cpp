// The history encoder: what the viewer reconstructs stays within the stated fraction of the peak
// roof displacement, at every floor and frame, through the tile codec too.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "qv/prep/HistoryEncoder.h"
#include "qv/prep/ResponseImport.h"

using namespace qv;
using namespace qv::prep;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A shear-building-like history: two modes (first and second shape of a uniform building) with a
// decaying beat, starting at `arrivalS`; frame-major [frame * storeys + i].
std::vector<float> history(std::size_t storeys, std::size_t frames, double dt, double periodS, double amplitudeM,
                           double arrivalS, double phase) {
  std::vector<float> out(storeys * frames, 0.0f);
  for (std::size_t f = 0; f < frames; ++f) {
    const double t = static_cast<double>(f) * dt - arrivalS;
    if (t <= 0.0) continue;
    const double envelope = std::min(1.0, t / 2.0) * std::exp(-0.05 * t);
    const double q1 = amplitudeM * envelope * std::sin(2.0 * kPi * t / periodS + phase);
    const double q2 = 0.15 * amplitudeM * envelope * std::sin(2.0 * kPi * t / (periodS / 3.0) + 2.0 * phase);
    for (std::size_t i = 0; i < storeys; ++i) {
      const double z = static_cast<double>(i + 1) / static_cast<double>(storeys);
      out[f * storeys + i] = static_cast<float>(q1 * std::sin(0.5 * kPi * z) + q2 * std::sin(1.5 * kPi * z));
    }
  }
  return out;
}

}  // namespace

TEST_CASE("encoded histories stay within the tolerance of the peak roof displacement", "[response][encoder]") {
  const auto storeys = static_cast<std::size_t>(GENERATE(1, 3, 6, 20));
  const double period = GENERATE(0.3, 1.5);
  const double dt = 0.01;
  const std::size_t frames = 3000;
  const auto x = history(storeys, frames, dt, period, 0.08, 1.0, 0.0);
  const auto y = history(storeys, frames, dt, period * 1.1, 0.05, 1.0, 0.7);
  CAPTURE(storeys, period);
  const EncodedHistory e = encodeHistory(x, y, storeys, frames, dt);
  REQUIRE(e.history.floors == storeys);
  REQUIRE(e.peakRoofM > 0.05);
  CHECK(e.relativeError() <= 0.019);
  // The encoder's own measure matches what sampleHistory (the viewer) reconstructs.
  const double measured = historyMaxError(e.history, x, y, storeys, frames, dt);
  CHECK(measured <= 0.0191 * e.peakRoofM);
  // Far fewer samples than the input when the building is flexible: the rate follows its period.
  if (period > 1.0) CHECK(e.history.sampleCount < frames / 2);
  CHECK(e.history.startSeconds > 0.9f);  // nothing stored before the shaking arrives
  CHECK(e.history.startSeconds <= 1.0f);

  // Through the tile codec: the same reconstruction.
  ResponseHistoryTile tile;
  tile.durationSeconds = 30.0f;
  tile.buildings.push_back(e.history);
  const auto bytes = encodeResponseHistory(tile);
  auto decoded = decodeResponseHistory(bytes, "history");
  REQUIRE(decoded.ok());
  CHECK(historyMaxError(decoded->buildings[0], x, y, storeys, frames, dt) == Approx(measured).margin(1e-7));
}

TEST_CASE("a building at rest gets an empty-motion history", "[response][encoder]") {
  const std::vector<float> x(5 * 100, 0.0f);
  const EncodedHistory e = encodeHistory(x, {}, 5, 100, 0.02);
  CHECK(e.history.floors == 5);
  CHECK(e.peakRoofM == 0.0);
  CHECK(e.maxErrorM == 0.0);
  CHECK(e.history.x.modes == 0);
}

TEST_CASE("imported displacements give drifts, peaks and a Hazus damage state", "[response][import]") {
  BuildingAttributes a;
  a.id = "w1";
  a.storeys = 4;
  a.heightM = 12.0f;
  a.footprintAreaM2 = 300.0f;
  a.structuralType = StructuralType::C1L;
  a.codeEra = CodeEra::ModerateCode;
  const std::size_t frames = 2000;
  // Linear profile: every storey drifts by roof / 4 over a 3 m storey.
  for (double roof : {0.003, 0.5}) {
    std::vector<float> x(4 * frames);
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t i = 0; i < 4; ++i) {
        x[f * 4 + i] = static_cast<float>(roof * static_cast<double>(i + 1) / 4.0 *
                                          std::sin(2.0 * kPi * static_cast<double>(f) * 0.01 / 0.4));
      }
    }
    const DisplacementSummary s = summarizeDisplacements(a, x, {}, 4, frames, 0.01, 2.0, 0.019);
    CAPTURE(roof);
    REQUIRE(s.result.storeyPeakDrift.size() == 4);
    for (float d : s.result.storeyPeakDrift) CHECK(d == Approx(roof / 4.0 / 3.0).epsilon(0.01));
    CHECK(s.result.summary.peakRoofDisplacementM == Approx(roof).epsilon(0.01));
    CHECK(s.result.summary.source == ResponseSource::Imported);
    CHECK(s.result.history.startSeconds >= 2.0f);
    CHECK(s.relativeError <= 0.019);
    // 0.025 % drift is below C1L moderate-code slight (0.5 %); 4.2 % is past extensive (2.3 %).
    if (roof < 0.01) CHECK(s.result.summary.damage == DamageState::None);
    if (roof > 0.1) CHECK(static_cast<int>(s.result.summary.damage) >= static_cast<int>(DamageState::Extensive));
  }
}

TEST_CASE("length units", "[response][import]") {
  CHECK(parseDisplacementUnit("cm") == DisplacementUnit::Centimetre);
  CHECK(parseDisplacementUnit("ft") == DisplacementUnit::Foot);
  CHECK(metresPerDisplacementUnit(DisplacementUnit::Inch) == Approx(0.0254));
  CHECK(!parseDisplacementUnit("furlong"));
}
