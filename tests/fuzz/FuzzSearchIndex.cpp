// fuzz_search_index: arbitrary bytes into decodeSearchIndex, as fetched and with the size and
// checksum fields made right. An index that decodes must encode back to the same bytes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "FuzzSupport.h"
#include "qv/format/SearchIndex.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "fuzz/search.qvi";
  const std::span<const std::uint8_t> raw(data, size);
  fuzz::checkErrorNamesInput(decodeSearchIndex(raw, kName), kName);

  const std::vector<std::uint8_t> fixed = fuzz::withValidSizeAndCrc(raw);
  const auto entries = decodeSearchIndex(fixed, kName);
  fuzz::checkErrorNamesInput(entries, kName);
  if (!entries.ok()) return 0;
  for (const SearchEntry& e : *entries) {
    (void)matchesQuery(e.name, e.address);
    (void)matchesQuery(e.address, e.id);
    fuzz::check(std::isfinite(e.x) && std::isfinite(e.y) && e.heightM >= 0.0f && (e.lod == 1 || e.lod == 2),
                "a decoded entry has a value outside the documented ranges");
  }
  // LEB128 lengths have more than one spelling, so only the re-encoded bytes are canonical.
  const std::vector<std::uint8_t> encoded = encodeSearchIndex(*entries);
  const auto again = decodeSearchIndex(encoded, kName);
  if (!again.ok()) fuzz::contractBroken("a decoded index does not decode after encoding:", again.error());
  fuzz::check(encodeSearchIndex(*again) == encoded, "re-encoding changed the index");
  return 0;
}
