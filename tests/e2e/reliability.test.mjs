// Reliability in the browser: a failing tile server (500s, slow answers, truncated bodies, wrong
// content, dropped connections), a deliberately small memory budget and hostile ?data= addresses.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, openSection, waitForFunction, waitReady } from './lib/browser.mjs';
import { serveFaulty } from './lib/faulty-server.mjs';
import { changedFraction, decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const SYNTH = path.join(DATA, 'synth');
const LARGE = path.join(DATA, 'large');

before(() => {
  assert.ok(fs.existsSync(path.join(SYNTH, 'tileset.json')), `test city missing: ${SYNTH} (scripts/test.sh prepares it)`);
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});

async function calm(page, timeout = 60000) {
  await waitForFunction(page, () => {
    const s = window.quakeview.stats();
    window.__calm = s && s.tiles.pending === 0 ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, null, { timeout, polling: 250 });
}

// A view of the city's centre close enough that it refines into many leaf tiles.
function centreCamera(manifest) {
  const [x0, y0, x1, y1] = manifest.bounds;
  return { x: (x0 + x1) / 2, y: (y0 + y1) / 2, distance: 700, headingDeg: 20, pitchDeg: 50, fovDeg: 45 };
}

test('a failing tile server: failures are shown, the frame loop keeps going, and everything recovers once the server behaves', async () => {
  const manifest = JSON.parse(fs.readFileSync(path.join(SYNTH, 'tileset.json'), 'utf8'));
  const server = await serveFaulty(SYNTH);
  const { context, close } = await launchBrowser();
  try {
    const camera = centreCamera(manifest);
    const hash = `#cam=${[camera.x, camera.y, camera.distance, camera.headingDeg, camera.pitchDeg, camera.fovDeg].join(',')}&t=6`;
    // A fixed preset (no frame-time governor): the recovered and the healthy page are compared
    // pixel by pixel, so both must draw at the same detail.
    const { page } = await openPage(context, `${server.url}/?data=/city/tileset.json&quality=high${hash}`);
    // ready settles (resolves) even though tiles fail: the page never hangs.
    assert.deepEqual(await waitReady(page, 120000), { ok: true });
    await page.evaluate(() => window.quakeview.pause());
    // The legend (its "No result" count says when results are missing) in view.
    await openSection(page, 'Damage and colours');
    const injected = Object.entries(server.faults).filter(([k, v]) => k !== 'none' && v > 0).map(([k]) => k);
    assert.ok(injected.length >= 3, `several kinds of fault were injected: ${JSON.stringify(server.faults)}`);

    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.ok(errors.some((e) => /Tile \d+\/\d+\/\d+ failed/.test(e)), `failed tiles are named: ${JSON.stringify(errors)}`);
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /failed/);
    await page.screenshot({ path: path.join(ARTIFACTS, 'reliability-failing.png') });

    // The frame loop keeps running while tiles fail: time advances when playing.
    await page.evaluate(() => window.quakeview.play());
    const t0 = await page.evaluate(() => window.quakeview.time());
    await page.waitForTimeout(1000);
    assert.ok((await page.evaluate(() => window.quakeview.time())) > t0, 'time advances');
    await page.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(6); });

    // The server recovers; so does the city (retries back off up to 30 s for bad content).
    server.setFaulty(false);
    await waitForFunction(page, () => {
      const s = window.quakeview.stats();
      return s.tiles.failed === 0 && s.tiles.pending === 0 && !/No result \(hatched\): [1-9]/.test(window.quakeview.uiText());
    }, null, { timeout: 120000, polling: 500 });
    await calm(page);
    await page.waitForTimeout(500);
    // What recovered is no longer reported as failed.
    assert.deepEqual(await page.evaluate(() => window.quakeview.errors()), []);
    const recoveredStats = await page.evaluate(() => window.quakeview.stats());
    const recovered = decodePng(await page.screenshot({ path: path.join(ARTIFACTS, 'reliability-recovered.png') }));

    // The same view from a healthy server looks the same.
    const { page: healthy } = await openPage(context, `${server.url}/?data=/city/tileset.json&quality=high${hash}`);
    assert.deepEqual(await waitReady(healthy), { ok: true });
    await healthy.evaluate(() => { window.quakeview.pause(); window.quakeview.setTime(6); });
    await openSection(healthy, 'Damage and colours');  // the same panel, so the same view beside it
    await calm(healthy);
    await healthy.waitForTimeout(500);
    const healthyStats = await healthy.evaluate(() => window.quakeview.stats());
    const reference = decodePng(await healthy.screenshot());
    assert.equal(recoveredStats.buildings.visible, healthyStats.buildings.visible,
      `the same buildings in view: recovered ${JSON.stringify(recoveredStats.tiles)}, healthy ${JSON.stringify(healthyStats.tiles)}`);
    assert.equal(recoveredStats.tiles.loaded >= healthyStats.tiles.loaded, true);
    const city = { x: 420, y: 40, width: 840, height: 500 };
    const diff = changedFraction(recovered, reference, 40, city);
    assert.ok(diff < 0.02, `the recovered city matches a healthy load: ${(diff * 100).toFixed(2)} % of pixels differ`);
  } finally {
    await close();
    await server.close();
  }
});

// A stored file's size as decoded: a Zstandard frame's declared content size (RFC 8878 frame
// header; docs/formats.md "Compressed files"), else the file's own size.
function decodedSize(bytes) {
  if (bytes.length < 6 || bytes.readUInt32LE(0) !== 0xFD2FB528) return bytes.length;
  const descriptor = bytes[4];
  const sizeFlag = descriptor >> 6;
  const singleSegment = (descriptor >> 5) & 1;
  const at = 5 + (singleSegment ? 0 : 1) + [0, 1, 2, 4][descriptor & 3];
  const width = sizeFlag === 0 ? (singleSegment ? 1 : 0) : [1, 2, 4, 8][sizeFlag];
  assert.ok(width > 0, 'a frame without its content size');
  if (width === 1) return bytes[at];
  if (width === 2) return bytes.readUInt16LE(at) + 256;
  if (width === 4) return bytes.readUInt32LE(at);
  return Number(bytes.readBigUInt64LE(at));
}

test('a small memory budget: flying over a city several times larger keeps the heap bounded and the view correct', async () => {
  assert.ok(fs.existsSync(path.join(LARGE, 'tileset.json')), `test city missing: ${LARGE} (scripts/test.sh prepares it)`);
  const manifest = JSON.parse(fs.readFileSync(path.join(LARGE, 'tileset.json'), 'utf8'));
  const server = await serveSite({ '/large': LARGE });
  const { context, close } = await launchBrowser();
  const budgetMb = 24;
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/large/tileset.json&memory=${budgetMb}`);
    assert.deepEqual(await waitReady(page, 120000), { ok: true });
    const [x0, y0, x1, y1] = manifest.bounds;
    const heap = [];
    let visibleOk = 0;
    // A low pass over a 4 x 4 grid of points: each brings in other leaf tiles.
    for (let j = 0; j < 4; ++j) {
      for (let i = 0; i < 4; ++i) {
        const x = x0 + (x1 - x0) * ((j % 2 ? 3 - i : i) + 0.5) / 4;
        const y = y0 + (y1 - y0) * (j + 0.5) / 4;
        assert.ok(await page.evaluate((c) => window.quakeview.setCamera(c), { x, y, distance: 500, headingDeg: 0, pitchDeg: 45 }));
        await calm(page, 90000);
        const s = await page.evaluate(() => window.quakeview.stats());
        heap.push(s.heapBytes);
        if (s.buildings.visible > 0) visibleOk += 1;
      }
    }
    const mb = heap.map((b) => b / 1048576);
    fs.writeFileSync(path.join(ARTIFACTS, 'memory-budget-heap.json'), JSON.stringify({ budgetMb, heapMb: mb }, null, 1));
    console.log(`heap over the flight (MB, budget ${budgetMb}): ${mb.map((v) => v.toFixed(1)).join(' ')}`);
    // The tiles as the viewer decodes them (stored as Zstandard frames: their declared size).
    const files = fs.readdirSync(path.join(LARGE, 'tiles')).map((f) => decodedSize(fs.readFileSync(path.join(LARGE, 'tiles', f))));
    const cityMb = files.reduce((a, b) => a + b, 0) / 1048576;
    assert.ok(cityMb > 2 * budgetMb / 4, `the city's tiles (${cityMb.toFixed(1)} MB as files) decode to several times the budget`);
    // The budget bounds tiles, meshes, histories and the heap they leave uncounted; the engine's
    // own memory (what the heap held when the city opened) comes on top.
    const engineBaselineMb = 16;
    assert.ok(Math.max(...mb) < budgetMb + engineBaselineMb, `heap peaked at ${Math.max(...mb).toFixed(1)} MB`);
    assert.equal(visibleOk, heap.length, 'every stop of the flight shows buildings');
    // The coarse tiles hold only the city's largest buildings (--max-coarse-buildings); the search
    // index still lists every one, and selecting one from far away brings in its leaf.
    assert.ok(manifest.root.buildings < manifest.buildings, `a bounded root: ${manifest.root.buildings}`);
    await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 60000, polling: 250 });
    const all = await page.evaluate(() => window.quakeview.filteredList(0));
    assert.equal(all.total, manifest.buildings);
    assert.ok(await page.evaluate(() => window.quakeview.setCamera({ distance: 20000, pitchDeg: 60 })));
    const far = await page.evaluate(() => window.quakeview.search('s49999', 1));
    assert.equal(far.length, 1);
    assert.ok(await page.evaluate(() => window.quakeview.select('s49999')));
    await waitForFunction(page, () => window.quakeview.building('s49999') !== null, null, { timeout: 60000, polling: 250 });
    const b = await page.evaluate(() => window.quakeview.building('s49999'));
    assert.ok(Math.hypot(b.x - far[0].x, b.y - far[0].y) < 1, 'the index places it where its tile does');
    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.deepEqual(errors, []);
    assert.deepEqual(problems, []);
  } finally {
    await close();
    await server.close();
  }
});

test('hostile ?data= addresses: not JSON, missing, another site, other schemes; each says why and the page stays usable', async () => {
  const server = await serveSite({});
  // Another origin (another port) that answers JSON without Access-Control-Allow-Origin.
  const other = http.createServer((req, res) => {
    res.writeHead(200, { 'Content-Type': 'application/json' });
    res.end('{"format":"quakeview-tileset"}');
  });
  await new Promise((resolve) => other.listen(0, '127.0.0.1', resolve));
  const otherUrl = `http://127.0.0.1:${other.address().port}/tileset.json`;
  const cases = [
    { data: '/quakeview.css', expect: /quakeview\.css: not valid JSON/ },
    { data: '/nowhere/tileset.json', expect: /\/nowhere\/tileset\.json: HTTP 404/ },
    // Another origin is refused by the data origin policy before any request (trust.test.mjs).
    { data: otherUrl, expect: /a city from http:\/\/127\.0\.0\.1:\d+, which this site does not allow/ },
    { data: 'javascript:alert(1)', expect: /only http:\/\/ and https:\/\/ addresses .* not "javascript:"/ },
    { data: 'file:///etc/passwd', expect: /not "file:"/ },
  ];
  const { context, close } = await launchBrowser();
  try {
    for (const c of cases) {
      const { page, problems } = await openPage(context, `${server.url}/?data=${encodeURIComponent(c.data)}`);
      // The page settles (never hangs) and says what went wrong, naming the address.
      assert.deepEqual(await waitReady(page, 30000), { ok: true }, c.data);
      const errors = await page.evaluate(() => window.quakeview.errors());
      assert.ok(errors.some((e) => c.expect.test(e)), `${c.data}: ${JSON.stringify(errors)}`);
      const text = await page.evaluate(() => window.quakeview.uiText());
      assert.match(text, /== Errors ==/, c.data);
      // Still a working page: the API answers and the frame loop runs.
      await page.evaluate(() => window.quakeview.play());
      const t0 = await page.evaluate(() => window.quakeview.time());
      await page.waitForTimeout(300);
      assert.ok(Number.isFinite(await page.evaluate(() => window.quakeview.time())) && t0 >= 0, c.data);
      // No script errors: only the browser's own reports of the failed request itself.
      const own = problems.filter((p) => !/Failed to load resource|CORS policy|net::ERR_/.test(p));
      assert.deepEqual(own, [], c.data);
      await page.close();
    }
  } finally {
    await close();
    await server.close();
    other.close();
  }
});
