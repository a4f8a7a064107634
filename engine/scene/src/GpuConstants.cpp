#include "qv/scene/GpuConstants.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "qv/geometry/BuildingMesh.h"
#include "qv/scene/RenderDevice.h"

namespace qv {
namespace {

struct Field {
  const char* name;  // the C++ member's name, used as the GLSL member's
  std::size_t offsetBytes;
};

// What every vertex reads (three texels), and the sway's fields (the fourth texel), which only the
// buildings swaying from their drift series read.
constexpr std::array<Field, 12> kBuildingFields = {{
    {"storeyHeightMeters", offsetof(BuildingGpuRecord, storeyHeightMeters)},
    {"storeys", offsetof(BuildingGpuRecord, storeys)},
    {"floorBase", offsetof(BuildingGpuRecord, floorBase)},
    {"peakValue", offsetof(BuildingGpuRecord, peakValue)},
    {"damageState", offsetof(BuildingGpuRecord, damageState)},
    {"flags", offsetof(BuildingGpuRecord, flags)},
    {"baseZ", offsetof(BuildingGpuRecord, baseZ)},
    {"lossCode", offsetof(BuildingGpuRecord, lossCode)},
    {"seriesBase", offsetof(BuildingGpuRecord, seriesBase)},
    {"seriesStart", offsetof(BuildingGpuRecord, seriesStart)},
    {"seriesCount", offsetof(BuildingGpuRecord, seriesCount)},
    {"seriesRateHz", offsetof(BuildingGpuRecord, seriesRateHz)},
}};
constexpr std::array<Field, 4> kSwayFields = {{
    {"swayGainM", offsetof(BuildingGpuRecord, swayGainM)},
    {"swayPeriodXS", offsetof(BuildingGpuRecord, swayPeriodXS)},
    {"swayPeriodYS", offsetof(BuildingGpuRecord, swayPeriodYS)},
    {"reserved", offsetof(BuildingGpuRecord, reserved)},
}};
static_assert((kBuildingFields.size() + kSwayFields.size()) * sizeof(float) == sizeof(BuildingGpuRecord),
              "a field is missing");
static_assert(offsetof(BuildingGpuRecord, swayGainM) == 3 * kGpuTexelBytes, "the sway is the fourth texel");

constexpr std::array<Field, 4> kFloorFields = {{
    {"dxMeters", offsetof(FloorGpuRecord, dxMeters)},
    {"dyMeters", offsetof(FloorGpuRecord, dyMeters)},
    {"peakDriftAbove", offsetof(FloorGpuRecord, peakDriftAbove)},
    {"reserved", offsetof(FloorGpuRecord, reserved)},
}};
static_assert(kFloorFields.size() * sizeof(float) == sizeof(FloorGpuRecord), "a field is missing");
static_assert(sizeof(FloorGpuRecord) == kGpuTexelBytes, "a floor row is one texel");

struct ColorModeName {
  ColorMode mode;
  const char* name;
};
constexpr std::array<ColorModeName, kColorModeCount> kColorModeNames = {{
    {ColorMode::CurrentDrift, "kModeCurrentDrift"},
    {ColorMode::PeakDrift, "kModePeakDrift"},
    {ColorMode::DamageState, "kModeDamageState"},
    {ColorMode::Neutral, "kModeNeutral"},
    {ColorMode::ModerateOrWorse, "kModeModerateOrWorse"},
    {ColorMode::ExpectedDamage, "kModeExpectedDamage"},
    {ColorMode::InspectionTag, "kModeInspectionTag"},
}};

std::string intConstant(const char* name, long long value) {
  return "const int " + std::string(name) + " = " + std::to_string(value) + ";\n";
}

std::string uintConstant(const char* name, unsigned value) {
  return "const uint " + std::string(name) + " = " + std::to_string(value) + "u;\n";
}

// Floats here are whole numbers (exact in float); GLSL needs the decimal point.
std::string floatConstant(const char* name, float value) {
  return "const float " + std::string(name) + " = " + std::to_string(static_cast<long long>(value)) + ".0;\n";
}

// A struct holding `fields` and its reader: row i's texels start at texel `firstTexel` (GLSL of i).
template <std::size_t N>
std::string rowReader(const char* structName, const char* readerName, const char* firstTexel,
                      const std::array<Field, N>& fields) {
  std::string s = "struct " + std::string(structName) + " {";
  for (const Field& f : fields) s += " float " + std::string(f.name) + ";";
  s += " };\n";
  s += std::string(structName) + " " + readerName + "(sampler2D table, int i) {\n";
  // Only the texels the fields are in (named by their place in the row: t3 is its fourth).
  std::size_t first = SIZE_MAX, last = 0;
  for (const Field& f : fields) {
    first = std::min(first, f.offsetBytes / kGpuTexelBytes);
    last = std::max(last, f.offsetBytes / kGpuTexelBytes);
  }
  for (std::size_t t = first; t <= last; ++t) {
    s += "  vec4 t" + std::to_string(t) + " = texel(table, " + firstTexel + " + " + std::to_string(t) + ");\n";
  }
  s += "  " + std::string(structName) + " r;\n";
  for (const Field& f : fields) {
    const std::size_t texel = f.offsetBytes / kGpuTexelBytes;
    const char component = "xyzw"[f.offsetBytes % kGpuTexelBytes / sizeof(float)];
    s += "  r." + std::string(f.name) + " = t" + std::to_string(texel) + "." + component + ";\n";
  }
  s += "  return r;\n}\n";
  return s;
}

}  // namespace

std::string glslConstants() {
  std::string s = "// Generated from qv/scene/RenderDevice.h and qv/geometry/BuildingMesh.h (qv::glslConstants).\n";
  s += intConstant("kTableWidth", kGpuTableWidth);
  s += intConstant("kBuildingTexels", kBuildingTexels);
  s += uintConstant("kFlagSelected", kFlagSelected);
  s += uintConstant("kFlagDimmed", kFlagDimmed);
  s += uintConstant("kFlagHidden", kFlagHidden);
  // The kind's low bits hold the VertexKind, below the first of the LOD2 bits.
  s += intConstant("kKindMask", kKindModel - 1);
  s += intConstant("kKindWall", kWall);
  s += intConstant("kKindRoof", kRoof);
  s += intConstant("kKindGround", kGround);
  s += intConstant("kKindModel", kKindModel);
  s += intConstant("kKindFallback", kKindFallback);
  for (const ColorModeName& m : kColorModeNames) s += intConstant(m.name, static_cast<int>(m.mode));
  s += floatConstant("kDamageComplete", kDamageComplete);
  s += floatConstant("kDamageNoResult", kDamageNoResult);
  s += floatConstant("kDamagePending", kDamagePending);
  s += floatConstant("kLossCodeLevels", static_cast<float>(kLossCodeLevels));
  s += floatConstant("kLossCodeExpectedFactor", static_cast<float>(kLossCodeExpectedFactor));
  s += floatConstant("kLossCodeTagFactor", static_cast<float>(kLossCodeTagFactor));
  s += "vec4 texel(sampler2D table, int i) { return texelFetch(table, ivec2(i % kTableWidth, i / kTableWidth), 0); }\n";
  s += rowReader("BuildingRow", "readBuilding", "i * kBuildingTexels", kBuildingFields);
  s += rowReader("SwayRow", "readSway", "i * kBuildingTexels", kSwayFields);
  s += rowReader("FloorRow", "readFloor", "i", kFloorFields);
  // The series table (RGBA8, kSeriesSamplesPerTexel codes a texel): code i as code / 255.
  s += "const float kSeriesFullScale = " + std::to_string(kSeriesFullScale).substr(0, 8) + ";\n";
  s += intConstant("kSeriesSamplesPerTexel", kSeriesSamplesPerTexel);
  s += "float seriesCode(sampler2D series, int i) {\n"
       "  int t = i / kSeriesSamplesPerTexel;\n"
       "  vec4 v = texelFetch(series, ivec2(t % kTableWidth, t / kTableWidth), 0);\n"
       "  int c = i - t * kSeriesSamplesPerTexel;\n"
       "  return c == 0 ? v.x : (c == 1 ? v.y : (c == 2 ? v.z : v.w));\n"
       "}\n";
  return s;
}

std::string withGlslConstants(std::string_view source) {
  static constexpr std::string_view kMarker = "@CONSTANTS@";
  std::string s(source);
  const std::string block = glslConstants();
  for (auto at = s.find(kMarker); at != std::string::npos; at = s.find(kMarker, at + block.size())) {
    s.replace(at, kMarker.size(), block);
  }
  return s;
}

}  // namespace qv
