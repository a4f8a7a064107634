// The colours of drift and damage, shared by the shaders (which the render layer generates from
// this table) and the legend, so what the legend says is what the city shows.
//
// A sequential scale from light to dark — light grey, yellow, orange, red, dark red — whose
// lightness falls monotonically (about L* 93, 85, 66, 45, 21), so it reads in greyscale and for
// the common colour-vision deficiencies (it runs along the yellow-red axis that deuteranopes and
// protanopes still see as a lightness ramp). Buildings without a result are blue-grey and hatched.
//
// In the current-drift mode a building has a drift "now" when it is animated floor by floor
// (within the animation radius, up to the cap, in full-detail tiles) or has a drift series (the
// far view's, in the tile summaries). A building with neither shows its peak drift over the whole
// record, and so that it is never mistaken for damage that has already happened, it uses cool grey
// levels instead of the warm ramp (kNotAnimatedPalette), with their own legend entry.
#pragma once

#include <array>
#include <string>

namespace qv {

struct Rgb {
  float r, g, b;
};

/// The five stops: none, slight, moderate, extensive, complete (and the drift ramp's 0, ¼, ½, ¾, 1).
inline constexpr std::array<Rgb, 5> kDamagePalette = {{{0.92f, 0.92f, 0.90f},
                                                       {0.99f, 0.82f, 0.40f},
                                                       {0.96f, 0.55f, 0.22f},
                                                       {0.80f, 0.20f, 0.13f},
                                                       {0.40f, 0.03f, 0.08f}}};
inline constexpr Rgb kNoResultColor = {0.60f, 0.70f, 0.85f};
/// Post-earthquake inspection tags (ATC-20 placards): green (inspected), yellow (restricted use), red
/// (unsafe). The conventional colours, at clearly different lightness (about L* 55, 87, 45) and named
/// in the legend, so the three stay apart for colour-vision deficiencies and in greyscale.
inline constexpr std::array<Rgb, 3> kTagPalette = {
    {{0.15f, 0.62f, 0.38f}, {0.99f, 0.86f, 0.22f}, {0.78f, 0.12f, 0.12f}}};
inline constexpr Rgb kSelectedColor = {0.10f, 0.75f, 1.00f};
inline constexpr Rgb kDimmedColor = {0.90f, 0.91f, 0.92f};

/// Not animated, in the current-drift mode: peak drift over the whole record at the drifts of
/// kDriftStops, from light grey to dark slate (about L* 75, 63, 51, 40, 27; CIE chroma below
/// 9, a faint blue cast). The lightest level stays clearly darker than ramp(0) and kDimmedColor,
/// every level apart from kNoResultColor (bluer, and hatched) by CIE76 ΔE*ab 17 or more, and far
/// from the warm stops (ΔE*ab over 45).
inline constexpr std::array<Rgb, 5> kNotAnimatedPalette = {{{0.70f, 0.72f, 0.75f},
                                                            {0.58f, 0.60f, 0.64f},
                                                            {0.46f, 0.48f, 0.53f},
                                                            {0.35f, 0.37f, 0.42f},
                                                            {0.23f, 0.25f, 0.30f}}};

/// The map under the city (qv::GroundClass order: land, green, forest, park, water, path, rail,
/// street, major, motorway): muted, light, and none in the hues of the warm ramp (streets and
/// motorways are neutral or blue-grey, never the beige or orange of road maps), so a road or a
/// park is never read as a building's drift or damage.
inline constexpr std::array<Rgb, 10> kGroundPalette = {{{0.60f, 0.63f, 0.60f},
                                                        {0.56f, 0.65f, 0.53f},
                                                        {0.46f, 0.57f, 0.46f},
                                                        {0.52f, 0.66f, 0.50f},
                                                        {0.55f, 0.68f, 0.80f},
                                                        {0.70f, 0.71f, 0.70f},
                                                        {0.46f, 0.46f, 0.50f},
                                                        {0.80f, 0.80f, 0.80f},
                                                        {0.88f, 0.88f, 0.88f},
                                                        {0.76f, 0.79f, 0.86f}}};

/// The drift ratios at the ramp's five stops: 0, 0.1 %, 0.5 %, 1 % and 2 % (piecewise linear in
/// between). The first coloured stop is low so that a moderate earthquake's shaking shows (0.1 %:
/// felt and visible motion, below most building types' slight-damage drift in HAZUS, 0.2–0.5 %);
/// orange at 0.5 % is about slight to moderate damage, red at 1 % moderate to extensive, dark red at
/// 2 % beyond most buildings' extensive damage. The legend prints these values.
inline constexpr std::array<float, 5> kDriftStops = {0.0f, 0.001f, 0.005f, 0.01f, 0.02f};
/// Drift ratio shown at the top of the ramp.
inline constexpr float kDriftFullScale = kDriftStops[4];

/// Where a drift ratio sits on the ramp: 0, ¼, ½, ¾ or 1 at the stops of kDriftStops, linear in
/// between, clamped to [0, 1] (so paletteRamp(driftRampPosition(d)) is the colour of drift d).
float driftRampPosition(float drift);

/// The ramp at t in [0, 1] (clamped), piecewise linear through the five stops.
Rgb paletteRamp(float t);

/// The not-animated grey at t in [0, 1] (clamped), piecewise linear through kNotAnimatedPalette.
Rgb notAnimatedGrey(float t);

/// The palette as GLSL ES 3.00, inserted by the render layer at the `@PALETTE@` marker of its
/// building shader: `const vec3 kNoResult`, `kSelected`, `kDimmed`, `kTagGreen`, `kTagYellow`,
/// `kTagRed`; `vec3 ramp(float t)` (paletteRamp) and `vec3 notAnimatedGrey(float t)`
/// (notAnimatedGrey), each with t clamped to [0, 1]; `float driftPosition(float drift)`
/// (driftRampPosition); `const vec3[10] kGroundClass` (kGroundPalette). Colours are written with 4
/// decimals.
std::string paletteGlsl();

}  // namespace qv
