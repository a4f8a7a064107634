// formatDouble: the one number formatting of messages and text files.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "qv/core/NumberFormat.h"

using qv::formatDouble;

TEST_CASE("formatDouble gives six significant digits by default, rounded to nearest", "[core][format]") {
  CHECK(formatDouble(0.1) == "0.1");
  CHECK(formatDouble(2.0) == "2");
  CHECK(formatDouble(1.0 / 3.0) == "0.333333");
  CHECK(formatDouble(2.0 / 3.0) == "0.666667");
  CHECK(formatDouble(1234567.0) == "1.23457e+06");
  CHECK(formatDouble(123456.0) == "123456");
  CHECK(formatDouble(0.00012345) == "0.00012345");
  CHECK(formatDouble(0.000012345) == "1.2345e-05");
  CHECK(formatDouble(-9.81) == "-9.81");
  // 0.125 and 0.375 are exact in binary: ties round to even, as printf does.
  CHECK(formatDouble(0.125, 2) == "0.12");
  CHECK(formatDouble(0.375, 2) == "0.38");
}

TEST_CASE("formatDouble takes the digits asked for, within 1 to 17", "[core][format]") {
  CHECK(formatDouble(0.02, 10) == "0.02");
  CHECK(formatDouble(1.0 / 3.0, 10) == "0.3333333333");
  CHECK(formatDouble(123.456, 1) == "1e+02");
  CHECK(formatDouble(123.456, 0) == "1e+02");  // clamped to 1
  // 17 digits round-trip any double; more are clamped to 17.
  const double awkward = 0.1 + 0.2;
  CHECK(formatDouble(awkward, 17) == "0.30000000000000004");
  CHECK(formatDouble(awkward, 40) == "0.30000000000000004");
  CHECK(std::stod(formatDouble(awkward, 17)) == awkward);
  CHECK(formatDouble(-std::numeric_limits<double>::max(), 17) == "-1.7976931348623157e+308");
  CHECK(formatDouble(std::numeric_limits<double>::denorm_min(), 17) == "4.9406564584124654e-324");
}

TEST_CASE("formatDouble keeps negative zero and names non-finite values", "[core][format]") {
  CHECK(formatDouble(0.0) == "0");
  CHECK(formatDouble(-0.0) == "-0");
  CHECK(formatDouble(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(formatDouble(-std::numeric_limits<double>::infinity()) == "-inf");
  CHECK(formatDouble(std::numeric_limits<double>::quiet_NaN()) == "nan");
  CHECK(formatDouble(-std::numeric_limits<double>::quiet_NaN()) == "-nan");
}

TEST_CASE("formatDouble agrees with printf's %g in the C locale over many magnitudes", "[core][format]") {
  // Values spread over 600 decades, both signs, at several precisions.
  for (int e = -300; e <= 300; e += 7) {
    for (const double mantissa : {1.0, -2.5, 9.999995, 3.14159265358979}) {
      const double v = mantissa * std::pow(10.0, e);
      for (const int digits : {1, 6, 10, 17}) {
        char expected[64];
        std::snprintf(expected, sizeof expected, "%.*g", digits, v);
        INFO(expected);
        CHECK(formatDouble(v, digits) == expected);
      }
    }
  }
}
