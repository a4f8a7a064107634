// Runs the built quakeview-prep mdof and checks its output (native only).
#include <simdjson.h>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "ToolRun.h"

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;
const std::string kRecords = std::string(QUAKEVIEW_SHARED_DATA_DIR) + "/ground-motions/";
const std::string kFixtures = std::string(QUAKEVIEW_SEISMIC_TEST_DATA) + "/";

using Run = qv::test::ToolRun;

// Runs the tool with `arguments`; stdout only, or stdout and stderr together.
Run run(const std::string& arguments, bool withStderr = false) {
  return qv::test::runTool(kTool, "mdof " + arguments, withStderr);
}

double number(simdjson::dom::element doc, const char* key) {
  double v = 0.0;
  const auto error = doc[key].get(v);
  INFO(key);
  REQUIRE(error == simdjson::SUCCESS);
  return v;
}

const std::string kChopra = "--storeys 5 --mass 45000 --stiffness 5.482e6 --height 4 --modal-damping --damping 0.05 ";

}  // namespace

TEST_CASE("mdof --json reproduces Chopra Example 13.2.6", "[seismic][cli]") {
  const Run r = run(kChopra + "--linear --motion '" + kRecords + "elCentro.AT2' --json");
  REQUIRE(r.exitCode == 0);
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
  REQUIRE(parser.parse(r.output).get(doc) == simdjson::SUCCESS);
  CHECK(number(doc, "peak_roof_displacement_m") == Approx(0.173303).epsilon(1e-4));
  CHECK(number(doc, "peak_base_shear_n") == Approx(323561.2).epsilon(1e-4));
  CHECK(number(doc, "peak_base_moment_nm") == Approx(3800187.4).epsilon(1e-4));
  simdjson::dom::array periods;
  REQUIRE(doc["periods_s"].get(periods) == simdjson::SUCCESS);
  const double published[] = {2.000, 0.6852, 0.4346, 0.3383, 0.2967};
  std::size_t j = 0;
  for (const auto p : periods) {
    double v = 0.0;
    REQUIRE(p.get(v) == simdjson::SUCCESS);
    REQUIRE(j < 5);
    CHECK(v == Approx(published[j++]).epsilon(2e-4));
  }
  CHECK(j == 5);
  simdjson::dom::array drift;
  REQUIRE(doc["peak_drift_ratio"].get(drift) == simdjson::SUCCESS);
  CHECK(drift.size() == 5);
  double first = 0.0;
  REQUIRE(drift.at(0).get(first) == simdjson::SUCCESS);
  simdjson::dom::array shear;
  REQUIRE(doc["peak_storey_shear_n"].get(shear) == simdjson::SUCCESS);
  double topShear = 0.0;
  REQUIRE(shear.at(4).get(topShear) == simdjson::SUCCESS);
  CHECK(topShear == Approx(153613.9).epsilon(1e-4));
  CHECK(first == Approx(323561.2 / 5.482e6 / 4.0).epsilon(1e-4));  // linear: drift = shear / k
  int64_t substeps = 0;
  REQUIRE(doc["solver"]["substeps"].get(substeps) == simdjson::SUCCESS);
  CHECK(substeps == 1);
  std::string_view units;
  REQUIRE(doc["motion"]["units"].get(units) == simdjson::SUCCESS);
  CHECK(units == "g");
  (void)number(doc, "residual_roof_displacement_m");
}

TEST_CASE("mdof prints a table, runs Bouc-Wen with free vibration and reads value files", "[seismic][cli]") {
  const Run table = run(kChopra + "--motion '" + kRecords + "elCentro.AT2'");
  REQUIRE(table.exitCode == 0);
  CHECK(table.output.find("peak roof displacement      0.173303 m") != std::string::npos);
  CHECK(table.output.find("   1      2.0000") != std::string::npos);

  const Run bw =
      run("--storeys 3 --mass 45000 --stiffness 5.482e6 --height 4 --bouc-wen 0.1,1,50,50 "
          "--free-vibration 10 --motion '" +
          kRecords + "tabasFN.txt' --dt 0.02 --units g --scale 0.5 --json");
  REQUIRE(bw.exitCode == 0);
  simdjson::dom::parser parser;
  simdjson::dom::element doc;
  REQUIRE(parser.parse(bw.output).get(doc) == simdjson::SUCCESS);
  // Yield displacement (gamma + beta)^(-1/n) = 0.01 m: the base storey shear stays near
  // alpha k δ + (1 - alpha) k dy, far below the linear k δ.
  simdjson::dom::array drift;
  REQUIRE(doc["peak_drift_m"].get(drift) == simdjson::SUCCESS);
  double baseDrift = 0.0;
  REQUIRE(drift.at(0).get(baseDrift) == simdjson::SUCCESS);
  CHECK(baseDrift > 0.02);
  CHECK(number(doc, "peak_base_shear_n") <= 0.1 * 5.482e6 * baseDrift + 0.9 * 5.482e6 * 0.01 + 1.0);
  CHECK(std::fabs(number(doc, "residual_roof_displacement_m")) > 0.0);
  std::string_view law;
  REQUIRE(doc["model"]["storey_law"].get(law) == simdjson::SUCCESS);
  CHECK(law == "bouc-wen");
}

TEST_CASE("mdof usage errors exit 2, bad files exit 1 naming the file and line", "[seismic][cli]") {
  struct Case {
    std::string arguments;
    int exitCode;
    std::string message;
  };
  const std::string motion = "--motion '" + kRecords + "elCentro.AT2' ";
  const Case cases[] = {
      {kChopra + "--linear --bouc-wen 0.1,1,50,50 " + motion, 2, "--linear and --bouc-wen exclude each other"},
      {kChopra, 2, "--motion is required"},
      {"--storeys 5 --mass 1,2,3 --stiffness 1e6 " + motion, 2, "--mass takes 1 or 5 values, not 3"},
      {"--storeys 0 --mass 1 --stiffness 1e6 " + motion, 2, "--storeys must be a whole number from 1 to 1000"},
      {kChopra + "--rayleigh 0.1,0.01 " + motion, 2, "--modal-damping and --rayleigh exclude each other"},
      {kChopra + "--units furlongs " + motion, 2, "--units must be g, m/s2 or cm/s2, not 'furlongs'"},
      {kChopra + "--bouc-wen 0.1,1,50 " + motion, 2, "--bouc-wen takes ALPHA,N,GAMMA,BETA"},
      {kChopra + "--frobnicate " + motion, 2, "unknown option --frobnicate"},
      {kChopra + "--motion '" + kFixtures + "nan.AT2'", 1, "nan.AT2:6: value 'NaN' is not a finite number"},
      {kChopra + "--motion '" + kFixtures + "wrong-npts.AT2'", 1, "wrong-npts.AT2:4: NPTS = 10 in the header"},
      {kChopra + "--motion '" + kRecords + "tabasFN.txt' --units g", 1,
       "tabasFN.txt: the file gives no time step: pass one (--dt)"},
      {kChopra + "--motion '" + kFixtures + "missing.AT2'", 1, "missing.AT2: cannot open the file"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.arguments);
    const Run r = run(c.arguments, true);
    CHECK(r.exitCode == c.exitCode);
    CHECK(r.output.find(c.message) != std::string::npos);
  }
  const Run help = run("--help");
  CHECK(help.exitCode == 0);
  CHECK(help.output.find("--bouc-wen A,N,G,B") != std::string::npos);
}
