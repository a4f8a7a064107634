// fuzz_city_tile: arbitrary bytes into decodeCityTile, as fetched (the integrity checks) and with
// the size and checksum fields made right (everything behind them). A tile that decodes must be
// internally consistent and survive encode -> decode unchanged.
#include <cstddef>
#include <cstdint>
#include <span>

#include "CityTileChecks.h"
#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv;
  constexpr std::string_view kName = "fuzz/1-2-3.qvt";
  const std::span<const std::uint8_t> raw(data, size);
  fuzz::checkErrorNamesInput(decodeCityTile(raw, kName), kName);

  const std::vector<std::uint8_t> fixed = fuzz::withValidSizeAndCrc(raw);
  const Result<CityTile> tile = decodeCityTile(fixed, kName);
  fuzz::checkErrorNamesInput(tile, kName);
  if (!tile.ok()) return 0;
  fuzz::checkTileConsistent(*tile);
  const Result<CityTile> again = decodeCityTile(encodeCityTile(*tile), kName);
  if (!again.ok()) fuzz::contractBroken("a decoded tile does not decode after encoding:", again.error());
  fuzz::checkSameTile(*tile, *again, 0.0f);
  return 0;
}
