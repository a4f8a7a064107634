// fuzz_osm: OpenStreetMap input through our libosmium handler and the rest of the ingest. Inputs
// that start with '<' are read as OSM XML (.osm), anything else as PBF (.osm.pbf).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "IngestFuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool xml = first != std::string_view::npos && bytes[first] == '<';
  qv::fuzz::ingestOne(qv::fuzz::writeInput(bytes, xml ? "input.osm" : "input.osm.pbf"));
  return 0;
}
