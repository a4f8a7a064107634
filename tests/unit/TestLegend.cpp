// The legend ("Damage and colours") says what every building shows: in the current-drift mode the
// animated buildings their drift now, the others their peak over the whole record in grey, with
// the animation radius that separates them. Read through the text mirror behind uiText().
#include <catch2/catch.hpp>

#include <imgui.h>

#include <regex>
#include <string>

#include "HeadlessImGui.h"
#include "MiniCity.h"
#include "qv/core/Crc32.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/seismic/ConsequencesFile.h"
#include "qv/ui/ControlPanel.h"
#include "qv/ui/TextMirror.h"

using namespace qv;

namespace {

struct NoHost final : UiHost {
  void openUrl(const std::string&) override {}
  void download(const std::string&, const std::string&, const std::string&) override {}
  void saveImage() override {}
};

// The mini city in a viewer, settled, looked at from 500 m: its buildings are within the default
// animation radius (1 km).
struct LegendSetup {
  /// `withSeries`: the city's summaries carry drift series (MiniCity's `withSeries`).
  /// `withConsequences`: the response carries damage probabilities (a consequences file).
  explicit LegendSetup(bool withSeries = false, bool withConsequences = false)
      : city(true, false, test::MiniCity::kSide * test::MiniCity::kSide, {}, withSeries) {
    if (withConsequences) {
      seismic::ConsequenceTotals totals;
      totals.timeOfDay = "day";
      totals.city.buildings = city.tileset.buildings;
      const std::string json = seismic::consequencesToJson(totals);
      const std::vector<std::uint8_t> bytes(json.begin(), json.end());
      city.tileset.response->consequences = CityFile{"response/consequences.json", bytes.size(), crc32(bytes)};
      city.tileset.response->timeOfDay = "day";
      city.files["city/response/consequences.json"] = bytes;
      const std::string manifest = tilesetToJson(city.tileset);
      city.files["city/tileset.json"] = std::vector<std::uint8_t>(manifest.begin(), manifest.end());
    }
    city.serve(fetcher);
    panel.openSection("Damage and colours");  // folded at first: the map overlay has the colour key
    viewer.openCity("city/tileset.json", fetcher);
    viewer.setViewport(1280, 720, 1280.0, 720.0);
    viewer.setCamera(CameraState{0.0, 0.0, 500.0, 0.0, 60.0, 45.0});
    // Exaggerated, so that the test city's sways (5 to 15 cm) show from 500 m.
    viewer.setAmplitude(50.0f);
    for (int i = 0; i < 20; ++i) viewer.frame(1.0 / 60.0);
  }
  std::string draw() {
    viewer.frame(1.0 / 60.0);
    ImGui::NewFrame();
    mirror.beginFrame();
    ui::Widgets w(mirror);
    panel.draw(viewer, w, MemoryInfo{}, host);
    ImGui::Render();
    mirror.endFrame();
    return mirror.text();
  }
  HeadlessImGui imgui;
  test::MiniCity city;
  test::FakeFetcher fetcher;
  NullRenderDevice device;
  Viewer viewer{device};
  TextMirror mirror;
  ControlPanel panel;
  NoHost host;
};

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The "Damage and colours" section of the mirror (up to the next section header).
std::string legendOf(const std::string& text) {
  const std::size_t begin = text.find("v Damage and colours");
  if (begin == std::string::npos) return {};
  const std::size_t end = text.find("\n> ", begin);
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

}  // namespace

TEST_CASE("In the current-drift mode the legend names the grey peak colours of buildings that are not animated",
          "[ui][city][legend]") {
  LegendSetup setup;
  REQUIRE(setup.viewer.settled());
  REQUIRE(setup.viewer.colorMode() == ColorMode::CurrentDrift);  // the default mode
  const std::string legend = legendOf(setup.draw());
  INFO(legend);
  REQUIRE_FALSE(legend.empty());
  CHECK(has(legend, "Inter-storey drift (now), animated buildings:\n"));
  CHECK(has(legend, "Not animated (beyond the animation radius): peak drift over the whole record\n"));
  // Five grey levels, labelled like the ramp, after the ramp's own five.
  const std::size_t greys = legend.find("Not animated");
  CHECK(legend.find("2 % drift or more\n") < greys);
  CHECK(legend.find("0 % peak drift\n", greys) != std::string::npos);
  CHECK(legend.find("1 % peak drift\n", greys) != std::string::npos);
  CHECK(legend.find("2 % peak drift or more\n", greys) != std::string::npos);
  // The radius that separates the two, with its value, and how many are animated now.
  std::smatch m;
  REQUIRE(std::regex_search(legend, m,
                            std::regex("Animated: the buildings within 1\\.00 km of the camera whose sway \\(times "
                                       "the amplitude\\) reaches a pixel on screen, at most 20000 \\(Performance "
                                       "panel\\), ([0-9]+) now; the others and the far-view tiles are grey\\.")));
  const unsigned animated = setup.viewer.stats().latest.buildingsAnimated;
  CHECK(animated > 0);
  CHECK(std::stoul(m[1]) == animated);

  SECTION("the radius line follows the option") {
    setup.viewer.city()->mutableOptions().animationRadiusM = 300.0f;
    CHECK(has(legendOf(setup.draw()), "Animated: the buildings within 300.0 m of the camera"));
    setup.viewer.setShowFeet(true);
    CHECK(has(legendOf(setup.draw()), "Animated: the buildings within 984 ft of the camera"));
  }
  SECTION("with animation off, every building is grey and the legend says so") {
    setup.viewer.city()->mutableOptions().animationRadiusM = 0.0f;
    const std::string off = legendOf(setup.draw());
    CHECK(has(off, "Animation is off (General panel): every building shows its peak drift in grey."));
    CHECK_FALSE(has(off, "Animated: the buildings within"));
    CHECK(setup.viewer.stats().latest.buildingsAnimated == 0);
  }
}

TEST_CASE("The other colour modes have no not-animated entry", "[ui][city][legend]") {
  LegendSetup setup;
  REQUIRE(setup.viewer.settled());
  for (ColorMode mode : {ColorMode::PeakDrift, ColorMode::DamageState, ColorMode::Neutral, ColorMode::ModerateOrWorse,
                         ColorMode::ExpectedDamage, ColorMode::InspectionTag}) {
    setup.viewer.setColorMode(mode);
    const std::string legend = legendOf(setup.draw());
    INFO(static_cast<int>(mode) << ": " << legend);
    REQUIRE_FALSE(legend.empty());
    CHECK_FALSE(has(legend, "Not animated"));
    CHECK_FALSE(has(legend, "peak drift in grey"));
  }
  setup.viewer.setColorMode(ColorMode::PeakDrift);
  CHECK(has(legendOf(setup.draw()), "Inter-storey drift (peak):\n"));
}

TEST_CASE("With drift series every building follows its response and the legend says so, without a grey entry",
          "[ui][city][legend]") {
  LegendSetup setup(true);
  REQUIRE(setup.viewer.settled());
  REQUIRE(setup.viewer.city()->hasDriftSeries());
  const std::string legend = legendOf(setup.draw());
  INFO(legend);
  CHECK(has(legend, "Inter-storey drift (now), every building: its largest storey (close by, each storey):\n"));
  CHECK_FALSE(has(legend, "Not animated"));
  std::smatch m;
  REQUIRE(std::regex_search(
      legend, m,
      std::regex("([0-9]+) buildings in view follow their response now; within 1\\.00 km of the "
                 "camera \\(at most 20000\\) each storey moves by its own displacement "
                 "where the sway \\(times the amplitude\\) reaches a pixel on screen: [0-9]+ now\\. The others "
                 "sway as their drift series gives")));
  // The far sway says what it is: a picture of the motion from the drift series, not its record.
  CHECK(has(legend, "(an approximation of the history, not its record)"));
  CHECK(std::stoul(m[1]) == setup.viewer.stats().latest.buildingsAnimated);
  CHECK(setup.viewer.stats().latest.buildingsAnimated == setup.viewer.stats().latest.buildingsVisible);
  // The map overlay keys the colours whatever the panel's state, mode by mode.
  CHECK(has(setup.draw(), "Colour: storey drift now: 0 0.1 0.5 1 2 %\n"));
  setup.viewer.setColorMode(ColorMode::ModerateOrWorse);
  CHECK(has(setup.draw(), "Colour: P(moderate damage or worse): 0 25 50 75 100 %\n"));
  setup.viewer.setColorMode(ColorMode::InspectionTag);
  CHECK(has(setup.draw(), "Colour: most likely inspection tag: green yellow red\n"));
  setup.viewer.setColorMode(ColorMode::Neutral);
  CHECK_FALSE(has(setup.draw(), "Colour:"));
}

TEST_CASE("Playback stops at the end of the record, where the city shows its damage probabilities",
          "[ui][city][legend]") {
  LegendSetup setup(true, true);
  Viewer& viewer = setup.viewer;
  REQUIRE(viewer.duration() > 0.0);
  REQUIRE(viewer.playing());
  // During the shaking: the drift now, as chosen.
  CHECK(viewer.shownColorMode() == ColorMode::CurrentDrift);
  CHECK(has(setup.draw(), "Colour: storey drift now: "));
  // Played past the end: it stops there, and the city shows P(moderate or worse), said so twice.
  viewer.frame(viewer.duration() + 5.0);
  CHECK(viewer.ended());
  CHECK_FALSE(viewer.playing());
  CHECK(viewer.time() == viewer.duration());
  CHECK(viewer.colorMode() == ColorMode::CurrentDrift);  // the choice is kept
  CHECK(viewer.shownColorMode() == ColorMode::ModerateOrWorse);
  CHECK(viewer.showingDamageAfterShaking());
  std::string text = setup.draw();
  CHECK(has(text, "Colour: P(moderate damage or worse), after the shaking: 0 25 50 75 100 %\n"));
  CHECK(has(text, "The shaking is over: each building shows its probability of moderate damage or worse"));
  CHECK(has(text, "Probability of moderate damage or worse (HAZUS 5.1 fragility):"));
  // Paused at a moment of the shaking: the drift of that moment again.
  viewer.setTime(viewer.duration() * 0.5);
  CHECK(viewer.shownColorMode() == ColorMode::CurrentDrift);
  viewer.setTime(viewer.duration());
  // The switch turns it off; other chosen modes are never replaced.
  viewer.setDamageAfterShaking(false);
  CHECK(viewer.shownColorMode() == ColorMode::CurrentDrift);
  viewer.setDamageAfterShaking(true);
  viewer.setColorMode(ColorMode::PeakDrift);
  CHECK(viewer.shownColorMode() == ColorMode::PeakDrift);
  viewer.setColorMode(ColorMode::CurrentDrift);
  // Play at the end starts again before the shaking arrives and runs.
  viewer.play();
  CHECK(viewer.playing());
  CHECK(viewer.time() < viewer.duration() * 0.5);
  viewer.frame(0.5);
  CHECK(viewer.playing());
  CHECK(viewer.shownColorMode() == ColorMode::CurrentDrift);
  // Looping (the benchmark flight's way): past the end, it goes on from the start.
  viewer.setLoop(true);
  viewer.frame(viewer.duration() * 0.75);
  CHECK(viewer.playing());
  CHECK(viewer.time() < viewer.duration());
}

TEST_CASE("Without damage probabilities the end of the record keeps the drift colours", "[ui][city][legend]") {
  LegendSetup setup(true, false);
  setup.viewer.frame(setup.viewer.duration() + 5.0);
  CHECK(setup.viewer.ended());
  CHECK(setup.viewer.shownColorMode() == ColorMode::CurrentDrift);
  CHECK(has(setup.draw(), "Colour: storey drift now: "));
}
