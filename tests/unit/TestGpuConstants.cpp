// The GLSL block generated from the C++ GPU table definitions, and the shader sources that use it.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "qv/geometry/BuildingMesh.h"
#include "qv/scene/GpuConstants.h"
#include "qv/scene/Palette.h"
#include "qv/scene/RenderDevice.h"

using namespace qv;

namespace {

std::string shaderSources() {
  std::ifstream in(std::string(QUAKEVIEW_SOURCE_DIR) + "/engine/render/src/Shaders.cpp");
  REQUIRE(in);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The value a generated reader gives field `name` of a row, reading `floats` (the row's texels as
// the device uploads them) where the generated `r.<name> = t<T>.<c>;` line says.
float readByGlsl(const std::string& glsl, const std::string& reader, const std::string& name, const float* floats) {
  const auto begin = glsl.find(reader + "(sampler2D table, int i)");
  REQUIRE(begin != std::string::npos);
  const std::regex line("  r\\." + name + " = t([0-9]+)\\.([xyzw]);");
  std::smatch m;
  const std::string body = glsl.substr(begin, glsl.find("return r;", begin) - begin);
  REQUIRE(std::regex_search(body, m, line));
  const int texel = std::stoi(m[1].str());
  const int component = static_cast<int>(std::string("xyzw").find(m[2].str()[0]));
  return floats[texel * 4 + component];
}

}  // namespace

TEST_CASE("The GLSL constants carry the C++ values", "[scene][gpu]") {
  const std::string glsl = glslConstants();
  CHECK(contains(glsl, "const int kTableWidth = " + std::to_string(kGpuTableWidth) + ";"));
  CHECK(contains(
      glsl, "const int kBuildingTexels = " + std::to_string(sizeof(BuildingGpuRecord) / (4 * sizeof(float))) + ";"));
  CHECK(contains(glsl, "const uint kFlagSelected = " + std::to_string(unsigned{kFlagSelected}) + "u;"));
  CHECK(contains(glsl, "const uint kFlagDimmed = " + std::to_string(unsigned{kFlagDimmed}) + "u;"));
  CHECK(contains(glsl, "const uint kFlagHidden = " + std::to_string(unsigned{kFlagHidden}) + "u;"));
  CHECK(contains(glsl, "const int kKindRoof = " + std::to_string(int{kRoof}) + ";"));
  CHECK(contains(glsl, "const int kKindModel = " + std::to_string(int{kKindModel}) + ";"));
  CHECK(contains(glsl, "const int kKindFallback = " + std::to_string(int{kKindFallback}) + ";"));
  CHECK(contains(glsl,
                 "const int kModeInspectionTag = " + std::to_string(static_cast<int>(ColorMode::InspectionTag)) + ";"));
  CHECK(contains(glsl, "const int kModeNeutral = " + std::to_string(static_cast<int>(ColorMode::Neutral)) + ";"));
  CHECK(contains(glsl, "const float kDamagePending = " + std::to_string(static_cast<int>(kDamagePending)) + ".0;"));

  SECTION("the kind mask keeps every VertexKind and drops both LOD2 bits") {
    std::smatch m;
    REQUIRE(std::regex_search(glsl, m, std::regex("const int kKindMask = ([0-9]+);")));
    const int mask = std::stoi(m[1].str());
    for (int kind : {int{kWall}, int{kRoof}, int{kGround}}) CHECK((kind & mask) == kind);
    CHECK((kKindModel & mask) == 0);
    CHECK((kKindFallback & mask) == 0);
  }

  SECTION("the loss-code constants unpack what packLossCode packs") {
    auto value = [&](const std::string& name) {
      std::smatch m;
      REQUIRE(std::regex_search(glsl, m, std::regex("const float " + name + " = ([0-9]+)\\.0;")));
      return std::stof(m[1].str());
    };
    const float code = packLossCode(0.4f, 2.0f, 1);
    const float tag = std::floor(code / value("kLossCodeTagFactor"));
    const float rest = code - tag * value("kLossCodeTagFactor");
    const float expected = std::floor(rest / value("kLossCodeExpectedFactor"));
    const float moderate = rest - expected * value("kLossCodeExpectedFactor");
    CHECK(tag == 1.0f);
    CHECK(std::fabs(expected / value("kLossCodeLevels") - 2.0f / 4.0f) <= 1.0f / 255.0f);
    CHECK(std::fabs(moderate / value("kLossCodeLevels") - 0.4f) <= 1.0f / 255.0f);
  }
}

TEST_CASE("The generated row readers read each field where the device stores it", "[scene][gpu]") {
  const std::string glsl = glslConstants();
  BuildingGpuRecord b;
  b.storeyHeightMeters = 3.5f;
  b.storeys = 12.0f;
  b.floorBase = 40.0f;
  b.peakValue = 0.011f;
  b.damageState = 3.0f;
  b.flags = 5.0f;
  b.baseZ = 7.25f;
  b.lossCode = 70000.0f;
  b.seriesBase = 123456.0f;
  b.seriesStart = 4.25f;
  b.seriesCount = 161.0f;
  b.seriesRateHz = 4.0f;
  b.swayGainM = 31.5f;
  b.swayPeriodXS = 1.25f;
  b.swayPeriodYS = 0.75f;
  b.reserved = -3.0f;
  float texels[16];
  static_assert(sizeof texels == sizeof b);
  std::memcpy(texels, &b, sizeof b);  // the bytes writeBuildings sends
  const std::map<std::string, float> building = {{"storeyHeightMeters", b.storeyHeightMeters},
                                                 {"storeys", b.storeys},
                                                 {"floorBase", b.floorBase},
                                                 {"peakValue", b.peakValue},
                                                 {"damageState", b.damageState},
                                                 {"flags", b.flags},
                                                 {"baseZ", b.baseZ},
                                                 {"lossCode", b.lossCode},
                                                 {"seriesBase", b.seriesBase},
                                                 {"seriesStart", b.seriesStart},
                                                 {"seriesCount", b.seriesCount},
                                                 {"seriesRateHz", b.seriesRateHz}};
  for (const auto& [name, expected] : building) {
    INFO(name);
    CHECK(readByGlsl(glsl, "readBuilding", name, texels) == expected);
  }
  // The sway's fields, read by their own reader from the fourth texel only.
  const std::map<std::string, float> sway = {{"swayGainM", b.swayGainM},
                                             {"swayPeriodXS", b.swayPeriodXS},
                                             {"swayPeriodYS", b.swayPeriodYS},
                                             {"reserved", b.reserved}};
  for (const auto& [name, expected] : sway) {
    INFO(name);
    CHECK(readByGlsl(glsl, "readSway", name, texels) == expected);
  }
  CHECK(contains(glsl, "vec4 t3 = texel(table, i * kBuildingTexels + 3);"));
  const std::size_t swayAt = glsl.find("readSway(");
  const std::string swayReader = glsl.substr(swayAt, glsl.find("return r;", swayAt) - swayAt);
  CHECK_FALSE(contains(swayReader, "vec4 t0"));  // not the other three
  CHECK_FALSE(contains(swayReader, "vec4 t2"));
  FloorGpuRecord f{0.25f, -0.5f, 0.013f, 0.0f};
  float floorTexel[4];
  std::memcpy(floorTexel, &f, sizeof f);
  CHECK(readByGlsl(glsl, "readFloor", "dxMeters", floorTexel) == f.dxMeters);
  CHECK(readByGlsl(glsl, "readFloor", "dyMeters", floorTexel) == f.dyMeters);
  CHECK(readByGlsl(glsl, "readFloor", "peakDriftAbove", floorTexel) == f.peakDriftAbove);
}

TEST_CASE("The shader sources take the table layout from the generated block only", "[scene][gpu]") {
  const std::string source = shaderSources();
  REQUIRE(contains(source, "@CONSTANTS@"));
  const std::string generated = withGlslConstants(source);
  CHECK_FALSE(contains(generated, "@CONSTANTS@"));
  CHECK(contains(generated, glslConstants()));

  SECTION("no literal of a generated value") {
    CHECK_FALSE(contains(source, std::to_string(kGpuTableWidth)));
    for (int bits : {int{kKindModel}, int{kKindFallback}, kKindModel - 1}) {
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%x", static_cast<unsigned>(bits));
      CHECK_FALSE(contains(source, hex));
      CHECK_FALSE(std::regex_search(source, std::regex("[&|] *" + std::to_string(bits) + "\\b")));
    }
    for (unsigned flag : {unsigned{kFlagSelected}, unsigned{kFlagDimmed}, unsigned{kFlagHidden}}) {
      CHECK_FALSE(std::regex_search(source, std::regex("& *" + std::to_string(flag) + "u")));
    }
    CHECK_FALSE(std::regex_search(source, std::regex("\\bcolorMode *[=<>!]+ *[0-9]")));
    CHECK_FALSE(contains(source, std::to_string(kLossCodeTagFactor)));
    CHECK_FALSE(contains(source, std::to_string(kLossCodeExpectedFactor) + ".0"));
    CHECK_FALSE(contains(source, std::to_string(kLossCodeLevels) + ".0"));
    CHECK_FALSE(contains(source, "texelFetch"));  // only the generated texel() reads the tables
  }

  SECTION("every constant the shaders name is declared by a generated block") {
    const std::string constants = glslConstants();
    // The palette's names (qv/scene/Palette.h, inserted at @PALETTE@ by the device).
    const std::string palette = paletteGlsl();
    const std::string glsl = source.substr(source.find("R\"("));
    std::set<std::string> names;
    const std::regex identifier("\\bk[A-Z][A-Za-z]*\\b");
    for (auto it = std::sregex_iterator(glsl.begin(), glsl.end(), identifier); it != std::sregex_iterator(); ++it)
      names.insert(it->str());
    REQUIRE_FALSE(names.empty());
    for (const std::string& name : names) {
      INFO(name);
      // kBuildingVertex etc. are the C++ names of the sources themselves.
      if (contains(name, "Vertex") || contains(name, "Fragment")) continue;
      // A scalar, vector or array constant: "const vec3 kSelected = ", "const vec3[10] kGroundClass = ".
      CHECK(std::regex_search(constants + palette, std::regex("const \\w+(\\[\\d+\\])? " + name + " = ")));
    }
  }
}
