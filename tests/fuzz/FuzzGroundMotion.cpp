// fuzz_ground_motion: acceleration records (PEER AT2, values, two columns) into parseGroundMotion.
// The first byte picks the caller's options (format, units, time step); the rest is the file. A
// record that parses must be usable by the solvers: a finite step in (0, 10] s and finite samples.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "FuzzSupport.h"
#include "GroundMotionInputs.h"
#include "qv/seismic/GroundMotionReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qv::seismic;
  if (size == 0) return 0;
  const GroundMotionReadOptions options = qv::fuzz::groundMotionOptions(data[0]);
  constexpr std::string_view kName = "records/fuzz.AT2";
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  GroundMotionSource source;
  const qv::Result<GroundMotion> motion = parseGroundMotion(text, kName, options, &source);
  qv::fuzz::checkErrorNamesInput(motion, kName);
  if (!motion.ok()) return 0;
  qv::fuzz::check(std::isfinite(motion->timeStepS) && motion->timeStepS > 0.0 && motion->timeStepS <= 10.0,
                  "a parsed record has an invalid time step");
  qv::fuzz::check(motion->size() > 0, "a parsed record without samples");
  for (double a : motion->accelerationMps2)
    qv::fuzz::check(std::isfinite(a), "a parsed record has a non-finite sample");
  (void)motion->peakAbsMps2();
  (void)motion->accelerationAt(0.5 * motion->durationS());
  return 0;
}
