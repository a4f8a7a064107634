// Colours that tell the truth at every moment (issue 22, item 1). In the current-drift mode only
// animated buildings show their drift now, on the warm ramp; every other building shows its peak
// over the whole record in grey levels. Paused at t = 0, before any shaking, no pixel of the city
// may have a warm ramp colour, at the overview or close by; during strong shaking warm colours do
// appear near the camera; the legend names the grey entry.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, waitForFunction, waitReady } from './lib/browser.mjs';
import { decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const SYNTH = path.join(DATA, 'synth');

// The palette as the engine has it (engine/scene/include/qv/scene/Palette.h): the thresholds
// below are derived from these values, not written down a second time.
function paletteTable(name) {
  const header = fs.readFileSync(path.join(REPO, 'engine/scene/include/qv/scene/Palette.h'), 'utf8');
  const match = header.match(new RegExp(`${name}\\s*=\\s*\\{\\{([^;]*)\\}\\};`));
  assert.ok(match, `${name} in Palette.h`);
  const stops = [...match[1].matchAll(/\{\s*([0-9.]+)f,\s*([0-9.]+)f,\s*([0-9.]+)f\s*\}/g)].map((m) => m.slice(1, 4).map(Number));
  assert.equal(stops.length, 5, name);
  return stops;
}
const RAMP = paletteTable('kDamagePalette');
const GREYS = paletteTable('kNotAnimatedPalette');

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
function warmClassifier(farthest) {
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
  return { isWarm, minHue, maxHue, minSat };
}

// The canvas without the panels: the collapsed control panel's title bar at the top and the map
// overlay (north arrow, scale bar) at the bottom right.
const excluded = (x, y, width, height) => y < 40 || (x >= width - 380 && y >= height - 90);

function warmPixels(image, isWarm) {
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

let server;
let manifest;
before(async () => {
  assert.ok(fs.existsSync(path.join(SYNTH, 'tileset.json')), `test city missing: ${SYNTH} (scripts/test.sh prepares it)`);
  manifest = JSON.parse(fs.readFileSync(path.join(SYNTH, 'tileset.json'), 'utf8'));
  server = await serveSite({ '/data': DATA });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => {
  if (server) await server.close();
});

// Waits until the view has streamed in and the buildings near the camera are animated.
async function settle(page, { animated }) {
  await waitForFunction(page, (wantAnimated) => {
    const s = window.quakeview.stats();
    const ok = s && s.tiles.pending === 0 && (!wantAnimated || s.buildings.animated > 0);
    window.__calm = ok ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, animated, { timeout: 90000, polling: 250 });
  await page.waitForTimeout(800);
}

test('paused at t = 0 in the current-drift mode no building has a damage colour; during the shaking nearby ones do', async (t) => {
  const { context, close } = await launchBrowser();
  try {
    // A link paused at the start, at full detail (on SwiftShader the page would start in the
    // weak-device preset, whose smaller animation radius the closer pose below does not reach).
    const { page, problems } = await openPage(context, `${server.url}/?data=/data/synth/tileset.json&quality=high#t=0&play=0`);
    assert.deepEqual(await waitReady(page), { ok: true });
    assert.equal(await page.evaluate(() => window.quakeview.colorMode()), 'drift');
    assert.equal(await page.evaluate(() => window.quakeview.playing()), false);
    assert.equal(await page.evaluate(() => window.quakeview.time()), 0);
    await settle(page, { animated: false });

    // The legend says what the greys are and where the animation stops.
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /Inter-storey drift \(now\), animated buildings:/);
    assert.match(text, /Not animated \(beyond the animation radius\): peak drift over the whole record\n0\.0 % peak drift\n/);
    assert.match(text, /2\.0 % peak drift or more\n/);
    assert.match(text, /Animated: the buildings within 1\.00 km of the camera, at most \d+ \(Performance panel\), \d+ now/);

    // Collapse the control panel (its title bar's arrow) so the whole city is in view.
    await page.mouse.click(20, 19);
    await page.waitForTimeout(800);
    assert.doesNotMatch(await page.evaluate(() => window.quakeview.uiText()), /Damage and colours/, 'the panel collapsed');

    const [bx0, by0, bx1, by1] = manifest.bounds;
    const diagonal = Math.hypot(bx1 - bx0, by1 - by0, manifest.maxHeight);
    const overview = await page.evaluate(() => window.quakeview.getCamera());
    const warmFar = warmClassifier(overview.distance + diagonal);
    const warmNear = warmClassifier(700 + diagonal);
    t.diagnostic(`warm: hue ${warmFar.minHue.toFixed(1)} to ${warmFar.maxHue.toFixed(1)} deg, saturation at least ` +
      `${warmFar.minSat.toFixed(3)} (overview) or ${warmNear.minSat.toFixed(3)} (close)`);
    const overviewShot = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'colours-overview-t0.png') }));
    const atOverview = warmPixels(overviewShot, warmFar.isWarm);
    const statsOverview = await page.evaluate(() => window.quakeview.stats());
    assert.ok(statsOverview.buildings.visible > 1000, 'the city is in view');
    assert.equal(atOverview.warm, 0, `warm pixels at the overview, t = 0 (thresholds ${JSON.stringify(warmFar)})`);

    // Closer: buildings within the radius animate (at rest at t = 0), the farther ones are grey.
    await page.evaluate((o) => window.quakeview.setCamera({ x: o.x, y: o.y, distance: 700, pitchDeg: 40, headingDeg: 30 }), overview);
    await settle(page, { animated: true });
    const near = await page.evaluate(() => window.quakeview.stats());
    assert.ok(near.buildings.animated > 0 && near.buildings.visible > near.buildings.animated,
      `animated and not animated buildings in view: ${JSON.stringify(near.buildings)}`);
    const closeShot = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'colours-street-t0.png') }));
    const atClose = warmPixels(closeShot, warmNear.isWarm);
    assert.equal(atClose.warm, 0, 'warm pixels close by, t = 0');

    // During the strongest shaking (the record's peak, reaching the buildings after their
    // travel-time delays) the animated buildings show their drift now: warm colours appear.
    const preview = manifest.response.motionPreviewG;
    let peak = 0;
    for (let i = 1; i < preview.length; ++i) if (Math.abs(preview[i]) > Math.abs(preview[peak])) peak = i;
    const peakSeconds = peak / manifest.response.motionPreviewRateHz;
    const duration = await page.evaluate(() => window.quakeview.duration());
    let best = { warm: -1 };
    for (let seconds = peakSeconds; seconds <= Math.min(peakSeconds + 8, duration); seconds += 1) {
      await page.evaluate((s) => window.quakeview.setTime(s), seconds);
      await page.waitForTimeout(700);
      const shot = await page.screenshot();
      const counts = warmPixels(decodePng(shot), warmNear.isWarm);
      t.diagnostic(`t = ${seconds.toFixed(1)} s: ${counts.warm} warm of ${counts.counted} pixels`);
      if (counts.warm > best.warm) best = { ...counts, t: seconds, shot };
    }
    fs.writeFileSync(path.join(ARTIFACTS, 'colours-street-shaking.png'), best.shot);
    assert.ok(best.warm > 0.002 * best.counted,
      `warm colours during the shaking: ${best.warm} of ${best.counted} pixels at t = ${best.t} s`);
    // Back to the start: the warm colours go again (they showed the drift of that moment).
    await page.evaluate(() => window.quakeview.setTime(0));
    await page.waitForTimeout(700);
    assert.equal(warmPixels(decodePng(await page.screenshot()), warmNear.isWarm).warm, 0, 'warm pixels back at t = 0');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
