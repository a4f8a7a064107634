// Fixture for tests/CMakeLists.txt: a test case that runs but checks nothing. Run with the
// project's Catch2 arguments it must fail (the ctest entry is WILL_FAIL); it is not a test of the
// product and is never registered with quakeview_add_test.
#include <catch2/catch.hpp>

TEST_CASE("A test case that computes but asserts nothing", "[fixture]") {
  volatile int sum = 0;
  for (int i = 0; i < 3; ++i) sum = sum + i;
}
