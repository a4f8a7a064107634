// Critical facilities as emergency managers define them, on a small test city with PLANTED uses
// (tests/e2e/data/critical-facilities.geojson, prepared by scripts/test.sh with a synthetic
// scenario): essential facilities (hospital, fire, police, ambulance), schools, a 150 m office
// tower, a multi-part residential building, a stadium, a fuel station, a clinic, a bus stop's
// shelter (OSM amenity=shelter: no facility), a social facility that is a shelter, and unnamed
// buildings with and without an address. Each planted feature says what it should be in its
// `expect_category` and `expect_use` properties (the normalized use: an `amenity=clinic` is a
// "clinic", not an essential facility), which the prep tool ignores.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, settle, waitForFunction, waitReady } from './lib/browser.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const CITY = path.join(DATA, 'critical');
const SOURCE = path.join(REPO, 'tests/e2e/data/critical-facilities.geojson');

let server;
let planted; // [{id, name, address, expect}] from the source file
before(async () => {
  assert.ok(fs.existsSync(path.join(CITY, 'tileset.json')), `test city missing: ${CITY} (scripts/test.sh prepares it)`);
  const source = JSON.parse(fs.readFileSync(SOURCE, 'utf8'));
  planted = source.features.filter((f) => f.properties.expect_category).map((f) => {
    const p = f.properties;
    const street = [p['addr:housenumber'], p['addr:street']].filter(Boolean).join(' ');
    return { sourceId: p.id, name: p.name || '', street, expect: p.expect_category, use: p.expect_use,
      kind: p.expect_kind || '' };
  });
  server = await serveSite({ '/data': DATA });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => {
  if (server) await server.close();
});

async function openCity(context, hash) {
  const { page, problems } = await openPage(context, `${server.url}/?data=/data/critical/tileset.json#${hash}`);
  assert.deepEqual(await waitReady(page), { ok: true });
  await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 60000 });
  return { page, problems };
}

// The viewer's row for a planted feature: its id ends with the source id ("g:c3" for "c3").
function plantedOf(entry) {
  const found = planted.filter((p) => entry.id === p.sourceId || entry.id.endsWith(':' + p.sourceId));
  assert.equal(found.length, 1, `one planted feature for ${entry.id}`);
  return found[0];
}

test('the critical filter from a link returns exactly the planted essential facilities and schools', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context, 'f=,,1');
    assert.deepEqual(await page.evaluate(() => window.quakeview.filters()),
      { minDamage: null, minProbability: null, use: '', criticalOnly: true, categories: [] });
    // The kept facilities are marked on the map: a disc of a fixed size at each one's roof, one
    // draw call of two triangles each, with the panel naming the one under the pointer.
    await settle(page);
    const kept = await page.evaluate(() => window.quakeview.filteredList(1000).buildings);
    const marked = await page.evaluate(() => window.quakeview.stats());
    await page.evaluate(() => window.quakeview.setFilters({ criticalOnly: false }));
    await page.waitForTimeout(300);
    const unmarked = await page.evaluate(() => window.quakeview.stats());
    assert.equal(marked.lastFrame.triangles - unmarked.lastFrame.triangles, 2 * kept.length,
      `two triangles a marker: ${marked.lastFrame.triangles} with, ${unmarked.lastFrame.triangles} without`);
    assert.ok(await page.evaluate(() => window.quakeview.setFilters({ criticalOnly: true })));
    await page.waitForTimeout(300);
    // From 2 km, the pointer on one of them (its roof, where its marker is) names it.
    const target = kept.find((b) => b.name) || kept[0];
    await page.evaluate((b) => window.quakeview.setCamera({ x: b.x - 150, y: b.y, distance: 2000, headingDeg: 0, pitchDeg: 60 }), target);
    await settle(page);
    const roof = await page.evaluate((b) => {
      const info = window.quakeview.building(b.id);
      return window.quakeview.worldToScreen(b.x, b.y, info ? info.heightM : 0);
    }, target);
    assert.ok(roof && roof[0] > 560 && roof[1] > 40, `the facility is in view right of the panel: ${roof}`);
    await page.mouse.move(roof[0], roof[1]);
    await waitForFunction(page, (name) => window.quakeview.uiText().includes(name + ' ('), target.label, { timeout: 10000 });
    const list = await page.evaluate(() => window.quakeview.filteredList(1000));
    const wanted = planted.filter((p) => p.expect === 'essential' || p.expect === 'school_shelter');
    assert.ok(wanted.length >= 5, 'the city plants essential facilities and schools');
    const got = list.buildings.map((b) => plantedOf(b).sourceId).sort();
    assert.deepEqual(got, wanted.map((p) => p.sourceId).sort());
    assert.equal(list.total, wanted.length);
    // Neither the 150 m tower nor the multi-part building, nor the clinic without beds.
    for (const b of list.buildings) assert.ok(['essential', 'school_shelter'].includes(b.facility), JSON.stringify(b));
    // Every planted category arrives as the viewer's category.
    const everything = await page.evaluate(() => {
      window.quakeview.setFilters({});
      return window.quakeview.filteredList(1000).buildings;
    });
    assert.ok(everything.length > list.total, `${everything.length} buildings in all`);
    for (const b of everything) {
      const p = plantedOf(b);
      assert.equal(b.facility, p.expect, `${p.sourceId} (${p.name || p.street}) is ${p.expect}`);
      assert.equal(b.use, p.use, `${p.sourceId} is used as ${p.use}`);
      // The kind that made it a facility (what the list shows where the use is generic).
      assert.equal(b.facilityKind, p.kind, `${p.sourceId}'s facility kind is ${p.kind || 'none'}`);
    }
    // Categories by name in the link's critical field.
    const hazardous = await page.evaluate(() => {
      window.quakeview.setFilters({ categories: ['hazardous', 'high_occupancy'] });
      return window.quakeview.filteredList(1000).buildings.map((b) => b.facility).sort();
    });
    assert.deepEqual(hazardous, planted.filter((p) => p.expect === 'hazardous' || p.expect === 'high_occupancy')
      .map((p) => p.expect).sort());
    // The link keeps the categories in its critical field.
    await waitForFunction(page, () => /f=,,(hazardous\+high_occupancy|high_occupancy\+hazardous)(&|$)/.test(location.hash),
      null, { timeout: 10000 });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('several uses at once from a link; rows show the address of unnamed buildings; the export name carries the filter', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context, 'f=,hospital+school,');
    const list = await page.evaluate(() => window.quakeview.filteredList(1000));
    const uses = [...new Set(list.buildings.map((b) => b.use))].sort();
    assert.deepEqual(uses, ['hospital', 'school']);
    const wanted = planted.filter((p) => p.use === 'hospital' || p.use === 'school');
    assert.deepEqual(list.buildings.map((b) => plantedOf(b).sourceId).sort(), wanted.map((p) => p.sourceId).sort());
    assert.equal(list.total, wanted.length);
    // A row names a building by its name, else its address, never only its id when it has one.
    for (const b of list.buildings) {
      const p = plantedOf(b);
      if (p.name) assert.equal(b.label, p.name);
      else {
        assert.ok(p.street && b.label.startsWith(p.street), `${b.id}: label ${b.label}, address ${p.street}`);
        assert.notEqual(b.label, b.id);
      }
    }
    assert.ok(list.buildings.some((b) => !plantedOf(b).name), 'an unnamed school with an address is planted');
    // The export's file name and provenance line carry both uses.
    const downloadPromise = page.waitForEvent('download', { timeout: 15000 });
    const csv = await page.evaluate(() => window.quakeview.exportList('csv'));
    const download = await downloadPromise;
    assert.match(download.suggestedFilename(), /^quakeview-.*-scenario-buildings-use-hospital-school\.csv$/);
    assert.match(csv.split('\r\n')[0], /Filter: use: hospital or school/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'critical-uses.png') });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('a bad critical field in a link is refused with the field named, and every building shows', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page } = await openPage(context, `${server.url}/?data=/data/critical/tileset.json#f=,,tall`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.ok(errors.some((e) => /critical 'tall' is not 0, 1 or categories/.test(e)), JSON.stringify(errors));
    assert.equal(await page.evaluate(() => window.quakeview.filters().criticalOnly), false);
  } finally {
    await close();
  }
});
