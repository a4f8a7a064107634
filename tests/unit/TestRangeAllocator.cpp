#include <catch2/catch.hpp>

#include "qv/core/RangeAllocator.h"

TEST_CASE("RangeAllocator reuses freed ranges and merges neighbours", "[core][allocator]") {
  qv::RangeAllocator a(100);
  CHECK(a.allocate(40) == 0u);
  CHECK(a.allocate(40) == 40u);
  CHECK_FALSE(a.allocate(30).has_value());
  CHECK(a.allocate(20) == 80u);
  CHECK(a.used() == 100u);
  a.release(0, 40);
  a.release(40, 40);  // merges with [0, 40) into [0, 80)
  CHECK(a.allocate(70) == 0u);
  a.release(0, 70);
  a.release(80, 20);
  CHECK(a.used() == 0u);
  CHECK(a.allocate(100) == 0u);  // everything merged back
  CHECK_FALSE(a.allocate(0).has_value());
}

TEST_CASE("RangeAllocator's end is one past the highest index in use now, not ever", "[core][allocator]") {
  qv::RangeAllocator a(100);
  CHECK(a.end() == 0u);
  CHECK(a.allocate(30) == 0u);
  CHECK(a.allocate(30) == 30u);
  CHECK(a.end() == 60u);
  a.release(30, 30);  // the top range: the end falls back
  CHECK(a.end() == 30u);
  CHECK(a.allocate(70) == 30u);  // up to the capacity: no free range at the top
  CHECK(a.end() == 100u);
  a.release(0, 30);  // a hole below does not lower it
  CHECK(a.end() == 100u);
  a.release(30, 70);
  CHECK(a.end() == 0u);
}
