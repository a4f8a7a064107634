// The ground tiler (qv/prep/GroundTiler.h): features in, ground files out, read back with the
// viewer's codec. Streets become ribbons cut exactly at the cells, areas keep their area and their
// holes, coastlines split the cells into land and sea, inner levels keep what is seen from afar,
// names are placed and cleaned, and the same input always gives the same bytes.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "qv/core/Crc32.h"
#include "qv/format/GroundTile.h"
#include "qv/prep/GroundTiler.h"

namespace fs = std::filesystem;
using namespace qv;
using namespace qv::prep;

namespace {

// A fresh directory under the system's temporary directory, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = (fs::temp_directory_path() / ("qv-ground-" + std::to_string(getpid()) + "-" + std::to_string(counter++)))
                .string();
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::vector<std::uint8_t> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Cell {
  GroundNode node;
  GroundTile tile;
};

// Every file of the layer, decoded; checks sizes, checksums, node order and the tile contract.
struct Ground {
  GroundTilerReport report;
  std::vector<Cell> cells;

  [[nodiscard]] const GroundLayer& layer() const { return report.layer; }

  // The area of the class's triangles over the cells of one level, square metres.
  [[nodiscard]] double area(int level, GroundClass c) const {
    double sum = 0.0;
    for (const Cell& cell : cells) {
      if (cell.node.level != level) continue;
      for (const GroundRun& run : cell.tile.runs) {
        if (run.groundClass != c) continue;
        for (std::uint32_t t = run.firstTriangle; t < run.firstTriangle + run.triangleCount; ++t) {
          const glm::vec2 a = cell.tile.vertices[cell.tile.triangles[3 * t]];
          const glm::vec2 b = cell.tile.vertices[cell.tile.triangles[3 * t + 1]];
          const glm::vec2 d = cell.tile.vertices[cell.tile.triangles[3 * t + 2]];
          sum += 0.5 * (static_cast<double>(b.x - a.x) * (d.y - a.y) - static_cast<double>(d.x - a.x) * (b.y - a.y));
        }
      }
    }
    return sum;
  }

  // Cells of a level drawing the class.
  [[nodiscard]] int cellsWith(int level, GroundClass c) const {
    int n = 0;
    for (const Cell& cell : cells) {
      if (cell.node.level != level) continue;
      for (const GroundRun& run : cell.tile.runs) n += run.groundClass == c && run.triangleCount > 0 ? 1 : 0;
    }
    return n;
  }

  // True when a triangle of the class at the level covers the point (city frame).
  [[nodiscard]] bool covers(int level, GroundClass c, glm::dvec2 p) const {
    for (const Cell& cell : cells) {
      if (cell.node.level != level) continue;
      const glm::dvec2 q = p - glm::dvec2(cell.tile.originX, cell.tile.originY);
      for (const GroundRun& run : cell.tile.runs) {
        if (run.groundClass != c) continue;
        for (std::uint32_t t = run.firstTriangle; t < run.firstTriangle + run.triangleCount; ++t) {
          glm::dvec2 v[3];
          for (std::uint32_t k = 0; k < 3; ++k) v[k] = glm::dvec2(cell.tile.vertices[cell.tile.triangles[3 * t + k]]);
          bool inside = true;
          for (int k = 0; k < 3; ++k) {
            const glm::dvec2 a = v[k], b = v[(k + 1) % 3];
            if ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x) < 0.0) inside = false;
          }
          if (inside) return true;
        }
      }
    }
    return false;
  }

  [[nodiscard]] std::vector<GroundLabel> labels(int level) const {
    std::vector<GroundLabel> out;
    for (const Cell& cell : cells) {
      if (cell.node.level == level) out.insert(out.end(), cell.tile.labels.begin(), cell.tile.labels.end());
    }
    return out;
  }
};

Ground tile(const GroundFeatures& features, const Rect& city, const std::string& dir, GroundTilerOptions options = {}) {
  auto report = writeGroundTiles(features, city, dir, options);
  INFO((report.ok() ? std::string() : report.error()));
  REQUIRE(report.ok());
  Ground g;
  g.report = std::move(report).value();
  std::uint64_t bytes = 0, triangles = 0;
  for (std::size_t i = 0; i < g.layer().nodes.size(); ++i) {
    const GroundNode& node = g.layer().nodes[i];
    if (i > 0) {
      const GroundNode& before = g.layer().nodes[i - 1];
      CHECK(std::tie(before.level, before.y, before.x) < std::tie(node.level, node.y, node.x));
    }
    CHECK(node.level < g.layer().levels);
    CHECK(node.file == groundFileName(node.level, node.x, node.y));
    CHECK((node.geometricErrorM == 0.0f) == (node.level + 1 == g.layer().levels));
    const std::vector<std::uint8_t> file = readBytes(dir + "/" + node.file);
    CHECK(file.size() == node.bytes);
    CHECK(crc32(file) == node.crc32);
    bytes += file.size();
    auto decoded = decodeGroundTile(file, node.file);
    INFO((decoded.ok() ? std::string() : decoded.error()));
    REQUIRE(decoded.ok());
    const double side = g.layer().size / std::ldexp(1.0, node.level);
    CHECK(decoded->originX == Approx(g.layer().minX + node.x * side));
    CHECK(decoded->originY == Approx(g.layer().minY + node.y * side));
    CHECK(decoded->extent == Approx(side));
    for (const glm::vec2& v : decoded->vertices) {
      CHECK(v.x >= 0.0f);
      CHECK(v.y >= 0.0f);
      CHECK(v.x <= decoded->extent);
      CHECK(v.y <= decoded->extent);
    }
    triangles += decoded->triangles.size() / 3;
    g.cells.push_back({node, std::move(decoded).value()});
  }
  CHECK(bytes == g.layer().bytes);
  CHECK(triangles == g.report.triangles);
  return g;
}

// A 2400 m city from (0, 0): three levels of 2400, 1200 and 600 m cells with the default options.
const Rect kCity{0.0f, 0.0f, 2400.0f, 2400.0f};

GroundLine line(GroundClass c, std::vector<glm::dvec2> points, float widthM, std::string name = {}) {
  GroundLine l;
  l.groundClass = c;
  l.points = std::move(points);
  l.widthM = widthM;
  l.name = std::move(name);
  return l;
}

GroundArea area(GroundClass c, std::vector<std::vector<glm::dvec2>> rings, std::string name = {}) {
  GroundArea a;
  a.groundClass = c;
  a.rings = std::move(rings);
  a.name = std::move(name);
  return a;
}

std::vector<glm::dvec2> square(double minX, double minY, double maxX, double maxY, bool clockwise = false) {
  if (clockwise) return {{minX, minY}, {minX, maxY}, {maxX, maxY}, {maxX, minY}};
  return {{minX, minY}, {maxX, minY}, {maxX, maxY}, {minX, maxY}};
}

}  // namespace

TEST_CASE("The pyramid is a square around the city in levels down to the leaf size", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  f.lines.push_back(line(GroundClass::Street, {{100, 100}, {200, 100}}, 8.0f));
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.layer().minX == Approx(0.0));
  CHECK(g.layer().minY == Approx(0.0));
  CHECK(g.layer().size == Approx(2400.0));
  CHECK(g.layer().levels == 3);
  CHECK(g.layer().features.at("street") == 1);
  // The street's leaf, and its ancestors as empty tiles so that the pyramid is connected.
  REQUIRE(g.cells.size() == 3);
  CHECK(g.cells[0].node.level == 0);
  CHECK(g.cells[0].tile.triangles.empty());
  CHECK(g.cells[1].node.level == 1);
  CHECK(g.cells[2].node.level == 2);
  CHECK(g.cells[2].node.x == 0);
  CHECK(g.cells[2].node.y == 0);
  CHECK(g.report.areaKm2 == Approx(0.36));
}

TEST_CASE("Nothing to tile writes nothing", "[prep][ground]") {
  TempDir dir;
  const Ground none = tile({}, Rect{}, dir.path());
  CHECK(none.layer().nodes.empty());
  CHECK(none.layer().levels == 0);
  CHECK(!fs::exists(dir.path() + "/ground"));
  // A city without ground features: a layer without nodes.
  const Ground empty = tile({}, kCity, dir.path());
  CHECK(empty.layer().nodes.empty());
}

TEST_CASE("A street across several leaves is a ribbon in each, cut exactly at the cells", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  const double widthM = 10.0;
  SECTION("straight along a row of leaves") {
    f.lines.push_back(line(GroundClass::Street, {{100, 900}, {2300, 900}}, static_cast<float>(widthM)));
    const Ground g = tile(f, kCity, dir.path());
    CHECK(g.cellsWith(2, GroundClass::Street) == 4);
    // Length × width, plus the two round ends (half a regular octagon each: √2 r²).
    const double expected = 2200.0 * widthM + 2.0 * std::sqrt(2.0) * 25.0;
    CHECK(g.area(2, GroundClass::Street) == Approx(expected).epsilon(0.002));
    CHECK(g.report.leafTriangles > 0);
  }
  SECTION("diagonal with bends, through corners of cells") {
    f.lines.push_back(
        line(GroundClass::Street, {{50, 50}, {1200, 1200}, {2350, 1150}, {2350, 2350}}, static_cast<float>(widthM)));
    const Ground g = tile(f, kCity, dir.path());
    CHECK(g.cellsWith(2, GroundClass::Street) >= 8);
    const double length = std::sqrt(2.0) * 1150.0 + std::sqrt(1150.0 * 1150.0 + 50.0 * 50.0) + 1200.0;
    // The bends add their outer wedges; the inner sides overlap (counted twice here).
    CHECK(g.area(2, GroundClass::Street) == Approx(length * widthM).epsilon(0.03));
  }
}

TEST_CASE("A square lake keeps its area across cells and levels", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  f.areas.push_back(area(GroundClass::Water, {square(1000, 500, 1800, 1300)}));
  const Ground g = tile(f, kCity, dir.path());
  for (int level = 0; level < 3; ++level) {
    INFO("level " << level);
    CHECK(g.area(level, GroundClass::Water) == Approx(800.0 * 800.0).epsilon(1e-4));
  }
  // Columns 1 and 2 (the east shore is the boundary of column 3), rows 0 to 2.
  CHECK(g.cellsWith(2, GroundClass::Water) == 6);
}

TEST_CASE("A lake with an island leaves the island open", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  // The island crosses a cell boundary (x = 1200), the lake too; the hole is clockwise, then not.
  const bool clockwiseHole = GENERATE(false, true);
  f.areas.push_back(
      area(GroundClass::Water, {square(700, 700, 1700, 1700), square(1100, 1000, 1300, 1100, clockwiseHole)}));
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.area(2, GroundClass::Water) == Approx(1000.0 * 1000.0 - 200.0 * 100.0).epsilon(1e-4));
  CHECK(!g.covers(2, GroundClass::Water, {1150.0, 1050.0}));
  CHECK(!g.covers(2, GroundClass::Water, {1250.0, 1050.0}));
  CHECK(g.covers(2, GroundClass::Water, {900.0, 900.0}));
}

TEST_CASE("A concave area leaving and entering a cell is cut without bridges", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  // A U open to the north whose arms reach into the leaf above (y > 600) as two separate pieces.
  f.areas.push_back(
      area(GroundClass::Park,
           {{{100, 100}, {500, 100}, {500, 900}, {400, 900}, {400, 200}, {200, 200}, {200, 900}, {100, 900}}}));
  const Ground g = tile(f, kCity, dir.path());
  const double expected = 400.0 * 100.0 + 2.0 * 100.0 * 700.0;
  CHECK(g.area(2, GroundClass::Park) == Approx(expected).epsilon(1e-4));
  CHECK(!g.covers(2, GroundClass::Park, {300.0, 700.0}));
  CHECK(g.covers(2, GroundClass::Park, {150.0, 700.0}));
}

TEST_CASE("A closed coastline makes land inside and sea around it", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  // An island (land on the left: counter-clockwise) in two ways, given out of order.
  f.coastlines.push_back({{800, 800}, {1600, 800}, {1600, 1600}});
  f.coastlines.push_back({{1600, 1600}, {800, 1600}, {800, 800}});
  std::swap(f.coastlines[0], f.coastlines[1]);
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.layer().skipped.count("unclosed-coastline") == 0);
  for (int level = 0; level < 3; ++level) {
    INFO("level " << level);
    CHECK(g.area(level, GroundClass::Land) == Approx(800.0 * 800.0).epsilon(1e-4));
    CHECK(g.area(level, GroundClass::Land) + g.area(level, GroundClass::Water) ==
          Approx(2400.0 * 2400.0).epsilon(1e-5));
  }
  // Every cell is land or sea: all 16 leaves have a file.
  CHECK(g.report.areaKm2 == Approx(2.4 * 2.4));
  CHECK(g.covers(2, GroundClass::Water, {100.0, 100.0}));
  CHECK(g.covers(2, GroundClass::Land, {1200.0, 1200.0}));
  CHECK(!g.covers(2, GroundClass::Water, {1200.0, 1200.0}));
}

TEST_CASE("A coastline that does not close is left out and counted", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  f.coastlines.push_back({{0, 1000}, {800, 1100}, {2400, 1000}});
  f.lines.push_back(line(GroundClass::Street, {{100, 100}, {200, 100}}, 8.0f));
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.layer().skipped.at("unclosed-coastline") == 1);
  CHECK(g.area(2, GroundClass::Land) == 0.0);
  CHECK(g.area(2, GroundClass::Water) == 0.0);
}

TEST_CASE("Inner levels keep motorways and large areas, leaves everything", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  f.lines.push_back(line(GroundClass::Street, {{100, 300}, {2300, 300}}, 8.0f));
  f.lines.push_back(line(GroundClass::Motorway, {{100, 1900}, {2300, 1900}}, 20.0f));
  f.areas.push_back(area(GroundClass::Park, {square(100, 1000, 105, 1005)}));  // 25 m²
  GroundTilerOptions options;
  options.leafCellM = 300.0;  // four levels: 2400, 1200, 600 and 300 m
  const Ground g = tile(f, kCity, dir.path(), options);
  REQUIRE(g.layer().levels == 4);
  for (int level = 0; level < 4; ++level) {
    INFO("level " << level);
    CHECK(g.cellsWith(level, GroundClass::Motorway) > 0);
    CHECK((g.cellsWith(level, GroundClass::Street) > 0) == (level >= 2));
    CHECK((g.cellsWith(level, GroundClass::Park) > 0) == (level >= 2));  // (600 / 128)² = 22 m², (1200 / 128)² = 88 m²
  }
  // The motorway is at least 1.5 × the geometric error wide at the root (2400 / 256 × 1.5 = 14 m < 20 m).
  CHECK(g.area(0, GroundClass::Motorway) == Approx(2200.0 * 20.0).epsilon(0.01));
}

TEST_CASE("A long enough named street gets a label along it", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  // Drawn from east to west and from north-east to south-west: the text still reads left to right.
  f.lines.push_back(line(GroundClass::Street, {{550, 300}, {350, 300}}, 8.0f, "Main Street"));
  f.lines.push_back(line(GroundClass::Major, {{1100, 1100}, {300, 300}}, 12.0f, "Diagonal Avenue"));
  f.lines.push_back(line(GroundClass::Street, {{100, 500}, {120, 500}}, 8.0f, "Short Lane"));
  f.lines.push_back(line(GroundClass::Water, {{100, 1000}, {300, 1200 - 1e-3}}, 20.0f, "Quiet River"));
  const Ground g = tile(f, kCity, dir.path());
  const std::vector<GroundLabel> leaf = g.labels(2);
  std::map<std::string, GroundLabel> byText;
  for (const GroundLabel& l : leaf) byText[l.text] = l;
  REQUIRE(byText.count("Main Street") == 1);
  const GroundLabel& main = byText["Main Street"];
  CHECK(main.kind == GroundLabelKind::Street);
  CHECK(main.rank == 140);
  CHECK(main.angleRad == Approx(0.0).margin(1e-6));
  CHECK(main.lengthM == Approx(200.0));
  CHECK(main.position.x == Approx(450.0).margin(0.01));
  CHECK(main.position.y == Approx(300.0).margin(0.01));
  REQUIRE(byText.count("Diagonal Avenue") == 1);
  CHECK(byText["Diagonal Avenue"].angleRad == Approx(std::numbers::pi / 4.0).margin(1e-6));
  CHECK(byText["Diagonal Avenue"].rank == 100);
  CHECK(byText.count("Short Lane") == 0);
  // A river's name: along its direction, at a point (lengthM is for streets).
  REQUIRE(byText.count("Quiet River") == 1);
  CHECK(byText["Quiet River"].kind == GroundLabelKind::Water);
  CHECK(byText["Quiet River"].rank == 50);
  CHECK(byText["Quiet River"].angleRad == Approx(std::numbers::pi / 4.0).margin(1e-4));
  CHECK(byText["Quiet River"].lengthM == 0.0f);
  CHECK(byText["Quiet River"].position.y == Approx(500.0).margin(0.01));  // in the leaf (0, 1)
  // The major road crosses the corner (600, 600): one label in each of its two leaves.
  int diagonal = 0;
  for (const GroundLabel& l : leaf) diagonal += l.text == "Diagonal Avenue" ? 1 : 0;
  CHECK(diagonal == 2);
  // Street names only at the two finest levels, major roads' also one coarser (here: every level).
  for (const GroundLabel& l : g.labels(0)) CHECK(l.text != "Main Street");
  int rootDiagonal = 0;
  for (const GroundLabel& l : g.labels(0)) rootDiagonal += l.text == "Diagonal Avenue" ? 1 : 0;
  CHECK(rootDiagonal == 1);
  CHECK(g.layer().features.at("labels") == 4);
}

TEST_CASE("Labels are cleaned of control characters, deduplicated and ranked", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  f.lines.push_back(line(GroundClass::Street, {{100, 100}, {300, 100}}, 8.0f, "Broad\x01way\nAvenue"));
  f.lines.push_back(line(GroundClass::Street, {{100, 200}, {300, 200}}, 8.0f, "\x02\x03"));
  // The same name twice, 20 m apart: one label.
  f.lines.push_back(line(GroundClass::Street, {{100, 400}, {300, 400}}, 8.0f, "Twin Road"));
  f.lines.push_back(line(GroundClass::Street, {{100, 420}, {250, 420}}, 8.0f, "Twin Road"));
  GroundPlace town;
  town.kind = GroundLabelKind::Settlement;
  town.position = {500, 500};
  town.name = "Springfield";
  f.places.push_back(town);
  GroundPlace quarter;
  quarter.kind = GroundLabelKind::Neighbourhood;
  quarter.position = {450, 450};
  quarter.name = std::string(300, 'x');
  f.places.push_back(quarter);
  f.areas.push_back(area(GroundClass::Water, {square(100, 500, 110, 508)}, "Pond"));  // 80 m²
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.layer().skipped.at("label-cleaned") == 3);  // the control characters, the empty name, the long name
  const std::vector<GroundLabel> leaf = g.labels(2);
  REQUIRE(leaf.size() == 5);
  CHECK(leaf[0].text == "Springfield");
  CHECK(leaf[0].rank == 10);
  CHECK(leaf[1].kind == GroundLabelKind::Neighbourhood);
  CHECK(leaf[1].text.size() == 255);
  CHECK(leaf[2].text == "Pond");
  CHECK(leaf[2].kind == GroundLabelKind::Water);
  CHECK(leaf[2].position.x == Approx(105.0).margin(0.01));
  CHECK(leaf[2].position.y == Approx(504.0).margin(0.01));
  CHECK(leaf[3].text == "Broadway Avenue");
  CHECK(leaf[4].text == "Twin Road");
  CHECK(leaf[4].lengthM == Approx(200.0));
  // Places at every level, streets at the two finest, the pond where it is drawn: the leaves only
  // ((1200 / 128)² = 88 m² at level 1).
  CHECK(g.labels(0).size() == 2);
  CHECK(g.labels(1).size() == 4);
}

TEST_CASE("Broken features are skipped and counted, never a crash", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  f.lines.push_back(line(GroundClass::Street, {{0, 0}, {nan, 5}}, 8.0f));
  f.lines.push_back(line(GroundClass::Street, {{0, 0}, {inf, 5}}, 8.0f));
  f.lines.push_back(line(GroundClass::Street, {{10, 10}, {10, 10}}, 8.0f));
  f.lines.push_back(line(GroundClass::Street, std::vector<glm::dvec2>{glm::dvec2(10, 10)}, 8.0f));
  f.lines.push_back(line(GroundClass::Street, {{10, 10}, {20, 10}}, 0.0f));
  f.areas.push_back(area(GroundClass::Park, {{{0, 0}, {10, 0}}}));
  f.areas.push_back(area(GroundClass::Park, {{{0, 0}, {10, 0}, {20, 0}}}));
  f.areas.push_back(area(GroundClass::Park, {}));
  f.areas.push_back(area(GroundClass::Park, {{{0, 0}, {10, nan}, {20, 20}}}));
  // A bow tie (self-intersecting): triangulated by the even-odd rule, both lobes kept.
  f.areas.push_back(area(GroundClass::Green, {{{100, 100}, {300, 300}, {300, 100}, {100, 300}}}));
  // A hole of nothing: the area stays, the hole goes.
  f.areas.push_back(area(GroundClass::Forest, {square(1000, 1000, 1100, 1100), {{1050, 1050}, {1060, 1050}}}));
  f.skipped["broken-multipolygon"] = 2;
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.layer().skipped.at("non-finite") == 3);
  CHECK(g.layer().skipped.at("degenerate") == 7);
  CHECK(g.layer().skipped.at("broken-multipolygon") == 2);
  CHECK(g.layer().features.at("street") == 5);
  CHECK(g.area(2, GroundClass::Green) == Approx(2.0 * 100.0 * 200.0 / 2.0).epsilon(1e-4));
  CHECK(g.area(2, GroundClass::Forest) == Approx(100.0 * 100.0).epsilon(1e-4));
}

TEST_CASE("Huge polygons and far-away features are tiled without trouble", "[prep][ground]") {
  TempDir dir;
  GroundFeatures f;
  // A forest of 20,000 points larger than the city, and a lake 100 km away: the pyramid reaches
  // 4 × the city's size (9600 m) around its centre towards it, and the lake is cut off.
  std::vector<glm::dvec2> circle;
  for (int i = 0; i < 20000; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 20000.0;
    circle.emplace_back(1200.0 + 3000.0 * std::cos(a), 1200.0 + 3000.0 * std::sin(a));
  }
  f.areas.push_back(area(GroundClass::Forest, {circle}));
  f.areas.push_back(area(GroundClass::Water, {square(100000, 100000, 100100, 100100)}));
  const Ground g = tile(f, kCity, dir.path());
  CHECK(g.layer().size == Approx(6000.0 + 1800.0).epsilon(1e-9));
  CHECK(g.layer().minX == Approx(-1800.0).epsilon(1e-9));
  CHECK(g.layer().levels == 5);
  CHECK(g.area(g.layer().levels - 1, GroundClass::Water) == 0.0);
  const double disc = std::numbers::pi * 3000.0 * 3000.0;
  CHECK(g.area(g.layer().levels - 1, GroundClass::Forest) == Approx(disc).epsilon(1e-4));
  CHECK(g.area(0, GroundClass::Forest) == Approx(disc).epsilon(0.03));  // simplified to 7800 / 256 m
}

TEST_CASE("The same input gives the same files, whatever the threads", "[prep][ground]") {
  GroundFeatures f;
  for (int i = 0; i < 40; ++i) {
    const double y = 30.0 + 57.0 * i;
    f.lines.push_back(line(i % 5 == 0 ? GroundClass::Major : GroundClass::Street,
                           {{10.0, y}, {800.0, y + 40.0}, {1500.0, y - 20.0}, {2390.0, y + 5.0}}, 9.0f,
                           "Street " + std::to_string(i)));
  }
  f.areas.push_back(area(GroundClass::Park, {square(300, 300, 1500, 900), square(500, 400, 700, 600)}, "Park"));
  f.coastlines.push_back({{2000, 2000}, {2300, 2000}, {2300, 2300}, {2000, 2300}, {2000, 2000}});
  TempDir one, four;
  GroundTilerOptions options;
  options.threads = 1;
  const Ground a = tile(f, kCity, one.path(), options);
  options.threads = 4;
  const Ground b = tile(f, kCity, four.path(), options);
  REQUIRE(a.layer().nodes.size() == b.layer().nodes.size());
  for (std::size_t i = 0; i < a.layer().nodes.size(); ++i) {
    CHECK(a.layer().nodes[i].file == b.layer().nodes[i].file);
    CHECK(a.layer().nodes[i].crc32 == b.layer().nodes[i].crc32);
    CHECK(readBytes(one.path() + "/" + a.layer().nodes[i].file) ==
          readBytes(four.path() + "/" + b.layer().nodes[i].file));
  }
  CHECK(a.report.labels == b.report.labels);
  CHECK(a.report.labels > 40);
}
