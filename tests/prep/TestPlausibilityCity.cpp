// What a user of quakeview-prep sees of underground buildings and of the plausibility rules
// (docs/attributes.md): the `city` summary, the manifest, `info --json` and `info --building`, on
// the hand-written tests/ingest/data/plausibility.osm and on the Midtown fixture (Pennsylvania
// Station). Runs the built tool (native only).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "ToolRun.h"

namespace fs = std::filesystem;

namespace {

const std::string kTool = QUAKEVIEW_PREP_EXE;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string tempCity(const std::string& name) {
  const std::string dir = (fs::temp_directory_path() / ("qv-" + name + "-" + std::to_string(getpid()))).string();
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST_CASE("Underground buildings are counted by city and the manifest and info, which shows the notes",
          "[prep][plausibility]") {
  const std::string dir = tempCity("plausibility");
  const auto made = qv::test::runTool(
      kTool,
      "city --input '" + std::string(QUAKEVIEW_SOURCE_DIR) + "/tests/ingest/data/plausibility.osm' --out '" + dir + "'",
      true);
  INFO(made.output);
  REQUIRE(made.exitCode == 0);
  CHECK(contains(made.output, "excluded    underground 2; (neither drawn nor analysed)"));
  CHECK(contains(made.output, "warning: w812714851: location=underground: underground, neither drawn nor analysed"));

  const auto json = qv::test::runTool(kTool, "info '" + dir + "' --json");
  REQUIRE(json.exitCode == 0);
  CHECK(contains(json.output, "\"buildings\":11,"));
  CHECK(contains(json.output, "\"excluded\":{\"underground\":2}"));
  const auto text = qv::test::runTool(kTool, "info '" + dir + "'");
  CHECK(contains(text.output, "excluded    underground 2; (neither drawn nor analysed)"));

  const auto penn = qv::test::runTool(kTool, "info '" + dir + "' --building w812714851", true);
  CHECK(penn.exitCode != 0);
  CHECK(contains(penn.output, "no building with id 'w812714851'"));

  const auto cathedral = qv::test::runTool(kTool, "info '" + dir + "' --building w266010379 --json");
  REQUIRE(cathedral.exitCode == 0);
  CHECK(contains(cathedral.output, "\"storeys\":7,\"storeys_source\":\"inferred\""));
  CHECK(contains(cathedral.output, "\"structural_type\":\"URMM\""));
  CHECK(contains(cathedral.output, "\"attribute_notes\":[\"storeys-from-nave\",\"pre-frame-masonry\"]"));
  const auto zero = qv::test::runTool(kTool, "info '" + dir + "' --building w4");
  CHECK(contains(zero.output, "height 7.0 m (inferred)"));
  CHECK(contains(zero.output, "note: height=0 is tagged but the building stands above ground: height inferred"));
  const auto conflict = qv::test::runTool(kTool, "info '" + dir + "' --building w8");
  CHECK(contains(conflict.output, "5 storeys (inferred)"));
  CHECK(contains(conflict.output,
                 "note: the tagged height and levels give storeys under 2.2 m or over 7 m: storeys inferred from the "
                 "height"));
  fs::remove_all(dir);
}

TEST_CASE("Pennsylvania Station is not drawn across the Midtown rail yard", "[prep][plausibility][data]") {
  const std::string dir = tempCity("midtown-penn");
  const auto made = qv::test::runTool(kTool,
                                      "city --input '" + std::string(QUAKEVIEW_SHARED_DATA_DIR) +
                                          "/osm/fixture-midtown-empire-state.osm' --out '" + dir + "'",
                                      true);
  INFO(made.output);
  REQUIRE(made.exitCode == 0);
  const auto json = qv::test::runTool(kTool, "info '" + dir + "' --json");
  CHECK(contains(json.output, "\"buildings\":393,"));
  CHECK(contains(json.output, "\"excluded\":{\"underground\":2}"));
  const auto penn = qv::test::runTool(kTool, "info '" + dir + "' --building w812714851", true);
  CHECK(contains(penn.output, "no building with id 'w812714851'"));
  fs::remove_all(dir);
}
