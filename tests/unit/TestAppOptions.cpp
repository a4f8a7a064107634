#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "qv/options/AppOptions.h"

using namespace qv;

namespace {

struct Parsed {
  AppOptions options;
  std::vector<std::string> errors;
};

Parsed parse(const std::vector<std::string>& args) {
  Parsed p;
  p.options = parseAppOptions(args, p.errors);
  return p;
}

std::string readText(const std::string& relativePath) {
  std::ifstream in(std::string(QUAKEVIEW_SOURCE_DIR) + "/" + relativePath);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("Without URL options the viewer opens the default city, playing, in the default view", "[options]") {
  const Parsed p = parse({});
  CHECK(p.errors.empty());
  CHECK(p.options.scene.empty());
  CHECK(p.options.dataUrl.empty());
  CHECK(p.options.antialias);
  CHECK(p.options.benchSeconds == 0.0);
  CHECK(p.options.city.memoryBudgetBytes == 512ull * 1024 * 1024);  // README: "default 512"
  CHECK_FALSE(p.options.camera);
  CHECK_FALSE(p.options.timeSeconds);
  CHECK(p.options.playing);
  CHECK(p.options.select.empty());
  CHECK_FALSE(p.options.filters);
  CHECK(p.options.city.origin.allowedOrigins.empty());
}

TEST_CASE("Every URL option the README documents reaches the options", "[options]") {
  SECTION("?data, and the origins the shell adds for the data origin policy") {
    const Parsed p = parse({"--data", "https://data.example.org/nyc/tileset.json", "--page-origin",
                            "https://viewer.example.org", "--data-origin", "https://data.example.org", "--allow-origin",
                            "https://data.example.org", "--allow-origin", "https://mirror.example.org"});
    CHECK(p.errors.empty());
    CHECK(p.options.dataUrl == "https://data.example.org/nyc/tileset.json");
    CHECK(p.options.city.origin.pageOrigin == "https://viewer.example.org");
    CHECK(p.options.city.origin.urlOrigin == "https://data.example.org");
    CHECK(p.options.city.origin.allowedOrigins ==
          std::vector<std::string>{"https://data.example.org", "https://mirror.example.org"});
  }
  SECTION("?scene=test shows the test scene instead of any city") {
    const Parsed p = parse({"--data", "data/default/tileset.json", "--scene", "test"});
    CHECK(p.errors.empty());
    CHECK(p.options.scene == "test");
    CHECK(p.options.dataUrl.empty());
  }
  SECTION("?aa=0 turns antialiasing off") {
    CHECK_FALSE(parse({"--no-antialias"}).options.antialias);
    CHECK_FALSE(parse({"--no-antialias"}).options.antialiasForced);
  }
  SECTION("?aa=1 forces antialiasing on, also on a software renderer; the later flag wins") {
    const Parsed on = parse({"--antialias"});
    CHECK(on.errors.empty());
    CHECK(on.options.antialias);
    CHECK(on.options.antialiasForced);
    CHECK_FALSE(parse({"--antialias", "--no-antialias"}).options.antialias);
    CHECK_FALSE(parse({}).options.antialiasForced);
  }
  SECTION("?quality= fixes a preset; anything else lets the device decide, with a message") {
    CHECK(parse({}).options.quality == QualityChoice::Auto);
    CHECK(parse({"--quality", "high"}).options.quality == QualityChoice::High);
    CHECK(parse({"--quality", "balanced"}).options.quality == QualityChoice::Balanced);
    CHECK(parse({"--quality", "low"}).options.quality == QualityChoice::Low);
    CHECK(parse({"--quality", "auto"}).options.quality == QualityChoice::Auto);
    const Parsed bad = parse({"--quality", "ultra"});
    CHECK(bad.options.quality == QualityChoice::Auto);
    REQUIRE(bad.errors.size() == 1);
    CHECK(bad.errors[0] ==
          "The quality in the URL (quality=ultra) is not auto, high, balanced or low; the device decides.");
  }
  SECTION("the shell passes the WebGL renderer's name, made safe to display") {
    CHECK(parse({"--webgl-renderer", "llvmpipe, or similar"}).options.webGlRenderer == "llvmpipe, or similar");
    CHECK(parse({"--webgl-renderer", std::string(500, 'x')}).options.webGlRenderer.size() <= 200);
  }
  SECTION("?memory=MB, 16 to 4096") {
    CHECK(parse({"--memory-mb", "256"}).options.city.memoryBudgetBytes == 256ull << 20);
    CHECK(parse({"--memory-mb", "16"}).options.city.memoryBudgetBytes == 16ull << 20);
    CHECK(parse({"--memory-mb", "4096"}).options.city.memoryBudgetBytes == 4096ull << 20);
    CHECK(parse({"--memory-mb", "1.5e3"}).options.city.memoryBudgetBytes == 1500ull << 20);
  }
  SECTION("?bench=SECONDS, 1 to 3600") {
    CHECK(parse({"--bench", "30"}).options.benchSeconds == 30.0);
    CHECK(parse({"--bench", "3600"}).options.benchSeconds == 3600.0);
  }
  SECTION("#cam=x,y,distance,heading,pitch[,fov]") {
    const Parsed six = parse({"--camera", "120.5,-80.25,900,33,40,50"});
    CHECK(six.errors.empty());
    REQUIRE(six.options.camera);
    CHECK(six.options.camera->x == 120.5);
    CHECK(six.options.camera->y == -80.25);
    CHECK(six.options.camera->distance == 900.0);
    CHECK(six.options.camera->headingDeg == 33.0);
    CHECK(six.options.camera->pitchDeg == 40.0);
    CHECK(six.options.camera->fovDeg == 50.0);
    const Parsed five = parse({"--camera", "1,2,300,0,90"});
    REQUIRE(five.options.camera);
    CHECK(five.options.camera->fovDeg == 45.0);
    // A heading is an angle: any turn is fine, and is reported within [0, 360).
    const Parsed turned = parse({"--camera", "1,2,300,-90,45"});
    CHECK(turned.errors.empty());
    REQUIRE(turned.options.camera);
    CHECK(turned.options.camera->headingDeg == 270.0);
  }
  SECTION("#t=seconds") {
    CHECK(parse({"--time", "7.5"}).options.timeSeconds == 7.5);
    CHECK(parse({"--time", "0"}).options.timeSeconds == 0.0);
  }
  SECTION("#play=0|1: a link copied while paused opens paused") {
    CHECK_FALSE(parse({"--playing", "0"}).options.playing);
    CHECK(parse({"--playing", "1"}).options.playing);
  }
  SECTION("#sel=id") {
    CHECK(parse({"--select", "w263410589"}).options.select == "w263410589");
    CHECK(parse({"--select", "Café № 5"}).options.select == "Café № 5");
  }
  SECTION("#f=minDamage,use,critical") {
    const Parsed p = parse({"--filters", "2,hospital,1"});
    CHECK(p.errors.empty());
    REQUIRE(p.options.filters);
    CHECK(p.options.filters->minDamage == 2);
    CHECK(p.options.filters->use == "hospital");
    CHECK(p.options.filters->criticalOnly);
  }
  SECTION("a later repeat wins") {
    CHECK(parse({"--time", "3", "--time", "4"}).options.timeSeconds == 4.0);
  }
}

TEST_CASE("Filter text: empty fields mean any, as the shell writes them", "[options]") {
  struct Case {
    const char* text;
    int minDamage;
    const char* use;
    bool critical;
  };
  const Case c = GENERATE(Case{",,", -1, "", false}, Case{"1,,", 1, "", false}, Case{",school,", -1, "school", false},
                          Case{",,1", -1, "", true}, Case{"0,,0", 0, "", false},
                          Case{"4,place_of_worship,1", 4, "place_of_worship", true},
                          Case{",hospital+school+fire_station,", -1, "hospital+school+fire_station", false});
  CAPTURE(c.text);
  const Result<BuildingFilters> f = parseFilters(c.text);
  REQUIRE(f.ok());
  CHECK(f->minDamage == c.minDamage);
  CHECK(f->use == c.use);
  CHECK(f->criticalOnly == c.critical);
}

TEST_CASE("Filter text: a fourth field state:percent filters by the probability of damage", "[options]") {
  const Result<BuildingFilters> f = parseFilters("1,,,2:10");
  REQUIRE(f.ok());
  CHECK(f->minDamage == 1);
  CHECK(f->probabilityState == 2);
  CHECK(f->minProbabilityPercent == 10);
  CHECK(f->probabilityActive());
  CHECK(f->active());
  // An empty fourth field, or none (links made before it), leaves it off.
  for (const char* text : {",,,", ",,"}) {
    const Result<BuildingFilters> off = parseFilters(text);
    REQUIRE(off.ok());
    CHECK_FALSE(off->probabilityActive());
    CHECK_FALSE(off->active());
  }
  // P(>= moderate) = P(moderate) + P(extensive) + P(complete) = 0.06 + 0.03 + 0.01 = 10 %: passes at
  // 10 %, not at 11 %; a building without probabilities never passes.
  BuildingResponse r;
  r.source = ResponseSource::Model;
  r.damage = DamageState::None;
  BuildingLoss loss;
  const float p[5] = {0.7f, 0.2f, 0.06f, 0.03f, 0.01f};
  std::copy(p, p + 5, loss.structural);
  CHECK(loss.structuralAtLeast(2) == Approx(0.10f));
  CHECK(loss.structuralAtLeast(0) == 1.0f);
  CHECK(loss.structuralAtLeast(5) == 0.0f);
  const Result<BuildingFilters> ten = parseFilters(",,,2:10");
  REQUIRE(ten.ok());
  CHECK(ten->passes(FacilityCategory::None, "office", &r, &loss));
  CHECK_FALSE(ten->passes(FacilityCategory::None, "office", &r, static_cast<const BuildingLoss*>(nullptr)));
  const Result<BuildingFilters> eleven = parseFilters(",,,2:11");
  REQUIRE(eleven.ok());
  CHECK_FALSE(eleven->passes(FacilityCategory::None, "office", &r, &loss));
  const Result<BuildingFilters> slight = parseFilters(",,,1:30");
  REQUIRE(slight.ok());
  CHECK(slight->passes(FacilityCategory::None, "office", &r, &loss));  // 0.2 + 0.1 = 30 %
  // The deterministic state is "none", yet the probability filter finds the building.
  const Result<BuildingFilters> deterministic = parseFilters("1,,");
  REQUIRE(deterministic.ok());
  CHECK_FALSE(deterministic->passes(FacilityCategory::None, "office", &r, &loss));
}

TEST_CASE("Filter text: the critical field takes facility categories joined by '+'", "[options]") {
  const Result<BuildingFilters> f = parseFilters(",,essential+high_occupancy");
  REQUIRE(f.ok());
  CHECK_FALSE(f->criticalOnly);
  BuildingFilters want;
  want.categories =
      facilityCategoryBit(FacilityCategory::Essential) | facilityCategoryBit(FacilityCategory::HighOccupancy);
  CHECK(*f == want);
  // "1" keeps its meaning: essential facilities, schools and shelters.
  const Result<BuildingFilters> one = parseFilters(",,1");
  REQUIRE(one.ok());
  CHECK(one->passes(FacilityCategory::Essential, "hospital", nullptr));
  CHECK(one->passes(FacilityCategory::SchoolShelter, "school", nullptr));
  CHECK_FALSE(one->passes(FacilityCategory::HighOccupancy, "sports", nullptr));
  CHECK_FALSE(one->passes(FacilityCategory::None, "office", nullptr));
  const Result<BuildingFilters> all = parseFilters(",,essential+school_shelter+high_occupancy+hazardous");
  REQUIRE(all.ok());
  CHECK(all->passes(FacilityCategory::Hazardous, "retail", nullptr));
  CHECK_FALSE(all->passes(FacilityCategory::None, "office", nullptr));
  // Several uses: a building passes with any of them.
  const Result<BuildingFilters> uses = parseFilters(",hospital+school,");
  REQUIRE(uses.ok());
  CHECK(uses->usePasses("school"));
  CHECK(uses->usePasses("hospital"));
  CHECK_FALSE(uses->usePasses("schoo"));
  CHECK_FALSE(uses->usePasses("hospital+school"));
  CHECK_FALSE(uses->usePasses("office"));
}

TEST_CASE("Bad filter text is refused with the field at fault", "[options]") {
  struct Case {
    std::string text;
    const char* expected;
  };
  const Case c = GENERATE(
      Case{"banana", "1 field where 3 or 4 are expected"}, Case{"1,,,,", "5 fields where 3 or 4"},
      Case{",,,5:10", "probability '5:10'"}, Case{",,,2:0", "probability '2:0'"},
      Case{",,,2:101", "probability '2:101'"}, Case{",,,2", "probability '2'"}, Case{",,,2:", "probability '2:'"},
      Case{",,,0:10", "probability '0:10'"}, Case{",,,2:1x", "probability '2:1x'"},
      Case{",,,2:-5", "probability '2:-5'"}, Case{"9,,", "minDamage '9'"}, Case{"12,,", "minDamage '12'"},
      Case{"x,,", "minDamage 'x'"}, Case{"1,Hospital,0", "use 'Hospital'"}, Case{"1,hos pital,0", "use 'hos pital'"},
      Case{"1,,2", "critical '2'"}, Case{"1,,yes", "critical 'yes'"},
      Case{",hospital+,", "use 'hospital+' has an empty use"}, Case{",+school,", "use '+school' has an empty use"},
      Case{",hospital++school,", "use 'hospital++school' has an empty use"},
      Case{",Hospital+school,", "use 'Hospital+school'"},
      Case{",,essential+critical", "critical 'essential+critical' is not 0, 1 or categories"},
      Case{",,essential+", "critical 'essential+'"}, Case{",,none", "critical 'none'"},
      Case{",,Essential", "critical 'Essential'"}, Case{std::string(301, ','), "longer than 300 characters"});
  CAPTURE(c.text);
  const Result<BuildingFilters> f = parseFilters(c.text);
  REQUIRE_FALSE(f.ok());
  CHECK_THAT(f.error(), Catch::Contains(c.expected));
}

TEST_CASE("A bad URL value keeps the default and the message names the parameter and the value", "[options]") {
  struct Case {
    const char* argument;
    std::string value;
    const char* named;     // what the message must show
    const char* location;  // "in the link" for the shareable view's hash, "in the URL" for the query
  };
  const Case c = GENERATE(
      Case{"--memory-mb", "abc", "memory=abc", "in the URL"}, Case{"--memory-mb", "8", "memory=8", "in the URL"},
      Case{"--memory-mb", "5000", "memory=5000", "in the URL"}, Case{"--bench", "0.5", "bench=0.5", "in the URL"},
      Case{"--bench", "soon", "bench=soon", "in the URL"}, Case{"--scene", "city", "scene=city", "in the URL"},
      Case{"--camera", "12,abc,9", "cam=12,abc,9", "in the link"},
      Case{"--camera", "1,2,abc,4,5", "distance 'abc' is not a number", "in the link"},
      Case{"--camera", "1,2,900,4,120", "pitch 120 is outside", "in the link"},
      Case{"--camera", "1,2,900,4,45,nan", "fov 'nan'", "in the link"}, Case{"--time", "-3", "t=-3", "in the link"},
      Case{"--time", "abc", "t=abc", "in the link"}, Case{"--time", "inf", "t=inf", "in the link"},
      Case{"--playing", "yes", "play=yes", "in the link"}, Case{"--select", "a\tb", "sel=a b", "in the link"},
      Case{"--select", std::string(201, 'w'), "sel=www", "in the link"},
      Case{"--filters", "banana", "f=banana", "in the link"},
      Case{"--filters", "9,,", "minDamage '9' is not a damage state", "in the link"});
  CAPTURE(c.argument, c.value);
  const Parsed p = parse({c.argument, c.value});
  REQUIRE(p.errors.size() == 1);
  CHECK_THAT(p.errors[0], Catch::Contains(c.named) && Catch::Contains(c.location));
  const AppOptions defaults;
  CHECK(p.options.city.memoryBudgetBytes == defaults.city.memoryBudgetBytes);
  CHECK(p.options.benchSeconds == 0.0);
  CHECK_FALSE(p.options.camera);
  CHECK_FALSE(p.options.timeSeconds);
  CHECK(p.options.playing);
  CHECK(p.options.select.empty());
  CHECK_FALSE(p.options.filters);
  if (std::string(c.argument) == "--scene") CHECK(p.options.scene == "test");  // unknown scene: the test scene
}

TEST_CASE("The messages the page shows stay short and readable whatever the link holds", "[options]") {
  const std::string hostile = std::string(500, 'x') + "\n\u202Eevil";
  const Parsed p = parse({"--time", hostile, "--select", hostile, "--filters", hostile});
  REQUIRE(p.errors.size() == 3);
  for (const std::string& e : p.errors) {
    CAPTURE(e);
    CHECK(e.size() < 250);
    CHECK_FALSE(contains(e, "\n"));
    CHECK_FALSE(contains(e, "\u202E"));
  }
}

TEST_CASE("Unknown engine arguments and missing values are reported and ignored", "[options]") {
  const Parsed unknown = parse({"--colour", "red", "--time", "2"});
  CHECK(unknown.options.timeSeconds == 2.0);
  REQUIRE(unknown.errors.size() == 2);
  CHECK_THAT(unknown.errors[0], Catch::Contains("'--colour'"));
  CHECK_THAT(unknown.errors[1], Catch::Contains("'red'"));
  const Parsed missing = parse({"--time"});
  CHECK_FALSE(missing.options.timeSeconds);
  REQUIRE(missing.errors.size() == 1);
  CHECK_THAT(missing.errors[0], Catch::Contains("'--time'") && Catch::Contains("without a value"));
  // The shell's own problems (a broken config.json) pass through unchanged.
  const Parsed shell = parse({"--shell-error", "config.json: not valid JSON"});
  CHECK(shell.errors == std::vector<std::string>{"config.json: not valid JSON"});
}

TEST_CASE("The URL names are the contract the README and the page shell share", "[options]") {
  const std::string readme = readText("README.md");
  const std::string shell = readText("web/quakeview.js");
  REQUIRE_FALSE(readme.empty());
  REQUIRE_FALSE(shell.empty());
  std::vector<std::string> known;
  for (const AppArgument& a : appArguments()) {
    const std::string argument(a.argument), name(a.urlName);
    CAPTURE(argument, name);
    known.push_back(argument);
    CHECK(contains(shell, "'" + argument + "'"));
    if (a.source == ArgumentSource::UrlQuery) {
      CHECK(contains(readme, "?" + name + "="));
      CHECK(contains(shell, "params.get('" + name + "')"));
    } else if (a.source == ArgumentSource::UrlHash) {
      CHECK((contains(readme, "#" + name + "=") || contains(readme, "&" + name + "=")));
      CHECK(contains(shell, "hash.get('" + name + "')"));
    }
  }
  // And every argument the shell passes ('--name' in its source) is one the engine knows.
  for (std::size_t at = shell.find("'--"); at != std::string::npos; at = shell.find("'--", at + 1)) {
    const std::size_t begin = at + 1;
    const std::string argument = shell.substr(begin, shell.find('\'', begin) - begin);
    CAPTURE(argument);
    CHECK(std::find(known.begin(), known.end(), argument) != known.end());
  }
}
