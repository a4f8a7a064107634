// The inspection window as an engineer reads it, on the Midtown cut around the Empire State
// Building (see interaction.test.mjs): values in units that show them, one peak drift with its
// source, plots with axes and the current time, per-storey drifts on a fixed scale with the HAZUS
// thresholds; the window fits 720 px, scrolls with the wheel and starts at the top for each
// building; Fly to leaves a low-rise building among towers visible. Screenshots of the window for a
// low-rise and a tall building go to the artifacts folder (and QUAKEVIEW_SHOTS when set).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, waitForFunction, settle, waitReady } from './lib/browser.mjs';
import { changedFraction, decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const ESB = 'w34633854';
const SHOTS = process.env.QUAKEVIEW_SHOTS || ARTIFACTS;
// The inspection window: 370 px wide, 10 px from the top right corner of the 1280 x 720 canvas.
const WINDOW_TOP = { x: 900, y: 10, width: 370, height: 70 };
const WINDOW = { x: 900, y: 10, width: 370, height: 620 };

let server;
before(async () => {
  assert.ok(fs.existsSync(path.join(DATA, 'midtown/tileset.json')), `test city missing: ${DATA}/midtown`);
  server = await serveSite({ '/data': DATA });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  fs.mkdirSync(SHOTS, { recursive: true });
});
after(async () => {
  if (server) await server.close();
});

// Selects `id`, flies to it, waits for the flight, the tiles and the window's motion plots.
async function inspect(page, id) {
  assert.equal(await page.evaluate((b) => window.quakeview.select(b), id), true);
  assert.equal(await page.evaluate(() => window.quakeview.flyToSelection()), true);
  await page.waitForTimeout(1500);  // the 1.2 s flight
  await settle(page);
  await waitForFunction(page, () => /Roof displacement over time/.test(window.quakeview.uiText()), null, { timeout: 30000 });
  await page.waitForTimeout(300);
}

// The inspection window's text (the "== Building … ==" section of uiText()).
function windowText(all) {
  const start = all.indexOf('== Building ');
  assert.ok(start >= 0, 'the inspection window is shown');
  const end = all.indexOf('\n== ', start + 3);
  return end < 0 ? all.slice(start) : all.slice(start, end);
}

function expectedMillimetres(metres) {
  const mm = metres * 1000;
  return mm < 9.95 ? `${mm.toFixed(1)} mm` : `${mm.toFixed(0)} mm`;
}

test('the inspection window: units that show values, one peak drift with its source, plots with axes, fixed storey scale; Fly to shows a low-rise building', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/data/midtown/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await page.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(8); });
    await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 30000 });
    // Load the blocks around the Empire State Building, whose loaded buildings building() describes.
    const esb = JSON.parse(fs.readFileSync(path.join(DATA, 'midtown-esb.json'), 'utf8'));
    assert.ok(await page.evaluate(({ x, y }) => window.quakeview.setCamera({ x, y, distance: 900, headingDeg: 0, pitchDeg: 70, fovDeg: 45 }),
      { x: esb.x_m, y: esb.y_m }));
    await settle(page);
    // A low-rise building (at most 3 storeys, a few millimetres to centimetres at its roof) with the
    // most buildings over 100 m within 200 m: the case where Fly to used to leave it behind towers.
    const low = await page.evaluate(({ x, y }) => {
      const near = window.quakeview.filteredList(100000).buildings.filter((e) => Math.hypot(e.x - x, e.y - y) < 400);
      const all = near.map((e) => window.quakeview.building(e.id)).filter((b) => b);
      const towers = all.filter((b) => b.heightM > 100);
      let best = null;
      for (const b of all) {
        if (b.storeys > 3 || !(b.peakRoofDisplacementM > 0.001 && b.peakRoofDisplacementM < 0.5)) continue;
        if (Math.hypot(b.x - x, b.y - y) > 250) continue;
        const n = towers.filter((t) => Math.hypot(t.x - b.x, t.y - b.y) < 200).length;
        if (!best || n > best.n) best = { id: b.id, n };
      }
      return best;
    }, { x: esb.x_m, y: esb.y_m });
    assert.ok(low && low.n >= 3, `a low-rise building among towers: ${JSON.stringify(low)}`);

    await inspect(page, low.id);
    const b = await page.evaluate((id) => window.quakeview.building(id), low.id);
    // Fly to: the building's centre is on screen and nothing hides it (picking there finds it).
    const at = await page.evaluate(({ x, y, z }) => window.quakeview.worldToScreen(x, y, z),
      { x: b.x, y: b.y, z: (b.minHeightM || 0) + b.heightM / 2 });
    assert.ok(at && at[0] > 0 && at[0] < 1280 && at[1] > 0 && at[1] < 720, `centre on screen: ${JSON.stringify(at)}`);
    const picked = await page.evaluate(([x, y]) => window.quakeview.pick(x, y), at);
    assert.equal(picked && picked.id, low.id, `the building is seen at its centre, not ${picked && picked.id}`);

    const text = windowText(await page.evaluate(() => window.quakeview.uiText()));
    // One peak drift, with its source; no second "peak" from the plot.
    assert.equal(text.match(/Peak inter-storey drift/g).length, 1, text);
    assert.match(text, /Peak inter-storey drift: \d+\.\d{2,3} % in storey \d+ \(exact peak from the solver\)/);
    assert.doesNotMatch(text, /over time: peak/);
    // The roof displacement in millimetres, as the building's value reads.
    assert.match(text, new RegExp(`Peak roof displacement: ${expectedMillimetres(b.peakRoofDisplacementM).replace('.', '\\.')}`));
    assert.doesNotMatch(text, /Peak roof displacement: 0\.0 m/);
    // The plots: axes, units, the current time; the history's error bound is stated.
    assert.match(text, /Largest inter-storey drift over time \(%\), now /);
    assert.match(text, /Roof displacement over time \(mm\), now /);
    assert.match(text, /drift within ±\d+\.\d+ % of the solver's; the peak above is the solver's exact value/);
    assert.match(text, /Plot axes: time 0 to \d+\.\d s, the current time 8\.0 s marked/);
    // The storey bars: a fixed scale holding the HAZUS thresholds, bars coloured by state.
    assert.match(text, /fixed scale 0 to \d\.\d\d %; lines: slight, moderate, extensive(, complete)? thresholds/);
    assert.match(text, /Storeys by the state their drift reaches: \d+ (none|slight|moderate|extensive|complete)/);
    // The site's own shaking (the scenario's medians there), and the scaled record's PGA named as the record's.
    assert.equal(b.siteShaking && b.siteShaking.source, 'scenario', JSON.stringify(b.siteShaking));
    assert.ok(b.siteShaking.pgaG > 0 && b.siteShaking.psa03G > b.siteShaking.psa30G, JSON.stringify(b.siteShaking));
    assert.equal(b.siteShaking.pgvCmS, null, 'a value the field does not give is null, not 0');
    const site = text.match(/Shaking at the site \(scenario median \(BSSA14\)\): PGA (\d+\.\d{3}) g, PSA 0\.3 s/);
    assert.ok(site && Math.abs(Number(site[1]) - b.siteShaking.pgaG) < 0.00051, `site line: ${text}`);
    const record = text.match(/Record's PGA \(scaled\): (\d+\.\d{3}) g/);
    assert.ok(record && Math.abs(Number(record[1]) - b.recordPgaG) < 0.00051, `record line: ${text}`);
    assert.doesNotMatch(text, /Peak ground acceleration/);
    const lowShot = await page.screenshot({ path: path.join(SHOTS, 'inspection-low-rise.png') });

    // A tall building: its window is taller than 720 px and scrolls with the wheel.
    await inspect(page, ESB);
    const tallText = windowText(await page.evaluate(() => window.quakeview.uiText()));
    assert.match(tallText, /Empire State Building/);
    assert.match(tallText, /Peak roof displacement: (\d+ mm|\d+\.\d\d m)/);
    const tallTop = decodePng(await page.screenshot({ path: path.join(SHOTS, 'inspection-tall.png') }));
    await page.mouse.move(1085, 400);
    await page.mouse.wheel(0, 600);
    await page.waitForTimeout(400);
    const scrolled = decodePng(await page.screenshot({ path: path.join(SHOTS, 'inspection-tall-scrolled.png') }));
    assert.ok(changedFraction(tallTop, scrolled, 24, WINDOW) > 0.05, 'the wheel scrolls the window');

    // The next building starts at the top: its name and first lines look as they did before.
    await inspect(page, low.id);
    const again = decodePng(await page.screenshot());
    assert.ok(changedFraction(decodePng(lowShot), again, 24, WINDOW_TOP) < 0.02, 'the window starts at the top');
    // Its plots and storey bars, further down.
    await page.mouse.move(1085, 400);
    await page.mouse.wheel(0, 1500);
    await page.waitForTimeout(1000);
    await page.screenshot({ path: path.join(SHOTS, 'inspection-low-rise-plots.png') });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
