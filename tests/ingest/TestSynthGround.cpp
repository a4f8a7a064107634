// The synthetic city's map (docs/synth-city.md "Map"): streets between its blocks and never under
// a building, parks in its empty blocks, a river beside it, 4 to 8 neighbourhoods, the same
// buildings with and without it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <glm/geometric.hpp>

#include "qv/prep/SynthCity.h"

using namespace qv;
using namespace qv::prep;

namespace {

CityModel synth(std::uint64_t buildings, bool ground = true) {
  SynthCityOptions options;
  options.buildings = buildings;
  options.seed = 1;
  options.ground = ground;
  return generateSynthCity(options);
}

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  const glm::dvec2 d = p - (a + t * ab);
  return std::sqrt(glm::dot(d, d));
}

bool insideRing(glm::dvec2 p, const std::vector<glm::dvec2>& ring) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const glm::dvec2 a = ring[i], b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

}  // namespace

TEST_CASE("synth-city's map lies between its buildings", "[synth][ground]") {
  const std::uint64_t n = GENERATE(std::uint64_t{20}, std::uint64_t{3000});
  INFO(n << " buildings");
  const CityModel model = synth(n);
  const GroundFeatures& g = model.ground;
  REQUIRE(model.buildings.size() == n);

  SECTION("named avenues and streets, none under a building") {
    std::set<std::string> names;
    for (const GroundLine& l : g.lines) {
      REQUIRE(l.points.size() == 2);
      CHECK((l.groundClass == GroundClass::Major || l.groundClass == GroundClass::Street));
      CHECK(!l.name.empty());
      CHECK(names.insert(l.name).second);  // one line per street
      for (const Building& b : model.buildings) {
        for (const glm::dvec2& p : b.parts[0].points) {
          const double d = distanceToSegment(p, l.points[0], l.points[1]);
          if (d < l.widthM / 2) FAIL(b.attributes.id << " stands on " << l.name);
        }
      }
    }
    CHECK(names.count("1st Avenue") == 1);
    CHECK(names.count("2nd Avenue") == 1);
    CHECK(names.count("North 2nd Street") == 1);
    const auto third =
        std::find_if(g.lines.begin(), g.lines.end(), [](const GroundLine& l) { return l.name == "3rd Avenue"; });
    if (third != g.lines.end()) CHECK(third->groundClass == GroundClass::Major);
    // The streets carry the names of the addresses of the lots facing them from the south.
    std::size_t addressed = 0;
    for (const Building& b : model.buildings) {
      const std::string& address = b.attributes.address;
      const std::string street = address.substr(address.find(' ') + 1);
      addressed += names.count(street);
    }
    CHECK(addressed * 3 >= model.buildings.size());
  }
  SECTION("water and parks hold no building") {
    REQUIRE(std::count_if(g.areas.begin(), g.areas.end(),
                          [](const GroundArea& a) { return a.groundClass == GroundClass::Water; }) == 1);
    for (const GroundArea& a : g.areas) {
      REQUIRE(a.rings.size() == 1);
      CHECK(a.rings[0].size() >= 4);
      CHECK((a.groundClass == GroundClass::Water || a.groundClass == GroundClass::Park));
      for (const Building& b : model.buildings) {
        if (insideRing({b.attributes.centroidX, b.attributes.centroidY}, a.rings[0]))
          FAIL(b.attributes.id << " stands in " << a.name);
      }
    }
    const bool river = std::any_of(g.areas.begin(), g.areas.end(), [](const GroundArea& a) {
      return a.groundClass == GroundClass::Water && a.name == "Synthetic River";
    });
    CHECK(river);
  }
  SECTION("4 to 8 neighbourhoods, downtown at the centre") {
    CHECK(g.places.size() >= 4);
    CHECK(g.places.size() <= 8);
    std::set<std::string> names;
    for (const GroundPlace& p : g.places) {
      CHECK(p.kind == GroundLabelKind::Neighbourhood);
      CHECK(names.insert(p.name).second);
    }
    CHECK(names.count("Downtown") == 1);
  }
  CHECK(g.coastlines.empty());
}

TEST_CASE("synth-city's map takes no random numbers: the same buildings without it", "[synth][ground]") {
  const CityModel with = synth(3000);
  const CityModel without = synth(3000, false);
  CHECK(without.ground.empty());
  REQUIRE(with.buildings.size() == without.buildings.size());
  for (std::size_t i = 0; i < with.buildings.size(); ++i) {
    const Building& a = with.buildings[i];
    const Building& b = without.buildings[i];
    REQUIRE(a.attributes.id == b.attributes.id);
    CHECK(a.attributes.heightM == b.attributes.heightM);
    CHECK(a.parts[0].points == b.parts[0].points);
  }
  // Empty blocks are parks: a city of 3000 buildings leaves a few.
  const auto parks = std::count_if(with.ground.areas.begin(), with.ground.areas.end(),
                                   [](const GroundArea& a) { return a.groundClass == GroundClass::Park; });
  CHECK(parks >= 3);
  // The same map on every run.
  const CityModel again = synth(3000);
  REQUIRE(again.ground.lines.size() == with.ground.lines.size());
  for (std::size_t i = 0; i < with.ground.lines.size(); ++i) {
    CHECK(again.ground.lines[i].name == with.ground.lines[i].name);
    CHECK(again.ground.lines[i].points == with.ground.lines[i].points);
  }
}
