// LOD2 in the browser: a synthetic city into which `quakeview-prep lod2` placed the Den Haag
// CityJSON models (scripts/test.sh prepares it). The models stream in their tiles' MESH sections,
// are drawn instead of the extruded footprints, are picked on their own triangles, and the
// inspection window says what they are; with the LOD2 switch off their extrusions come back.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, waitForFunction, waitReady } from './lib/browser.mjs';
import { changedFraction, decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const CITY = path.join(DATA, 'lod2');
const INFO = path.join(DATA, 'lod2-info.json');

let server;
before(async () => {
  assert.ok(fs.existsSync(path.join(CITY, 'tileset.json')), `test city missing: ${CITY} (scripts/test.sh prepares it)`);
  server = await serveSite({ '/lod2': CITY });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => {
  if (server) await server.close();
});

async function calm(page, timeout = 60000) {
  await waitForFunction(page, () => {
    const s = window.quakeview.stats();
    window.__calm = s && s.tiles.pending === 0 ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, null, { timeout, polling: 250 });
}

test('LOD2 models are drawn from their meshes, picked on them, described in the inspection window and replaced by their LOD1 extrusions when the LOD2 switch is off', async () => {
  const info = JSON.parse(fs.readFileSync(INFO, 'utf8'));
  assert.equal(info.lod2, 4, 'the four Den Haag models replaced four buildings');
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/lod2/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await page.evaluate(() => window.quakeview.pause());
    // One that replaced a synthetic building (in its place, among its neighbours).
    const id = info.lod2_ids.find((i) => i.startsWith('s'));
    assert.ok(id, `a replaced building among ${JSON.stringify(info.lod2_ids)}`);
    const overview = await page.evaluate((i) => window.quakeview.building(i), id);
    assert.ok(overview, `${id} is loaded (coarse) from the start`);
    assert.equal(overview.lod, 2);
    // Above it, looking straight down (nothing taller can stand between): its leaf tile (the
    // skinned mesh) comes in.
    await page.evaluate((b) => window.quakeview.setCamera({ x: b.x, y: b.y, distance: 120, headingDeg: 0, pitchDeg: 89 }), overview);
    await calm(page);
    const detailed = await page.evaluate((i) => window.quakeview.building(i), id);
    assert.equal(detailed.modelSource, 'cityjson');
    assert.ok(detailed.modelTriangles > 12, `a detailed model, not a box: ${detailed.modelTriangles} triangles`);
    // The view's centre (drawn in the middle of the canvas beside the panel) looks at its
    // footprint centre: the pick meets the model.
    const [cx, cy] = await page.evaluate((b) => window.quakeview.worldToScreen(b.x, b.y, 0), overview);
    const picked = await page.evaluate(([x, y]) => window.quakeview.pick(x, y), [cx, cy]);
    assert.ok(picked, 'something is under the screen centre');
    assert.equal(picked.id, id);
    assert.ok(await page.evaluate((i) => window.quakeview.select(i), id));
    await page.waitForTimeout(300);
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /LOD2 detailed model from CityJSON, \d+ triangles/);
    assert.match(text, /Results from: MDOF shear-building model/);
    const shown = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-model.png') }));

    // LOD2 off with the General panel's switch (the API's equivalent): the building is its LOD1
    // extrusion again (a flat-roofed box over the model's footprint), still drawn and picked.
    await page.evaluate(() => window.quakeview.setLodVisibility({ lod1: true, lod2: false }));
    await page.waitForTimeout(500);
    assert.deepEqual(await page.evaluate(() => window.quakeview.lodVisibility()), { lod1: true, lod2: false });
    const extruded = await page.evaluate(([x, y]) => window.quakeview.pick(x, y), [cx, cy]);
    assert.ok(extruded && extruded.id === id, `the LOD1 extrusion is picked: ${JSON.stringify(extruded)}`);
    const boxed = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-as-lod1.png') }));
    // The model's roofs, seen from above, around the view's centre (drawn beside the panel).
    const roof = { x: Math.round(cx) - 80, y: Math.round(cy) - 80, width: 160, height: 160 };
    assert.ok(changedFraction(shown, boxed, 24, roof) > 0.05, 'the model gives way to its extrusion');

    // LOD1 off too: nothing of it is drawn or picked.
    await page.evaluate(() => window.quakeview.setLodVisibility({ lod1: false, lod2: false }));
    await page.waitForTimeout(500);
    const again = await page.evaluate(([x, y]) => window.quakeview.pick(x, y), [cx, cy]);
    assert.ok(!again || again.id !== id, 'a hidden building is not picked');
    const hidden = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-hidden.png') }));
    const centre = { x: Math.round(cx) - 10, y: Math.round(cy) - 10, width: 20, height: 20 };  // within its roof
    assert.ok(changedFraction(boxed, hidden, 24, centre) > 0.5, 'hiding every building uncovers the ground at the centre');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('A LOD2 model deforms storey by storey: its silhouette moves between two times', async () => {
  const info = JSON.parse(fs.readFileSync(INFO, 'utf8'));
  const { context, close } = await launchBrowser();
  try {
    // Full detail (a fixed preset, no governor): the model 160 m from the eye must animate, also on
    // the software renderers the tests run on, whose weak-device preset animates less far.
    const { page, problems } = await openPage(context, `${server.url}/?data=/lod2/tileset.json&quality=high`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const id = info.lod2_ids.find((i) => i.startsWith('s'));
    const b = await page.evaluate((i) => window.quakeview.building(i), id);
    assert.ok(b && b.lod === 2, `${id} is a LOD2 building`);
    // Only the models, in one plain colour (so only motion can change pixels), motion exaggerated.
    assert.ok(await page.evaluate(() => window.quakeview.setColorMode('neutral')));
    assert.equal(await page.evaluate(() => window.quakeview.colorMode()), 'neutral');
    assert.ok(await page.evaluate(() => window.quakeview.setAmplitude(200)));
    assert.equal(await page.evaluate(() => window.quakeview.setAmplitude(1e9)), false, 'out of range is refused');
    assert.equal(await page.evaluate(() => window.quakeview.amplitude()), 200);
    await page.evaluate(() => window.quakeview.setLodVisibility({ lod1: false, lod2: true }));
    await page.evaluate((c) => { window.quakeview.pause(); window.quakeview.setTime(0); window.quakeview.setCamera(c); },
      { x: b.x, y: b.y, distance: 160, headingDeg: 20, pitchDeg: 12 });
    await calm(page);
    assert.ok((await page.evaluate(() => window.quakeview.stats())).buildings.animated > 0, 'the models are animated');
    await page.waitForTimeout(300);
    const rest = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-rest.png') }));
    // Pixels are compared around the model only (not in the panels, whose time line moves too):
    // 200 px either side of it, right of the panel.
    const [sx] = await page.evaluate((p) => window.quakeview.worldToScreen(p.x, p.y, 0), b);
    const panel = (await page.evaluate(() => window.quakeview.uiLayout())).windows.find((w) => w.title === 'QuakeView');
    const x0 = Math.max(Math.round(sx) - 200, panel ? Math.ceil(panel.x + panel.width) + 1 : 0);
    const x1 = Math.min(Math.round(sx) + 200, rest.width);
    assert.ok(x1 - x0 > 100, `the model is in view right of the panel (${x0}..${x1})`);
    const around = { x: x0, y: 0, width: x1 - x0, height: rest.height };
    const duration = await page.evaluate(() => window.quakeview.duration());
    let most = 0;
    let when = 0;
    for (const f of [0.15, 0.2, 0.25, 0.3, 0.4]) {
      await page.evaluate((t) => window.quakeview.setTime(t), f * duration);
      await page.waitForTimeout(300);
      const moved = decodePng(await page.screenshot());
      const changed = changedFraction(rest, moved, 24, around) * around.width * around.height;  // pixels
      if (changed > most) { most = changed; when = f * duration; }
    }
    await page.evaluate((t) => window.quakeview.setTime(t), when);
    await page.waitForTimeout(300);
    await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-deformed.png') });
    assert.ok(most >= 800, `the models' silhouettes move (${Math.round(most)} pixels changed around them at ${when.toFixed(1)} s)`);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
