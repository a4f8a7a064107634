// fuzz_ground_tile: arbitrary bytes into decodeGroundTile, as fetched (the integrity checks) and
// with the size and checksum fields made right (everything behind them). A ground tile is
// canonical: one that decodes must keep the contract of GroundTile and encode back to exactly the
// bytes it came from (its stored form expanded).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "FuzzSupport.h"
#include "GroundTileChecks.h"
#include "qv/format/GroundTile.h"
#include "qv/format/StoredFile.h"

namespace {

using namespace qv;

constexpr std::string_view kName = "fuzz/ground/4-3-2.qvg";

/// A decoded tile encodes back to the bytes it came from (the file itself behind its stored form).
void checkCanonical(const GroundTile& tile, std::span<const std::uint8_t> input) {
  const Result<std::vector<std::uint8_t>> file = unpackStoredFile(input, kName);
  if (!file.ok()) fuzz::contractBroken("a tile decoded from a stored form that does not unpack:", file.error());
  if (encodeGroundTile(tile) != *file) fuzz::contractBroken("a decoded tile does not encode to the same bytes");
}

void decodeAndCheck(std::span<const std::uint8_t> bytes) {
  const Result<GroundTile> tile = decodeGroundTile(bytes, kName);
  fuzz::checkErrorNamesInput(tile, kName);
  if (!tile.ok()) return;
  fuzz::checkGroundTileConsistent(*tile);
  checkCanonical(*tile, bytes);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> raw(data, size);
  decodeAndCheck(raw);
  decodeAndCheck(qv::fuzz::withValidSizeAndCrc(raw));
  return 0;
}
