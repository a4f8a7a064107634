// The palette's promises (qv/scene/Palette.h): the not-animated greys of the current-drift mode
// read as a lightness scale, carry no colour, and cannot be taken for any colour that means
// something else (the warm drift ramp, no result, dimmed, selected); the shader draws the same
// greys the legend shows.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "qv/scene/Palette.h"

using namespace qv;

namespace {

// CIE 1976 L*a*b* of an sRGB colour (IEC 61966-2-1 transfer, D65 white).
struct Lab {
  double l, a, b;
};

double linear(float c) {
  const double v = c;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Lab toLab(const Rgb& c) {
  const double r = linear(c.r), g = linear(c.g), b = linear(c.b);
  const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
  auto f = [](double t) { return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; };
  return {116.0 * f(y) - 16.0, 500.0 * (f(x) - f(y)), 200.0 * (f(y) - f(z))};
}

double chroma(const Rgb& c) {
  const Lab lab = toLab(c);
  return std::hypot(lab.a, lab.b);
}

// CIE76 colour difference: about 2.3 is just noticeable; 15 is plainly a different colour.
double deltaE(const Rgb& p, const Rgb& q) {
  const Lab a = toLab(p), b = toLab(q);
  return std::hypot(a.l - b.l, a.a - b.a, a.b - b.b);
}

std::vector<float> samples(int n) {
  std::vector<float> t;
  for (int i = 0; i <= n; ++i) t.push_back(static_cast<float>(i) / static_cast<float>(n));
  return t;
}

// Evaluates a five-stop ramp function `name` of the generated GLSL at t: each line
// "if (t < N.0) return mix(vec3(...), vec3(...), t - M.0);" and the last "return vec3(...);".
Rgb evaluateGlslRamp(const std::string& glsl, const std::string& name, float t) {
  const std::size_t begin = glsl.find("vec3 " + name + "(float t) {");
  REQUIRE(begin != std::string::npos);
  const std::string body = glsl.substr(begin, glsl.find("\n}\n", begin) - begin);
  REQUIRE(body.find("clamp(t, 0.0, 1.0) * 4.0") != std::string::npos);
  const double s = std::clamp(static_cast<double>(t), 0.0, 1.0) * 4.0;
  const std::string number = "(-?[0-9.]+)";
  const std::string vec = "vec3\\(" + number + ", " + number + ", " + number + "\\)";
  const std::regex segment("if \\(t < " + number + "\\) return mix\\(" + vec + ", " + vec + ", t - " + number + "\\);");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), segment); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    if (!(s < std::stod(m[1]))) continue;
    const double f = s - std::stod(m[8]);
    auto lerp = [&](std::size_t k) {
      return static_cast<float>(std::stod(m[2 + k]) * (1.0 - f) + std::stod(m[5 + k]) * f);
    };
    return {lerp(0), lerp(1), lerp(2)};
  }
  std::smatch last;
  REQUIRE(std::regex_search(body, last, std::regex("\n  return " + vec + ";")));
  return {std::stof(last[1]), std::stof(last[2]), std::stof(last[3])};
}

}  // namespace

TEST_CASE("The not-animated greys darken steadily from no drift to full scale", "[scene][palette]") {
  // The stops: a clear lightness step between neighbours, so five levels can be told apart.
  for (std::size_t k = 0; k + 1 < kNotAnimatedPalette.size(); ++k) {
    INFO("stop " << k);
    CHECK(toLab(kNotAnimatedPalette[k]).l - toLab(kNotAnimatedPalette[k + 1]).l >= 8.0);
  }
  // Every value between: darker for a larger peak drift, never lighter.
  double previous = 101.0;
  for (float t : samples(200)) {
    const double l = toLab(notAnimatedGrey(t)).l;
    INFO("t = " << t);
    CHECK(l < previous);
    previous = l;
  }
  // Beyond the full scale and below zero: the ends.
  CHECK(deltaE(notAnimatedGrey(3.0f), kNotAnimatedPalette.back()) < 1e-6);
  CHECK(deltaE(notAnimatedGrey(-1.0f), kNotAnimatedPalette.front()) < 1e-6);
  // From light grey to dark slate.
  CHECK(toLab(notAnimatedGrey(0.0f)).l > 70.0);
  CHECK(toLab(notAnimatedGrey(1.0f)).l < 35.0);
}

TEST_CASE("The not-animated greys carry no colour and are never warm", "[scene][palette]") {
  for (float t : samples(100)) {
    const Rgb c = notAnimatedGrey(t);
    INFO("t = " << t << ": " << c.r << ", " << c.g << ", " << c.b);
    CHECK(chroma(c) < 10.0);
    CHECK(toLab(c).b <= 0.0);  // a cool cast if any: not towards yellow
    CHECK(toLab(c).a < 2.0);   // nor towards red
  }
  // The warm stops it must not resemble are plainly coloured (the check above can fail).
  for (std::size_t k = 1; k < kDamagePalette.size(); ++k) CHECK(chroma(kDamagePalette[k]) > 40.0);
}

TEST_CASE("No not-animated grey can be taken for a colour that means something else", "[scene][palette]") {
  struct Named {
    const char* name;
    Rgb colour;
  };
  std::vector<Named> others = {{"no result", kNoResultColor}, {"dimmed", kDimmedColor}, {"selected", kSelectedColor}};
  for (float u : samples(100)) others.push_back({"the warm drift ramp", paletteRamp(u)});
  for (float t : samples(100)) {
    const Rgb grey = notAnimatedGrey(t);
    for (const Named& other : others) {
      INFO("grey at t = " << t << " against " << other.name << " (" << other.colour.r << ", " << other.colour.g << ", "
                          << other.colour.b << ")");
      CHECK(deltaE(grey, other.colour) >= 15.0);
    }
  }
  // The warm stops from slight on are farther still.
  for (const Rgb& grey : kNotAnimatedPalette) {
    for (std::size_t k = 1; k < kDamagePalette.size(); ++k) CHECK(deltaE(grey, kDamagePalette[k]) >= 40.0);
  }
}

TEST_CASE("The shader's palette is the legend's palette", "[scene][palette][gpu]") {
  const std::string glsl = paletteGlsl();
  for (const char* name : {"kNoResult", "kSelected", "kDimmed", "kTagGreen", "kTagYellow", "kTagRed"}) {
    CHECK(glsl.find("const vec3 " + std::string(name) + " = vec3(") != std::string::npos);
  }
  for (float t : samples(64)) {
    INFO("t = " << t);
    CHECK(deltaE(evaluateGlslRamp(glsl, "notAnimatedGrey", t), notAnimatedGrey(t)) < 0.05);
    CHECK(deltaE(evaluateGlslRamp(glsl, "ramp", t), paletteRamp(t)) < 0.05);
  }
  CHECK(deltaE(evaluateGlslRamp(glsl, "notAnimatedGrey", 2.0f), kNotAnimatedPalette.back()) < 0.05);
  // The two functions differ (a generator writing one ramp twice would fail here).
  CHECK(deltaE(evaluateGlslRamp(glsl, "notAnimatedGrey", 0.5f), evaluateGlslRamp(glsl, "ramp", 0.5f)) > 30.0);
}

namespace {

// Evaluates the generated `float driftPosition(float d)` as a GPU would: its ifs in order.
float evaluateGlslDriftPosition(const std::string& glsl, float d) {
  const std::size_t begin = glsl.find("float driftPosition(float d) {");
  REQUIRE(begin != std::string::npos);
  const std::string body = glsl.substr(begin, glsl.find("\n}\n", begin) - begin);
  const std::string number = "(-?[0-9.]+)";
  const std::regex segment("if \\(d < " + number + "\\) return \\(" + number + " \\+ \\(d - " + number + "\\) / " +
                           number + "\\) \\* 0\\.25;");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), segment); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    if (!(static_cast<double>(d) < std::stod(m[1]))) continue;
    return static_cast<float>((std::stod(m[2]) + (static_cast<double>(d) - std::stod(m[3])) / std::stod(m[4])) * 0.25);
  }
  REQUIRE(body.find("\n  return 1.0;") != std::string::npos);
  return 1.0f;
}

}  // namespace

TEST_CASE("Drift ratios map onto the ramp at the legend's stops: 0, 0.1, 0.5, 1 and 2 %", "[scene][palette]") {
  // The legend's values are the stops: each drift there gets exactly that stop's colour.
  const std::array<float, 5> positions = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
  for (std::size_t k = 0; k < kDriftStops.size(); ++k) {
    INFO("stop " << k);
    CHECK(driftRampPosition(kDriftStops[k]) == Approx(positions[k]).margin(1e-6));
  }
  CHECK(kDriftStops[1] == Approx(0.001f));
  CHECK(kDriftFullScale == Approx(0.02f));
  // Between stops, linear; beyond the ends, clamped; no drift (or NaN) is the first stop.
  CHECK(driftRampPosition(0.0005f) == Approx(0.125f));
  CHECK(driftRampPosition(0.003f) == Approx(0.375f));
  CHECK(driftRampPosition(0.015f) == Approx(0.875f));
  CHECK(driftRampPosition(0.5f) == 1.0f);
  CHECK(driftRampPosition(-0.01f) == 0.0f);
  CHECK(driftRampPosition(std::nanf("")) == 0.0f);
  // A moderate earthquake's drift of 0.05 % is already visibly off white (a colour difference a
  // person sees at a glance), and larger drifts are always darker.
  CHECK(deltaE(paletteRamp(driftRampPosition(0.0005f)), kDamagePalette[0]) > 10.0);
  double previous = 101.0;
  for (float t : samples(200)) {
    const double l = toLab(paletteRamp(driftRampPosition(t * 0.025f))).l;
    CHECK(l <= previous);
    previous = l;
  }
  // The shader's twin gives the same positions.
  const std::string glsl = paletteGlsl();
  for (float d : {0.0f, 0.0002f, 0.001f, 0.0031f, 0.0072f, 0.0123f, 0.02f, 0.3f}) {
    INFO("drift " << d);
    CHECK(evaluateGlslDriftPosition(glsl, d) == Approx(driftRampPosition(d)).margin(1e-5));
  }
}
