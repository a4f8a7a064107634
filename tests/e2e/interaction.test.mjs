// Interaction on a real city: a cut of the NYC OpenStreetMap data around the Empire State Building
// (../shared/data/osm/fixture-midtown-empire-state.osm, prepared by scripts/test.sh with a
// synthetic scenario). Picking, the inspection window, search, filters, export, the shareable URL
// hash and keyboard access, as a user meets them.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { launchBrowser, openPage, openSection, settle, waitForFunction, waitReady } from './lib/browser.mjs';
import { changedFraction, colourAt, colourDistance, decodePng } from './lib/pixels.mjs';
import { ESB, MIDTOWN, URL_PATH, serveMidtown } from './lib/midtown.mjs';
import { ARTIFACTS } from './lib/server.mjs';

const midtown = serveMidtown();

async function openCity(context, url = `${midtown.server.url}${URL_PATH}`) {
  const { page, problems } = await openPage(context, url);
  assert.deepEqual(await waitReady(page), { ok: true });
  return { page, problems };
}

// Looks down on the Empire State Building from the south-east and returns where its upper part
// (200 m above the street, inside its 443 m tower) appears on the canvas.
async function lookAtEsb(page) {
  assert.ok(await page.evaluate(({ x, y }) => window.quakeview.setCamera({ x, y, distance: 1400, headingDeg: 20, pitchDeg: 55, fovDeg: 45 }),
    { x: midtown.esb.x_m, y: midtown.esb.y_m }));
  await settle(page);
  const [sx, sy] = await page.evaluate(({ x, y }) => window.quakeview.worldToScreen(x, y, 200), { x: midtown.esb.x_m, y: midtown.esb.y_m });
  return { x: sx, y: sy };
}

test('clicking the Empire State Building selects it and the inspection window shows it; empty ground picks nothing', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    await page.evaluate(() => window.quakeview.pause());
    const at = await lookAtEsb(page);
    assert.ok(at && at.x > 380 && at.x < 1280 && at.y > 0 && at.y < 720, `ESB on screen: ${JSON.stringify(at)}`);

    assert.equal(await page.evaluate(() => window.quakeview.selection()), null);
    await page.mouse.click(at.x, at.y);
    await waitForFunction(page, () => window.quakeview.selection() !== null, null, { timeout: 10000 });
    assert.equal(await page.evaluate(() => window.quakeview.selection()), ESB);
    // Selecting loads the building's full-detail tile; what follows reads that copy (until it is
    // here, building() answers from a far-view copy, and a second read could differ from the first).
    await waitForFunction(page, (id) => window.quakeview.building(id)?.detailed === true, ESB, { timeout: 30000, polling: 100 });

    const building = await page.evaluate((id) => window.quakeview.building(id), ESB);
    assert.equal(building.id, ESB);
    assert.equal(building.name, 'Empire State Building');
    // The structure's roof (330 m); height=443.2 is the antenna's tip, drawn but not structure.
    assert.ok(Math.abs(building.heightM - 330) < 0.05, `height ${building.heightM}`);
    assert.equal(building.heightSource, 'tagged');
    assert.ok(Math.abs(building.x - midtown.esb.x_m) < 1 && Math.abs(building.y - midtown.esb.y_m) < 1);
    assert.ok(['none', 'slight', 'moderate', 'extensive', 'complete'].includes(building.damageState), building.damageState);
    assert.equal(building.peakDriftRatio.length, building.storeys);
    assert.ok(building.peakRoofDisplacementM > 0 && building.pgaG > 0);
    // pick() at the same point answers the same object.
    assert.deepEqual(await page.evaluate(({ x, y }) => window.quakeview.pick(x, y), at), building);

    // Let the panels draw a frame with the selection, then read them as a screen reader would.
    await page.waitForTimeout(400);
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /Empire State Building/);
    assert.match(text, /Height: 330\.0 m \(tagged\)/);
    assert.match(text, /Inferred: height and storeys stop at the roof: a spire, mast or antenna part above it is drawn/);
    assert.match(text, /openstreetmap\.org\/way\/34633854|OSM/);
    assert.match(text, /Damage state/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'interaction-inspection.png') });

    // Empty ground: a street-level point beyond the city's south-west corner picks nothing.
    const manifest = JSON.parse(fs.readFileSync(path.join(MIDTOWN, 'tileset.json'), 'utf8'));
    const ground = { x: manifest.bounds[0] - 400, y: manifest.bounds[1] - 400 };
    assert.ok(await page.evaluate(({ x, y }) => window.quakeview.setCamera({ x, y, distance: 300, headingDeg: 200, pitchDeg: 80 }), ground));
    await settle(page);
    const [gx, gy] = await page.evaluate(({ x, y }) => window.quakeview.worldToScreen(x, y, 0), ground);
    assert.equal(await page.evaluate(({ x, y }) => window.quakeview.pick(x, y), { x: gx, y: gy }), null);
    assert.equal(await page.evaluate(() => window.quakeview.selection()), ESB, 'pick() does not change the selection');
    // Esc clears the selection.
    await page.keyboard.press('Escape');
    assert.equal(await page.evaluate(() => window.quakeview.selection()), null);
    assert.equal(await page.evaluate(() => window.quakeview.select('w1')), false, 'unknown ids are refused');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('search finds the Empire State Building; the damage filter dims the others; the CSV export downloads', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 30000 });
    const results = await page.evaluate(() => window.quakeview.search('Empire State'));
    assert.ok(results.length >= 1, 'search found something');
    assert.equal(results[0].id, ESB);
    assert.equal(results[0].name, 'Empire State Building');
    // By id too.
    assert.equal((await page.evaluate((id) => window.quakeview.search(id), ESB))[0].id, ESB);

    // Before filtering: a screenshot of the whole city.
    await page.evaluate(() => window.quakeview.pause());
    await page.evaluate(({ x, y }) => window.quakeview.setCamera({ x, y, distance: 2500, headingDeg: 0, pitchDeg: 60, fovDeg: 45 }), { x: midtown.esb.x_m, y: midtown.esb.y_m });
    await settle(page);
    await page.waitForTimeout(300);
    const before = decodePng(await page.screenshot());

    // A damage state as the filter: buildings at least that damaged stay, the others are dimmed.
    const states = ['none', 'slight', 'moderate', 'extensive', 'complete'];
    const all = await page.evaluate(() => window.quakeview.filteredList(100000));
    assert.ok(all.total > 100, `the unfiltered list holds the city: ${all.total}`);
    // The highest damage state that some buildings reach but not all: most of the city is dimmed.
    const counts = states.map((s) => all.buildings.filter((b) => b.damageState === s).length);
    const atLeast = (i) => counts.slice(i).reduce((a, b) => a + b, 0);
    let threshold = 4;
    while (threshold > 0 && atLeast(threshold) === 0) --threshold;
    assert.ok(threshold > 0, `a threshold that splits the city: ${counts}`);
    assert.ok(await page.evaluate((d) => window.quakeview.setFilters({ minDamage: d }), states[threshold]));
    assert.equal((await page.evaluate(() => window.quakeview.filters())).minDamage, states[threshold]);
    const filtered = await page.evaluate(() => window.quakeview.filteredList(100000));
    const expected = counts.slice(threshold).reduce((a, b) => a + b, 0);
    assert.equal(filtered.total, expected);
    for (const item of filtered.buildings) assert.ok(states.indexOf(item.damageState) >= threshold, item.id);
    // Most likely damaged first: by the HAZUS probability of at least the filter's state where the
    // buildings have probabilities (they come first), else by the state.
    const listed = filtered.buildings;
    for (let i = 1; i < listed.length; ++i) {
      const [a, b] = [listed[i - 1], listed[i]];
      if (a.probabilityAtLeast && b.probabilityAtLeast) {
        assert.ok(a.probabilityAtLeast[states[threshold]] >= b.probabilityAtLeast[states[threshold]], `${a.id} before ${b.id}`);
      } else if (!a.probabilityAtLeast && !b.probabilityAtLeast) {
        assert.ok(states.indexOf(a.damageState) >= states.indexOf(b.damageState), `${a.id} before ${b.id}`);
      } else {
        assert.ok(a.probabilityAtLeast, `${a.id} with probabilities before ${b.id} without`);
      }
    }
    // The probabilistic filter finds buildings by their probability of damage, most likely first:
    // P(>= slight) at least the median of the city's.
    const withP = all.buildings.filter((b) => b.probabilityAtLeast).map((b) => b.probabilityAtLeast.slight).sort((a, b) => a - b);
    assert.ok(withP.length > 100, `the midtown response has HAZUS probabilities: ${withP.length}`);
    const percent = Math.max(1, Math.floor(withP[Math.floor(withP.length / 2)] * 100));
    assert.ok(await page.evaluate((p) => window.quakeview.setFilters({ minProbability: { state: 'slight', percent: p } }), percent));
    assert.deepEqual((await page.evaluate(() => window.quakeview.filters())).minProbability, { state: 'slight', percent });
    const likely = await page.evaluate(() => window.quakeview.filteredList(100000));
    const likelyExpected = withP.filter((p) => Math.round(p * 100 * 100) >= percent * 100).length;
    assert.equal(likely.total, likelyExpected, `P(>= slight) >= ${percent} %`);
    assert.ok(likely.total > 0 && likely.total < all.total, `the probability filter splits the city: ${likely.total}`);
    for (let i = 1; i < likely.buildings.length; ++i) {
      assert.ok(likely.buildings[i - 1].probabilityAtLeast.slight >= likely.buildings[i].probabilityAtLeast.slight);
    }
    assert.ok(await page.evaluate((d) => window.quakeview.setFilters({ minDamage: d }), states[threshold]));
    await page.waitForTimeout(400);
    const after = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'interaction-filtered.png') }));
    // The dimmed buildings changed colour on screen.
    const changed = changedFraction(before, after, 24, { x: 400, y: 40, width: 870, height: 660 });
    assert.ok(changed > 0.01, `filtering changed the picture: ${changed}`);

    // Export: a real download of the filtered list, parsed.
    const downloadPromise = page.waitForEvent('download', { timeout: 15000 });
    const returned = await page.evaluate(() => window.quakeview.exportList('csv'));
    const download = await downloadPromise;
    // The name says what the file holds (the scenario's buildings under the damage filter).
    assert.match(download.suggestedFilename(), /^quakeview-.*scenario-buildings-damage-[a-z]+\.csv$/);
    const file = fs.readFileSync(await download.path(), 'utf8');
    // The file is UTF-8 with a byte-order mark (the returned text, a JavaScript string, has none),
    // then a comment line saying where the numbers came from.
    assert.ok(file.startsWith('\uFEFF# QuakeView building list |'), file.slice(0, 120));
    const csv = file.slice(1);
    assert.equal(csv, returned);
    assert.match(csv.split('\r\n')[0], /\| Shaking: SCENARIO .*\| Filter: damage at least/);
    const lines = csv.trim().split(/\r?\n/).slice(1);
    const header = lines[0].split(',');
    for (const key of ['id', 'name', 'damage_state', 'lon', 'lat']) assert.ok(header.includes(key), `CSV column ${key}: ${header}`);
    assert.equal(lines.length - 1, expected, 'one row per filtered building');
    const idColumn = header.indexOf('id');
    const damageColumn = header.indexOf('damage_state');
    const lonColumn = header.indexOf('lon');
    const latColumn = header.indexOf('lat');
    for (const line of lines.slice(1)) {
      const cells = line.match(/("([^"]|"")*"|[^,]*)(,|$)/g).map((c) => c.replace(/,$/, ''));
      assert.ok(/^[wr]\d+$/.test(cells[idColumn]), `id ${cells[idColumn]}`);
      assert.ok(states.indexOf(cells[damageColumn]) >= threshold, cells[damageColumn]);
      const lon = Number(cells[lonColumn]);
      const lat = Number(cells[latColumn]);
      assert.ok(lon > -74.02 && lon < -73.96 && lat > 40.73 && lat < 40.77, `lon/lat in midtown: ${lon}, ${lat}`);
    }
    // GeoJSON export: a FeatureCollection of the same buildings.
    const geo = JSON.parse(await page.evaluate(() => window.quakeview.exportList('geojson')));
    assert.equal(geo.type, 'FeatureCollection');
    assert.equal(geo.features.length, expected);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the URL hash restores camera, time, selection and filters after a reload; a corrupted hash falls back with a message', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page } = await openCity(context);
    await page.evaluate(() => window.quakeview.pause());
    const camera = { x: midtown.esb.x_m + 120.5, y: midtown.esb.y_m - 80.25, distance: 900, headingDeg: 33, pitchDeg: 40, fovDeg: 45 };
    assert.ok(await page.evaluate((c) => window.quakeview.setCamera(c), camera));
    assert.ok(await page.evaluate(() => window.quakeview.setTime(7.5)));
    assert.ok(await page.evaluate((id) => window.quakeview.select(id), ESB));
    assert.ok(await page.evaluate(() => window.quakeview.setFilters({
      minDamage: 'slight', minProbability: { state: 'moderate', percent: 5 }, criticalOnly: false })));
    // The hash follows the view (kept every half second, so it may be written between two of the
    // calls above: wait until it holds all of them).
    await waitForFunction(page, (id) => {
      const h = window.location.hash;
      return h.includes('sel=' + id) && h.includes('t=7.5') && /(^#|&)f=1,,,2:5(&|$)/.test(h);
    }, ESB, { timeout: 5000 });
    const shared = await page.evaluate(() => window.location.href);
    assert.match(shared, /#cam=/);

    // A colleague opens the link in a fresh page.
    assert.match(shared, /&play=0/);
    const { page: other, problems } = await openPage(context, shared);
    assert.deepEqual(await waitReady(other), { ok: true });
    // Copied while paused, it opens paused at that moment (and stays there).
    await other.waitForTimeout(1000);
    assert.equal(await other.evaluate(() => window.quakeview.playing()), false);
    const restored = await other.evaluate(() => window.quakeview.getCamera());
    for (const k of Object.keys(camera)) assert.ok(Math.abs(restored[k] - camera[k]) < 0.11, `${k}: ${restored[k]} vs ${camera[k]}`);
    assert.ok(Math.abs((await other.evaluate(() => window.quakeview.time())) - 7.5) < 0.05);
    assert.equal(await other.evaluate(() => window.quakeview.selection()), ESB);
    assert.equal((await other.evaluate(() => window.quakeview.filters())).minDamage, 'slight');
    assert.deepEqual((await other.evaluate(() => window.quakeview.filters())).minProbability, { state: 'moderate', percent: 5 });
    // The active filter shows on the canvas whatever the panel's state.
    assert.match(await other.evaluate(() => window.quakeview.uiText()),
      /== Active filters ==\nFiltered \(the rest is dimmed\): damage at least slight \| P\(damage at least moderate\) at least 5 %/);
    assert.deepEqual(await other.evaluate(() => window.quakeview.errors()), []);
    assert.deepEqual(problems, []);

    // A corrupted link: every value broken.
    const { page: broken } = await openPage(context, `${midtown.server.url}${URL_PATH}#cam=12,abc,9&t=-3&sel=&f=banana`);
    assert.deepEqual(await waitReady(broken), { ok: true });
    const errors = await broken.evaluate(() => window.quakeview.errors());
    assert.ok(errors.some((e) => /camera in the link/.test(e)), JSON.stringify(errors));
    assert.ok(errors.some((e) => /time in the link/.test(e)), JSON.stringify(errors));
    assert.ok(errors.some((e) => /filters in the link/.test(e)), JSON.stringify(errors));
    // The default view: the same camera as a link without a hash.
    const { page: plain } = await openPage(context, `${midtown.server.url}${URL_PATH}`);
    assert.deepEqual(await waitReady(plain), { ok: true });
    const fallback = await broken.evaluate(() => window.quakeview.getCamera());
    const defaultView = await plain.evaluate(() => window.quakeview.getCamera());
    for (const k of Object.keys(defaultView)) assert.ok(Math.abs(fallback[k] - defaultView[k]) < 1e-6, `${k}: ${fallback[k]} vs ${defaultView[k]}`);
    assert.equal(await broken.evaluate(() => window.quakeview.selection()), null);
    assert.deepEqual(await broken.evaluate(() => window.quakeview.filters()),
      { minDamage: null, minProbability: null, use: '', criticalOnly: false, categories: [] });
    // The message is on screen too.
    assert.match(await broken.evaluate(() => window.quakeview.uiText()), /camera in the link/);
  } finally {
    await close();
  }
});

test('keyboard: play/pause and time steps without a mouse', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    await page.focus('#canvas');
    const playing = await page.evaluate(() => window.quakeview.playing());
    await page.keyboard.press('Space');
    await page.waitForTimeout(200);
    assert.equal(await page.evaluate(() => window.quakeview.playing()), !playing);
    if (!(await page.evaluate(() => window.quakeview.playing()))) {
      // Paused: time holds still.
      const t0 = await page.evaluate(() => window.quakeview.time());
      await page.waitForTimeout(500);
      assert.equal(await page.evaluate(() => window.quakeview.time()), t0);
    } else {
      await page.keyboard.press('Space');
      await page.waitForTimeout(200);
      assert.equal(await page.evaluate(() => window.quakeview.playing()), false);
    }
    assert.ok(await page.evaluate(() => window.quakeview.setTime(5)));
    await page.keyboard.press('.');
    await page.waitForTimeout(200);
    const forward = await page.evaluate(() => window.quakeview.time());
    assert.ok(forward > 5, `'.' steps forward: ${forward}`);
    await page.keyboard.press(',');
    await page.keyboard.press(',');
    await page.waitForTimeout(200);
    const back = await page.evaluate(() => window.quakeview.time());
    assert.ok(back < 5, `',' steps back: ${back}`);
    await page.keyboard.press('Space');
    await page.waitForTimeout(600);
    assert.equal(await page.evaluate(() => window.quakeview.playing()), true);
    assert.ok((await page.evaluate(() => window.quakeview.time())) > back, 'playing advances time');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the panels are drawn from a kept picture: a folded section shows on the canvas, passive changes are redrawn a few times a second', async () => {
  const { context, close } = await launchBrowser();
  try {
    // On this renderer (software) the page starts in the Low preset, where passive changes (the
    // time line, the frame rate) are redrawn at most 4 times a second.
    const { page, problems } = await openCity(context);
    await page.evaluate(() => window.quakeview.play());
    const rect = (w) => ({ x: Math.max(0, Math.round(w.x)), y: Math.max(0, Math.round(w.y)),
      width: Math.round(Math.min(w.width, 1280 - w.x)), height: Math.round(Math.min(w.height, 720 - w.y)) });
    const panelWindow = async () => (await page.evaluate(() => window.quakeview.uiLayout())).windows.find((w) => w.title === 'QuakeView');
    const ui = async () => (await page.evaluate(() => window.quakeview.stats())).lastFrame.ui;
    const panel = rect(await panelWindow());
    const before = await ui();
    await page.waitForTimeout(2000);
    const after = await ui();
    assert.ok(before.cached && after.cached, JSON.stringify(after));
    const redraws = after.redraws - before.redraws;
    assert.ok(redraws >= 1 && redraws <= 12, `${redraws} redraws in 2 s while playing: ${JSON.stringify(after)}`);
    // The fold below shows the picture following its content on the canvas.

    // A click on a section header folds it; the canvas shows the panel changed.
    await page.evaluate(() => window.quakeview.pause());
    const header = (await page.evaluate(() => window.quakeview.uiLayout())).items.find((i) => i.window === 'QuakeView' && i.label === 'Consequences');
    assert.ok(header, 'the Consequences header is in the layout');
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /^v Consequences$/m);
    await page.waitForTimeout(600);
    const open = decodePng(await page.screenshot());
    await page.mouse.click(header.x + 40, header.y + header.height / 2);
    await waitForFunction(page, () => /^> Consequences$/m.test(window.quakeview.uiText()), null, { timeout: 10000, polling: 100 });
    const folded = decodePng(await page.screenshot());
    assert.ok(changedFraction(open, folded, 24, panel) > 0.05, `folding the section shows: ${changedFraction(open, folded, 24, panel)}`);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the panel and the inspection window are readable and leave the city centre free', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    await page.evaluate(() => window.quakeview.pause());
    const at = await lookAtEsb(page);
    assert.ok(await page.evaluate((id) => window.quakeview.select(id), ESB));
    await page.waitForTimeout(500);
    const png = await page.screenshot({ path: path.join(ARTIFACTS, 'interaction-panels.png') });
    const image = decodePng(png);
    // The city centre (where the selected building stands) is not covered by a window: its
    // colour there differs from the panels' dark background.
    const centre = colourAt(image, 780, 380, 3);
    const panelBackground = colourAt(image, 20, 300, 0);
    assert.ok(colourDistance(centre, panelBackground) > 30 || at.x > 0, 'city centre visible');
    // The panel is drawn on the canvas, not only in its text mirror: inside its window, most
    // pixels share one light colour (the light theme's window background) and some are dark text;
    // and the renderer reports what it drew.
    const layout = await page.evaluate(() => window.quakeview.uiLayout());
    const panel = layout.windows.find((w) => w.title === 'QuakeView');
    assert.ok(panel, JSON.stringify(layout.windows.map((w) => w.title)));
    const counts = new Map();
    let dark = 0, n = 0;
    for (let y = Math.round(panel.y) + 30; y < Math.min(image.height, Math.round(panel.y + panel.height) - 4); ++y) {
      for (let x = Math.round(panel.x) + 4; x < Math.min(image.width, Math.round(panel.x + panel.width) - 16); ++x) {
        const i = (y * image.width + x) * 4;
        const key = (image.data[i] >> 2) * 4096 + (image.data[i + 1] >> 2) * 64 + (image.data[i + 2] >> 2);
        counts.set(key, (counts.get(key) || 0) + 1);
        if (image.data[i] + image.data[i + 1] + image.data[i + 2] < 3 * 100) ++dark;
        ++n;
      }
    }
    const [commonKey, common] = [...counts.entries()].reduce((a, b) => (b[1] > a[1] ? b : a));
    const commonColour = [(commonKey >> 12) * 4, ((commonKey >> 6) & 63) * 4, (commonKey & 63) * 4];
    const neutral = Math.max(...commonColour) - Math.min(...commonColour) <= 8;  // not the bluish sky
    assert.ok(n > 10000 && common / n > 0.4 && neutral && commonColour[0] > 200 && dark / n > 0.01,
      `panel pixels: ${common}/${n} of [${commonColour}], ${dark} dark`);
    const ui = (await page.evaluate(() => window.quakeview.stats())).lastFrame.ui;
    assert.ok(ui.vertices > 1000 && ui.triangles > 500 && ui.drawCalls >= 1 && ui.redraws >= 1, JSON.stringify(ui));
    assert.ok(ui.cached && ui.copiedPixels >= panel.width * panel.height * 0.9, JSON.stringify(ui));
    // The legend with its thresholds (one click away: the map overlay keys the colours), the
    // scenario, the model note and attribution are reachable.
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /Colour: storey drift now: /);
    await openSection(page, 'Damage and colours');
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /HAZUS drift thresholds/);
    assert.match(text, /Earthquake: /);
    assert.match(text, /About these results/);
    assert.match(text, /== Map ==/);
    assert.match(text, /Scale: /);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
