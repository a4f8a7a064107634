// fuzz_response_import: external analysis results (JSON through simdjson, or CSV: chosen by the
// content) through our reader: buildings or an error naming the file, never a crash; what is read
// is consistent (histories as long as frames × floors, finite, a positive time step).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "IngestFuzzSupport.h"
#include "qv/prep/ResponseImport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path =
      qv::fuzz::writeInput(std::string_view(reinterpret_cast<const char*>(data), size), "results.input");
  qv::prep::ImportedResults results;
  const qv::Status read = qv::prep::readImportedResponse(path, std::nullopt, results);
  if (!read.ok()) {
    qv::fuzz::check(read.error().find("results.input") != std::string::npos,
                    "import error does not name the file:", read.error());
    return 0;
  }
  if (!results.buildings.empty()) {
    qv::fuzz::check(std::isfinite(results.timeStepS) && results.timeStepS > 0.0, "time step not positive");
  }
  for (const auto& b : results.buildings) {
    qv::fuzz::check(!b.id.empty(), "a building without an id", b.place);
    qv::fuzz::check(b.x.size() == b.frames * b.floors, "x history size is not frames × floors", b.place);
    qv::fuzz::check(b.y.empty() || b.y.size() == b.x.size(), "y history size differs from x", b.place);
    for (const float v : b.x) qv::fuzz::check(std::isfinite(v), "non-finite displacement", b.place);
    for (const float v : b.y) qv::fuzz::check(std::isfinite(v), "non-finite displacement", b.place);
    qv::fuzz::check(std::isfinite(b.startSeconds) && b.startSeconds >= 0.0, "start time", b.place);
  }
  return 0;
}
