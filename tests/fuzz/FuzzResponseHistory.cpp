// fuzz_response_history: arbitrary bytes into decodeResponseHistory (as fetched, and with size and
// checksum made right); what decodes must be sampleable and survive encode -> decode.
#include <cstddef>
#include <cstdint>
#include <span>

#include "FuzzSupport.h"
#include "ResponseChecks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "fuzz/response-1/2-1-1.qvh";
  const std::span<const std::uint8_t> raw(data, size);
  fuzz::checkErrorNamesInput(decodeResponseHistory(raw, kName), kName);

  const std::vector<std::uint8_t> fixed = fuzz::withValidSizeAndCrc(raw);
  const Result<ResponseHistoryTile> tile = decodeResponseHistory(fixed, kName);
  fuzz::checkErrorNamesInput(tile, kName);
  if (!tile.ok()) return 0;
  fuzz::checkHistoryUsable(*tile);
  const Result<ResponseHistoryTile> again = decodeResponseHistory(encodeResponseHistory(*tile), kName);
  if (!again.ok()) fuzz::contractBroken("a decoded history does not decode after encoding:", again.error());
  fuzz::checkSameHistory(*tile, *again);
  return 0;
}
