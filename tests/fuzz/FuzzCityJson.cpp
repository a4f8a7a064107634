// fuzz_cityjson: CityJSON documents through our reader (simdjson): a model per Building or an error
// naming the input, never a crash; what is read is consistent.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "FuzzSupport.h"
#include "qv/prep/Lod2CityJson.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string name = "input.city.json";
  const auto file = qv::prep::parseCityJson(text, name);
  qv::fuzz::checkErrorNamesInput(file, name);
  if (!file.ok()) return 0;
  for (const auto& b : file->buildings) {
    qv::fuzz::check(b.triangles.size() % 3 == 0, "triangle indices not a multiple of 3", b.objectId);
    qv::fuzz::check(b.kinds.size() == b.triangles.size() / 3, "one kind per triangle", b.objectId);
    for (const std::uint32_t i : b.triangles) qv::fuzz::check(i < b.positions.size(), "index out of range", b.objectId);
    for (const auto& p : b.positions) {
      qv::fuzz::check(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "non-finite vertex");
    }
  }
  return 0;
}
