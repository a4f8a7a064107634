// Records the ground-motion fuzzer found (tests/fuzz/regressions/ground_motion/; the first byte
// chooses the caller's options, as in fuzz_ground_motion) and hostile records written by hand:
// either a clean error naming the file and line, or a record the solvers can use.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <string_view>

#include "../fuzz/GroundMotionInputs.h"
#include "../fuzz/RegressionInputs.h"
#include "qv/seismic/GroundMotionReader.h"

using namespace qv;
using namespace qv::seismic;

TEST_CASE("Fuzzer-found ground-motion records are read or rejected cleanly", "[seismic][reader][fuzz]") {
  std::string missing;
  const auto inputs = fuzz::requiredInputs(QUAKEVIEW_SOURCE_DIR, "ground_motion", missing);
  INFO(missing);
  REQUIRE(missing.empty());
  for (const fuzz::SavedInput& input : inputs) {
    if (input.bytes.empty()) continue;
    SECTION(input.path) {
      const std::string_view text(reinterpret_cast<const char*>(input.bytes.data()) + 1, input.bytes.size() - 1);
      const auto motion = parseGroundMotion(text, input.path, fuzz::groundMotionOptions(input.bytes[0]));
      if (!motion.ok()) {
        INFO(motion.error());
        CHECK(motion.error().rfind(input.path + ":", 0) == 0);
      } else {
        CHECK((motion->timeStepS > 0.0 && motion->timeStepS <= 10.0));
        for (double a : motion->accelerationMps2) CHECK(std::isfinite(a));
      }
    }
  }
}

TEST_CASE("Records whose values overflow when converted are refused", "[seismic][reader][fuzz]") {
  GroundMotionReadOptions options;
  options.units = AccelerationUnit::G;
  options.timeStepS = 0.01;
  const auto motion = parseGroundMotion("0.1\n1.7e308\n", "huge.txt", options);
  REQUIRE_FALSE(motion.ok());
  CHECK(motion.error() == "huge.txt: sample 2 (1.7e+308 g) is too large to be an acceleration");
}

TEST_CASE("Two-column records with a step beyond 10 s are refused like a header's DT", "[seismic][reader][fuzz]") {
  GroundMotionReadOptions options;
  options.units = AccelerationUnit::G;
  const auto motion = parseGroundMotion("0 0.1\n100 0.2\n200 0.1\n", "times.txt", options);
  REQUIRE_FALSE(motion.ok());
  CHECK(motion.error() == "times.txt:2: the times give a step of 100 s (at most 10 s)");
}

TEST_CASE("Files with more lines or values than a record can hold are refused before reading them whole",
          "[seismic][reader][fuzz]") {
  GroundMotionReadOptions options;
  options.units = AccelerationUnit::G;
  options.timeStepS = 0.01;
  // About 100 bytes of bookkeeping a line: 2.2 million blank lines must not be split and classified.
  const auto blank = parseGroundMotion(std::string(2200000, '\n'), "blank.txt", options);
  REQUIRE_FALSE(blank.ok());
  CHECK(blank.error() == "blank.txt: too many lines (more than 2162688; a record holds at most 2097152 values)");

  std::string oneLine;
  for (int i = 0; i < 2100000; ++i) oneLine += "0 ";
  const auto wide = parseGroundMotion(oneLine, "wide.txt", options);
  REQUIRE_FALSE(wide.ok());
  CHECK(wide.error() == "wide.txt:1: too many values (the limit is 2097152)");

  std::string line;
  for (int k = 0; k < 1000; ++k) line += "1 ";
  std::string manyLines;
  for (int i = 0; i < 2200; ++i) manyLines += line + "\n";
  const auto many = parseGroundMotion(manyLines, "many.txt", options);
  REQUIRE_FALSE(many.ok());
  CHECK(many.error() == "many.txt:2098: too many values (the limit is 2097152)");
}
