// A city folder with several scenarios (scenarios.json beside its manifests, docs/formats.md): the
// panel lists them with their event types; choosing another shows its results in the same view
// (its consequences, its event, its colours), the link follows and opens it again; the API does the
// same; a hostile catalogue entry is refused with a message while the city opens; the 2D city's
// HTML panel offers the same list.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, openSection, settle, waitForFunction, waitReady } from './lib/browser.mjs';
import { warmClassifier, warmPixels } from './lib/colours.mjs';
import { changedFraction, decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const CITY = path.join(DATA, 'scenarios');
const FIRST = 'M6.6 scenario, Lower Manhattan';
const SECOND = 'M5.0 scenario, Lower East Side';
// Listed in the catalogue, never run: its manifest is not there (HTTP 404).
const THIRD = 'M7.2 scenario, not yet run';
let server;
let scratch;

before(async () => {
  for (const file of ['tileset.json', 'scenario-1.json', 'scenario-2.json', 'scenarios.json']) {
    assert.ok(fs.existsSync(path.join(CITY, file)),
      `test city file missing: ${path.join(CITY, file)} (scripts/test.sh makes it with tests/e2e/data/make-scenario-city.sh)`);
  }
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  // The same city under a catalogue with a hostile entry: a manifest outside its folder.
  scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-scenarios-'));
  const hostile = path.join(scratch, 'scenarios.json');
  fs.writeFileSync(hostile, JSON.stringify({ format: 'quakeview-scenarios', version: 1, scenarios: [
    { index: 1, name: FIRST, manifest: 'scenario-1.json' },
    { index: 2, name: 'Another city', manifest: '../elsewhere/tileset.json' },
  ] }));
  // A mount naming a file serves that file: it takes the place of the city's own catalogue.
  server = await serveSite({ '/hostile/scenarios.json': hostile, '/hostile': CITY, '/scen': CITY });
});
after(async () => {
  await server?.close();
  if (scratch) fs.rmSync(scratch, { recursive: true, force: true });
});

// Pixels of the screenshot outside the panels' windows (as uiLayout last drew them).
function outsideWindows(layout) {
  const rects = layout.windows.map((w) => [w.x - 2, w.y - 2, w.x + w.width + 2, w.y + w.height + 2]);
  return (x, y) => rects.some(([x0, y0, x1, y1]) => x >= x0 && x < x1 && y >= y0 && y < y1);
}

// The panel's row of the scenario named `name` (its visible text starts with the name).
async function scenarioRow(page, name) {
  for (let attempt = 0; attempt < 8; ++attempt) {
    const layout = await page.evaluate(() => window.quakeview.uiLayout());
    const item = layout.items.find((i) => i.window === 'QuakeView' && i.label.startsWith(name + ':'));
    const panel = layout.windows.find((w) => w.title === 'QuakeView');
    if (!item || !panel) throw new Error(`the panel has no row for "${name}": ${JSON.stringify(layout.items.map((i) => i.label))}`);
    const centreY = item.y + item.height / 2;
    if (centreY > panel.y + 20 && centreY < panel.y + panel.height - 10) return item;
    await page.mouse.move(panel.x + panel.width / 2, panel.y + panel.height / 2);
    await page.mouse.wheel(0, centreY - (panel.y + panel.height / 2));
    await page.waitForTimeout(300);
  }
  throw new Error(`the row for "${name}" stays outside the panel`);
}

const cityTotals = () => {
  const c = window.quakeview.consequences();
  return c && c.city ? { moderateOrWorse: c.city.moderateOrWorse.expected, red: c.city.tags.red.expected, eventType: c.eventType } : null;
};

test('the panel lists the scenarios; choosing another shows its results in the same view, and the link opens it',
  async () => {
    const { context, close } = await launchBrowser();
    try {
      const { page, problems } = await openPage(context, `${server.url}/?data=/scen/tileset.json`);
      assert.deepEqual(await waitReady(page), { ok: true });
      // The list, once both manifests have been read: their event types too.
      const list = await page.evaluate(() => window.quakeview.scenarios());
      assert.deepEqual(list.map((s) => [s.index, s.name, s.manifest]),
        [[1, FIRST, 'scenario-1.json'], [2, SECOND, 'scenario-2.json'], [3, THIRD, 'scenario-3.json']]);
      // Opened as tileset.json, which the catalogue does not name: none is current by file name.
      assert.deepEqual(list.map((s) => s.current), [false, false, false]);
      await waitForFunction(page, async () => {
        const l = await window.quakeview.scenarios();
        return l[0].eventType === 'SCENARIO' && l[1].eventType === 'SCENARIO' && l[2].state === 'not ready';
      }, null, { timeout: 30000, polling: 250 });
      assert.equal((await page.evaluate(() => window.quakeview.scenarios()))[2].eventType, null);
      assert.equal((await page.evaluate(() => window.quakeview.scenarios()))[0].sameResultsAsOpen, true);
      await waitForFunction(page, cityTotals, null, { timeout: 30000 });
      const before = await page.evaluate(cityTotals);
      assert.equal(before.eventType, 'SCENARIO');
      let text = await page.evaluate(() => window.quakeview.uiText());
      assert.match(text, /Scenario: "M6\.6 scenario, Lower Manhattan" \(the same results, opened as tileset\.json\)/);
      assert.match(text, /Earthquake: M6\.6/);

      await openSection(page, 'Scenarios');
      text = await page.evaluate(() => window.quakeview.uiText());
      assert.match(text, /> M6\.6 scenario, Lower Manhattan: SCENARIO \(the same results as shown\)/);
      assert.match(text, /> M5\.0 scenario, Lower East Side: SCENARIO/);
      assert.match(text, /> M7\.2 scenario, not yet run: not ready/);

      // The end of the record: the city in its probability of moderate damage or worse.
      await page.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(window.quakeview.duration()); });
      await settle(page);
      await page.waitForTimeout(500);
      assert.equal(await page.evaluate(() => window.quakeview.shownColorMode()), 'p-moderate');
      const camera = await page.evaluate(() => window.quakeview.getCamera());
      const layout = await page.evaluate(() => window.quakeview.uiLayout());
      const shotBefore = await page.screenshot({ path: path.join(ARTIFACTS, 'scenarios-before.png') });

      // A click on the second scenario's row, as a person would choose it.
      const row = await scenarioRow(page, SECOND);
      await page.mouse.click(row.x + 30, row.y + row.height / 2);
      await waitForFunction(page, () => {
        const m = window.quakeview.uiText().match(/Scenario 2 of 3: M5\.0 scenario, Lower East Side/);
        return m && window.quakeview.consequences()?.city != null;
      }, null, { timeout: 60000, polling: 200 });
      await settle(page);
      await page.waitForTimeout(500);
      const afterTotals = await page.evaluate(cityTotals);
      // The M5.0 scenario damages far fewer buildings than the M6.6.
      assert.ok(afterTotals.moderateOrWorse < 0.5 * before.moderateOrWorse,
        `moderate or worse: ${before.moderateOrWorse} before, ${afterTotals.moderateOrWorse} after`);
      text = await page.evaluate(() => window.quakeview.uiText());
      assert.match(text, /Earthquake: M5\.0/);
      assert.doesNotMatch(text, /Earthquake: M6\.6/);
      assert.match(text, /> M5\.0 scenario, Lower East Side: SCENARIO \(shown\)/);
      const now = await page.evaluate(() => window.quakeview.scenarios());
      assert.deepEqual(now.map((s) => s.current), [false, true, false]);
      // The view stays: the camera, and the time at the end of the (new) record.
      const cameraAfter = await page.evaluate(() => window.quakeview.getCamera());
      for (const k of ['x', 'y', 'distance', 'headingDeg', 'pitchDeg']) {
        assert.ok(Math.abs(cameraAfter[k] - camera[k]) < 1e-6, `${k}: ${camera[k]} -> ${cameraAfter[k]}`);
      }
      assert.equal(await page.evaluate(() => window.quakeview.playing()), false);
      assert.equal(await page.evaluate(() => window.quakeview.time() === window.quakeview.duration()), true);
      assert.equal(await page.evaluate(() => window.quakeview.shownColorMode()), 'p-moderate');
      const shotAfter = await page.screenshot({ path: path.join(ARTIFACTS, 'scenarios-after.png') });

      // The buildings' colours changed: far fewer warm (damaged) pixels under the smaller earthquake.
      const a = decodePng(shotBefore);
      const b = decodePng(shotAfter);
      const { isWarm } = warmClassifier(camera.distance * 2);
      const panels = outsideWindows(layout);
      const warmBefore = warmPixels(a, isWarm, panels).warm;
      const warmAfter = warmPixels(b, isWarm, panels).warm;
      assert.ok(warmBefore > 2000, `the M6.6 scenario shows damage: ${warmBefore} warm pixels`);
      assert.ok(warmAfter < 0.5 * warmBefore, `warm pixels ${warmBefore} before, ${warmAfter} after`);
      const right = { x: 600, y: 80, width: 600, height: 560 };
      assert.ok(changedFraction(a, b, 24, right) > 0.01, 'the city looks different');

      // The link follows (the page's URL keeps the view): ?data= names the scenario shown.
      await waitForFunction(page, () => new URLSearchParams(window.location.search).get('data') === '/scen/scenario-2.json',
        null, { timeout: 5000 });
      const link = await page.evaluate(() => window.location.href);
      assert.match(link, /\?data=\/scen\/scenario-2\.json#cam=/);
      // Reloading it opens the second scenario.
      await page.goto(link, { waitUntil: 'load' });
      assert.deepEqual(await waitReady(page), { ok: true });
      const reloaded = await page.evaluate(() => window.quakeview.scenarios());
      assert.deepEqual(reloaded.map((s) => s.current), [false, true, false]);
      await waitForFunction(page, cityTotals, null, { timeout: 30000 });
      const again = await page.evaluate(cityTotals);
      assert.ok(Math.abs(again.moderateOrWorse - afterTotals.moderateOrWorse) < 1e-6);
      assert.match(await page.evaluate(() => window.quakeview.uiText()), /Scenario 2 of 3: M5\.0 scenario, Lower East Side/);
      assert.deepEqual(problems, []);
    } finally {
      await close();
    }
  });

test('quakeview.selectScenario resolves once the scenario has loaded, and refuses what the list does not hold',
  async () => {
    const { context, close } = await launchBrowser();
    try {
      const { page, problems } = await openPage(context, `${server.url}/?data=/scen/scenario-2.json`);
      assert.deepEqual(await waitReady(page), { ok: true });
      const list = await page.evaluate(() => window.quakeview.scenarios());
      assert.deepEqual(list.map((s) => s.current), [false, true, false]);
      await waitForFunction(page, cityTotals, null, { timeout: 30000 });
      const second = await page.evaluate(cityTotals);
      const chosen = await page.evaluate(() => window.quakeview.selectScenario(1));
      assert.equal(chosen.index, 1);
      assert.equal(chosen.current, true);
      assert.equal(chosen.eventType, 'SCENARIO');
      // Resolved means loaded: the totals are the first scenario's at once.
      const first = await page.evaluate(cityTotals);
      assert.ok(first.moderateOrWorse > 2 * second.moderateOrWorse, `${first.moderateOrWorse} vs ${second.moderateOrWorse}`);
      assert.equal(await page.evaluate(() => new URLSearchParams(window.location.search).get('data')), '/scen/scenario-1.json');
      // What is not in the list, or no index, is refused with the reason.
      const refusals = await page.evaluate(async () => {
        const reasons = [];
        for (const index of [7, 3, 1.5, '2', 0]) {
          try {
            await window.quakeview.selectScenario(index);
            reasons.push(null);
          } catch (e) {
            reasons.push(e.message);
          }
        }
        return reasons;
      });
      assert.equal(refusals[0], "the city's scenario list has no scenario 7");
      // Listed but not run yet: refused with why, and the scenario shown stays.
      assert.match(refusals[1], /^Scenario 3 "M7\.2 scenario, not yet run" cannot be shown yet: scenario-3\.json is not there yet \(HTTP 404\)/);
      for (const r of refusals.slice(2)) assert.match(r, /a scenario's index is a whole number from 1/);
      assert.equal(await page.evaluate(() => new URLSearchParams(window.location.search).get('data')), '/scen/scenario-1.json');
      const stillFirst = await page.evaluate(cityTotals);
      assert.ok(Math.abs(stillFirst.moderateOrWorse - first.moderateOrWorse) < 1e-6);
      // Every existing name of the API is still there.
      const names = await page.evaluate(() => Object.keys(window.quakeview));
      for (const name of ['ready', 'stats', 'consequences', 'report', 'screenshot', 'scenarios', 'selectScenario']) {
        assert.ok(names.includes(name), name);
      }
      assert.deepEqual(problems, []);
    } finally {
      await close();
    }
  });

test('a catalogue entry pointing outside the city folder is refused with a message, and the city still opens',
  async () => {
    const { context, close } = await launchBrowser();
    try {
      const { page, problems } = await openPage(context, `${server.url}/?data=/hostile/tileset.json`);
      assert.deepEqual(await waitReady(page), { ok: true });
      const list = await page.evaluate(() => window.quakeview.scenarios());
      assert.deepEqual(list.map((s) => s.name), [FIRST]);
      const errors = await page.evaluate(() => window.quakeview.errors());
      assert.ok(errors.some((e) => e.includes('(scenario 2) has the manifest "../elsewhere/tileset.json", which is a path') &&
        e.includes('it is left out')), JSON.stringify(errors));
      assert.match(await page.evaluate(() => window.quakeview.uiText()), /== Errors ==[\s\S]*which is a path/);
      const stats = await page.evaluate(() => window.quakeview.stats());
      assert.ok(stats.buildings.loaded > 0 && stats.tiles.loaded > 0, JSON.stringify(stats.tiles));
      await waitForFunction(page, cityTotals, null, { timeout: 30000 });
      // Nothing outside the folder was asked for.
      const fetched = await page.evaluate(() => performance.getEntriesByType('resource').map((r) => r.name));
      assert.deepEqual(fetched.filter((u) => u.includes('elsewhere')), []);
      assert.deepEqual(problems, []);
    } finally {
      await close();
    }
  });

test('the 2D city offers the scenarios as a list, and choosing one shows it', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/scen/scenario-1.json&view=2d`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await waitForFunction(page, () => {
      const select = document.getElementById('qv-map2d-scenario');
      return select && !document.getElementById('qv-map2d-scenarios').hidden && select.options.length === 3 &&
        select.value === '1';
    }, null, { timeout: 30000 });
    const options = await page.evaluate(() => [...document.getElementById('qv-map2d-scenario').options].map((o) => o.text));
    assert.ok(options[0].startsWith(FIRST) && options[1].startsWith(SECOND), JSON.stringify(options));
    await waitForFunction(page, () => document.getElementById('qv-map2d-scenario').options[2].text.endsWith('(not ready)'),
      null, { timeout: 30000 });
    await waitForFunction(page, cityTotals, null, { timeout: 30000 });
    const first = await page.evaluate(cityTotals);
    await page.evaluate(() => {
      const select = document.getElementById('qv-map2d-scenario');
      select.value = '2';
      select.dispatchEvent(new Event('change'));
    });
    await waitForFunction(page, async () => (await window.quakeview.scenarios()).find((s) => s.current)?.index === 2 &&
      window.quakeview.consequences()?.city != null, null, { timeout: 60000, polling: 200 });
    const second = await page.evaluate(cityTotals);
    assert.ok(second.moderateOrWorse < 0.5 * first.moderateOrWorse);
    await waitForFunction(page, () => new URLSearchParams(window.location.search).get('data') === '/scen/scenario-2.json' &&
      new URLSearchParams(window.location.search).get('view') === '2d', null, { timeout: 5000 });
    assert.match(await page.evaluate(() => document.getElementById('qv-panel').innerText), /Scenario 2 of 3: M5\.0 scenario/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'scenarios-map2d.png') });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
