// The viewer's colours as a test sees them on a screenshot: the palette read from the engine's
// header (engine/scene/include/qv/scene/Palette.h, never written down a second time) and a
// classifier of "warm ramp" pixels (a drift shown now) that the greys, the ground and the sky never
// pass.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { REPO } from './server.mjs';

// The palette as the engine has it (engine/scene/include/qv/scene/Palette.h): the thresholds
// below are derived from these values, not written down a second time.
export function paletteTable(name, count = 5) {
  const header = fs.readFileSync(path.join(REPO, 'engine/scene/include/qv/scene/Palette.h'), 'utf8');
  const match = header.match(new RegExp(`${name}\\s*=\\s*\\{\\{([^;]*)\\}\\};`));
  assert.ok(match, `${name} in Palette.h`);
  const stops = [...match[1].matchAll(/\{\s*([0-9.]+)f,\s*([0-9.]+)f,\s*([0-9.]+)f\s*\}/g)].map((m) => m.slice(1, 4).map(Number));
  assert.equal(stops.length, count, name);
  return stops;
}
export const RAMP = paletteTable('kDamagePalette');
export const GREYS = paletteTable('kNotAnimatedPalette');
// The map under the city (streets, water, parks): never a warm colour, near or far.
export const GROUND = paletteTable('kGroundPalette', 10);

// How the building shader shades a colour (engine/render/src/Shaders.cpp): lighting from 0.42 to
// 1.19 times the colour (roofs 1.08 times more), clamped, then fog towards the sky colour with
// weight 0.7 (1 - exp(-0.000035 d)) at distance d.
const LIGHT = [0.42, 0.6, 0.8, 1.0, 1.19, 1.19 * 1.08];
const FOG_COLOUR = [0.80, 0.85, 0.90];
const fogAt = (d) => 0.7 * (1 - Math.exp(-d * 0.000035));
function shaded(c, light, fog) {
  return c.map((v, i) => Math.min(v * light, 1) * (1 - fog) + FOG_COLOUR[i] * fog);
}

// Hue in degrees (-180, 180] and HSV saturation of an [r, g, b] in 0..1.
function hueSat([r, g, b]) {
  const max = Math.max(r, g, b);
  const min = Math.min(r, g, b);
  const d = max - min;
  let h = 0;
  if (d > 0) {
    if (max === r) h = 60 * ((g - b) / d);
    else if (max === g) h = 60 * ((b - r) / d + 2);
    else h = 60 * ((r - g) / d + 4);
  }
  if (h > 180) h -= 360;
  return { hue: h, sat: max > 0 ? d / max : 0 };
}

// "Warm ramp colour": the hues of the slight, moderate, extensive and complete stops under every
// lighting and the fog up to `farthest` metres (with 10° to spare), with at least half of the
// lowest saturation any of them keeps. A drift of about a tenth of the full scale (0.2 %) already
// counts; the ramp's own "none" stop, the greys, the ground and the sky do not (checked below).
export function warmClassifier(farthest) {
  const samples = [];
  for (const stop of RAMP.slice(1)) {
    for (const light of LIGHT) {
      for (const fog of [0, fogAt(farthest) / 2, fogAt(farthest)]) samples.push(hueSat(shaded(stop, light, fog)));
    }
  }
  const minHue = Math.min(...samples.map((s) => s.hue)) - 10;
  const maxHue = Math.max(...samples.map((s) => s.hue)) + 10;
  const minSat = Math.min(...samples.map((s) => s.sat)) / 2;
  const isWarm = (rgb) => {
    const { hue, sat } = hueSat(rgb);
    return sat >= minSat && hue >= minHue && hue <= maxHue;
  };
  // The classifier must tell the colours apart, or the test could not fail (or always would).
  for (const light of LIGHT) {
    for (const fog of [0, fogAt(farthest)]) {
      for (const grey of GREYS) assert.ok(!isWarm(shaded(grey, light, fog)), `grey ${grey} under ${light}, ${fog}`);
      assert.ok(!isWarm(shaded(RAMP[0], light, fog)), `the ramp's none stop under ${light}, ${fog}`);
      for (const stop of RAMP.slice(1)) assert.ok(isWarm(shaded(stop, light, fog)), `warm stop ${stop}`);
    }
  }
  assert.ok(!isWarm([0.60, 0.63, 0.60]) && !isWarm(FOG_COLOUR), 'the ground and the sky are not warm');
  for (const colour of GROUND) {
    for (const fog of [0, fogAt(farthest)]) assert.ok(!isWarm(shaded(colour, 1, fog)), `the map's ${colour} is not warm`);
  }
  return { isWarm, minHue, maxHue, minSat };
}

/// Counts the warm pixels of `image` outside `excluded(x, y, width, height)` (the panels).
export function warmPixels(image, isWarm, excluded = () => false) {
  const { width, height, data } = image;
  let warm = 0;
  let counted = 0;
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) {
      if (excluded(x, y, width, height)) continue;
      const i = (y * width + x) * 4;
      ++counted;
      if (isWarm([data[i] / 255, data[i + 1] / 255, data[i + 2] / 255])) ++warm;
    }
  }
  return { warm, counted };
}
