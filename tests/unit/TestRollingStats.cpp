#include <catch2/catch.hpp>

#include "qv/core/RollingStats.h"

TEST_CASE("RollingStats reports the median of the most recent samples", "[core][stats]") {
  qv::RollingStats stats(5);
  CHECK(stats.median() == 0.0);
  for (double v : {10.0, 1.0, 3.0, 2.0, 100.0}) stats.add(v);
  CHECK(stats.median() == 3.0);
  CHECK(stats.count() == 5);
  // Two more samples push out 10 and 1.
  stats.add(4.0);
  stats.add(5.0);
  CHECK(stats.count() == 5);
  CHECK(stats.median() == 4.0);  // {3, 2, 100, 4, 5}
  CHECK(stats.last() == 5.0);
  CHECK(stats.percentile(1.0) == 100.0);
  CHECK(stats.percentile(0.0) == 2.0);
}

TEST_CASE("RollingStats median is robust to one slow frame", "[core][stats]") {
  qv::RollingStats stats(120);
  for (int i = 0; i < 119; ++i) stats.add(16.0);
  stats.add(500.0);
  CHECK(stats.median() == 16.0);
  CHECK(stats.percentile(0.95) == 16.0);
  stats.clear();
  CHECK(stats.count() == 0);
}
