// The map under the city in the viewer: the ground pyramid's cells chosen by screen-space error
// (never a cell and its children at once), streamed through the city's file loader, their labels
// in the city frame; and the placement of the names on the screen.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "MiniCity.h"
#include "qv/core/Crc32.h"
#include "qv/format/GroundTile.h"
#include "qv/scene/GroundScene.h"
#include "qv/scene/MapLabels.h"
#include "qv/scene/NullRenderDevice.h"

using namespace qv;
using qv::test::FakeFetcher;

namespace {

constexpr double kSize = 2000.0;  // the level-0 cell: 2 km, south-west corner at (-1000, -1000)

// A cell's tile: one square of water filling it, plus one label at its centre named after it.
GroundTile cellTile(int level, std::uint32_t x, std::uint32_t y) {
  const double side = kSize / std::ldexp(1.0, level);
  GroundTile t;
  t.originX = -1000.0 + side * x;
  t.originY = -1000.0 + side * y;
  t.extent = static_cast<float>(side);
  const auto s = static_cast<float>(side);
  t.vertices = {{0, 0}, {s, 0}, {s, s}, {0, s}};
  t.triangles = {0, 1, 2, 0, 2, 3};
  t.runs = {GroundRun{GroundClass::Water, 0, 2}};
  GroundLabel label;
  label.kind = GroundLabelKind::Neighbourhood;
  label.rank = static_cast<std::uint8_t>(10 + level);
  label.position = {0.5f * s, 0.5f * s};
  label.text = "cell " + std::to_string(level) + "/" + std::to_string(x) + "/" + std::to_string(y);
  t.labels.push_back(label);
  return t;
}

struct GroundRig {
  FakeFetcher fetcher;
  FakeClock clock;
  NullRenderDevice device;
  std::vector<LoadError> errors;
  FileLoader loader{fetcher, clock, [this](const LoadError& e) { errors.push_back(e); }};
  GroundLayer layer;

  GroundRig() {
    layer.minX = -1000.0;
    layer.minY = -1000.0;
    layer.size = kSize;
    layer.levels = 2;
    add(0, 0, 0, kSize / 256.0);
    for (std::uint32_t q = 0; q < 4; ++q) add(1, q % 2, q / 2, 0.0);
  }
  void add(int level, std::uint32_t x, std::uint32_t y, double error) {
    GroundNode n;
    n.level = static_cast<std::uint8_t>(level);
    n.x = x;
    n.y = y;
    n.geometricErrorM = static_cast<float>(error);
    n.file = "ground/" + std::to_string(level) + "-" + std::to_string(x) + "-" + std::to_string(y) + ".qvg";
    const std::vector<std::uint8_t> bytes = encodeGroundTile(cellTile(level, x, y));
    n.bytes = bytes.size();
    n.crc32 = crc32(bytes);
    fetcher.files["city/" + n.file] = bytes;
    layer.nodes.push_back(n);
  }
};

CameraView viewOf(CameraState c) {
  return CameraView(c, 1280, 720);
}

// Frames until the ground settles (at most n); each frame polls the fetcher first, as the city does.
void settle(GroundScene& g, FakeFetcher& f, const CameraView& view, int n = 10) {
  for (int i = 0; i < n; ++i) {
    f.poll();
    g.update(view);
    if (g.settled()) return;
  }
}

}  // namespace

TEST_CASE("The map's top cell covers the city from afar and its children replace it up close", "[scene][ground]") {
  GroundRig rig;
  GroundScene ground(rig.device, rig.loader, "city/tileset.json", rig.layer);
  const CameraView far = viewOf(CameraState{0.0, 0.0, 20000.0, 0.0, 60.0, 45.0});
  settle(ground, rig.fetcher, far);
  REQUIRE(ground.settled());
  CHECK(rig.fetcher.count("city/ground/0-0-0.qvg") == 1);
  CHECK(rig.fetcher.count("city/ground/1-0-0.qvg") == 0);
  REQUIRE(ground.items().size() == 1);
  CHECK(ground.items()[0].origin.x == Approx(-1000.0f));
  CHECK(ground.trianglesDrawn() == 2);
  REQUIRE(ground.labels().size() == 1);
  CHECK(*ground.labels()[0].text == "cell 0/0/0");
  CHECK(ground.labels()[0].position.x == Approx(0.0).margin(0.05));  // cell-local centre + the cell's corner

  // Close over the south-west quadrant: the children in view are requested; until they are all
  // there the top cell stays, and once they are, only they are drawn (never both).
  const CameraView near = viewOf(CameraState{-500.0, -500.0, 300.0, 0.0, 89.0, 45.0});
  rig.fetcher.held.insert("city/ground/1-0-0.qvg");
  rig.fetcher.poll();
  ground.update(near);
  rig.fetcher.poll();
  ground.update(near);
  CHECK_FALSE(ground.settled());
  REQUIRE(ground.items().size() == 1);
  CHECK(*ground.labels()[0].text == "cell 0/0/0");
  rig.fetcher.held.clear();
  settle(ground, rig.fetcher, near);
  REQUIRE(ground.settled());
  std::vector<std::string> names;
  for (const MapLabel& l : ground.labels()) names.push_back(*l.text);
  CHECK(std::find(names.begin(), names.end(), "cell 1/0/0") != names.end());
  CHECK(std::find(names.begin(), names.end(), "cell 0/0/0") == names.end());
  for (const GroundDrawItem& item : ground.items()) CHECK(item.origin.x < 1000.0f);
  CHECK(ground.memoryBytes() > 0);
}

TEST_CASE("A broken ground tile is reported by its URL and leaves the rest of the map", "[scene][ground]") {
  GroundRig rig;
  rig.fetcher.files["city/ground/1-1-1.qvg"][10] ^= 0xFF;  // the manifest's CRC no longer matches
  GroundScene ground(rig.device, rig.loader, "city/tileset.json", rig.layer);
  const CameraView top = viewOf(CameraState{0.0, 0.0, 600.0, 0.0, 89.0, 45.0});
  settle(ground, rig.fetcher, top, 20);
  CHECK(ground.settled());
  CHECK(ground.cellsFailed() == 1);
  REQUIRE(rig.errors.size() == 1);
  CHECK(rig.errors[0].kind == FileKind::Ground);
  CHECK(rig.errors[0].message.find("city/ground/1-1-1.qvg") != std::string::npos);
  // The three good quadrants are drawn; the broken one is left empty, not drawn twice by its parent.
  CHECK(ground.items().size() == 3);
}

TEST_CASE("The ground mesh gives each vertex its run's class, copying shared vertices", "[scene][ground]") {
  GroundTile t;
  t.extent = 10.0f;
  t.vertices = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  t.triangles = {0, 1, 2, 0, 2, 3};
  t.runs = {GroundRun{GroundClass::Park, 0, 1}, GroundRun{GroundClass::Street, 1, 1}};
  std::vector<GroundVertex> vertices;
  std::vector<std::uint32_t> indices;
  groundMesh(t, vertices, indices);
  REQUIRE(indices.size() == 6);
  CHECK(vertices.size() == 6);  // 0 and 2 are in both runs
  CHECK(vertices[indices[0]].groundClass == static_cast<std::uint8_t>(GroundClass::Park));
  CHECK(vertices[indices[5]].groundClass == static_cast<std::uint8_t>(GroundClass::Street));
  CHECK(vertices[indices[4]].x == 10.0f);
}

namespace {

// Looking straight down at (0, 0) from 1000 m: 1280 x 720 pixels.
glm::mat4 topDown() {
  return viewOf(CameraState{0.0, 0.0, 1000.0, 0.0, 90.0, 45.0}).viewProjection();
}

glm::vec2 fixedSize(std::string_view text, GroundLabelKind) {
  return {8.0f * static_cast<float>(text.size()), 14.0f};
}

MapLabel labelAt(const std::string& text, double x, double y, GroundLabelKind kind = GroundLabelKind::Neighbourhood,
                 std::uint8_t rank = 30) {
  MapLabel l;
  l.kind = kind;
  l.rank = rank;
  l.position = {x, y};
  l.text = &text;
  return l;
}

}  // namespace

TEST_CASE("Map names never overlap each other or a panel and the more important wins", "[scene][ground][labels]") {
  const std::string a = "Chelsea", b = "Hell's Kitchen", c = "Midtown", d = "Far away";
  // a and b at nearly the same place: b is placed first (given first, in rank order), a is left out.
  const std::vector<MapLabel> labels = {labelAt(b, 0.0, 0.0), labelAt(a, 5.0, 2.0), labelAt(c, 200.0, 0.0),
                                        labelAt(d, 90000.0, 0.0)};
  const glm::vec2 viewport(1280.0f, 720.0f);
  std::vector<PlacedLabel> placed = placeMapLabels(labels, topDown(), viewport, fixedSize, {});
  REQUIRE(placed.size() == 2);
  CHECK(placed[0].text == b);
  CHECK(placed[1].text == c);
  CHECK(placed[0].center.x == Approx(640.0f).margin(1.0f));
  CHECK(placed[0].center.y == Approx(360.0f).margin(1.0f));
  for (std::size_t i = 0; i < placed.size(); ++i) {
    for (std::size_t j = i + 1; j < placed.size(); ++j) {
      const bool apartX = std::abs(placed[i].center.x - placed[j].center.x) * 2 >= placed[i].size.x + placed[j].size.x;
      const bool apartY = std::abs(placed[i].center.y - placed[j].center.y) * 2 >= placed[i].size.y + placed[j].size.y;
      CHECK((apartX || apartY));
    }
  }
  // A panel over the middle of the screen keeps the centre name out.
  const std::vector<Rect> panel = {Rect{600.0f, 300.0f, 700.0f, 400.0f}};
  placed = placeMapLabels(labels, topDown(), viewport, fixedSize, panel);
  for (const PlacedLabel& p : placed) CHECK(p.text != b);
}

TEST_CASE("Street names run along their street, upright, only where the street has room", "[scene][ground][labels]") {
  const std::string name = "West 34th Street";
  MapLabel street = labelAt(name, 0.0, 0.0, GroundLabelKind::Street, 140);
  // Pointing west-north-west: the text must not read upside down.
  street.angleRad = std::numbers::pi_v<float> * 0.9f;
  street.lengthM = 600.0f;
  const glm::vec2 viewport(1280.0f, 720.0f);
  std::vector<PlacedLabel> placed = placeMapLabels(std::vector<MapLabel>{street}, topDown(), viewport, fixedSize, {});
  REQUIRE(placed.size() == 1);
  CHECK(std::abs(placed[0].angleRad) <= std::numbers::pi_v<float> * 0.5f + 1e-4f);
  CHECK(std::abs(std::abs(placed[0].angleRad) - std::numbers::pi_v<float> * 0.1f) < 0.05f);
  // A stretch shorter on screen than the name carries none.
  street.lengthM = 20.0f;
  placed = placeMapLabels(std::vector<MapLabel>{street}, topDown(), viewport, fixedSize, {});
  CHECK(placed.empty());
}

TEST_CASE("A long street's name repeats only far apart", "[scene][ground][labels]") {
  const std::string name = "Broadway";
  std::vector<MapLabel> labels;
  for (int i = -4; i <= 4; ++i) {
    MapLabel l = labelAt(name, 40.0 * i, 0.0, GroundLabelKind::Street, 100);
    l.lengthM = 150.0f;
    labels.push_back(l);
  }
  const std::vector<PlacedLabel> placed = placeMapLabels(labels, topDown(), glm::vec2(1280.0f, 720.0f), fixedSize, {});
  REQUIRE_FALSE(placed.empty());
  for (std::size_t i = 0; i < placed.size(); ++i) {
    for (std::size_t j = i + 1; j < placed.size(); ++j)
      CHECK(std::abs(placed[i].center.x - placed[j].center.x) >= 300.0f);
  }
}
