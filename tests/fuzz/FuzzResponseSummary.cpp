// fuzz_response_summary: arbitrary bytes into decodeResponseSummary (as fetched, and with size and
// checksum made right); what decodes must be consistent and survive encode -> decode.
#include <cstddef>
#include <cstdint>
#include <span>

#include "FuzzSupport.h"
#include "ResponseChecks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "fuzz/response-1/1-0-1.qvs";
  const std::span<const std::uint8_t> raw(data, size);
  fuzz::checkErrorNamesInput(decodeResponseSummary(raw, kName), kName);

  const std::vector<std::uint8_t> fixed = fuzz::withValidSizeAndCrc(raw);
  const Result<ResponseSummaryTile> tile = decodeResponseSummary(fixed, kName);
  fuzz::checkErrorNamesInput(tile, kName);
  if (!tile.ok()) return 0;
  fuzz::checkSummaryConsistent(*tile);
  const Result<ResponseSummaryTile> again = decodeResponseSummary(encodeResponseSummary(*tile), kName);
  if (!again.ok()) fuzz::contractBroken("a decoded summary does not decode after encoding:", again.error());
  fuzz::checkSameSummary(*tile, *again);
  return 0;
}
