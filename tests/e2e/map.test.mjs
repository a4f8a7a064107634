// The map under the city (issue "where"): streets, water, parks and their names, drawn under the
// buildings from the city's own input. The Midtown city (a real OpenStreetMap cut with its streets,
// parks and neighbourhoods) shows streets with their names along them and neighbourhood names, never
// overlapping each other or the panels; the demo shows its river and neighbourhoods; a city whose
// input had buildings only says so in the panel, and one made with --no-ground says that; a broken
// ground tile is reported by name and the rest of the map and the city still show.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { BROWSER, launchBrowser, openPage, settle, waitReady } from './lib/browser.mjs';
import { decodePng } from './lib/pixels.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const FIXTURE = path.join(REPO, '../shared/data/osm/fixture-midtown-empire-state.osm');
let server;
let scratch;

before(async () => {
  for (const city of ['midtown', 'demo', 'hostile', 'noground']) {
    assert.ok(fs.existsSync(path.join(DATA, city, 'tileset.json')), `test city missing: ${path.join(DATA, city)} (scripts/test.sh prepares it)`);
  }
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  // Midtown with its ground tiles damaged on the server (their bytes no longer match the manifest).
  scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-map-'));
  fs.cpSync(path.join(DATA, 'midtown'), path.join(scratch, 'broken'), { recursive: true, dereference: true });
  const manifest = JSON.parse(fs.readFileSync(path.join(scratch, 'broken', 'tileset.json'), 'utf8'));
  for (const node of manifest.ground.nodes) {
    const file = path.join(scratch, 'broken', node.file);
    const bytes = fs.readFileSync(file);
    bytes[Math.floor(bytes.length / 2)] ^= 0xff;
    fs.writeFileSync(file, bytes);
  }
  server = await serveSite({ '/data': DATA, '/scratch': scratch });
});
after(async () => {
  await server?.close();
  if (scratch) fs.rmSync(scratch, { recursive: true, force: true });
});

// Hue (degrees) and saturation of an 8-bit pixel.
function hueSat(r, g, b) {
  const max = Math.max(r, g, b);
  const min = Math.min(r, g, b);
  const d = max - min;
  let h = 0;
  if (d > 0) {
    if (max === r) h = 60 * (((g - b) / d) % 6);
    else if (max === g) h = 60 * ((b - r) / d + 2);
    else h = 60 * ((r - g) / d + 4);
  }
  if (h < 0) h += 360;
  return { hue: h, sat: max > 0 ? d / max : 0 };
}

// Fraction of the pixels outside the windows whose hue is in [lo, hi] with saturation >= minSat.
function hueFraction(image, layout, cssWidth, lo, hi, minSat) {
  const rects = layout.windows.map((w) => [w.x, w.y, w.x + w.width, w.y + w.height]);
  const scale = image.width / cssWidth;
  let n = 0;
  let total = 0;
  for (let y = 0; y < image.height; y += 2) {
    for (let x = 0; x < image.width; x += 2) {
      const cx = x / scale;
      const cy = y / scale;
      if (rects.some(([x0, y0, x1, y1]) => cx >= x0 && cx < x1 && cy >= y0 && cy < y1)) continue;
      const i = (y * image.width + x) * 4;
      const { hue, sat } = hueSat(image.data[i], image.data[i + 1], image.data[i + 2]);
      total += 1;
      if (sat >= minSat && hue >= lo && hue <= hi) n += 1;
    }
  }
  return total > 0 ? n / total : 0;
}

// No two labels' boxes (the screen box around each turned text, as placed) overlap, none lies under
// a window, and none reads upside down.
function assertLabelsApart(labels, layout) {
  const box = (l) => {
    const a = (Math.abs(l.angleDeg) * Math.PI) / 180;
    const hw = (l.width * Math.cos(a) + l.height * Math.sin(a)) / 2;
    const hh = (l.width * Math.sin(a) + l.height * Math.cos(a)) / 2;
    return [l.x - hw, l.y - hh, l.x + hw, l.y + hh];
  };
  const overlap = (p, q) => p[0] < q[2] - 0.5 && q[0] < p[2] - 0.5 && p[1] < q[3] - 0.5 && q[1] < p[3] - 0.5;
  for (const l of labels) {
    assert.ok(l.width > 0 && l.height > 0, `"${l.text}" has a size`);
    for (const w of layout.windows) {
      assert.ok(!overlap(box(l), [w.x, w.y, w.x + w.width, w.y + w.height]),
        `the label "${l.text}" at ${Math.round(l.x)},${Math.round(l.y)} is under the window "${w.title}"`);
    }
    assert.ok(Math.abs(l.angleDeg) <= 90.01, `"${l.text}" reads upside down (${l.angleDeg}°)`);
  }
  for (let i = 0; i < labels.length; ++i) {
    for (let j = i + 1; j < labels.length; ++j) {
      assert.ok(!overlap(box(labels[i]), box(labels[j])), `the labels "${labels[i].text}" and "${labels[j].text}" overlap`);
    }
  }
}

async function openCity(context, city, camera) {
  const { page, problems } = await openPage(context, `${server.url}/?data=/data/${city}/tileset.json`);
  assert.deepEqual(await waitReady(page), { ok: true });
  if (camera) assert.ok(await page.evaluate((c) => window.quakeview.setCamera(c), camera));
  await settle(page);
  await page.waitForTimeout(500);  // a few frames with everything loaded: the labels are placed
  return { page, problems };
}

test('the Midtown city shows its streets with their names, its parks and its neighbourhoods under the buildings', async () => {
  const names = new Set([...fs.readFileSync(FIXTURE, 'utf8').matchAll(/<tag k="name" v="([^"]*)"/g)]
    .map((m) => m[1].replace(/&amp;/g, '&').replace(/&apos;/g, "'").replace(/&quot;/g, '"')));
  const { context, close } = await launchBrowser();
  try {
    // Street level over the Empire State Building's blocks.
    const esb = JSON.parse(fs.readFileSync(path.join(DATA, 'midtown-esb.json'), 'utf8'));
    const { page, problems } = await openCity(context, 'midtown',
      { x: esb.x_m, y: esb.y_m, distance: 700, headingDeg: 20, pitchDeg: 60, fovDeg: 45 });
    const map = await page.evaluate(() => window.quakeview.map());
    assert.equal(map.layer, 'present');
    assert.ok(map.features.street > 0 || map.features.major > 0, `streets read: ${JSON.stringify(map.features)}`);
    assert.ok(map.cellsDrawn > 0 && map.triangles > 0, `the map is drawn: ${JSON.stringify(map)}`);
    const streets = map.labels.filter((l) => l.kind === 'street');
    assert.ok(streets.length >= 2, `street names along the streets at street level: ${JSON.stringify(map.labels.map((l) => l.text))}`);
    // Every name shown is the input's own.
    for (const l of map.labels) assert.ok(names.has(l.text), `"${l.text}" is not a name in the input`);
    const layout = await page.evaluate(() => window.quakeview.uiLayout());
    assertLabelsApart(map.labels, layout);
    // The panel says where the map comes from; the names are mirrored as text.
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /Map from the input: \d+ streets, \d+ water, \d+ parks/);
    assert.match(text, /Map labels: /);
    const shot = await page.screenshot();
    fs.writeFileSync(path.join(ARTIFACTS, `map-midtown-street-${BROWSER}.png`), shot);

    // The overview: neighbourhood names over the whole city.
    assert.ok(await page.evaluate(() => window.quakeview.setCamera({ distance: 3500, pitchDeg: 55 })));
    await settle(page);
    await page.waitForTimeout(500);
    const overview = await page.evaluate(() => window.quakeview.map());
    assert.ok(overview.labels.some((l) => l.kind === 'neighbourhood'),
      `neighbourhood names at the overview: ${JSON.stringify(overview.labels.map((l) => `${l.kind}:${l.text}`))}`);
    assertLabelsApart(overview.labels, await page.evaluate(() => window.quakeview.uiLayout()));
    fs.writeFileSync(path.join(ARTIFACTS, `map-midtown-overview-${BROWSER}.png`), await page.screenshot());
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the demo shows its river, parks and neighbourhoods from the opening view', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context, 'demo', null);
    const map = await page.evaluate(() => window.quakeview.map());
    assert.equal(map.layer, 'present');
    assert.ok(map.features.water > 0, `the demo has water: ${JSON.stringify(map.features)}`);
    assert.ok(map.labels.some((l) => l.kind === 'neighbourhood'), `neighbourhood names: ${JSON.stringify(map.labels)}`);
    const layout = await page.evaluate(() => window.quakeview.uiLayout());
    const image = decodePng(await page.screenshot());
    fs.writeFileSync(path.join(ARTIFACTS, `map-demo-overview-${BROWSER}.png`), await page.screenshot());
    // Water is blue (hue about 210°): the river is on the screen from the start.
    const cssWidth = await page.evaluate(() => window.innerWidth);
    const water = hueFraction(image, layout, cssWidth, 195, 225, 0.15);
    assert.ok(water > 0.002, `water on the opening view: ${(100 * water).toFixed(2)} % of the pixels`);
    // Closer, over the middle of the city: its parks (green, hue about 110°) and their names.
    const camera = await page.evaluate(() => window.quakeview.getCamera());
    assert.ok(await page.evaluate((c) => window.quakeview.setCamera({ x: c.x, y: c.y, distance: 1500, pitchDeg: 70 }), camera));
    await settle(page);
    await page.waitForTimeout(500);
    const near = decodePng(await page.screenshot());
    const green = hueFraction(near, await page.evaluate(() => window.quakeview.uiLayout()), cssWidth, 90, 140, 0.12);
    const close = await page.evaluate(() => window.quakeview.map());
    assert.ok(green > 0.001, `parks near the centre: ${(100 * green).toFixed(2)} % of the pixels`);
    assert.ok(close.labels.some((l) => l.kind === 'street' || l.kind === 'park'),
      `street or park names near the centre: ${JSON.stringify(close.labels.map((l) => `${l.kind}:${l.text}`))}`);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('a city without streets or water in its input, and one made without the map, say so', async () => {
  const { context, close } = await launchBrowser();
  try {
    // A city from a GeoJSON of footprints: buildings only.
    let { page, problems } = await openCity(context, 'hostile', null);
    assert.equal((await page.evaluate(() => window.quakeview.map())).layer, 'empty');
    assert.match(await page.evaluate(() => window.quakeview.uiText()),
      /Map: none in the input \(no streets, water or parks\)/);
    assert.deepEqual(problems, []);
    await page.close();
    ({ page, problems } = await openCity(context, 'noground', null));
    assert.equal((await page.evaluate(() => window.quakeview.map())).layer, 'none');
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /Map: none \(made with --no-ground or an older tool\)/);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('a damaged ground tile is reported by name; the city and the rest of the map still show', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page } = await openPage(context, `${server.url}/?data=/scratch/broken/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await settle(page);
    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.ok(errors.some((e) => /Ground tile .*ground\/\d+-\d+-\d+\.qvg/.test(e)), `the damaged tile is named: ${JSON.stringify(errors)}`);
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.ok(stats.buildings.visible > 0, 'the buildings still show');
  } finally {
    await close();
  }
});
