// Memory benchmark in headless Chromium: opens a prepared city (by default under the viewer's
// default 512 MB budget, or ?memory=MB), then flies a low pass over an N x N grid of the city (each
// stop brings in other leaf tiles, responses and histories) and back to the overview, recording
// quakeview.stats().heapBytes (live WASM heap) and the tiles and buildings loaded at every stop.
// The city-wide search index (and the response in its order) is waited for after the overview, so
// the whole flight carries it, as a user's session does once search and the lists are ready.
// Not part of the test run (a benchmark, not a test); prints the heap curve as a markdown table.
//
//   node tests/e2e/bench-memory.mjs CITY_DIR [--memory MB] [--grid N] [--distance M] [--params k=v&...]
// (--params adds URL parameters, e.g. quality=high: the preset of a device with a GPU, which
// sways the buildings near the camera floor by floor from their histories)
import fs from 'node:fs';
import path from 'node:path';
import { launchBrowser, openPage, waitForFunction, waitReady } from './lib/browser.mjs';
import { serveSite } from './lib/server.mjs';

const args = process.argv.slice(2);
let dir = null;
let memoryMb = null;
let grid = 5;
let distance = 600;
let params = '';
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--memory') memoryMb = Number(args[++i]);
  else if (args[i] === '--grid') grid = Number(args[++i]);
  else if (args[i] === '--distance') distance = Number(args[++i]);
  else if (args[i] === '--params') params = `&${args[++i]}`;
  else dir = path.resolve(args[i]);
}
if (!dir || !fs.existsSync(path.join(dir, 'tileset.json'))) {
  console.error('usage: node tests/e2e/bench-memory.mjs CITY_DIR [--memory MB] [--grid N] [--distance M] [--params k=v&...]');
  process.exit(2);
}
const manifest = JSON.parse(fs.readFileSync(path.join(dir, 'tileset.json'), 'utf8'));
const [x0, y0, x1, y1] = manifest.bounds;

async function calm(page, timeout = 300000) {
  await waitForFunction(page, () => {
    const s = window.quakeview.stats();
    window.__calm = s && s.tiles.pending === 0 ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, null, { timeout, polling: 250 });
}

const server = await serveSite({ '/city': dir });
const { context, close } = await launchBrowser();
const rows = [];
const started = Date.now();
try {
  const query = memoryMb ? `&memory=${memoryMb}` : '';
  const { page } = await openPage(context, `${server.url}/?data=/city/tileset.json${query}${params}`);
  const ready = await waitReady(page, 300000);
  if (!ready.ok) throw new Error(ready.message);
  await page.evaluate(() => window.quakeview.play());
  const record = async (stop) => {
    const s = await page.evaluate(() => window.quakeview.stats());
    rows.push({ stop, seconds: (Date.now() - started) / 1000, heapMb: s.heapBytes / 1048576,
      reservedMb: s.heapReservedBytes / 1048576, tiles: s.tiles.loaded, loaded: s.buildings.loaded,
      visible: s.buildings.visible, animated: s.buildings.animated, memory: s.memory,
      index: await page.evaluate(() => window.quakeview.searchReady()) });
  };
  await record('overview');
  await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 1800000, polling: 1000 });
  await calm(page);
  await record('overview, city index loaded');
  for (let j = 0; j < grid; ++j) {
    for (let i = 0; i < grid; ++i) {
      const x = x0 + (x1 - x0) * ((j % 2 ? grid - 1 - i : i) + 0.5) / grid;
      const y = y0 + (y1 - y0) * (j + 0.5) / grid;
      await page.evaluate((c) => window.quakeview.setCamera(c), { x, y, distance, headingDeg: 30, pitchDeg: 45 });
      await calm(page);
      await record(`low pass ${j * grid + i + 1}`);
    }
  }
  await page.evaluate(() => window.quakeview.setCamera({ distance: 1e9 }));
  await calm(page);
  await record('overview again');
  const errors = await page.evaluate(() => window.quakeview.errors());
  if (errors.length) console.log('errors:', errors);
} finally {
  await close();
  await server.close();
}

const budget = memoryMb || 512;
console.log(`\nLive WASM heap over a flight of ${manifest.buildings} buildings (${path.basename(dir)}), budget ${budget} MB${params ? `, ${params.slice(1)}` : ''}\n`);
console.log('| stop | s | heap MB | WASM memory MB | counted MB | index | tiles | meshes | histories | map | unused table rows | rest of heap | tiles loaded | buildings loaded | visible | animated | city index |');
console.log('| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |');
const mb = (b) => (b / 1048576).toFixed(1);
for (const r of rows) {
  const m = r.memory;
  console.log(`| ${r.stop} | ${r.seconds.toFixed(0)} | ${r.heapMb.toFixed(1)} | ${r.reservedMb.toFixed(0)} | ` +
    `${mb(m.countedBytes)} | ${mb(m.indexBytes)} | ${mb(m.tilesBytes)} | ${mb(m.meshBytes)} | ${mb(m.historyBytes)} | ` +
    `${mb(m.groundBytes)} | ${mb(m.tableSlackBytes)} | ${mb(m.otherHeapBytes)} | ${r.tiles} | ${r.loaded} | ${r.visible} | ${r.animated} | ${r.index ? 'loaded' : 'not yet'} |`);
}
console.log('\n(counted: what the viewer counts against its budget, by part; meshes live on the GPU, outside the WASM heap)');
const peak = Math.max(...rows.map((r) => r.heapMb));
console.log(`\npeak live heap ${peak.toFixed(1)} MB (budget ${budget} MB: the heap and the meshes on the GPU, beyond the engine's own memory)`);
