#include "CityFiles.h"

#include <cstdio>

#include "qv/core/Crc32.h"
#include "qv/prep/Files.h"

namespace qv::prep {

Result<Tileset> loadTileset(const std::string& dir) {
  const std::string path = dir + "/tileset.json";
  auto text = readTextFile(path, 256ull << 20);
  if (!text.ok()) return Error{text.error() + " (is " + dir + " a QuakeView city directory?)"};
  return parseTileset(*text, path);
}

namespace {

Result<std::vector<std::uint8_t>> loadChecked(const std::string& path, std::uint64_t expectedBytes,
                                              std::uint32_t expectedCrc) {
  auto bytes = readFile(path, 1ull << 31);
  if (!bytes.ok()) return Error{bytes.error()};
  if (bytes->size() != expectedBytes) {
    return Error{path + ": " + std::to_string(bytes->size()) + " bytes, the manifest says " +
                 std::to_string(expectedBytes)};
  }
  if (const std::uint32_t crc = crc32(*bytes); crc != expectedCrc) {
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, ": CRC-32 %08x, the manifest says %08x", crc, expectedCrc);
    return Error{path + buffer};
  }
  return bytes;
}

}  // namespace

Result<std::vector<std::uint8_t>> loadCityFile(const std::string& dir, const CityFile& file) {
  return loadChecked(dir + "/" + file.file, file.bytes, file.crc32);
}

Result<CityTile> loadCityTile(const std::string& dir, const TileNode& node) {
  const std::string path = dir + "/" + node.file;
  auto bytes = loadChecked(path, node.bytes, node.crc32);
  if (!bytes.ok()) return Error{bytes.error()};
  return decodeCityTile(*bytes, path);
}

}  // namespace qv::prep
