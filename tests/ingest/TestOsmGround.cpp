// The map under the buildings read from OpenStreetMap (docs/attributes.md "Ground features"): the
// streets, parks and places of the Midtown fixture, the Rhine, forests and villages of
// Liechtenstein (OSM's 2013 extract from Debian's osm2pgsql sources, which scripts/setup.sh puts in
// .deps/osm-data/), the tag table on a hand-written file, and hostile input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "IngestTestData.h"
#include "qv/prep/DefaultDistricts.h"

using namespace qv;
using namespace qv::prep;
using namespace qv::prep::test;

namespace {

std::uint64_t skipped(const GroundFeatures& ground, const std::string& reason) {
  const auto it = ground.skipped.find(reason);
  return it == ground.skipped.end() ? 0 : it->second;
}

std::vector<const GroundLine*> linesNamed(const GroundFeatures& ground, const std::string& name) {
  std::vector<const GroundLine*> found;
  for (const GroundLine& line : ground.lines) {
    if (line.name == name) found.push_back(&line);
  }
  return found;
}

const GroundPlace* placeNamed(const GroundFeatures& ground, const std::string& name) {
  for (const GroundPlace& place : ground.places) {
    if (place.name == name) return &place;
  }
  return nullptr;
}

std::size_t areasOf(const GroundFeatures& ground, GroundClass c) {
  return static_cast<std::size_t>(
      std::count_if(ground.areas.begin(), ground.areas.end(), [c](const GroundArea& a) { return a.groundClass == c; }));
}

std::size_t linesOf(const GroundFeatures& ground, GroundClass c) {
  return static_cast<std::size_t>(
      std::count_if(ground.lines.begin(), ground.lines.end(), [c](const GroundLine& l) { return l.groundClass == c; }));
}

/// The largest distance of any ground point from the city frame's origin, metres.
double farthestPointM(const GroundFeatures& ground) {
  double far = 0.0;
  auto see = [&far](glm::dvec2 p) { far = std::max(far, std::hypot(p.x, p.y)); };
  for (const GroundLine& l : ground.lines) std::for_each(l.points.begin(), l.points.end(), see);
  for (const GroundArea& a : ground.areas) {
    for (const auto& ring : a.rings) std::for_each(ring.begin(), ring.end(), see);
  }
  for (const GroundPlace& p : ground.places) see(p.position);
  return far;
}

/// Liechtenstein, read once; a clear failure (not a skip) when set-up did not provide it.
const Ingested& liechtenstein() {
  static const Ingested ingested = [] {
    const std::string path = QUAKEVIEW_OSM_LIECHTENSTEIN;
    if (!std::filesystem::exists(path)) return Ingested{Error{path + " is missing: run scripts/setup.sh"}, {}};
    return ingest({path});
  }();
  return ingested;
}

/// An OSM XML file: a building (so that readCity has a city) at 47.0 N, 9.5 E, the nodes 1..n of
/// `nodes` ({id, lon, lat} as text), then `ways` and `relations` verbatim.
std::string osm(const std::string& nodes, const std::string& ways, const std::string& relations = "") {
  return "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\">\n"
         "<node id=\"9001\" lat=\"47.0000\" lon=\"9.5000\"/><node id=\"9002\" lat=\"47.0000\" lon=\"9.5002\"/>\n"
         "<node id=\"9003\" lat=\"47.0002\" lon=\"9.5002\"/><node id=\"9004\" lat=\"47.0002\" lon=\"9.5000\"/>\n" +
         nodes +
         "<way id=\"9000\"><nd ref=\"9001\"/><nd ref=\"9002\"/><nd ref=\"9003\"/><nd ref=\"9004\"/><nd "
         "ref=\"9001\"/><tag k=\"building\" v=\"yes\"/></way>\n" +
         ways + relations + "</osm>\n";
}

std::string node(int id, double lon, double lat, const std::string& tags = "") {
  return "<node id=\"" + std::to_string(id) + "\" lat=\"" + std::to_string(lat) + "\" lon=\"" + std::to_string(lon) +
         "\">" + tags + "</node>\n";
}

std::string way(int id, const std::vector<int>& refs, const std::string& tags) {
  std::string xml = "<way id=\"" + std::to_string(id) + "\">";
  for (const int r : refs) xml += "<nd ref=\"" + std::to_string(r) + "\"/>";
  return xml + tags + "</way>\n";
}

std::string tag(const std::string& k, const std::string& v) {
  return "<tag k=\"" + k + "\" v=\"" + v + "\"/>";
}

}  // namespace

TEST_CASE("The Midtown fixture's streets, parks and places", "[ingest][osm][ground]") {
  const Ingested& in = midtownFixture();
  REQUIRE(in.model.ok());
  const GroundFeatures& g = in.model->ground;
  CHECK(in.stats.groundLines == g.lines.size());
  CHECK(in.stats.groundAreas == g.areas.size());
  CHECK(in.stats.groundPlaces == g.places.size());
  CHECK(g.coastlines.empty());  // Midtown has no shore

  SECTION("streets with their names, classes and widths") {
    // 434 highway ways, less tunnels, areas and the elevator: hundreds of lines.
    CHECK(g.lines.size() > 300);
    const auto fifth = linesNamed(g, "5th Avenue");
    REQUIRE(!fifth.empty());
    for (const GroundLine* l : fifth) {
      CHECK(l->groundClass == GroundClass::Major);
      CHECK(l->widthM >= 10.0f);
      CHECK(l->widthM <= 20.0f);
      CHECK(l->points.size() >= 2);
    }
    const auto west34 = linesNamed(g, "West 34th Street");
    REQUIRE(!west34.empty());
    for (const GroundLine* l : west34) {
      CHECK((l->groundClass == GroundClass::Major || l->groundClass == GroundClass::Street));
      CHECK(l->widthM >= 5.0f);
      CHECK(l->widthM <= 20.0f);
    }
    CHECK(!linesNamed(g, "Broadway").empty());
    // Footways and steps are paths 3 m wide; the area=yes squares are path areas.
    CHECK(linesOf(g, GroundClass::Path) > 100);
    CHECK(areasOf(g, GroundClass::Path) > 0);
    // Railway and road tunnels (Penn Station's tracks, the PATH) are not on the map.
    CHECK(skipped(g, "tunnel") > 0);
  }
  SECTION("parks and open land") {
    CHECK(areasOf(g, GroundClass::Park) >= 3);
    const bool greeley = std::any_of(g.areas.begin(), g.areas.end(), [](const GroundArea& a) {
      return a.groundClass == GroundClass::Park && a.name == "Greeley Square Park";
    });
    CHECK(greeley);
    CHECK(areasOf(g, GroundClass::Green) >= 1);  // the pitches
    for (const GroundArea& a : g.areas) {
      REQUIRE(!a.rings.empty());
      CHECK(a.rings[0].size() >= 3);
      CHECK(a.rings[0].front() != a.rings[0].back());  // closed implicitly
    }
  }
  SECTION("places: nodes, a way and a boundary relation, at their positions") {
    for (const char* name : {"Koreatown", "Midtown South", "Chelsea District"}) {
      const GroundPlace* p = placeNamed(g, name);
      INFO(name);
      REQUIRE(p != nullptr);
      CHECK(p->kind == GroundLabelKind::Neighbourhood);
    }
    CHECK(g.places.size() >= 3);
    // Koreatown's node (40.7477 N, 73.9867 W) lies within a kilometre of the Empire State Building's
    // neighbourhood the fixture is centred on.
    const GroundPlace* korea = placeNamed(g, "Koreatown");
    CHECK(std::hypot(korea->position.x, korea->position.y) < 1500.0);
  }
  SECTION("the ground does not move the projection: same origin and buildings as without it") {
    IngestOptions off;
    off.ground = false;
    const Ingested without = ingest({sharedData("osm/fixture-midtown-empire-state.osm")}, off);
    REQUIRE(without.model.ok());
    CHECK(without.model->originLon == in.model->originLon);
    CHECK(without.model->originLat == in.model->originLat);
    CHECK(without.model->buildings.size() == in.model->buildings.size());
    CHECK(without.model->ground.empty());
    CHECK(without.model->ground.skipped.empty());
    CHECK(without.stats.groundLines == 0);
    CHECK(without.stats.groundAreas == 0);
    CHECK(without.stats.groundPlaces == 0);
    CHECK(without.stats.groundSkipped == 0);
  }
  // The extract's streets run a few hundred metres past its buildings, not kilometres.
  CHECK(farthestPointM(g) < 5000.0);
}

TEST_CASE("Liechtenstein: the Rhine, forests, lakes and villages", "[ingest][osm][ground]") {
  const Ingested& in = liechtenstein();
  INFO("the Liechtenstein extract comes from Debian's osm2pgsql source package through scripts/setup.sh");
  REQUIRE(in.model.ok());
  const GroundFeatures& g = in.model->ground;

  const auto rhine = linesNamed(g, "Rhein");
  REQUIRE(!rhine.empty());
  for (const GroundLine* l : rhine) {
    CHECK(l->groundClass == GroundClass::Water);
    CHECK(l->widthM == 30.0f);  // waterway=river
  }
  CHECK(linesOf(g, GroundClass::Water) > 10);  // streams and canals too
  CHECK(areasOf(g, GroundClass::Forest) >= 50);
  CHECK(areasOf(g, GroundClass::Water) >= 10);  // lakes and ponds (natural=water), the riverbank
  CHECK(linesOf(g, GroundClass::Street) + linesOf(g, GroundClass::Major) > 1000);
  CHECK(linesOf(g, GroundClass::Path) > 100);

  const GroundPlace* vaduz = placeNamed(g, "Vaduz");
  REQUIRE(vaduz != nullptr);
  CHECK(vaduz->kind == GroundLabelKind::Settlement);
  const GroundPlace* malbun = placeNamed(g, "Malbun");
  REQUIRE(malbun != nullptr);
  CHECK(malbun->kind == GroundLabelKind::Settlement);  // a hamlet
  CHECK(malbun->rank > vaduz->rank);                   // a town's name wins over a hamlet's
  const GroundPlace* schaan = placeNamed(g, "Schaan");
  REQUIRE(schaan != nullptr);
  // Schaan lies 2.9 km north and a little west of Vaduz (47.1663 N 9.5103 E; 47.1393 N 9.5228 E).
  const glm::dvec2 d = schaan->position - vaduz->position;
  CHECK(d.y == Approx(3008.0).margin(60.0));
  CHECK(d.x == Approx(-947.0).margin(60.0));
  // Broken multipolygons at the extract's edge are counted, not fatal.
  for (const auto& [reason, n] : g.skipped) CHECK(n > 0);
  CHECK(in.stats.groundSkipped > 0);
}

TEST_CASE("The tag table: classes, widths, skipped objects", "[ingest][osm][ground]") {
  // Ways along a row of nodes; each names its tags, so the table below checks them by name.
  std::string nodes;
  for (int i = 0; i < 40; ++i) nodes += node(i + 1, 9.49 + 0.0005 * i, 47.001);
  nodes += node(101, 9.50, 47.002) + node(102, 9.501, 47.002) + node(103, 9.501, 47.003) + node(104, 9.50, 47.003);
  int id = 1;
  auto line = [&](const std::string& tags) {
    const int n = id++;
    return way(n, {1 + n % 30, 2 + n % 30, 3 + n % 30}, tags);
  };
  auto area = [&](const std::string& tags) { return way(id++, {101, 102, 103, 104, 101}, tags); };
  const std::string ways =
      line(tag("highway", "motorway") + tag("name", "motorway")) +
      line(tag("highway", "trunk_link") + tag("name", "trunk_link")) +
      line(tag("highway", "primary") + tag("name", "primary")) +
      line(tag("highway", "secondary") + tag("name", "secondary")) +
      line(tag("highway", "tertiary") + tag("name", "tertiary")) +
      line(tag("highway", "residential") + tag("name", "residential")) +
      line(tag("highway", "living_street") + tag("name", "living_street")) +
      line(tag("highway", "service") + tag("name", "service")) +
      line(tag("highway", "footway") + tag("name", "footway")) + line(tag("highway", "steps") + tag("name", "steps")) +
      line(tag("highway", "residential") + tag("width", "7.5") + tag("name", "width 7.5")) +
      line(tag("highway", "residential") + tag("width", "12 m") + tag("name", "width 12 m")) +
      line(tag("highway", "residential") + tag("width", "500") + tag("name", "width 500")) +
      line(tag("highway", "residential") + tag("width", "wide") + tag("name", "width wide")) +
      line(tag("railway", "tram") + tag("name", "tram")) + line(tag("waterway", "river") + tag("name", "river")) +
      line(tag("waterway", "canal") + tag("name", "canal")) + line(tag("waterway", "stream") + tag("name", "stream")) +
      // Not drawn: tunnels, a subway, a culvert, a road under construction, a bus route's stop.
      line(tag("highway", "primary") + tag("tunnel", "yes") + tag("name", "tunnel")) +
      line(tag("railway", "subway") + tag("name", "subway")) +
      line(tag("waterway", "stream") + tag("tunnel", "culvert") + tag("name", "culvert")) +
      line(tag("highway", "construction") + tag("name", "construction")) +
      line(tag("highway", "proposed") + tag("name", "proposed")) + area(tag("natural", "water") + tag("name", "lake")) +
      area(tag("landuse", "reservoir")) + area(tag("waterway", "riverbank")) +
      area(tag("leisure", "park") + tag("name", "park")) + area(tag("leisure", "garden")) +
      area(tag("landuse", "forest")) + area(tag("natural", "scrub")) + area(tag("landuse", "cemetery")) +
      area(tag("leisure", "pitch")) + area(tag("highway", "pedestrian") + tag("area", "yes") + tag("name", "square")) +
      area(tag("landuse", "residential")) +  // not drawn: the buildings show it
      area(tag("place", "village") + tag("name", "Area Village"));
  TempDir dir;
  const Ingested in = ingest({dir.write("table.osm", osm(nodes, ways))});
  REQUIRE(in.model.ok());
  const GroundFeatures& g = in.model->ground;

  struct Row {
    const char* name;
    GroundClass groundClass;
    float widthM;
  };
  const Row rows[] = {
      {"motorway", GroundClass::Motorway, 20.0f},
      {"trunk_link", GroundClass::Major, 14.0f},
      {"primary", GroundClass::Major, 14.0f},
      {"secondary", GroundClass::Major, 12.0f},
      {"tertiary", GroundClass::Street, 10.0f},
      {"residential", GroundClass::Street, 8.0f},
      {"living_street", GroundClass::Street, 8.0f},
      {"service", GroundClass::Street, 5.0f},
      {"footway", GroundClass::Path, 3.0f},
      {"steps", GroundClass::Path, 3.0f},
      {"width 7.5", GroundClass::Street, 7.5f},
      {"width 12 m", GroundClass::Street, 12.0f},
      {"width 500", GroundClass::Street, 8.0f},
      {"width wide", GroundClass::Street, 8.0f},
      {"tram", GroundClass::Rail, 4.0f},
      {"river", GroundClass::Water, 30.0f},
      {"canal", GroundClass::Water, 15.0f},
      {"stream", GroundClass::Water, 4.0f},
  };
  for (const Row& row : rows) {
    INFO(row.name);
    const auto found = linesNamed(g, row.name);
    REQUIRE(found.size() == 1);
    CHECK(found[0]->groundClass == row.groundClass);
    CHECK(found[0]->widthM == row.widthM);
    CHECK(found[0]->points.size() == 3);
  }
  for (const char* name : {"tunnel", "subway", "culvert", "construction", "proposed"}) {
    INFO(name);
    CHECK(linesNamed(g, name).empty());
  }
  CHECK(g.lines.size() == std::size(rows));
  CHECK(skipped(g, "tunnel") == 3);
  // Motorways' names win over streets', streets' over footways'.
  CHECK(linesNamed(g, "motorway")[0]->rank < linesNamed(g, "residential")[0]->rank);
  CHECK(linesNamed(g, "residential")[0]->rank < linesNamed(g, "footway")[0]->rank);

  CHECK(areasOf(g, GroundClass::Water) == 3);
  CHECK(areasOf(g, GroundClass::Park) == 2);
  CHECK(areasOf(g, GroundClass::Forest) == 2);
  CHECK(areasOf(g, GroundClass::Green) == 2);
  CHECK(areasOf(g, GroundClass::Path) == 1);
  CHECK(g.areas.size() == 10);
  for (const GroundArea& a : g.areas) {
    REQUIRE(a.rings.size() == 1);
    CHECK(a.rings[0].size() == 4);  // the closing node is not repeated
  }
  const GroundPlace* village = placeNamed(g, "Area Village");
  REQUIRE(village != nullptr);
  CHECK(village->kind == GroundLabelKind::Settlement);
  // At the square's centre: the middle of its corners, in the city frame.
  const auto& square = g.areas.front().rings[0];
  glm::dvec2 mean{0.0};
  for (const glm::dvec2& p : square) mean += p / 4.0;
  CHECK(village->position.x == Approx(mean.x).margin(0.05));
  CHECK(village->position.y == Approx(mean.y).margin(0.05));
}

TEST_CASE("Hostile ground input is counted, never fatal", "[ingest][osm][ground]") {
  const std::string nodes = node(1, 9.500, 47.001) + node(2, 9.501, 47.001) + node(3, 9.501, 47.002) +
                            node(4, 9.500, 47.002) + node(5, 9.502, 47.001) + node(6, 9.503, 47.001) +
                            node(7, 9.503, 47.002) +
                            // Far beyond the city's projection (30 degrees east): a line through it is left out.
                            node(8, 39.5, 47.0) + node(20, 9.5005, 47.0015, tag("place", "neighbourhood")) +  // no name
                            node(21, 9.5006, 47.0016, tag("place", "suburb") + tag("name", "Tab&#9;and&#10;newline")) +
                            node(22, 9.5007, 47.0017, tag("place", "locality") + tag("name", "not a settlement"));
  const std::string ways =
      // A water multipolygon whose outer ring does not close (3 of a square's 4 sides).
      way(10, {1, 2, 3}, "") + way(11, {3, 4}, "") +
      // A highway of one node, and one of a node repeated.
      way(12, {5}, tag("highway", "residential") + tag("name", "One Node Street")) +
      way(13, {5, 5}, tag("highway", "residential")) +
      // A name with control characters (the ones XML can carry), kept as it is: the tiler cleans names.
      way(14, {5, 6, 7}, tag("highway", "primary") + tag("name", "Bell&#9;Street&#13;")) +
      // Nodes missing from the file: the pieces between them are kept.
      way(15, {1, 2, 404, 3, 4}, tag("highway", "service")) + way(16, {404, 405}, tag("highway", "service")) +
      way(17, {5, 6, 8}, tag("highway", "motorway")) +
      // An open ring tagged as a lake, and a closed way of three nodes.
      way(18, {1, 2, 3}, tag("natural", "water")) + way(19, {1, 2, 1}, tag("leisure", "park")) +
      // A coastline (land on its left), a relation with a missing member, an empty one.
      way(30, {5, 6, 7}, tag("natural", "coastline"));
  const std::string relations =
      "<relation id=\"40\"><member type=\"way\" ref=\"10\" role=\"outer\"/><member type=\"way\" ref=\"11\" "
      "role=\"outer\"/>" +
      tag("type", "multipolygon") + tag("natural", "water") + tag("name", "Broken Lake") + "</relation>\n" +
      "<relation id=\"41\"><member type=\"way\" ref=\"999\" role=\"outer\"/>" + tag("type", "multipolygon") +
      tag("leisure", "park") + "</relation>\n" + "<relation id=\"42\">" + tag("type", "multipolygon") +
      tag("landuse", "forest") + "</relation>\n" +
      "<relation id=\"43\"><member type=\"way\" ref=\"10\" role=\"outer\"/>" + tag("type", "boundary") +
      tag("boundary", "place") + tag("place", "quarter") + tag("name", "Open Quarter") + "</relation>\n";
  TempDir dir;
  const Ingested in = ingest({dir.write("hostile.osm", osm(nodes, ways, relations))});
  REQUIRE(in.model.ok());
  const GroundFeatures& g = in.model->ground;
  CHECK(in.model->buildings.size() == 1);

  CHECK(skipped(g, "broken-multipolygon") == 2);      // r40 (open ring) and r43
  CHECK(skipped(g, "incomplete-multipolygon") == 2);  // r41 (no way 999) and r42 (no member)
  CHECK(skipped(g, "too-few-points") == 3);           // w12, w13 (one point after the repeat), w19
  CHECK(skipped(g, "unclosed-area") == 1);            // w18
  CHECK(skipped(g, "missing-nodes") == 2);            // w15, w16
  CHECK(skipped(g, "outside-projection") == 1);       // w17
  CHECK(skipped(g, "unnamed-place") == 1);            // n20
  CHECK(in.stats.groundSkipped == 12);
  CHECK(g.areas.empty());

  const auto bell = linesNamed(g, "Bell\tStreet\r");
  REQUIRE(bell.size() == 1);
  CHECK(bell[0]->groundClass == GroundClass::Major);
  // w15 in two pieces around the missing node; w16 has nothing left.
  std::size_t service = 0;
  for (const GroundLine& l : g.lines) {
    if (l.groundClass == GroundClass::Street && l.widthM == 5.0f) {
      ++service;
      CHECK(l.points.size() == 2);
    }
  }
  CHECK(service == 2);
  CHECK(g.lines.size() == 3);

  REQUIRE(g.places.size() == 1);
  CHECK(g.places[0].name == "Tab\tand\nnewline");
  CHECK(g.places[0].kind == GroundLabelKind::Neighbourhood);
  REQUIRE(g.coastlines.size() == 1);
  CHECK(g.coastlines[0].size() == 3);
}

TEST_CASE("GeoJSON inputs have no ground", "[ingest][geojson][ground]") {
  const Ingested in = ingest({fixture("footprints.geojson")});
  REQUIRE(in.model.ok());
  CHECK(in.model->ground.empty());
  CHECK(in.model->ground.skipped.empty());
}

namespace {

std::vector<const GroundBoundary*> boundariesOf(const GroundFeatures& ground, const std::string& source) {
  std::vector<const GroundBoundary*> found;
  for (const GroundBoundary& b : ground.boundaries) {
    if (b.source == source) found.push_back(&b);
  }
  return found;
}

std::vector<glm::dvec2> buildingCentres(const CityModel& model) {
  std::vector<glm::dvec2> centres;
  for (const Building& b : model.buildings) centres.emplace_back(b.attributes.centroidX, b.attributes.centroidY);
  return centres;
}

}  // namespace

TEST_CASE("Boundaries for districts: Liechtenstein's municipalities and Midtown's neighbourhoods",
          "[ingest][osm][ground][districts]") {
  SECTION("Liechtenstein: its eleven municipalities (admin_level 8) divide the country") {
    const Ingested& in = liechtenstein();
    REQUIRE(in.model.ok());
    const GroundFeatures& g = in.model->ground;
    const auto municipalities = boundariesOf(g, "boundary=administrative admin_level=8");
    std::set<std::string> names;
    for (const GroundBoundary* b : municipalities) {
      names.insert(b->name);
      CHECK(b->fineness == 8);
      REQUIRE(!b->rings.empty());
      CHECK(b->rings[0].size() >= 3);
      CHECK(b->rings[0].front() != b->rings[0].back());  // closed implicitly
    }
    CHECK(names.size() == 11);
    for (const char* name : {"Vaduz", "Schaan", "Balzers", "Triesenberg", "Eschen", "Ruggell"}) {
      INFO(name);
      CHECK(names.count(name) == 1);
    }
    // The districts the city gets: the finest set that divides it, the municipalities, not the
    // country (admin_level 2: one area) nor inferred.
    const auto districts = chooseDistricts(g, buildingCentres(*in.model), "OpenStreetMap");
    REQUIRE(districts.has_value());
    CHECK(districts->source == "OpenStreetMap boundary=administrative admin_level=8 areas");
    CHECK(!districts->inferred);
    CHECK(districts->districts.size() == 11);
    CHECK(districts->coverage > 0.99);
    std::uint64_t inside = 0;
    for (const auto& d : districts->districts) inside += d.buildings;
    CHECK(inside == static_cast<std::uint64_t>(
                        std::llround(districts->coverage * static_cast<double>(in.model->buildings.size()))));
    // Vaduz, the capital, had about a hundred buildings mapped in 2013.
    const auto vaduz = std::find_if(districts->districts.begin(), districts->districts.end(),
                                    [](const auto& d) { return d.name == "Vaduz"; });
    REQUIRE(vaduz != districts->districts.end());
    CHECK(vaduz->buildings > 50);
  }
  SECTION("Midtown: neighbourhood areas cut by the extract are counted; the districts are inferred") {
    const Ingested& in = midtownFixture();
    REQUIRE(in.model.ok());
    const GroundFeatures& g = in.model->ground;
    // Herald Square (place=neighbourhood) and Koreatown (boundary=place) relations are whole in the
    // fixture, and the Chelsea District way; Chelsea's relation, Murray Hill, the Garment District,
    // Midtown South and the community boards are not.
    std::set<std::string> names;
    for (const GroundBoundary& b : g.boundaries) names.insert(b.name);
    CHECK(names == std::set<std::string>{"Chelsea District", "Herald Square", "Koreatown"});
    CHECK(skipped(g, "incomplete-boundary") == 6);
    // Two small areas hold few of the buildings: each building goes to its nearest neighbourhood name.
    const auto districts = chooseDistricts(g, buildingCentres(*in.model), "OpenStreetMap");
    REQUIRE(districts.has_value());
    CHECK(districts->inferred);
    CHECK(districts->coverage == 1.0);
    std::set<std::string> districtNames;
    std::uint64_t buildings = 0;
    for (const auto& d : districts->districts) {
      districtNames.insert(d.name);
      buildings += d.buildings;
      CHECK(d.buildings > 0);
    }
    CHECK(districtNames == std::set<std::string>{"Herald Square", "Koreatown", "Midtown South"});
    CHECK(buildings == in.model->buildings.size());
  }
}
