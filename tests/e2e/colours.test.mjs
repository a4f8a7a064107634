// Colours that tell the truth at every moment (issue 22, item 1; issue 31). In the current-drift
// mode every building shows its drift now, on the warm ramp: from its drift series (the far view's,
// in every tile summary) and, close by, storey by storey. Paused at t = 0, before any shaking, no
// pixel of the city may have a warm ramp colour, at the overview or close by; during strong shaking
// warm colours do appear; the legend says that every building follows its response.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, openSection, waitForFunction, waitReady } from './lib/browser.mjs';
import { warmClassifier, warmPixels as warmPixelsOutside } from './lib/colours.mjs';
import { decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const SYNTH = path.join(DATA, 'synth');

// The canvas without the panels: the collapsed control panel's title bar at the top and the
// map overlay (north arrow, scale bar, colour key) at the bottom right, as laid out now.
let overlay = { x: 1280 - 380, y: 720 - 130, width: 380, height: 130 };
const excluded = (x, y) => y < 40 || (x >= overlay.x - 2 && y >= overlay.y - 2);
const warmPixels = (image, isWarm) => warmPixelsOutside(image, isWarm, excluded);
async function findOverlay(page) {
  const map = (await page.evaluate(() => window.quakeview.uiLayout())).windows.find((w) => w.title === 'Map');
  if (map) overlay = map;
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

    // The map overlay keys the colours; the legend (one click away) says that every building
    // follows its response.
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /Colour: storey drift now: 0 0\.1 0\.5 1 2 %/);
    await openSection(page, 'Damage and colours');
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /Inter-storey drift \(now\), every building: its largest storey \(close by, each storey\):/);
    assert.doesNotMatch(text, /Not animated/);
    assert.match(text, /\d+ buildings in view follow their response now; within 1\.00 km of the camera \(at most \d+\) each storey moves by its own displacement[^\n]*The others sway as their drift series gives/);

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
    await findOverlay(page);
    const overviewShot = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'colours-overview-t0.png') }));
    const atOverview = warmPixels(overviewShot, warmFar.isWarm);
    const statsOverview = await page.evaluate(() => window.quakeview.stats());
    assert.ok(statsOverview.buildings.visible > 1000, 'the city is in view');
    assert.equal(atOverview.warm, 0, `warm pixels at the overview, t = 0 (thresholds ${JSON.stringify(warmFar)})`);

    // Every building in view follows its response, at the overview and closer (at rest at t = 0).
    assert.ok(statsOverview.buildings.animated >= 0.95 * statsOverview.buildings.visible,
      `buildings following their response at the overview: ${JSON.stringify(statsOverview.buildings)}`);
    await page.evaluate((o) => window.quakeview.setCamera({ x: o.x, y: o.y, distance: 700, pitchDeg: 40, headingDeg: 30 }), overview);
    await settle(page, { animated: true });
    const near = await page.evaluate(() => window.quakeview.stats());
    assert.ok(near.buildings.animated >= 0.95 * near.buildings.visible,
      `buildings following their response close by: ${JSON.stringify(near.buildings)}`);
    const closeShot = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'colours-street-t0.png') }));
    const atClose = warmPixels(closeShot, warmNear.isWarm);
    assert.equal(atClose.warm, 0, 'warm pixels close by, t = 0');

    // During the strongest shaking (the record's peak, reaching the buildings after their
    // travel-time delays) the buildings show their drift now: warm colours appear.
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
