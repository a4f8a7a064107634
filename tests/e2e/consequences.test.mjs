// Decision-grade results in the browser: whether the shaking is a SCENARIO or an ACTUAL event is on
// screen; the Consequences panel and `quakeview.consequences()` give the city's totals exactly as
// `quakeview-prep info --json` does, plus the view's and each district's; the probabilistic colour
// modes colour the city; a building's inspection shows its damage-state probabilities.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, openSection, panelItemInView, settle, waitForFunction, waitReady } from './lib/browser.mjs';
import { changedFraction, decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const ACTUAL = path.join(DATA, 'actual');
const SYNTH = path.join(DATA, 'synth');
// The city at the overview, right of the panel.
const CITY_RECT = { x: 540, y: 220, width: 460, height: 320 };
let server;

before(async () => {
  for (const dir of [ACTUAL, SYNTH]) {
    assert.ok(fs.existsSync(path.join(dir, 'tileset.json')), `test city missing: ${dir} (scripts/test.sh prepares it)`);
  }
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  server = await serveSite({ '/actual': ACTUAL, '/synth': SYNTH });
});
after(() => server?.close());

test('an ACTUAL ShakeMap is stated as such, and the totals match what the tool wrote', async () => {
  const info = JSON.parse(fs.readFileSync(path.join(DATA, 'actual-info.json'), 'utf8'));
  assert.equal(info.event_type, 'ACTUAL');
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/actual/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    // The city's totals (consequences.json) and the view's (the buildings' losses, from the index).
    await waitForFunction(page, () => window.quakeview.consequences()?.city != null && window.quakeview.consequences()?.view != null,
      null, { timeout: 30000 });
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /Shaking: ACTUAL EVENT \(ShakeMap of a recorded earthquake\)/);
    assert.match(text, /ShakeMap: qvtest2026 version 4, processed 2026-11-25T10:05:00Z/);
    assert.doesNotMatch(text, /SCENARIO/);

    const c = await page.evaluate(() => window.quakeview.consequences());
    assert.equal(c.eventType, 'ACTUAL');
    assert.equal(c.timeOfDay, 'night');
    assert.equal(c.shakemap.eventId, 'qvtest2026');
    // The city's totals are the file's, as info --json reports them.
    const states = ['none', 'slight', 'moderate', 'extensive', 'complete'];
    for (const s of states) {
      assert.ok(Math.abs(c.city.damageStates[s].expected - info.expected_damage_states[s]) < 1e-6, s);
    }
    const sum = states.reduce((a, s) => a + c.city.damageStates[s].expected, 0);
    assert.ok(Math.abs(sum - c.city.buildings) < 1e-6, `expected counts sum to ${sum}, not ${c.city.buildings}`);
    assert.ok(Math.abs(c.city.repairCostUsd.expected - info.consequences.repair_cost_usd.expected) < 1e-3);
    assert.equal(c.districts.length, 2);
    assert.equal(c.districts[0].name, 'West of -73.9995');
    assert.equal(c.districts[0].buildings + c.districts[1].buildings, c.city.buildings);
    // The whole small city is in view at the overview: the view's expected values are the city's.
    assert.equal(c.view.buildings, c.city.buildings);
    for (const s of states) {
      assert.ok(Math.abs(c.view.damageStates[s].expected - c.city.damageStates[s].expected) < 1e-3, s);
      assert.ok(c.view.damageStates[s].low <= c.view.damageStates[s].expected + 1e-9);
      assert.ok(c.view.damageStates[s].high >= c.view.damageStates[s].expected - 1e-9);
    }
    assert.ok(Math.abs(c.view.repairCostUsd.expected - c.city.repairCostUsd.expected) <=
      1e-4 * Math.max(1, c.city.repairCostUsd.expected));
    // The view says which ground it covers; closer in, it covers less, inside the overview's.
    const all = c.view.bounds;
    assert.ok(all && all.west < all.east && all.south < all.north, JSON.stringify(all));
    const camera = await page.evaluate(() => window.quakeview.getCamera());
    await page.evaluate((cam) => window.quakeview.setCamera({ ...cam, distance: cam.distance / 6 }), camera);
    await waitForFunction(page, (n) => window.quakeview.consequences().view.buildings < n, c.view.buildings,
      { timeout: 30000 });
    await page.waitForTimeout(500);
    const near = (await page.evaluate(() => window.quakeview.consequences())).view.bounds;
    const tol = 1e-6;  // degrees (0.1 m): the corners are projected one by one
    assert.ok(near.west >= all.west - tol && near.east <= all.east + tol && near.south >= all.south - tol &&
      near.north <= all.north + tol, `${JSON.stringify(near)} inside ${JSON.stringify(all)}`);
    assert.ok((near.east - near.west) * (near.north - near.south) < (all.east - all.west) * (all.north - all.south));
    await page.evaluate((cam) => window.quakeview.setCamera(cam), camera);
    await waitForFunction(page, (n) => window.quakeview.consequences().view.buildings === n, c.city.buildings,
      { timeout: 30000 });

    // The Consequences section of the panel (open by default) leads with the headline numbers;
    // one click opens all of them, the same table; the suite's spread follows once the city-wide
    // summary (loaded after the search index) is in.
    const headline = await page.evaluate(() => window.quakeview.uiText());
    assert.match(headline, /Red tags \(unsafe\) \| [\d.]+ \([\d.]+-[\d.]+\)/);
    assert.match(headline, /Deaths \| [\d.]+ \([\d.]+-[\d.]+\)/);
    assert.match(headline, /Repair cost \| \$/);
    await openSection(page, 'All consequences: city, view, districts');
    await waitForFunction(page, () => /Record-to-record spread: peak drifts/.test(window.quakeview.uiText()), null,
      { timeout: 30000 });
    const panel = await page.evaluate(() => window.quakeview.uiText());
    assert.match(panel, /\| City \| In view/);
    assert.match(panel, /Repair cost \| \$/);
    assert.match(panel, /West of -73.9995 \|/);
    // The city's people at every time of day (inferred from floor area and use: OSM gives no counts).
    assert.match(panel, /Occupants: [\d.,]+( million)? by day, [\d.,]+( million)? at night, [\d.,]+( million)? at commute time \(inferred/);
    // A suite of two records: its spread over the city is reported.
    assert.match(panel, /Record-to-record spread: peak drifts vary by a log standard deviation of \d\.\d\d/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'consequences-panel.png') });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the probabilistic colour modes colour the city, and the inspection shows the probabilities', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/synth/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await page.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(0); });
    const shots = {};
    for (const mode of ['neutral', 'p-moderate', 'expected-damage', 'tag']) {
      assert.equal(await page.evaluate((m) => window.quakeview.setColorMode(m), mode), true, mode);
      assert.equal(await page.evaluate(() => window.quakeview.colorMode()), mode);
      await page.waitForTimeout(300);
      shots[mode] = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, `colour-${mode}.png`) }));
    }
    for (const mode of ['p-moderate', 'expected-damage', 'tag']) {
      assert.ok(changedFraction(shots.neutral, shots[mode], 24, CITY_RECT) > 0.02, `${mode} colours the city`);
    }
    assert.equal(await page.evaluate(() => window.quakeview.setColorMode('probability')), false);

    const info = JSON.parse(fs.readFileSync(path.join(DATA, 'synth-s1.json'), 'utf8'));
    await page.evaluate(() => window.quakeview.select('s1'));
    await waitForFunction(page, () => window.quakeview.building('s1')?.damageProbabilities != null, null, { timeout: 30000 });
    const b = await page.evaluate(() => window.quakeview.building('s1'));
    const states = ['none', 'slight', 'moderate', 'extensive', 'complete'];
    const total = states.reduce((a, s) => a + b.damageProbabilities[s], 0);
    assert.ok(Math.abs(total - 1) < 1e-4, `probabilities sum to ${total}`);
    for (const s of states) assert.ok(Math.abs(b.damageProbabilities[s] - info.damage_probabilities[s]) < 1e-6, s);
    assert.ok(Math.abs(b.consequences.repairCostUsd - info.consequences.repair_cost_usd) <= 1e-3 * Math.max(1, info.consequences.repair_cost_usd));
    assert.equal(b.consequences.occupantsInferred, true);
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /Damage probabilities \(HAZUS 5.1 fragility\):/);
    assert.match(text, /Moderate: \d+\.\d %/);
    assert.match(text, /Occupants present: [\d.]+ \(inferred from floor area and use\)/);
    assert.match(text, /Shaking, X: T1 [\d.]+ s; target Sa\(T1\)/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'inspection-probabilities.png') });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

// The district rows of the panel's table as mirrored ("> name | buildings | >= moderate | ..."),
// in the order shown.
function districtRows(text) {
  return text.split('\n').filter((l) => /^> .+ \| \d+ \| /.test(l)).map((l) => {
    const cells = l.slice(2).split(' | ');
    return { name: cells[0], buildings: Number(cells[1]), moderate: Number(cells[2]) };
  });
}

// Pixels of the outline's navy (the report map's district lines, #1d3557) in a picture.
function navyPixels(image) {
  let n = 0;
  for (let i = 0; i < image.width * image.height; ++i) {
    const r = image.data[4 * i], g = image.data[4 * i + 1], b = image.data[4 * i + 2];
    if (Math.abs(r - 29) < 14 && Math.abs(g - 53) < 14 && Math.abs(b - 87) < 14) ++n;
  }
  return n;
}

test('districts by default: the neighbourhoods of the city\'s own input, a sortable table, a click flies there and outlines it', async () => {
  // The synthetic city was made and analysed without a districts file: its own neighbourhoods.
  const info = JSON.parse(fs.readFileSync(path.join(DATA, 'synth-s1.json'), 'utf8'));
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/synth/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await waitForFunction(page, () => window.quakeview.consequences()?.city != null, null, { timeout: 30000 });
    const c = await page.evaluate(() => window.quakeview.consequences());
    assert.ok(c.districts.length >= 4, `neighbourhood rows: ${JSON.stringify(c.districts.map((d) => d.name))}`);
    assert.equal(c.districts.reduce((a, d) => a + d.buildings, 0), c.city.buildings, 'the rows add up to the city');
    const repair = c.districts.reduce((a, d) => a + d.repairCostUsd.expected, 0);
    assert.ok(Math.abs(repair - c.city.repairCostUsd.expected) < 1e-6 * c.city.repairCostUsd.expected + 1e-3,
      `the districts' repair costs add up to the city's: ${repair} vs ${c.city.repairCostUsd.expected}`);
    assert.equal(c.districtsInferred, true);
    assert.match(c.districtsSource, /nearest synth-city neighbourhood name/);
    assert.ok(c.districts.some((d) => d.name === 'Downtown'));
    assert.ok(info.consequences, 'the tool wrote the consequences it was checked against');

    await openSection(page, 'All consequences: city, view, districts');
    let text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, new RegExp(`Districts \\(${c.districts.length}\\): each building to its nearest synth-city neighbourhood name.*INFERRED: not official boundaries`));
    // Sorted by damage, largest first, at the start.
    let rows = districtRows(text);
    assert.equal(rows.length, c.districts.length, text);
    for (let i = 1; i < rows.length; ++i) assert.ok(rows[i - 1].moderate >= rows[i].moderate, `by damage: ${JSON.stringify(rows)}`);
    // A click on the "Buildings" header sorts by buildings (largest first).
    const header = await panelItemInView(page, 'Buildings');
    await page.mouse.click(header.x + header.width / 2, header.y + header.height / 2);
    await waitForFunction(page, () => {
      const lines = window.quakeview.uiText().split('\n').filter((l) => /^> .+ \| \d+ \| /.test(l));
      const b = lines.map((l) => Number(l.split(' | ')[1]));
      return b.length > 1 && b.every((v, i) => i === 0 || b[i - 1] >= v);
    }, null, { timeout: 10000, polling: 200 });
    rows = districtRows(await page.evaluate(() => window.quakeview.uiText()));
    for (let i = 1; i < rows.length; ++i) assert.ok(rows[i - 1].buildings >= rows[i].buildings, `by buildings: ${JSON.stringify(rows)}`);

    // A click on a district's row flies there and outlines it on the ground.
    await page.evaluate(() => window.quakeview.pause());
    const before = await page.evaluate(() => window.quakeview.getCamera());
    const plain = decodePng(await page.screenshot());
    const target = rows[rows.length - 1].name;  // the smallest: the camera must move to it
    const row = await panelItemInView(page, target);
    await page.mouse.click(row.x + row.width / 2, row.y + row.height / 2);
    await waitForFunction(page, (name) => window.quakeview.shownDistrict() === name, target, { timeout: 10000 });
    await page.waitForTimeout(1800);  // the flight (1.2 s)
    await settle(page);
    const after = await page.evaluate(() => window.quakeview.getCamera());
    assert.ok(Math.hypot(after.x - before.x, after.y - before.y) > 50, `the camera flew: ${JSON.stringify([before, after])}`);
    assert.ok(after.distance < before.distance, 'closer than the overview');
    text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, new RegExp(`Outlined district: ${target}`));
    assert.match(text, new RegExp(`Outlined: ${target}`));
    const outlined = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'district-outlined.png') }));
    assert.ok(navyPixels(outlined) > 400 + navyPixels(plain), `the outline is drawn: ${navyPixels(outlined)} navy pixels`);
    // "Clear outline" takes it away; the API does the same as the click.
    const clear = await panelItemInView(page, 'Clear outline');
    await page.mouse.click(clear.x + clear.width / 2, clear.y + clear.height / 2);
    await waitForFunction(page, () => window.quakeview.shownDistrict() === '', null, { timeout: 5000 });
    assert.equal(await page.evaluate(() => window.quakeview.showDistrict('No such place')), false);
    assert.equal(await page.evaluate((n) => window.quakeview.showDistrict(n), rows[0].name), true);
    assert.equal(await page.evaluate(() => window.quakeview.shownDistrict()), rows[0].name);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
