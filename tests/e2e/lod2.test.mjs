// LOD2 in the browser: a synthetic city into which `quakeview-prep lod2` placed the Den Haag
// CityJSON models (scripts/test.sh prepares it). The models stream in their tiles' MESH sections,
// are drawn instead of the extruded footprints, are picked on their own triangles, and the
// inspection window says what they are; the LOD2 switch hides them.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, waitReady } from './lib/browser.mjs';
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
  await page.waitForFunction(() => {
    const s = window.quakeview.stats();
    window.__calm = s && s.tiles.pending === 0 ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, null, { timeout, polling: 250 });
}

test('LOD2 models are drawn from their meshes, picked on them, described in the inspection window and hidden by the LOD2 switch', async () => {
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
    // The screen centre looks at its footprint centre: the pick meets the model.
    const picked = await page.evaluate(() => window.quakeview.pick(640, 360));
    assert.ok(picked, 'something is under the screen centre');
    assert.equal(picked.id, id);
    assert.ok(await page.evaluate((i) => window.quakeview.select(i), id));
    await page.waitForTimeout(300);
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /LOD2 detailed model from CityJSON, \d+ triangles/);
    assert.match(text, /Results from: MDOF shear-building model/);
    const shown = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-model.png') }));

    // Hidden with the General panel's switch (the API's equivalent): no longer picked or drawn.
    await page.evaluate(() => window.quakeview.setLodVisibility({ lod1: true, lod2: false }));
    await page.waitForTimeout(500);
    const again = await page.evaluate(() => window.quakeview.pick(640, 360));
    assert.ok(!again || again.id !== id, 'a hidden model is not picked');
    const hidden = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'lod2-hidden.png') }));
    const centre = { x: 630, y: 350, width: 20, height: 20 };  // within the model's roof, seen from above
    assert.ok(changedFraction(shown, hidden, 24, centre) > 0.5, 'hiding LOD2 uncovers the ground at the centre');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
