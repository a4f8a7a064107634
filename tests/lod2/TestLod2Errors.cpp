// Bad input never crashes or throws: each failure is a Result error with a specific message naming
// the file and the place.
#include <fstream>
#include <random>
#include <sstream>

#include <catch2/catch.hpp>

#include "Lod2TestData.h"
#include "qv/prep/Lod2CityJson.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Obj.h"
#include "qv/prep/Projection.h"

namespace qv::prep::test {

TEST_CASE("lod2: An unknown CityJSON version is refused, naming the supported ones", "[lod2][errors]") {
  const Result<Lod2Import> imported = importModels(fixture("unknown_version.city.json"), placedInSyntheticCity());
  REQUIRE_FALSE(imported.ok());
  CHECK(imported.error() ==
        fixture("unknown_version.city.json") + ": unsupported CityJSON version \"3.0\" (supported: 1.0, 1.1, 2.0)");
  const Result<CityJsonFile> noVersion = parseCityJson(R"({"type": "CityJSON", "CityObjects": {}})", "x.json");
  REQUIRE_FALSE(noVersion.ok());
  CHECK(noVersion.error() == "x.json: no CityJSON \"version\" (a string such as \"2.0\")");
  const Result<CityJsonFile> geoJson = parseCityJson(R"({"type": "FeatureCollection", "features": []})", "y.json");
  REQUIRE_FALSE(geoJson.ok());
  CHECK(geoJson.error() == "y.json: not a CityJSON document: \"type\" is \"FeatureCollection\"");
  // Patch versions of supported ones are fine.
  CHECK(parseCityJson(R"({"type": "CityJSON", "version": "1.0.3", "CityObjects": {}, "vertices": []})", "z").ok());
}

TEST_CASE("lod2: A file without a CRS needs a placement", "[lod2][errors]") {
  Lod2ImportOptions options = placedInSyntheticCity();
  options.placement.reset();
  const Result<Lod2Import> refused = importModels(fixture("box_no_crs.city.json"), options);
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.error() == fixture("box_no_crs.city.json") +
                               ": no coordinate reference system (metadata.referenceSystem is missing): the models "
                               "cannot be georeferenced; give a placement (--place LON,LAT[,ROTATION_DEG]) to put the "
                               "models into the city");
  // The same file placed: a 10 x 10 x 9 m box (quantized coordinates with the transform applied).
  const Result<Lod2Import> placed = importModels(fixture("box_no_crs.city.json"), placedInSyntheticCity(45.0));
  REQUIRE(placed.ok());
  REQUIRE(placed->models.size() == 1);
  const Lod2Model& box = placed->models.front();
  CHECK(box.id == "cj:box-1");
  CHECK(box.attributes.heightM == Approx(9.0f));
  CHECK(box.attributes.footprintAreaM2 == Approx(100.0f).epsilon(1e-4));
  CHECK(enclosedVolumeM3(box.skinned.mesh) == Approx(900.0).epsilon(1e-9));
  CHECK(placed->report.lods.at("2.2") == 1);
}

TEST_CASE("lod2: A model outside the city's extent is refused without a placement", "[lod2][errors][data]") {
  Lod2ImportOptions options = placedInSyntheticCity();
  options.placement.reset();
  const Result<Lod2Import> refused = importModels(sharedData("cityjson/delft.json"), options);
  REQUIRE_FALSE(refused.ok());
  INFO(refused.error());
  CHECK(refused.error().rfind(sharedData("cityjson/delft.json") + ": cj:", 0) == 0);
  CHECK(refused.error().find(" lies at lon 4.3") != std::string::npos);
  CHECK(refused.error().find("(EPSG:7415), outside the city's extent (x ") != std::string::npos);
  CHECK(refused.error().find("about lon -74.0") != std::string::npos);
  CHECK(refused.error().find("give a placement (--place LON,LAT[,ROTATION_DEG])") != std::string::npos);

  options.skipOutsideExtent = true;
  const Result<Lod2Import> skipped = importModels(sharedData("cityjson/delft.json"), options);
  REQUIRE(skipped.ok());
  CHECK(skipped->report.imported == 0);
  CHECK(skipped->report.skipped.at("outside-extent") == 160);
}

TEST_CASE("lod2: Malformed CityJSON gives file:line:column", "[lod2][errors]") {
  const Result<Lod2Import> imported = importModels(fixture("malformed.city.json"), placedInSyntheticCity());
  REQUIRE_FALSE(imported.ok());
  CHECK(imported.error() ==
        fixture("malformed.city.json") + ":6:5: malformed JSON: unexpected '\"' in an object, expected ',' or '}'");
  const Result<CityJsonFile> truncated = parseCityJson("{\"type\": \"CityJSON\",\n \"version\": \"2.0", "t.json");
  REQUIRE_FALSE(truncated.ok());
  CHECK(truncated.error() == "t.json:2:17: malformed JSON: unexpected end of file in a string (missing closing quote)");
  const Result<CityJsonFile> empty = parseCityJson("", "e.json");
  REQUIRE_FALSE(empty.ok());
  CHECK(empty.error() == "e.json:1:1: malformed JSON: unexpected end of file, expected a value");
}

TEST_CASE("lod2: Structural errors name the CityObject and the JSON path", "[lod2][errors]") {
  const Result<CityJsonFile> badIndex = readCityJson(fixture("bad_index.city.json"));
  REQUIRE_FALSE(badIndex.ok());
  CHECK(badIndex.error() == fixture("bad_index.city.json") +
                                ": CityObjects[\"box-1\"].geometry[0] (Solid): boundaries[0][2][0][1]: vertex index 42 "
                                "out of range (8 vertices)");
  const Result<CityJsonFile> badVertex = parseCityJson(
      R"({"type": "CityJSON", "version": "2.0", "CityObjects": {}, "vertices": [[0, 0, 0], [1, "a", 2]]})", "v.json");
  REQUIRE_FALSE(badVertex.ok());
  CHECK(badVertex.error() == "v.json: vertices[1] is not an array of 3 numbers");
  const Result<CityJsonFile> noType =
      parseCityJson(R"({"type": "CityJSON", "version": "2.0", "CityObjects": {"x": {}}, "vertices": []})", "o.json");
  REQUIRE_FALSE(noType.ok());
  CHECK(noType.error() == "o.json: CityObjects[\"x\"] has no \"type\"");
  const Result<CityJsonFile> badRing = parseCityJson(
      R"({"type": "CityJSON", "version": "2.0", "vertices": [[0, 0, 0]],
          "CityObjects": {"b": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": "2",
                                                                  "boundaries": [[[0, -1, 0]]]}]}}})",
      "r.json");
  REQUIRE_FALSE(badRing.ok());
  CHECK(badRing.error() ==
        "r.json: CityObjects[\"b\"].geometry[0] (MultiSurface): boundaries[0][0][1]: vertex index -1 out of range "
        "(1 vertices)");
}

TEST_CASE("lod2: Degenerate faces are skipped and counted, not fatal", "[lod2][errors]") {
  const Result<CityJsonFile> file = parseCityJson(
      R"({"type": "CityJSON", "version": "2.0", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [2, 2, 0], [0, 0, 5]],
          "CityObjects": {"b": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": "2",
            "boundaries": [[[0, 1, 4]], [[0, 1, 1, 0]], [[0, 2, 3]]]}]}}})",
      "d.json");
  REQUIRE(file.ok());
  REQUIRE(file->buildings.size() == 1);
  CHECK(file->buildings[0].triangles.size() == 3);
  CHECK(file->facesSkipped == 2);  // two distinct points; three collinear points
  REQUIRE(file->warnings.size() == 2);
  CHECK(file->warnings[0] ==
        "d.json: CityObjects[\"b\"].geometry[0] (MultiSurface): face boundaries[1] skipped: its outer ring has fewer "
        "than 3 distinct vertices");
  CHECK(file->warnings[1].find("boundaries[2] skipped: it has no area or its rings cross") != std::string::npos);
}

TEST_CASE("lod2: A model that cannot be finished is left out with a warning", "[lod2][errors]") {
  Lod2ImportOptions options = placedInSyntheticCity();
  options.finish.remesh.maxVertices = 50;
  const Result<Lod2Import> imported = importModels(fixture("box_no_crs.city.json"), options);
  REQUIRE(imported.ok());
  CHECK(imported->models.empty());
  CHECK(imported->report.imported == 0);
  CHECK(imported->report.skipped.at("cannot-finish") == 1);
  REQUIRE(imported->report.warnings.size() == 1);
  CHECK(imported->report.warnings[0] == fixture("box_no_crs.city.json") +
                                            ": cj:box-1: re-meshing to edges of at most 1.500000 m would exceed 50 "
                                            "vertices (raise the target edge length); the model is left out");
}

TEST_CASE("lod2: Import options are checked", "[lod2][errors]") {
  Lod2ImportOptions options = placedInSyntheticCity();
  const Result<Lod2Import> format = importModels(fixture("model.ply"), options);
  REQUIRE_FALSE(format.ok());
  CHECK(format.error() ==
        fixture("model.ply") + ": unknown model format (expected .json or .city.json for CityJSON, .obj for OBJ)");
  options.placement.reset();
  const Result<Lod2Import> obj = importModels(fixture("box_cm_yup.obj"), options);
  REQUIRE_FALSE(obj.ok());
  CHECK(obj.error() == fixture("box_cm_yup.obj") +
                           ": OBJ models carry no georeference; give a placement (--place LON,LAT[,ROTATION_DEG]) to "
                           "put the models into the city");
  const Result<Lod2Import> missing = importModels(fixture("missing.city.json"), placedInSyntheticCity());
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.error().find("missing.city.json") != std::string::npos);
}

TEST_CASE("lod2: Models too tall or too large for a building are skipped (CityJSON) or refused (OBJ)",
          "[lod2][errors]") {
  // A 10 x 10 m pyramid: apex height and the x of one base corner vary.
  const auto pyramid = [](const std::string& apexZ, const std::string& cornerX) {
    return R"({"type": "CityJSON", "version": "2.0", "vertices": [[0, 0, 0], [)" + cornerX +
           R"(, 0, 0], [10, 10, 0], [0, 10, 0], [5, 5, )" + apexZ + R"(]],
          "CityObjects": {"b": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": "2",
            "boundaries": [[[0, 3, 2, 1]], [[0, 1, 4]], [[1, 2, 4]], [[2, 3, 4]], [[3, 0, 4]]]}]}}})";
  };
  struct Row {
    const char* apexZ;
    const char* cornerX;
    const char* skipped;  ///< nullptr: imported
    const char* warning;
  };
  const Row rows[] = {
      {"9", "10", nullptr, nullptr},
      {"9999", "10", nullptr, nullptr},
      {"10001", "10", "too-tall",
       "h.json: cj:b skipped: 10001 m tall (more than 10000 m): broken coordinates or a "
       "wrong unit?"},
      {"1e40", "10", "too-tall", "h.json: cj:b skipped: 1e+40 m tall (more than 10000 m)"},
      {"9", "2500", "too-large", "h.json: cj:b skipped: 2500 m wide (more than 2000 m)"},
  };
  for (const Row& row : rows) {
    INFO("apex " << row.apexZ << ", corner x " << row.cornerX);
    const Result<CityJsonFile> file = parseCityJson(pyramid(row.apexZ, row.cornerX), "h.json");
    REQUIRE(file.ok());
    REQUIRE(file->buildings.size() == 1);
    Lod2ImportReport report;
    const Result<std::vector<Lod2Model>> models =
        georeferenceCityJson(*file, "h.json", placedInSyntheticCity(), &report);
    REQUIRE(models.ok());
    if (row.skipped == nullptr) {
      REQUIRE(models->size() == 1);
      CHECK(report.skipped.empty());
      Lod2Model model = models->front();
      CHECK(finishModel(model).ok() == (std::string(row.apexZ) == "9"));  // 9999 m: more storeys than a tile holds
      continue;
    }
    CHECK(models->empty());
    CHECK(report.skipped == std::map<std::string, std::uint64_t>{{row.skipped, 1}});
    REQUIRE(report.warnings.size() == 1);
    CHECK(report.warnings[0].rfind(row.warning, 0) == 0);
  }

  SECTION("finishing refuses more storeys than a tile holds before re-meshing") {
    const Result<CityJsonFile> file = parseCityJson(pyramid("9999", "10"), "h.json");
    REQUIRE(file.ok());
    Result<std::vector<Lod2Model>> models = georeferenceCityJson(*file, "h.json", placedInSyntheticCity(), nullptr);
    REQUIRE(models.ok());
    Lod2Model& model = models->front();
    CHECK(model.attributes.storeys > 255);
    FinishOptions options;
    options.remesh.maxVertices = 10;  // re-meshing would fail with another message
    const Status s = finishModel(model, options);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error() == "cj:b: " + std::to_string(model.attributes.storeys) +
                           " storeys: a LOD2 model holds at most 255 (the tile format's limit)");
  }
  SECTION("an OBJ in the wrong unit") {
    ObjPlacement placement{kPlaceLon, kPlaceLat};
    placement.scale = 1000.0;  // a centimetre model read as metres, scaled again
    const Result<Lod2Model> model =
        readObjModel(fixture("box_cm_yup.obj"), placement, CityProjection(kPlaceLon, kPlaceLat));
    REQUIRE_FALSE(model.ok());
    CHECK(model.error() == fixture("box_cm_yup.obj") +
                               ": the model measures 200000 x 100000 x 1e+06 m (at most 2000 m wide and 10000 m "
                               "tall): are the unit and scale right?");
  }
}

TEST_CASE("lod2: Damaged CityJSON gives a result, never a crash: truncations and seeded byte changes",
          "[lod2][errors][robustness]") {
  std::ifstream in(fixture("geometry_types.city.json"), std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string original = buffer.str();
  REQUIRE(original.size() > 5000);
  // Every truncation before the closing brace is malformed JSON and says where.
  const std::size_t closingBrace = original.find_last_of('}');
  std::size_t truncationErrors = 0;
  for (std::size_t size = 0; size <= closingBrace; size += 3) {
    const Result<CityJsonFile> file = parseCityJson(std::string_view(original).substr(0, size), "t.json");
    if (!file.ok() && file.error().rfind("t.json:", 0) == 0) ++truncationErrors;
  }
  CHECK(truncationErrors == closingBrace / 3 + 1);
  // Digits changed: the JSON mostly stays valid (not with a leading zero) while vertex indices,
  // coordinates, the transform, LODs and storeys break. Whole imports (placed, with a small vertex
  // budget so that a model blown up by a changed coordinate fails fast) give either finished models
  // or an error naming the file.
  std::vector<std::size_t> digits;
  for (std::size_t i = 0; i < original.size(); ++i) {
    if (original[i] >= '0' && original[i] <= '9') digits.push_back(i);
  }
  TempFile damaged("lod2-damaged.city.json", "");
  Lod2ImportOptions options = placedInSyntheticCity();
  options.finish.remesh.maxVertices = 20000;
  std::mt19937 random(7);
  std::size_t ok = 0;
  std::size_t failed = 0;
  for (int round = 0; round < 40; ++round) {
    std::string text = original;
    const int changes = 1 + static_cast<int>(random() % 3);
    for (int c = 0; c < changes; ++c) {
      text[digits[random() % digits.size()]] = static_cast<char>('0' + random() % 10);
    }
    std::ofstream(damaged.path(), std::ios::binary | std::ios::trunc) << text;
    const Result<Lod2Import> imported = importModels(damaged.path(), options);
    if (imported.ok()) {
      ++ok;
      for (const Lod2Model& model : imported->models) {
        CHECK(model.skinned.finished);
        CHECK(model.attributes.heightM > model.attributes.minHeightM);
      }
    } else {
      ++failed;
      CHECK(imported.error().rfind(damaged.path() + ":", 0) == 0);
    }
  }
  INFO(ok << " imported, " << failed << " refused");
  CHECK(ok > 0);
  CHECK(failed > 0);
}

}  // namespace qv::prep::test
