// The viewer's scenario catalogue (qv/scene/CityScenarios.h) and switching between a city's
// scenarios (Viewer::selectScenario), on a MiniCity served by a fake fetcher.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "MiniCity.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/scene/Viewer.h"

using namespace qv;
using namespace qv::test;

namespace {

constexpr const char* kCatalogue = R"({"format":"quakeview-scenarios","version":1,"scenarios":[)"
                                   R"({"index":1,"name":"M6.6 test scenario","manifest":"scenario-1.json"},)"
                                   R"({"index":2,"name":"Recorded M5.0","manifest":"scenario-2.json"},)"
                                   R"({"index":3,"name":"Not written yet","manifest":"scenario-3.json"}]})";

std::vector<std::uint8_t> bytesOf(const std::string& text) {
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

// A MiniCity whose folder holds two scenarios: scenario-1.json, a copy of tileset.json, and
// scenario-2.json, an ACTUAL event with a shorter record (over the same files: what differs is the
// manifest's response). Scenario 3 is listed but not written.
struct ScenarioRig {
  MiniCity city;
  FakeFetcher fetcher;
  NullRenderDevice device;
  Viewer viewer{device};

  explicit ScenarioRig(const std::string& catalogue = kCatalogue, bool tilesetOutOfDate = false) {
    city.serve(fetcher);
    if (tilesetOutOfDate) {
      Tileset stale = city.tileset;
      stale.buildingsRevision = 2;  // the response was computed for revision 1
      fetcher.files["city/tileset.json"] = bytesOf(tilesetToJson(stale));
    }
    fetcher.files["city/scenario-1.json"] = fetcher.files["city/tileset.json"];
    fetcher.files["city/scenario-2.json"] = bytesOf(tilesetToJson(second()));
    if (!catalogue.empty()) fetcher.files["city/scenarios.json"] = bytesOf(catalogue);
  }
  [[nodiscard]] Tileset second() const {
    Tileset t = city.tileset;
    t.response->eventType = "ACTUAL";
    t.response->scenario = "M5.0 recorded";
    t.response->durationSeconds = 6.0;
    return t;
  }
  void open(const std::string& manifest = "city/tileset.json") {
    viewer.openCity(manifest, fetcher);
    viewer.setViewport(1280, 720, 1280.0, 720.0);
  }
  template <typename Done>
  bool runUntil(Done done, int maxFrames = 400) {
    for (int i = 0; i < maxFrames && !done(); ++i) viewer.frame(1.0 / 60.0);
    return done();
  }
  /// Until the view has loaded and every listed scenario has been checked (or the catalogue is
  /// known absent or refused).
  bool settle() {
    return runUntil([this] {
      const CityScenarios* s = viewer.scenarios();
      if (!viewer.settled() || s == nullptr || s->state() == CityScenarios::CatalogueState::Loading) return false;
      return std::none_of(s->scenarios().begin(), s->scenarios().end(), [](const ScenarioStatus& e) {
        return e.state == ScenarioState::Unchecked || e.state == ScenarioState::Checking;
      });
    });
  }
  bool switched() {
    return runUntil([this] {
      const ScenarioSwitch::State s = viewer.scenarioSwitch().state;
      return s == ScenarioSwitch::State::Loaded || s == ScenarioSwitch::State::Failed;
    });
  }
  [[nodiscard]] bool hasError(const std::string& part) const {
    return std::any_of(viewer.errors().begin(), viewer.errors().end(),
                       [&](const std::string& e) { return e.find(part) != std::string::npos; });
  }
};

}  // namespace

TEST_CASE("A city without scenarios.json has no catalogue, and says nothing about it", "[scene][scenarios]") {
  ScenarioRig rig("");
  rig.open();
  REQUIRE(rig.settle());
  REQUIRE(rig.viewer.scenarios() != nullptr);
  CHECK(rig.viewer.scenarios()->state() == CityScenarios::CatalogueState::Absent);
  CHECK_FALSE(rig.viewer.scenarios()->available());
  CHECK(rig.viewer.scenarios()->catalogueUrl() == "city/scenarios.json");
  CHECK(rig.viewer.errors().empty());
  CHECK(rig.fetcher.count("city/scenarios.json") == 1);
  std::string problem;
  CHECK(rig.viewer.selectScenario(1, &problem) == 0);
  CHECK(problem == "this city has no scenario list (scenarios.json beside its manifest)");
  CHECK(rig.viewer.scenarioSwitch().state == ScenarioSwitch::State::None);
}

TEST_CASE("The catalogue lists the scenarios, reads their event types and marks the one shown", "[scene][scenarios]") {
  SECTION("opened as tileset.json, which the catalogue does not list") {
    ScenarioRig rig;
    rig.open();
    // The catalogue is asked for once the manifest has loaded, not before.
    CHECK(rig.fetcher.count("city/scenarios.json") == 0);
    REQUIRE(rig.settle());
    const CityScenarios& s = *rig.viewer.scenarios();
    REQUIRE(s.available());
    REQUIRE(s.scenarios().size() == 3);
    CHECK(s.current() == nullptr);
    CHECK(s.openFileName() == "tileset.json");
    const ScenarioStatus& first = *s.find(1);
    CHECK(first.state == ScenarioState::Ready);
    CHECK(first.sameResultsAsOpen);  // a copy of tileset.json
    CHECK(first.hasResponse);
    const ScenarioStatus& second = *s.find(2);
    CHECK(second.state == ScenarioState::Ready);
    CHECK(second.eventType == "ACTUAL");
    CHECK(second.earthquake == "M5.0 recorded");
    CHECK_FALSE(second.sameResultsAsOpen);
    const ScenarioStatus& third = *s.find(3);
    CHECK(third.state == ScenarioState::NotReady);
    CHECK(third.problem == "scenario-3.json is not there yet (HTTP 404)");
    CHECK(s.find(4) == nullptr);
    CHECK(s.manifestUrl(third.entry) == "city/scenario-3.json");
    CHECK(rig.viewer.errors().empty());
    CHECK(rig.fetcher.count("city/scenarios.json") == 1);
  }
  SECTION("opened as one of them: marked by its file name, read without fetching it again") {
    ScenarioRig rig;
    rig.open("city/scenario-2.json");
    REQUIRE(rig.settle());
    const CityScenarios& s = *rig.viewer.scenarios();
    REQUIRE(s.current() != nullptr);
    CHECK(s.current()->entry.index == 2);
    CHECK(s.current()->eventType == "ACTUAL");
    CHECK_FALSE(s.current()->sameResultsAsOpen);
    CHECK(rig.fetcher.count("city/scenario-2.json") == 1);  // the viewer's own open
    CHECK_FALSE(s.find(1)->sameResultsAsOpen);
  }
}

TEST_CASE("Switching scenarios keeps the camera, the time, the filters, the levels shown and the selection",
          "[scene][scenarios]") {
  ScenarioRig rig;
  rig.open();
  REQUIRE(rig.settle());
  Viewer& viewer = rig.viewer;
  const CameraState camera{40.0, -20.0, 300.0, 30.0, 50.0, 45.0};
  viewer.setCamera(camera);
  viewer.pause();
  viewer.setTime(4.0);
  BuildingFilters filters;
  filters.minDamage = 2;
  viewer.city()->setFilters(filters);
  viewer.city()->setLodVisibility(true, false);
  REQUIRE(viewer.select("s10"));
  viewer.frame(1.0 / 60.0);

  const std::uint64_t serial = viewer.selectScenario(2);
  CHECK(serial > 0);
  CHECK(viewer.scenarioSwitch().serial == serial);
  CHECK(viewer.scenarioSwitch().index == 2);
  // Never in the middle of a frame: the city shown stays until the next one.
  CHECK(viewer.manifestUrl() == "city/tileset.json");
  REQUIRE(rig.switched());
  CHECK(viewer.scenarioSwitch().state == ScenarioSwitch::State::Loaded);
  CHECK(viewer.manifestUrl() == "city/scenario-2.json");
  REQUIRE(viewer.city()->tileset() != nullptr);
  CHECK(viewer.city()->tileset()->response->eventType == "ACTUAL");
  CHECK(viewer.camera().x == camera.x);
  CHECK(viewer.camera().y == camera.y);
  CHECK(viewer.camera().distance == camera.distance);
  CHECK(viewer.camera().headingDeg == camera.headingDeg);
  CHECK(viewer.time() == 4.0);
  CHECK_FALSE(viewer.playing());
  CHECK(viewer.duration() == 6.0);
  CHECK(viewer.city()->filters() == filters);
  CHECK_FALSE(viewer.city()->showLod2());
  CHECK(rig.runUntil([&] { return viewer.selection() == "s10"; }));
  // The catalogue is the folder's: kept, not fetched again; the new scenario is marked.
  CHECK(rig.fetcher.count("city/scenarios.json") == 1);
  REQUIRE(viewer.scenarios()->current() != nullptr);
  CHECK(viewer.scenarios()->current()->entry.index == 2);
  CHECK(viewer.errors().empty());

  // Back to the first: a new switch; selecting the one shown only waits for it.
  const std::uint64_t back = viewer.selectScenario(1);
  CHECK(back == serial + 1);
  REQUIRE(rig.switched());
  CHECK(viewer.manifestUrl() == "city/scenario-1.json");
  CHECK(viewer.duration() == 10.0);
  CHECK(viewer.time() == 4.0);
  const std::uint64_t same = viewer.selectScenario(1);
  CHECK(viewer.scenarioSwitch().state == ScenarioSwitch::State::Loading);
  REQUIRE(rig.switched());
  CHECK(viewer.scenarioSwitch().serial == same);
  CHECK(viewer.scenarioSwitch().state == ScenarioSwitch::State::Loaded);
  CHECK(viewer.manifestUrl() == "city/scenario-1.json");
}

TEST_CASE("A switch at the end of the record shows the new record's end, and a later time is clamped",
          "[scene][scenarios]") {
  for (const double t : {10.0, 8.0}) {
    INFO("time " << t);
    ScenarioRig rig;
    rig.open("city/scenario-1.json");
    REQUIRE(rig.settle());
    rig.viewer.pause();
    rig.viewer.setTime(t);
    CHECK(rig.viewer.ended() == (t == 10.0));
    REQUIRE(rig.viewer.selectScenario(2) > 0);
    REQUIRE(rig.switched());
    CHECK(rig.viewer.duration() == 6.0);
    CHECK(rig.viewer.time() == 6.0);
    CHECK(rig.viewer.ended());
  }
}

TEST_CASE("A scenario not written yet is refused with its reason and the city shown stays, and once written it opens",
          "[scene][scenarios]") {
  ScenarioRig rig;
  rig.open();
  REQUIRE(rig.settle());
  REQUIRE(rig.viewer.selectScenario(3) > 0);
  REQUIRE(rig.switched());
  const ScenarioSwitch& change = rig.viewer.scenarioSwitch();
  CHECK(change.state == ScenarioSwitch::State::Failed);
  CHECK(change.problem ==
        "Scenario 3 \"Not written yet\" cannot be shown yet: scenario-3.json is not there yet (HTTP 404).");
  CHECK(rig.hasError("cannot be shown yet: scenario-3.json is not there yet (HTTP 404)"));
  CHECK(rig.viewer.manifestUrl() == "city/tileset.json");
  CHECK(rig.viewer.city()->manifestLoaded());
  // Asked again, it is looked at again: written meanwhile, it opens and the message goes.
  rig.fetcher.files["city/scenario-3.json"] = bytesOf(tilesetToJson(rig.second()));
  REQUIRE(rig.viewer.selectScenario(3) > 0);
  REQUIRE(rig.switched());
  CHECK(rig.viewer.scenarioSwitch().state == ScenarioSwitch::State::Loaded);
  CHECK(rig.viewer.manifestUrl() == "city/scenario-3.json");
  CHECK_FALSE(rig.hasError("scenario-3.json"));

  // Not in the list: refused at once.
  std::string problem;
  CHECK(rig.viewer.selectScenario(9, &problem) == 0);
  CHECK(problem == "the city's scenario list has no scenario 9");
}

TEST_CASE("A scenario whose manifest is gone by the time it is opened is said so, and the city shown comes back",
          "[scene][scenarios]") {
  ScenarioRig rig;
  rig.open();
  REQUIRE(rig.settle());
  REQUIRE(rig.viewer.scenarios()->find(2)->state == ScenarioState::Ready);
  rig.viewer.pause();
  rig.viewer.setTime(3.0);
  rig.fetcher.files.erase("city/scenario-2.json");
  REQUIRE(rig.viewer.selectScenario(2) > 0);
  REQUIRE(rig.switched());
  const ScenarioSwitch& change = rig.viewer.scenarioSwitch();
  CHECK(change.state == ScenarioSwitch::State::Failed);
  CHECK(change.problem ==
        "Scenario 2 \"Recorded M5.0\" could not be opened: The city could not be loaded from city/scenario-2.json: "
        "HTTP 404");
  CHECK(rig.hasError("could not be opened"));
  CHECK(rig.viewer.manifestUrl() == "city/tileset.json");
  CHECK(rig.runUntil([&] { return rig.viewer.settled() && rig.viewer.city()->manifestLoaded(); }));
  CHECK(rig.viewer.time() == 3.0);
  CHECK(rig.viewer.stats().latest.buildingsLoaded > 0);
}

TEST_CASE("A manifest that is not a manifest makes its scenario broken, not the viewer", "[scene][scenarios]") {
  ScenarioRig rig;
  rig.fetcher.files["city/scenario-2.json"] = bytesOf("{\"format\":\"quakeview-tileset\",\"version\":9}");
  rig.open();
  REQUIRE(rig.settle());
  const ScenarioStatus& second = *rig.viewer.scenarios()->find(2);
  CHECK(second.state == ScenarioState::Broken);
  CHECK(second.problem.find("scenario-2.json: manifest: unsupported tileset version 9") != std::string::npos);
  REQUIRE(rig.viewer.selectScenario(2) > 0);
  REQUIRE(rig.switched());
  CHECK(rig.viewer.scenarioSwitch().state == ScenarioSwitch::State::Failed);
  CHECK(rig.viewer.scenarioSwitch().problem.find("Scenario 2 \"Recorded M5.0\" cannot be shown: ") == 0);
  CHECK(rig.viewer.manifestUrl() == "city/tileset.json");
}

TEST_CASE("A catalogue that cannot be read is reported once, and the city opens without scenarios",
          "[scene][scenarios]") {
  SECTION("not JSON") {
    ScenarioRig rig("{\"format\":\"quakeview-scenarios\",");
    rig.open();
    REQUIRE(rig.settle());
    CHECK(rig.viewer.scenarios()->state() == CityScenarios::CatalogueState::Failed);
    CHECK_FALSE(rig.viewer.scenarios()->available());
    REQUIRE(rig.viewer.errors().size() == 1);
    CHECK(rig.viewer.errors()[0].rfind("The city's scenario list was refused: city/scenarios.json: not valid JSON",
                                       0) == 0);
    CHECK(rig.viewer.city()->manifestLoaded());
    CHECK(rig.viewer.stats().latest.buildingsLoaded > 0);
  }
  SECTION("a server error") {
    ScenarioRig rig;
    rig.fetcher.statusOverride["city/scenarios.json"] = 500;
    rig.open();
    REQUIRE(rig.settle());
    REQUIRE(rig.viewer.errors().size() == 1);
    CHECK(rig.viewer.errors()[0] ==
          "The city's scenario list city/scenarios.json could not be loaded (HTTP 500); only the scenario "
          "opened is shown.");
  }
  SECTION("no response at all (another origin's 404 without a CORS header): no catalogue, no message") {
    ScenarioRig rig;
    rig.fetcher.statusOverride["city/scenarios.json"] = 0;
    rig.open();
    REQUIRE(rig.settle());
    CHECK(rig.viewer.scenarios()->state() == CityScenarios::CatalogueState::Absent);
    CHECK(rig.viewer.errors().empty());
    CHECK(rig.viewer.city()->manifestLoaded());
  }
}

TEST_CASE("A hostile entry is left out with a message, the others are listed, nothing outside the folder is fetched",
          "[scene][scenarios]") {
  ScenarioRig rig(R"({"format":"quakeview-scenarios","version":1,"scenarios":[)"
                  R"({"index":1,"name":"M6.6 test scenario","manifest":"scenario-1.json"},)"
                  R"({"index":2,"name":"Other city","manifest":"../other/tileset.json"},)"
                  R"({"index":3,"name":"Elsewhere","manifest":"https://evil.example/x.json"},)"
                  R"({"index":4,"name":"\u202Eevil","manifest":"scenario-2.json"}]})");
  rig.open();
  REQUIRE(rig.settle());
  const CityScenarios& s = *rig.viewer.scenarios();
  REQUIRE(s.scenarios().size() == 1);
  CHECK(s.scenarios()[0].entry.index == 1);
  REQUIRE(rig.viewer.errors().size() == 3);
  CHECK(
      rig.hasError("Scenario list: city/scenarios.json: entry 2 of \"scenarios\" (scenario 2) has the manifest "
                   "\"../other/tileset.json\", which is a path"));
  CHECK(rig.hasError("(scenario 3) has the manifest \"https://evil.example/x.json\""));
  CHECK(rig.hasError("(scenario 4) has the name"));
  for (const std::string& url : rig.fetcher.requested) {
    INFO(url);
    CHECK(url.find("other") == std::string::npos);
    CHECK(url.find("evil") == std::string::npos);
  }
  // The city's own messages go with it on a switch; the catalogue's stay.
  REQUIRE(rig.viewer.selectScenario(1) > 0);
  REQUIRE(rig.switched());
  CHECK(rig.viewer.errors().size() == 3);
}

TEST_CASE("A switch drops the messages of the city it replaces", "[scene][scenarios]") {
  ScenarioRig rig(kCatalogue, true);
  rig.open();
  REQUIRE(rig.settle());
  REQUIRE(rig.hasError("The response results are older than the buildings"));
  REQUIRE(rig.viewer.selectScenario(2) > 0);
  REQUIRE(rig.switched());
  CHECK(rig.viewer.scenarioSwitch().state == ScenarioSwitch::State::Loaded);
  CHECK_FALSE(rig.hasError("The response results are older than the buildings"));
}

TEST_CASE("Thousands of scenarios: each listed, a bounded number of manifests fetched on their own",
          "[scene][scenarios]") {
  std::string catalogue = R"({"format":"quakeview-scenarios","version":1,"scenarios":[)";
  for (int i = 1; i <= 1000; ++i) {
    catalogue += std::string(i > 1 ? "," : "") + R"({"index":)" + std::to_string(i) + R"(,"name":"Scenario )" +
                 std::to_string(i) + R"(","manifest":"many-)" + std::to_string(i) + R"(.json"})";
  }
  catalogue += "]}";
  ScenarioRig rig(catalogue);
  rig.open();
  REQUIRE(rig.runUntil([&] { return rig.viewer.settled() && rig.viewer.scenarios() != nullptr; }));
  for (int i = 0; i < 300; ++i) rig.viewer.frame(1.0 / 60.0);
  const CityScenarios& s = *rig.viewer.scenarios();
  CHECK(s.scenarios().size() == 1000);
  const auto fetched =
      static_cast<std::size_t>(std::count_if(rig.fetcher.requested.begin(), rig.fetcher.requested.end(),
                                             [](const std::string& url) { return url.find("city/many-") == 0; }));
  CHECK(fetched == CityScenarios::kMaxAutomaticChecks);
  CHECK(s.find(1)->state == ScenarioState::NotReady);
  CHECK(s.find(1000)->state == ScenarioState::Unchecked);
  // One chosen is checked when chosen.
  REQUIRE(rig.viewer.selectScenario(1000) > 0);
  REQUIRE(rig.switched());
  CHECK(rig.fetcher.count("city/many-1000.json") == 1);
  CHECK(rig.viewer.scenarioSwitch().state == ScenarioSwitch::State::Failed);
}
