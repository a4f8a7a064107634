#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "qv/seismic/GroundMotionReader.h"

using namespace qv::seismic;

namespace {

const std::string kRecords = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/ground-motions/";
const std::string kFixtures = std::string(QUAKEVIEW_SEISMIC_TEST_DATA) + "/";

GroundMotionReadOptions withUnitsAndStep(AccelerationUnit units, double dt) {
  GroundMotionReadOptions o;
  o.units = units;
  o.timeStepS = dt;
  return o;
}

}  // namespace

TEST_CASE("Every shared record gives its documented count, step and peak", "[seismic][reader]") {
  struct Case {
    const char* file;
    bool needsUnitsAndStep;
    std::size_t points;
    double dt;
    double peakG;            // signed
    std::size_t peakSample;  // 1-based: the sample at t = k·dt
    GroundMotionFormat format;
  };
  const Case cases[] = {
      {"elCentro.AT2", false, 1559, 0.02, -0.31882, 102, GroundMotionFormat::PeerAt2},
      {"TAK000.AT2", false, 4096, 0.01, 0.6177107, 583, GroundMotionFormat::PeerAt2},
      {"tabasFN.txt", true, 2500, 0.02, 0.899949, 526, GroundMotionFormat::ValuesOnly},
      {"tabasFP.txt", true, 2500, 0.02, 0.977238, 552, GroundMotionFormat::ValuesOnly},
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    GroundMotionSource source;
    const auto options = c.needsUnitsAndStep ? withUnitsAndStep(AccelerationUnit::G, 0.02) : GroundMotionReadOptions{};
    const auto motion = readGroundMotionFile(kRecords + c.file, options, &source);
    REQUIRE(motion.ok());
    CHECK(motion->name == c.file);
    CHECK(motion->size() == c.points);
    CHECK(motion->timeStepS == Approx(c.dt).epsilon(1e-12));
    CHECK(source.format == c.format);
    CHECK(source.unitsFromFile == !c.needsUnitsAndStep);
    CHECK(source.timeStepFromFile == !c.needsUnitsAndStep);
    CHECK(motion->peakIndex() + 1 == c.peakSample);
    CHECK(motion->accelerationMps2[motion->peakIndex()] / kGravityMps2 == Approx(c.peakG).epsilon(1e-9));
    // The time convention: sample k at t = k·dt, a(0) = 0, linear between samples.
    const double tPeak = static_cast<double>(c.peakSample) * c.dt;
    CHECK(motion->accelerationAt(tPeak) / kGravityMps2 == Approx(c.peakG).epsilon(1e-9));
    CHECK(motion->accelerationAt(0.0) == 0.0);
    CHECK(motion->accelerationAt(0.5 * c.dt) == Approx(0.5 * motion->accelerationMps2[0]));
    CHECK(motion->accelerationAt(motion->durationS() + 2.0 * c.dt) == 0.0);
  }
  // tabas peaks at 10.52 s and 11.04 s with the first sample at t = dt.
  const auto fn = readGroundMotionFile(kRecords + "tabasFN.txt", withUnitsAndStep(AccelerationUnit::G, 0.02));
  REQUIRE(fn.ok());
  CHECK(static_cast<double>(fn->peakIndex() + 1) * fn->timeStepS == Approx(10.52));
}

TEST_CASE("The elCentro header's units and step are read from the file", "[seismic][reader]") {
  // Units stated in the file and given again: accepted when they agree, an error when they do not.
  GroundMotionReadOptions agree;
  agree.units = AccelerationUnit::G;
  agree.timeStepS = 0.02;
  CHECK(readGroundMotionFile(kRecords + "elCentro.AT2", agree).ok());
  GroundMotionReadOptions disagree;
  disagree.units = AccelerationUnit::CentimetresPerSecond2;
  const auto units = readGroundMotionFile(kRecords + "elCentro.AT2", disagree);
  REQUIRE_FALSE(units.ok());
  CHECK(units.error() == "elCentro.AT2:3: the header gives units g but cm/s2 was given");
  GroundMotionReadOptions wrongStep;
  wrongStep.timeStepS = 0.01;
  const auto step = readGroundMotionFile(kRecords + "elCentro.AT2", wrongStep);
  REQUIRE_FALSE(step.ok());
  CHECK(step.error() == "elCentro.AT2:4: the header gives DT = 0.02 s but the step given is 0.01 s");
}

TEST_CASE("Malformed records give errors naming the file and line", "[seismic][reader]") {
  struct Case {
    const char* file;
    GroundMotionReadOptions options;
    const char* message;
  };
  const Case cases[] = {
      {"nan.AT2", {}, "nan.AT2:6: value 'NaN' is not a finite number"},
      {"garbage.txt", withUnitsAndStep(AccelerationUnit::G, 0.01), "garbage.txt:4: not a number: 'abc'"},
      {"empty.txt", withUnitsAndStep(AccelerationUnit::G, 0.01), "empty.txt: the file is empty"},
      {"wrong-npts.AT2", {}, "wrong-npts.AT2:4: NPTS = 10 in the header but 8 values follow (the last on line 6)"},
      {"nonuniform.txt", withUnitsAndStep(AccelerationUnit::G, 0.01),
       "nonuniform.txt:5: non-uniform time step: 0.02 s after t = 0.03 s, the record started with 0.01 s"},
      {"values.txt", {}, "values.txt: the file gives no time step: pass one (--dt)"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    const auto motion = readGroundMotionFile(kFixtures + c.file, c.options);
    REQUIRE_FALSE(motion.ok());
    CHECK(motion.error() == c.message);
  }
  GroundMotionReadOptions noUnits;
  noUnits.timeStepS = 0.01;
  const auto missingUnits = readGroundMotionFile(kFixtures + "values.txt", noUnits);
  REQUIRE_FALSE(missingUnits.ok());
  CHECK(missingUnits.error() == "values.txt: the file does not state its units: pass them (--units g|m/s2|cm/s2)");
  const auto missingFile = readGroundMotionFile(kFixtures + "no-such-file.AT2");
  REQUIRE_FALSE(missingFile.ok());
  CHECK(missingFile.error().find("no-such-file.AT2: cannot open the file") != std::string::npos);
}

TEST_CASE("Header variants: pre-NGA PEER, one-line header, Fortran fields, two columns", "[seismic][reader]") {
  SECTION("pre-NGA PEER line 'NPTS, DT' after the numbers") {
    const auto m = readGroundMotionFile(kFixtures + "old-peer.AT2");
    REQUIRE(m.ok());
    CHECK(m->size() == 8);
    CHECK(m->timeStepS == 0.02);
    CHECK(m->accelerationMps2[7] == Approx(-0.08 * 9.81));
  }
  SECTION("one-line numeric header 'NPTS DT'") {
    GroundMotionReadOptions o;
    o.units = AccelerationUnit::MetresPerSecond2;
    const auto m = readGroundMotionFile(kFixtures + "one-line-header.txt", o);
    REQUIRE(m.ok());
    CHECK(m->size() == 5);
    CHECK(m->timeStepS == 0.01);
    CHECK(m->accelerationMps2[4] == Approx(0.5));
  }
  SECTION("fields that run together, D exponents, cm/s/s from the header") {
    const auto m = readGroundMotionFile(kFixtures + "fortran.AT2");
    REQUIRE(m.ok());
    REQUIRE(m->size() == 6);
    CHECK(m->timeStepS == 0.005);
    CHECK(m->accelerationMps2[0] == Approx(0.125));
    CHECK(m->accelerationMps2[1] == Approx(-0.2325));
    CHECK(m->accelerationMps2[2] == Approx(0.1));
    CHECK(m->accelerationMps2[5] == Approx(-0.06));
  }
  SECTION("two columns: the step from the times, a leading zero row dropped") {
    GroundMotionReadOptions o;
    o.units = AccelerationUnit::G;
    GroundMotionSource source;
    const auto m = readGroundMotionFile(kFixtures + "two-column.txt", o, &source);
    REQUIRE(m.ok());
    CHECK(source.format == GroundMotionFormat::TimeAcceleration);
    CHECK(source.timeStepFromFile);
    CHECK(m->size() == 4);
    CHECK(m->timeStepS == Approx(0.01));
    CHECK(m->accelerationMps2[0] == Approx(0.1 * 9.81));
    CHECK(m->accelerationAt(0.04) == Approx(-0.4 * 9.81));
  }
  SECTION("two columns starting later keep each value at its time") {
    GroundMotionReadOptions o;
    o.units = AccelerationUnit::MetresPerSecond2;
    const auto m = parseGroundMotion("0.03 1.0\n0.04 2.0\n0.05 3.0\n", "late.txt", o);
    REQUIRE(m.ok());
    CHECK(m->size() == 5);
    CHECK(m->accelerationAt(0.03) == Approx(1.0));
    CHECK(m->accelerationAt(0.05) == Approx(3.0));
    CHECK(m->accelerationAt(0.02) == 0.0);
  }
}

TEST_CASE("An older PEER record whose units are followed by punctuation reads as g", "[seismic][reader]") {
  // Line 3: "ACCELERATION TIME HISTORY IN UNITS OF G. FILTER POINTS: HP=0.1 Hz LP=40.0 Hz", values
  // in E notation, 5 a line (issue 21: refused with "the file does not state its units").
  GroundMotionSource source;
  const auto m = readGroundMotionFile(kFixtures + "peer-filter-points.AT2", {}, &source);
  REQUIRE(m.ok());
  CHECK(source.unitsFromFile);
  CHECK(source.units == AccelerationUnit::G);
  CHECK(m->size() == 10);
  CHECK(m->timeStepS == 0.005);
  CHECK(m->accelerationMps2[0] == Approx(0.1234e-2 * 9.81));
  CHECK(m->accelerationMps2[9] == Approx(0.1023e-1 * 9.81));
}

TEST_CASE("Header units are recognised whatever the punctuation and spacing", "[seismic][reader]") {
  struct Case {
    const char* header;
    AccelerationUnit units;
  };
  const Case cases[] = {
      {"ACCELERATION TIME HISTORY IN UNITS OF G.", AccelerationUnit::G},
      {"ACCELERATION TIME HISTORY IN UNITS OF G, FILTERED", AccelerationUnit::G},
      {"Units of g; corrected", AccelerationUnit::G},
      {"Station 090 (g)", AccelerationUnit::G},
      {"Station 090 [ g ]", AccelerationUnit::G},
      {"horizontal component, values in g", AccelerationUnit::G},
      {"Acceleration in g.", AccelerationUnit::G},
      {"Acceleration, cm/s/s", AccelerationUnit::CentimetresPerSecond2},
      {"Acceleration (CM/SEC**2)", AccelerationUnit::CentimetresPerSecond2},
      {"ACCELERATION IN CM/SEC**2.", AccelerationUnit::CentimetresPerSecond2},
      {"UNITS: gal", AccelerationUnit::CentimetresPerSecond2},
      {"acceleration in gal, 200 Hz", AccelerationUnit::CentimetresPerSecond2},
      {"Acceleration (m/s**2)", AccelerationUnit::MetresPerSecond2},
      {"ACCEL M/S^2.", AccelerationUnit::MetresPerSecond2},
  };
  for (const Case& c : cases) {
    CAPTURE(c.header);
    GroundMotionReadOptions o;
    o.timeStepS = 0.01;
    GroundMotionSource source;
    const auto m = parseGroundMotion(std::string(c.header) + "\n0.5\n-0.25\n", "variant.txt", o, &source);
    REQUIRE(m.ok());
    CHECK(source.unitsFromFile);
    CHECK(source.units == c.units);
    CHECK(m->accelerationMps2[0] == Approx(0.5 * metresPerSecond2Per(c.units)));
  }
  // A lone letter g elsewhere in prose does not state units.
  GroundMotionReadOptions o;
  o.timeStepS = 0.01;
  const auto prose = parseGroundMotion("Station G, recorded 1979\n0.5\n", "prose.txt", o);
  REQUIRE_FALSE(prose.ok());
  CHECK(prose.error() == "prose.txt: the file does not state its units: pass them (--units g|m/s2|cm/s2)");
}

TEST_CASE("Unit conversions use g = 9.81 m/s2", "[seismic][reader]") {
  CHECK(metresPerSecond2Per(AccelerationUnit::G) == 9.81);
  CHECK(metresPerSecond2Per(AccelerationUnit::CentimetresPerSecond2) == 0.01);
  CHECK(parseAccelerationUnit("m/s2") == AccelerationUnit::MetresPerSecond2);
  CHECK(parseAccelerationUnit("gal") == AccelerationUnit::CentimetresPerSecond2);
  CHECK_FALSE(parseAccelerationUnit("furlongs").has_value());
  GroundMotionReadOptions o;
  o.units = AccelerationUnit::CentimetresPerSecond2;
  o.timeStepS = 0.01;
  const auto m = parseGroundMotion("981\n-981\n", "cm.txt", o);
  REQUIRE(m.ok());
  CHECK(m->accelerationMps2[0] == Approx(9.81));
  CHECK(m->peakAbsMps2() == Approx(9.81));
}
