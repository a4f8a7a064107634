// fuzz_search_index_roundtrip: search entries made from the fuzzer's bytes, encoded and decoded
// again; the decoder must accept them and give back the same entries. Lengths and values stay
// within the decoder's documented limits (id 256, name and address 1024, use 64 bytes; positions
// within 1e7 m, heights in [0, 1e4] m).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "FuzzSupport.h"
#include "qv/format/SearchIndex.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  FuzzedDataProvider in(data, size);
  std::vector<SearchEntry> entries(in.ConsumeIntegralInRange<std::size_t>(0, 64));
  for (SearchEntry& e : entries) {
    e.id = in.ConsumeRandomLengthString(256);
    e.name = in.ConsumeRandomLengthString(1024);
    e.address = in.ConsumeRandomLengthString(1024);
    e.use = in.ConsumeRandomLengthString(64);
    e.x = in.ConsumeFloatingPointInRange(-1e7f, 1e7f);
    e.y = in.ConsumeFloatingPointInRange(-1e7f, 1e7f);
    e.heightM = in.ConsumeFloatingPointInRange(0.0f, 1e4f);
    e.storeys = in.ConsumeIntegral<std::uint16_t>();
    e.importance = in.ConsumeBool() ? Importance::Critical : Importance::General;
    e.lod = in.ConsumeBool() ? 2 : 1;
    e.leaf = in.ConsumeIntegral<std::uint32_t>();
    e.facility = static_cast<FacilityCategory>(
        in.ConsumeIntegralInRange<unsigned>(0, static_cast<unsigned>(FacilityCategory::Count) - 1));
  }
  const auto decoded = decodeSearchIndex(encodeSearchIndex(entries), "roundtrip.qvi");
  if (!decoded.ok()) fuzz::contractBroken("the decoder rejects what the encoder wrote:", decoded.error());
  fuzz::check(decoded->size() == entries.size(), "round trip changed the entry count");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const SearchEntry& a = entries[i];
    const SearchEntry& b = (*decoded)[i];
    fuzz::check(a == b, "round trip changed an entry");
  }
  return 0;
}
