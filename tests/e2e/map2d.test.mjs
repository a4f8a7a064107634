// The 2D city where WebGL2 is missing (issue 33, item 4): in Chromium without its GPU and its
// software renderer, and in Firefox ESR with its default preferences (no WebGL on a machine without a
// GPU), the page opens the city from above instead of stopping: the footprints in the colours of the
// colour mode, the consequences in the HTML panel, search that selects, a click on the map that
// inspects, the CSV and the report downloaded; and on the 100,000-building demo panning stays
// responsive. Runs in Chromium and in Firefox ESR.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, swipe, waitForFunction, waitReady } from './lib/browser.mjs';
import { decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const DEMO = process.env.QUAKEVIEW_DEMO_DATA || path.join(REPO, 'build/demo-data/default');
const ACTUAL = path.join(DATA, 'actual');
const SYNTH = path.join(DATA, 'synth');
let server;

before(async () => {
  for (const dir of [ACTUAL, SYNTH, DEMO]) {
    assert.ok(fs.existsSync(path.join(dir, 'tileset.json')), `test city missing: ${dir} (scripts/test.sh prepares it)`);
  }
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  server = await serveSite({ '/actual': ACTUAL, '/synth': SYNTH, '/demo': DEMO });
});
after(() => server?.close());

// Pixels of the map (right of the panel) that are neither the map's background nor grey: buildings
// drawn in warm colours.
function warmPixels(png, region) {
  const image = decodePng(png);
  let warm = 0;
  for (let y = region.y; y < region.y + region.height; ++y) {
    for (let x = region.x; x < region.x + region.width; ++x) {
      const i = (y * image.width + x) * 4;
      const r = image.data[i], g = image.data[i + 1], b = image.data[i + 2];
      if (r > 150 && r - b > 60) ++warm;
    }
  }
  return warm;
}

// Clicks the element matching `selector` with the mouse (at its centre), as a person would.
async function clickOn(page, selector) {
  const r = await page.evaluate((sel) => {
    const e = document.querySelector(sel);
    if (!e) return null;
    e.scrollIntoView({ block: 'center' });
    const b = e.getBoundingClientRect();
    return { x: b.x + b.width / 2, y: b.y + b.height / 2 };
  }, selector);
  assert.ok(r, `${selector} is on the page`);
  await page.mouse.click(r.x, r.y);
}

test('without WebGL2 the city opens in 2D: map, consequences, search, inspection, CSV and report', async (t) => {
  const { context, close, browser } = await launchBrowser({ webgl: false });
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/synth/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    assert.match(await page.evaluate(() => document.getElementById('qv-map2d-notice')?.innerText || ''),
      /The 3D view is off/, 'the line saying why the 3D view is off');
    // The map: buildings drawn, coloured by their drift as the shaking goes on.
    await waitForFunction(page, () => (window.quakeview.map2d()?.shapes || 0) > 1000, null, { timeout: 30000 });
    await page.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(8); });
    await page.waitForTimeout(600);
    const shot = await page.screenshot();
    fs.writeFileSync(path.join(ARTIFACTS, `map2d-${browser}.png`), shot);
    const warm = warmPixels(shot, { x: 420, y: 40, width: 820, height: 640 });
    t.diagnostic(`${browser}: ${JSON.stringify(await page.evaluate(() => window.quakeview.map2d()))}, warm pixels ${warm}`);
    assert.ok(warm > 5000, `the city is drawn in the colours of its shaking: ${warm} warm pixels`);

    // The consequences in the HTML panel (the engine's panel text, shown).
    await waitForFunction(page, () => /Consequences|expected/.test(document.getElementById('qv-panel').innerText), null,
      { timeout: 30000 });
    const panelText = await page.evaluate(() => document.getElementById('qv-panel').innerText);
    assert.match(panelText, /SCENARIO/);
    assert.match(panelText, /Repair cost/);

    // Search selects a building, and shows it in the panel.
    await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 30000 });
    const target = await page.evaluate(() => window.quakeview.search('s1', 1)[0]);
    await clickOn(page, '#qv-map2d-search');
    await page.keyboard.type(target.label);
    await waitForFunction(page, () => document.querySelector('#qv-map2d-results button') !== null, null, { timeout: 10000 });
    await clickOn(page, '#qv-map2d-results button');
    await waitForFunction(page, (id) => window.quakeview.selection() === id, target.id, { timeout: 10000 });

    // A click on a building of the map inspects it.
    await page.evaluate(() => window.quakeview.select(''));
    await page.waitForTimeout(1500);  // the fly to the selection has ended
    const spot = await page.evaluate(() => {
      for (let y = 100; y < 660; y += 23) {
        for (let x = 460; x < 1240; x += 29) {
          const hit = window.quakeview.pick(x, y);
          if (hit) return { p: [x, y], id: hit.id };
        }
      }
      return null;
    });
    assert.ok(spot, 'a building is on the map');
    const picked = { id: spot.id };
    await page.mouse.click(spot.p[0], spot.p[1]);
    await waitForFunction(page, (id) => window.quakeview.selection() === id, picked.id, { timeout: 10000 });

    // The CSV and the report download from the HTML panel.
    let download = page.waitForEvent('download', { timeout: 20000 });
    await clickOn(page, '#qv-map2d-csv');
    const csv = await download;
    assert.match(csv.suggestedFilename(), /\.csv$/);
    assert.match(fs.readFileSync(await csv.path(), 'utf8'), /^\uFEFF# QuakeView building list/);
    download = page.waitForEvent('download', { timeout: 30000 });
    await clickOn(page, '#qv-map2d-report');
    const report = await download;
    assert.match(report.suggestedFilename(), /-report\.html$/);
    assert.equal(fs.readFileSync(await report.path(), 'utf8'), await page.evaluate(() => window.quakeview.report()));
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the 2D demo city of 100,000 buildings stays responsive while panning and zooming', async (t) => {
  const { context, close, browser } = await launchBrowser({ webgl: false });
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/demo/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await waitForFunction(page, () => (window.quakeview.map2d()?.shapes || 0) > 10000, null, { timeout: 60000 });
    await page.waitForTimeout(1000);
    fs.writeFileSync(path.join(ARTIFACTS, `map2d-demo-${browser}.png`), await page.screenshot());
    // Drag across the map for about three seconds, then zoom in with the wheel.
    const before = await page.evaluate(() => ({ camera: window.quakeview.getCamera(), frames: window.quakeview.map2d().frames }));
    const start = Date.now();
    await page.mouse.move(900, 360);
    await page.mouse.down();
    for (let i = 0; Date.now() - start < 3000; ++i) {
      await page.mouse.move(900 + 150 * Math.sin(i / 10), 360 + 100 * Math.cos(i / 13));
      await page.waitForTimeout(30);
    }
    await page.mouse.up();
    const seconds = (Date.now() - start) / 1000;
    const after = await page.evaluate(() => ({ camera: window.quakeview.getCamera(), state: window.quakeview.map2d() }));
    const fps = (after.state.frames - before.frames) / seconds;
    t.diagnostic(`${browser}: ${fps.toFixed(1)} frames/s while panning (${after.state.shapes} shapes, ` +
      `${after.state.drawMs.toFixed(1)} ms a frame of which the engine ${after.state.engineMs.toFixed(1)} ms)`);
    assert.notDeepEqual(after.camera, before.camera, 'the drag moved the map');
    assert.ok(fps > 5, `the map keeps drawing while panned: ${fps.toFixed(1)} frames/s`);
    for (let i = 0; i < 5; ++i) await page.mouse.wheel(0, -300);
    await page.waitForTimeout(800);
    const zoomed = await page.evaluate(() => window.quakeview.getCamera());
    assert.ok(zoomed.distance < after.camera.distance * 0.7, `the wheel zooms in: ${after.camera.distance} -> ${zoomed.distance}`);
    fs.writeFileSync(path.join(ARTIFACTS, `map2d-demo-zoomed-${browser}.png`), await page.screenshot());
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the 2D city pans with a finger and with the keys, zooms with the keys, and names the building tapped', async (t) => {
  const { context, close, browser } = await launchBrowser({ webgl: false, touch: true });
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/synth/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await waitForFunction(page, () => (window.quakeview.map2d()?.shapes || 0) > 1000, null, { timeout: 30000 });
    await page.waitForTimeout(1200);  // fitted to the map
    const camera = () => page.evaluate(() => window.quakeview.getCamera());
    // A finger dragged to the left moves the map with it: the view goes east.
    const start = await camera();
    await swipe(page, { x: 900, y: 400 }, { x: 700, y: 400 });
    await page.waitForTimeout(300);
    const swiped = await camera();
    t.diagnostic(`${browser}: swipe x ${start.x.toFixed(1)} -> ${swiped.x.toFixed(1)}`);
    assert.ok(swiped.x > start.x + 10, 'a swipe to the left shows what lies east');
    // Keys, with the focus on the map: an arrow pans, '+' zooms in.
    await page.evaluate(() => document.getElementById('canvas').focus());
    await page.keyboard.press('ArrowUp');
    await page.keyboard.press('+');
    await page.waitForTimeout(300);
    const keyed = await camera();
    assert.ok(keyed.y > swiped.y, 'ArrowUp shows what lies north');
    assert.ok(keyed.distance < swiped.distance * 0.9, '+ zooms in');
    // A tap on a building selects it, and the HTML panel names it.
    const spot = await page.evaluate(() => {
      for (let y = 100; y < 660; y += 23) {
        for (let x = 460; x < 1240; x += 29) {
          const hit = window.quakeview.pick(x, y);
          if (hit) return { x, y, id: hit.id };
        }
      }
      return null;
    });
    assert.ok(spot, 'a building is on the map');
    await page.touchscreen.tap(spot.x, spot.y);
    await waitForFunction(page, (id) => window.quakeview.selection() === id, spot.id, { timeout: 10000 });
    const label = await page.evaluate((id) => { const b = window.quakeview.building(id); return b && (b.name || b.address || b.id); }, spot.id);
    await waitForFunction(page, (text) => document.getElementById('qv-panel').innerText.includes(text), label, { timeout: 10000 });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
