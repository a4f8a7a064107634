// The districts a city gets from its own input (qv/prep/DefaultDistricts.h): the finest set of
// drawn boundaries that divides the city, else each building to its nearest place name (the
// places' Voronoi cells), else none; written as the GeoJSON `response --districts` reads, which
// puts every building in the district chosen for it.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "qv/prep/Consequences.h"
#include "qv/prep/DefaultDistricts.h"

using namespace qv;
using namespace qv::prep;

namespace {

GroundBoundary square(const std::string& name, const std::string& source, int fineness, double x0, double y0, double x1,
                      double y1) {
  return GroundBoundary{name, source, fineness, {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}};
}

/// A 1 km square city of 400 buildings on a 50 m grid, centred on the origin.
std::vector<glm::dvec2> gridCity() {
  std::vector<glm::dvec2> b;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) b.emplace_back(-475.0 + 50.0 * i, -475.0 + 50.0 * j);
  }
  return b;
}

const DefaultDistricts::District* named(const DefaultDistricts& d, const std::string& name) {
  for (const auto& district : d.districts) {
    if (district.name == name) return &district;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("Drawn boundaries: the finest set that divides the city", "[districts]") {
  const std::vector<glm::dvec2> city = gridCity();
  GroundFeatures g;
  // The city as one municipality (admin_level 8), two boroughs (9) and neighbourhoods (12) that
  // cover only its west half.
  g.boundaries.push_back(square("Town", "boundary=administrative admin_level=8", 8, -600, -600, 600, 600));
  g.boundaries.push_back(square("West", "boundary=administrative admin_level=9", 9, -600, -600, 0, 600));
  g.boundaries.push_back(square("East", "boundary=administrative admin_level=9", 9, 0, -600, 600, 600));
  g.boundaries.push_back(square("Northwest", "place=neighbourhood", 12, -600, 0, 0, 600));
  g.boundaries.push_back(square("Southwest", "place=neighbourhood", 12, -600, -600, 0, 0));

  SECTION("the neighbourhoods hold half the buildings: the boroughs are the districts") {
    const auto d = chooseDistricts(g, city, "OpenStreetMap");
    REQUIRE(d.has_value());
    CHECK(d->source == "OpenStreetMap boundary=administrative admin_level=9 areas");
    CHECK(!d->inferred);
    REQUIRE(d->districts.size() == 2);
    CHECK(d->districts[0].name == "East");  // by name
    CHECK(d->districts[0].buildings == 200);
    CHECK(d->districts[1].buildings == 200);
    CHECK(d->coverage == 1.0);
  }
  SECTION("neighbourhoods over 90 % of the buildings win; the rest is outside") {
    g.boundaries.push_back(square("East side", "place=neighbourhood", 12, 0, -600, 600, 400));
    const auto d = chooseDistricts(g, city, "OpenStreetMap");
    REQUIRE(d.has_value());
    CHECK(d->source == "OpenStreetMap place=neighbourhood areas");
    REQUIRE(d->districts.size() == 3);
    std::uint64_t inside = 0;
    for (const auto& district : d->districts) inside += district.buildings;
    CHECK(inside == 200 + 180);  // the east side's top 100 m (two rows of ten) is in none
    CHECK(d->coverage == Approx(380.0 / 400.0));
  }
  SECTION("a set that leaves one district is not a division: one area over the city is skipped") {
    GroundFeatures one;
    one.boundaries.push_back(square("Town", "boundary=administrative admin_level=8", 8, -600, -600, 600, 600));
    CHECK(!chooseDistricts(one, city, "OpenStreetMap").has_value());
  }
  SECTION("an area of several polygons is one district; holes are not in it") {
    GroundFeatures split;
    split.boundaries.push_back(square("Twin", "place=suburb", 10, -600, -600, -300, 600));
    split.boundaries.push_back(square("Twin", "place=suburb", 10, 300, -600, 600, 600));
    GroundBoundary middle = square("Middle", "place=suburb", 10, -300, -600, 300, 600);
    middle.rings.push_back({{-100, -100}, {100, -100}, {100, 100}, {-100, 100}});  // a hole
    split.boundaries.push_back(middle);
    const auto d = chooseDistricts(split, city, "OpenStreetMap");
    REQUIRE(d.has_value());
    REQUIRE(d->districts.size() == 2);
    CHECK(named(*d, "Twin")->polygons.size() == 2);
    CHECK(named(*d, "Twin")->buildings == 160);         // 4 columns of 20 on each side
    CHECK(named(*d, "Middle")->buildings == 240 - 16);  // 12 columns of 20, less the hole's 4 x 4
    CHECK(d->coverage == Approx(384.0 / 400.0));
  }
}

TEST_CASE("Named places: each building to its nearest name", "[districts]") {
  const std::vector<glm::dvec2> city = gridCity();
  GroundFeatures g;
  g.places.push_back({GroundLabelKind::Neighbourhood, {-250.0, 0.0}, "Westend", 80});
  g.places.push_back({GroundLabelKind::Neighbourhood, {250.0, 250.0}, "Northeast", 80});
  g.places.push_back({GroundLabelKind::Neighbourhood, {250.0, -250.0}, "Southeast", 80});
  g.places.push_back({GroundLabelKind::Neighbourhood, {9000.0, 0.0}, "Far away", 80});  // not near the city
  g.places.push_back({GroundLabelKind::Settlement, {0.0, 0.0}, "Town", 20});            // coarser: not used

  const auto d = chooseDistricts(g, city, "synth-city");
  REQUIRE(d.has_value());
  CHECK(d->inferred);
  CHECK(d->source.find("nearest synth-city neighbourhood name") != std::string::npos);
  REQUIRE(d->districts.size() == 3);
  CHECK(named(*d, "Far away") == nullptr);
  CHECK(d->coverage == 1.0);
  std::uint64_t total = 0;
  for (const auto& district : d->districts) total += district.buildings;
  CHECK(total == city.size());
  // Counted the plain way: each building to the nearest of the three.
  std::map<std::string, std::uint64_t> nearest;
  for (const glm::dvec2& b : city) {
    const double west = glm::length(b - glm::dvec2(-250.0, 0.0));
    const double north = glm::length(b - glm::dvec2(250.0, 250.0));
    const double south = glm::length(b - glm::dvec2(250.0, -250.0));
    ++nearest[west <= std::min(north, south) ? "Westend" : north <= south ? "Northeast" : "Southeast"];
  }
  for (const auto& [name, n] : nearest) {
    INFO(name);
    CHECK(named(*d, name)->buildings == n);
  }
  CHECK(nearest["Westend"] < 200);  // not the west half: the cells are the places' own, not a grid

  SECTION("the cells written as GeoJSON put each building in the district chosen for it") {
    const GeoFrame frame(-74.0, 40.75);
    const std::string json = districtsGeoJson(*d, frame);
    auto read = parseDistricts(json, "districts.geojson");
    REQUIRE(read.ok());
    CHECK(read->inferred);
    CHECK(read->source == d->source);
    CHECK(read->outsideName.empty());  // every building is in a district
    REQUIRE(read->names.size() == 3);
    // Buildings a little off the grid (never on a cell's edge), each to its nearest place.
    std::mt19937 random(5);
    std::uniform_real_distribution<double> jitter(-20.0, 20.0);
    const std::vector<glm::dvec2> sites{{-250.0, 0.0}, {250.0, 250.0}, {250.0, -250.0}};
    const std::vector<std::string> siteNames{"Westend", "Northeast", "Southeast"};
    for (const glm::dvec2& b : city) {
      const glm::dvec2 p = b + glm::dvec2(jitter(random), jitter(random));
      std::vector<std::pair<double, std::size_t>> byDistance;
      for (std::size_t i = 0; i < sites.size(); ++i) byDistance.emplace_back(glm::length(p - sites[i]), i);
      std::sort(byDistance.begin(), byDistance.end());
      if (byDistance[1].first - byDistance[0].first < 0.5) continue;  // too near an edge for centimetres
      const LonLat ll = frame.reverseUnchecked(p);
      const int found = read->find(ll.lon, ll.lat);
      REQUIRE(found >= 0);
      CHECK(read->names[static_cast<std::size_t>(found)] == siteNames[byDistance[0].second]);
    }
  }
  SECTION("fewer than two neighbourhoods: towns and villages") {
    GroundFeatures towns;
    towns.places.push_back({GroundLabelKind::Neighbourhood, {0.0, 0.0}, "Only", 80});
    towns.places.push_back({GroundLabelKind::Settlement, {-300.0, 0.0}, "Westville", 44});
    towns.places.push_back({GroundLabelKind::Settlement, {300.0, 0.0}, "Eastville", 44});
    const auto t = chooseDistricts(towns, city, "OpenStreetMap");
    REQUIRE(t.has_value());
    CHECK(t->districts.size() == 2);
    CHECK(t->source.find("town or village name (place=city, town, village, hamlet)") != std::string::npos);
  }
  SECTION("one name, or none: no districts") {
    GroundFeatures one;
    one.places.push_back({GroundLabelKind::Neighbourhood, {0.0, 0.0}, "Only", 80});
    one.places.push_back({GroundLabelKind::Neighbourhood, {10.0, 0.0}, "Only", 80});
    CHECK(!chooseDistricts(one, city, "OpenStreetMap").has_value());
    CHECK(!chooseDistricts(GroundFeatures{}, city, "OpenStreetMap").has_value());
    CHECK(!chooseDistricts(g, {}, "OpenStreetMap").has_value());
  }
}

TEST_CASE("A districts file's own members (source, inferred, outside), and bad ones named", "[districts]") {
  const std::string polygon = R"({"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon",
      "coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}})";
  auto plain = parseDistricts(R"({"type":"FeatureCollection","features":[)" + polygon + "]}", "d.geojson");
  REQUIRE(plain.ok());
  CHECK(plain->source.empty());
  CHECK(!plain->inferred);
  CHECK(plain->outsideName.empty());
  auto own = parseDistricts(
      R"({"type":"FeatureCollection","source":"S","inferred":true,"outside":"Rest","features":[)" + polygon + "]}",
      "d.geojson");
  REQUIRE(own.ok());
  CHECK(own->source == "S");
  CHECK(own->inferred);
  CHECK(own->outsideName == "Rest");
  auto badInferred = parseDistricts(R"({"inferred":"yes","features":[)" + polygon + "]}", "d.geojson");
  REQUIRE(!badInferred.ok());
  CHECK(badInferred.error() == "d.geojson: \"inferred\" must be true or false");
  auto badSource = parseDistricts(R"({"source":3,"features":[)" + polygon + "]}", "d.geojson");
  REQUIRE(!badSource.ok());
  CHECK(badSource.error() == "d.geojson: \"source\" must be a text of at most 1,000 bytes");
}
