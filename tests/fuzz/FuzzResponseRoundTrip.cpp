// fuzz_response_roundtrip: a response summary and a history tile made from the fuzzer's bytes
// (within the format's documented ranges), encoded and decoded again: the decoder must accept
// them and give back the same values.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>

#include "FuzzSupport.h"
#include "ResponseChecks.h"

namespace {

using namespace qv;

ResponseSummaryTile makeSummary(FuzzedDataProvider& in) {
  ResponseSummaryTile t;
  t.buildings.resize(in.ConsumeIntegralInRange<std::size_t>(0, 16));
  for (BuildingResponse& b : t.buildings) {
    b.source = static_cast<ResponseSource>(in.ConsumeIntegralInRange(0, 2));
    b.damage = in.ConsumeBool() ? DamageState::NoResult : static_cast<DamageState>(in.ConsumeIntegralInRange(0, 4));
    b.storeys = b.source == ResponseSource::None ? 0 : in.ConsumeIntegralInRange<std::uint16_t>(0, 60);
    b.peakDriftRatio = in.ConsumeFloatingPointInRange(0.0f, 1.0f);
    b.peakRoofDisplacementM = in.ConsumeFloatingPointInRange(0.0f, 10.0f);
    b.pgaG = in.ConsumeFloatingPointInRange(0.0f, 5.0f);
    b.peakFloorAccelerationMs2 = in.ConsumeFloatingPointInRange(0.0f, 100.0f);
    b.residualDriftRatio = in.ConsumeFloatingPointInRange(0.0f, 1.0f);
    b.firstStorey = static_cast<std::uint32_t>(t.storeyPeakDrift.size());
    for (std::uint16_t s = 0; s < b.storeys; ++s)
      t.storeyPeakDrift.push_back(in.ConsumeFloatingPointInRange(0.0f, 1.0f));
  }
  return t;
}

ResponseHistoryTile makeHistory(FuzzedDataProvider& in) {
  ResponseHistoryTile t;
  t.durationSeconds = in.ConsumeFloatingPointInRange(0.0f, 1000.0f);
  t.buildings.resize(in.ConsumeIntegralInRange<std::size_t>(0, 6));
  for (BuildingHistory& b : t.buildings) {
    b.floors = in.ConsumeIntegralInRange<std::uint16_t>(0, 30);
    if (b.floors == 0) continue;
    b.sampleRateHz = in.ConsumeFloatingPointInRange(0.01f, 1000.0f);
    b.startSeconds = in.ConsumeFloatingPointInRange(0.0f, 100.0f);
    b.sampleCount = in.ConsumeIntegralInRange<std::uint32_t>(1, 200);
    b.bits = in.ConsumeBool() ? 8 : 16;
    for (HistoryDirection* d : {&b.x, &b.y}) {
      d->modes = in.ConsumeIntegralInRange<std::uint8_t>(0, 4);
      d->shapes.resize(std::size_t{b.floors} * d->modes);
      for (float& v : d->shapes) v = in.ConsumeFloatingPointInRange(-10.0f, 10.0f);
      d->scales.resize(d->modes);
      for (float& v : d->scales) v = in.ConsumeFloatingPointInRange(-1.0f, 1.0f);
      d->coordinates.resize(std::size_t{d->modes} * b.sampleCount);
      for (std::int16_t& v : d->coordinates) {
        v = b.bits == 8 ? in.ConsumeIntegralInRange<std::int16_t>(-127, 127) : in.ConsumeIntegral<std::int16_t>();
      }
    }
  }
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const ResponseSummaryTile summary = makeSummary(in);
  const auto decodedSummary = decodeResponseSummary(encodeResponseSummary(summary), "roundtrip.qvs");
  if (!decodedSummary.ok()) fuzz::contractBroken("the decoder rejects the encoder's summary:", decodedSummary.error());
  fuzz::checkSummaryConsistent(*decodedSummary);
  fuzz::checkSameSummary(summary, *decodedSummary);

  const ResponseHistoryTile history = makeHistory(in);
  const auto decodedHistory = decodeResponseHistory(encodeResponseHistory(history), "roundtrip.qvh");
  if (!decodedHistory.ok()) fuzz::contractBroken("the decoder rejects the encoder's history:", decodedHistory.error());
  fuzz::checkHistoryUsable(*decodedHistory);
  fuzz::checkSameHistory(history, *decodedHistory);
  return 0;
}
