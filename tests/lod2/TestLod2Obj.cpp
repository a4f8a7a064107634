// OBJ models placed by the caller: anchor, rotation, scale, unit and up axis.
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>

#include "Lod2TestData.h"
#include "qv/prep/Lod2Obj.h"
#include "qv/prep/Projection.h"

namespace qv::prep::test {
namespace {

struct Box3 {
  glm::dvec3 min{1e300};
  glm::dvec3 max{-1e300};
};

Box3 boundsOf(const Lod2Mesh& mesh) {
  Box3 b;
  for (const glm::dvec3& p : mesh.positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

}  // namespace

TEST_CASE("lod2: An OBJ box lands where its placement says", "[lod2][obj]") {
  // box_cm_yup.obj: x 0..200, y (up) 0..1000, z -100..0 centimetres, faces outward.
  const CityProjection projection(kPlaceLon, kPlaceLat);
  ObjPlacement placement;
  placement.lon = -73.995;
  placement.lat = 40.712;
  placement.unit = ModelUnit::Centimetre;
  placement.scale = 2.0;  // 4 m east, 2 m north, 20 m tall
  const glm::dvec2 anchor = projection.forward(placement.lon, placement.lat);

  SECTION("unrotated, origin at the anchor") {
    const Result<Lod2Model> model = readObjModel(fixture("box_cm_yup.obj"), placement, projection);
    REQUIRE(model.ok());
    CHECK(model->id == "obj:box_cm_yup");
    CHECK(model->source == "obj:box_cm_yup.obj");
    CHECK_FALSE(model->replacesExisting);
    CHECK(model->verticesBefore == 8);
    const Box3 b = boundsOf(model->skinned.mesh);
    CHECK(b.min.x == Approx(anchor.x).margin(1e-9));
    CHECK(b.max.x == Approx(anchor.x + 4.0).margin(1e-9));
    CHECK(b.min.y == Approx(anchor.y).margin(1e-9));  // OBJ -z is north
    CHECK(b.max.y == Approx(anchor.y + 2.0).margin(1e-9));
    CHECK(b.min.z == 0.0);
    CHECK(b.max.z == Approx(20.0));
    // Orientation kept (outward faces: positive volume), kinds from normals.
    CHECK(enclosedVolumeM3(model->skinned.mesh) == Approx(160.0));
    CHECK(model->attributes.heightM == Approx(20.0f));
    CHECK(model->attributes.storeys == 6);  // 20 m at 3.5 m a storey (use unknown)
    CHECK(model->attributes.footprintAreaM2 == Approx(8.0f));
    CHECK(model->attributes.lod == 2);
    std::map<SurfaceKind, int> kinds;
    for (SurfaceKind k : model->skinned.mesh.kinds) ++kinds[k];
    CHECK(kinds[SurfaceKind::Roof] == 2);
    CHECK(kinds[SurfaceKind::Ground] == 2);
    CHECK(kinds[SurfaceKind::Wall] == 8);
  }
  SECTION("rotated 90 degrees clockwise: north becomes east, east becomes south") {
    placement.rotationDeg = 90.0;
    const Result<Lod2Model> model = readObjModel(fixture("box_cm_yup.obj"), placement, projection);
    REQUIRE(model.ok());
    const Box3 b = boundsOf(model->skinned.mesh);
    CHECK(b.min.x == Approx(anchor.x).margin(1e-9));
    CHECK(b.max.x == Approx(anchor.x + 2.0).margin(1e-9));
    CHECK(b.min.y == Approx(anchor.y - 4.0).margin(1e-9));
    CHECK(b.max.y == Approx(anchor.y).margin(1e-9));
    CHECK(enclosedVolumeM3(model->skinned.mesh) == Approx(160.0));
  }
  SECTION("feet, z up, centred on the anchor") {
    placement.unit = ModelUnit::Foot;
    placement.scale = 1.0;
    placement.up = UpAxis::Z;
    placement.centreOnAnchor = true;
    const Result<Lod2Model> model = readObjModel(fixture("box_cm_yup.obj"), placement, projection);
    REQUIRE(model.ok());
    const Box3 b = boundsOf(model->skinned.mesh);
    // Z up: x 0..200 ft east, y 0..1000 ft north, z -100..0 ft up (ground at the lowest point).
    CHECK(b.max.x - b.min.x == Approx(200 * 0.3048));
    CHECK(b.max.y - b.min.y == Approx(1000 * 0.3048));
    CHECK(b.max.z == Approx(100 * 0.3048));
    CHECK(0.5 * (b.min.x + b.max.x) == Approx(anchor.x).margin(1e-9));
    CHECK(0.5 * (b.min.y + b.max.y) == Approx(anchor.y).margin(1e-9));
    // Read as they are, the coordinates keep their orientation: still a positive volume.
    CHECK(enclosedVolumeM3(model->skinned.mesh) == Approx(200.0 * 1000.0 * 100.0 * std::pow(0.3048, 3)));
  }
  SECTION("through importModels, finished") {
    Lod2ImportOptions options = placedInSyntheticCity();
    options.placement = Placement{placement.lon, placement.lat, 0.0};
    options.objUnit = ModelUnit::Centimetre;
    options.objScale = 2.0;
    const Result<Lod2Import> imported = importModels(fixture("box_cm_yup.obj"), options);
    REQUIRE(imported.ok());
    CHECK(imported->report.format == "obj");
    REQUIRE(imported->models.size() == 1);
    const Lod2Model& model = imported->models.front();
    CHECK(model.verticesAfter > 8);
    requireSkinningRule(model.skinned, floorLevels(model.attributes));
  }
}

TEST_CASE("lod2: Units and up axes parse", "[lod2][obj]") {
  CHECK(parseModelUnit("cm") == ModelUnit::Centimetre);
  CHECK(parseModelUnit("Feet") == ModelUnit::Foot);
  CHECK(parseModelUnit("mm") == ModelUnit::Millimetre);
  CHECK(parseModelUnit("metres") == ModelUnit::Metre);
  CHECK_FALSE(parseModelUnit("yards").has_value());
  CHECK(metresPerUnit(ModelUnit::Foot) == 0.3048);
  CHECK(parseUpAxis("Z") == UpAxis::Z);
  CHECK(parseUpAxis("y") == UpAxis::Y);
  CHECK_FALSE(parseUpAxis("x").has_value());
}

TEST_CASE("lod2: Placements parse as LON,LAT[,ROTATION_DEG]", "[lod2][crs]") {
  const auto plain = parsePlacement("-74.00,40.71");
  REQUIRE(plain.has_value());
  CHECK(plain->lon == -74.0);
  CHECK(plain->lat == 40.71);
  CHECK(plain->rotationDeg == 0.0);
  const auto rotated = parsePlacement("4.37,52.01,-30");
  REQUIRE(rotated.has_value());
  CHECK(rotated->rotationDeg == -30.0);
  for (const char* bad : {"", "-74.00", "200,40", "-74,95", "a,b", "1,2,3,4", "-74,40.71,"}) {
    INFO(bad);
    CHECK_FALSE(parsePlacement(bad).has_value());
  }
}

TEST_CASE("lod2: Malformed OBJ files give clear errors", "[lod2][obj][errors]") {
  const CityProjection projection(kPlaceLon, kPlaceLat);
  const ObjPlacement placement{kPlaceLon, kPlaceLat};
  SECTION("index 0") {
    const Result<Lod2Model> model = readObjModel(fixture("zero_index.obj"), placement, projection);
    REQUIRE_FALSE(model.ok());
    CHECK(model.error().find("zero_index.obj: malformed OBJ: ") != std::string::npos);
    CHECK(model.error().find("line 5") != std::string::npos);
  }
  SECTION("index out of range") {
    const Result<Lod2Model> model = readObjModel(fixture("index_out_of_range.obj"), placement, projection);
    REQUIRE_FALSE(model.ok());
    CHECK(model.error() ==
          fixture("index_out_of_range.obj") + ": object (unnamed) face 2: vertex index 9 out of range (4 vertices)");
  }
  SECTION("no faces") {
    TempFile empty("lod2-empty.obj", "# nothing\nv 0 0 0\n");
    const Result<Lod2Model> model = readObjModel(empty.path(), placement, projection);
    REQUIRE_FALSE(model.ok());
    CHECK(model.error() == empty.path() + ": no faces with an area (0 degenerate faces, 1 vertices)");
  }
  SECTION("missing file") {
    const Result<Lod2Model> model = readObjModel(fixture("missing.obj"), placement, projection);
    REQUIRE_FALSE(model.ok());
    CHECK(model.error().find("missing.obj") != std::string::npos);
  }
}

TEST_CASE("lod2: Every truncation of an OBJ file gives a model or an error naming the file", "[lod2][obj][errors]") {
  std::ifstream in(fixture("box_cm_yup.obj"), std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string original = buffer.str();
  REQUIRE(original.size() > 100);
  const CityProjection projection(kPlaceLon, kPlaceLat);
  const ObjPlacement placement{kPlaceLon, kPlaceLat};
  TempFile truncated("lod2-truncated.obj", "");
  std::size_t models = 0;
  std::size_t errors = 0;
  for (std::size_t size = 0; size <= original.size(); ++size) {
    std::ofstream(truncated.path(), std::ios::binary | std::ios::trunc) << original.substr(0, size);
    const Result<Lod2Model> model = readObjModel(truncated.path(), placement, projection);
    if (model.ok()) {
      ++models;
      CHECK(model->skinned.mesh.kinds.size() == model->skinned.mesh.triangleCount());
      CHECK(heightRange(model->skinned.mesh).maxZ > 0.0);
    } else {
      ++errors;
      CHECK(model.error().rfind(truncated.path() + ": ", 0) == 0);
    }
  }
  INFO(models << " models, " << errors << " errors");
  CHECK(models > 0);  // once enough faces are complete
  CHECK(errors > 0);  // before any face
}

}  // namespace qv::prep::test
