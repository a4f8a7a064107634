// fuzz_geojson: GeoJSON FeatureCollections through our reader and the rest of the ingest.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "IngestFuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  qv::fuzz::ingestOne(qv::fuzz::writeInput(bytes, "input.geojson"));
  return 0;
}
