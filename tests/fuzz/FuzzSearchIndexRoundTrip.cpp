// fuzz_search_index_roundtrip: search entries made from the fuzzer's bytes, encoded and decoded
// again; the decoder must accept them and give back the same entries. Lengths stay within the
// decoder's documented limits (id 256, name and address 1024 bytes).
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
  }
  const auto decoded = decodeSearchIndex(encodeSearchIndex(entries), "roundtrip.qvi");
  if (!decoded.ok()) fuzz::contractBroken("the decoder rejects what the encoder wrote:", decoded.error());
  fuzz::check(decoded->size() == entries.size(), "round trip changed the entry count");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const SearchEntry& a = entries[i];
    const SearchEntry& b = (*decoded)[i];
    fuzz::check(a.id == b.id && a.name == b.name && a.address == b.address, "round trip changed an entry");
  }
  return 0;
}
