// The colours of drift and damage, shared by the shaders (which the render layer generates from
// this table) and the legend, so what the legend says is what the city shows.
//
// A sequential scale from light to dark — light grey, yellow, orange, red, dark red — whose
// lightness falls monotonically (about L* 93, 85, 66, 45, 21), so it reads in greyscale and for
// the common colour-vision deficiencies (it runs along the yellow-red axis that deuteranopes and
// protanopes still see as a lightness ramp). Buildings without a result are blue-grey and hatched.
#pragma once

#include <array>

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

/// Drift ratio shown at the top of the ramp (2 %: beyond most buildings' extensive damage).
inline constexpr float kDriftFullScale = 0.02f;

/// The ramp at t in [0, 1] (clamped), piecewise linear through the five stops.
Rgb paletteRamp(float t);

}  // namespace qv
