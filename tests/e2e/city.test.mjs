// The city in the browser: a prepared city streams over HTTP, renders, animates while playing and
// holds still while paused; broken tiles are reported while the rest renders.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, waitForFunction, waitReady } from './lib/browser.mjs';
import { changedFraction, colourAt, colourDistance, decodePng, luminanceStats } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const SYNTH = path.join(DATA, 'synth');

let server;
let broken;
before(async () => {
  assert.ok(fs.existsSync(path.join(SYNTH, 'tileset.json')), `test city missing: ${SYNTH} (scripts/test.sh prepares it)`);
  // A copy of the city with one leaf tile corrupted and another one missing.
  broken = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-broken-'));
  fs.cpSync(SYNTH, broken, { recursive: true });
  const manifest = JSON.parse(fs.readFileSync(path.join(broken, 'tileset.json'), 'utf8'));
  const leaves = [];
  (function walk(n) { if (!n.children) leaves.push(n); else n.children.forEach(walk); })(manifest.root);
  assert.ok(leaves.length >= 3, 'the test city needs several leaf tiles');
  // Break the two leaves nearest the city's centre, where the test looks.
  const [cx, cy] = [(manifest.bounds[0] + manifest.bounds[2]) / 2, (manifest.bounds[1] + manifest.bounds[3]) / 2];
  const distance = (n) => Math.hypot((n.bounds[0] + n.bounds[2]) / 2 - cx, (n.bounds[1] + n.bounds[3]) / 2 - cy);
  leaves.sort((a, b) => distance(a) - distance(b));
  const corrupt = path.join(broken, leaves[0].file);
  const bytes = fs.readFileSync(corrupt);
  bytes[Math.floor(bytes.length / 2)] ^= 0xff;
  fs.writeFileSync(corrupt, bytes);
  fs.rmSync(path.join(broken, leaves[1].file));
  server = await serveSite({ '/data': DATA, '/broken': broken });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => {
  if (server) await server.close();
  if (broken) fs.rmSync(broken, { recursive: true, force: true });
});

// The canvas region right of the control panel, where the city is.
const CITY_RECT = { x: 360, y: 40, width: 900, height: 640 };

async function openCity(context, url) {
  const { page, problems } = await openPage(context, url);
  const ready = await waitReady(page);
  assert.deepEqual(ready, { ok: true });
  return { page, problems };
}

async function frameWith(page, camera) {
  await page.evaluate((c) => window.quakeview.setCamera(c), camera);
  // Wait until the new view has streamed in (several frames in a row with nothing pending: the
  // view refines level by level).
  await waitForFunction(page, () => {
    const s = window.quakeview.stats();
    window.__calm = s && s.tiles.pending === 0 ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, null, { timeout: 60000, polling: 250 });
  await page.waitForTimeout(600);
}

test('the synthetic city streams over HTTP and renders buildings where they are', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context, `${server.url}/?data=/data/synth/tileset.json`);
    const manifest = JSON.parse(fs.readFileSync(path.join(SYNTH, 'tileset.json'), 'utf8'));
    const png = await page.screenshot({ path: path.join(ARTIFACTS, 'city-overview.png') });
    const image = decodePng(png);
    assert.ok(luminanceStats(image, CITY_RECT).variance > 50, 'the city area is not blank');
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.equal(stats.buildings.loaded, manifest.buildings);
    assert.ok(stats.tiles.loaded >= 1 && stats.tiles.failed === 0);
    assert.ok(stats.drawCalls <= 256);
    // A known building (quakeview-prep info --building s1) stands where it should: its roof
    // differs from the ground well outside the city.
    const s1 = JSON.parse(fs.readFileSync(path.join(DATA, 'synth-s1.json'), 'utf8'));
    const [bx0, by0, bx1, by1] = manifest.bounds;
    const at = (x, y, z = 0) => page.evaluate(([a, b, c]) => window.quakeview.worldToScreen(a, b, c), [x, y, z]);
    const outside = await at(bx1 + (bx1 - bx0) * 0.3, (by0 + by1) / 2);
    const ground = colourAt(image, outside[0], outside[1], 3);
    const roof = await at(s1.x_m, s1.y_m, s1.height_m);
    assert.ok(colourDistance(colourAt(image, roof[0], roof[1], 1), ground) > 25,
      `building s1 (${s1.height_m} m) is drawn at its place`);
    assert.deepEqual(await page.evaluate(() => window.quakeview.errors()), []);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('street level: full-detail tiles replace the coarse ones and buildings animate', async () => {
  const { context, close } = await launchBrowser();
  try {
    // Full detail, fixed (no governor): a step of the frame-time governor would change the picture
    // while paused.
    const { page, problems } = await openCity(context, `${server.url}/?data=/data/synth/tileset.json&quality=high`);
    const overview = await page.evaluate(() => window.quakeview.getCamera());
    await frameWith(page, { distance: 260, pitchDeg: 35, headingDeg: 30, x: overview.x, y: overview.y });
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.ok(stats.buildings.visible > 0 && stats.buildings.visible < stats.buildings.loaded, 'culling works');
    assert.ok(stats.buildings.animated > 0, 'buildings near the camera animate');
    assert.ok(stats.tiles.loaded >= 2, 'leaves were loaded');
    await page.screenshot({ path: path.join(ARTIFACTS, 'city-street.png') });

    // Paused: two frames half a second apart are the same picture.
    await page.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(6.0); });
    await page.waitForTimeout(400);
    const a = decodePng(await page.screenshot());
    await page.waitForTimeout(500);
    const b = decodePng(await page.screenshot());
    assert.ok(changedFraction(a, b, 24, CITY_RECT) < 0.001, 'nothing moves while paused');
    assert.equal(await page.evaluate(() => window.quakeview.time()), 6.0);

    // Playing: the picture changes as time passes.
    await page.evaluate(() => window.quakeview.play());
    await page.waitForTimeout(700);
    const c = decodePng(await page.screenshot());
    assert.ok(await page.evaluate(() => window.quakeview.time()) > 6.0);
    assert.ok(changedFraction(b, c, 24, CITY_RECT) > 0.002, 'buildings move and change colour while playing');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('a corrupted tile and a missing tile are reported while the rest renders', async () => {
  const { context, close } = await launchBrowser();
  try {
    // Full detail (a fixed preset, no governor): the broken leaves must be wanted by the view also on
    // the software renderers the tests run on, which otherwise start in the weak-device preset.
    const { page } = await openPage(context, `${server.url}/?data=/broken/tileset.json&quality=high`);
    assert.deepEqual(await waitReady(page), { ok: true });
    // The panel folded (its title bar's arrow): the whole canvas shows the city.
    await page.mouse.click(20, 19);
    await page.waitForTimeout(300);
    const overview = await page.evaluate(() => window.quakeview.getCamera());
    // Close enough that every leaf is wanted (the first view, framed beside the open panel, is a
    // little farther than the city's size alone asks).
    await page.evaluate((o) => window.quakeview.setCamera({ distance: o.distance * 0.3, pitchDeg: 70 }), overview);
    await waitForFunction(page, () => window.quakeview.stats().tiles.failed >= 2, null, { timeout: 60000 });
    await page.waitForTimeout(500);
    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.ok(errors.some((e) => /failed: .*(corrupt|checksum)/.test(e)), `a corrupt-tile error in ${JSON.stringify(errors)}`);
    assert.ok(errors.some((e) => /failed: .*HTTP 404/.test(e)), `a missing-tile error in ${JSON.stringify(errors)}`);
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /== Errors ==/);
    assert.match(text, /HTTP 404/);
    const png = await page.screenshot({ path: path.join(ARTIFACTS, 'city-broken-tiles.png') });
    assert.ok(luminanceStats(decodePng(png), CITY_RECT).variance > 50, 'the rest of the city still renders');
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.ok(stats.tiles.loaded >= 2);
  } finally {
    await close();
  }
});
