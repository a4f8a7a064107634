// Viewer benchmark in headless Chromium (SwiftShader: WebGL2 rendered on this CPU), 1280x720:
// page open to the first full frame (quakeview.ready), then the ?bench=SECONDS flight (an overview
// of the whole city, then a low pass through the densest area, playing) for each prepared city.
// Not part of the test run (timings are not tests); prints a markdown table.
//
//   node tests/e2e/bench-viewer.mjs NAME=CITY_DIR [NAME=CITY_DIR ...] [--seconds 20]
import path from 'node:path';
import { launchBrowser, openPage, waitReady } from './lib/browser.mjs';
import { serveSite } from './lib/server.mjs';

const args = process.argv.slice(2);
let seconds = 20;
const cities = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--seconds') seconds = Number(args[++i]);
  else {
    const [name, dir] = args[i].split('=');
    if (!dir) throw new Error(`expected NAME=CITY_DIR, got ${args[i]}`);
    cities.push({ name, dir: path.resolve(dir) });
  }
}
if (cities.length === 0) {
  console.error('usage: node tests/e2e/bench-viewer.mjs NAME=CITY_DIR [...] [--seconds 20]');
  process.exit(2);
}

const mounts = {};
cities.forEach((c, i) => { mounts[`/city${i}`] = c.dir; });
const server = await serveSite(mounts);
const rows = [];
try {
  for (const [i, city] of cities.entries()) {
    const { context, close } = await launchBrowser();
    try {
      // Page open to first full frame: a fresh page, no cache.
      const t0 = Date.now();
      const { page } = await openPage(context, `${server.url}/?data=/city${i}/tileset.json&bench=${seconds}`);
      const ready = await waitReady(page, 180000);
      const openMs = Date.now() - t0;
      if (!ready.ok) throw new Error(`${city.name}: ${ready.message}`);
      const stats = await page.evaluate(() => window.quakeview.stats());
      const result = await page.evaluate(() => window.quakeview.benchDone);
      rows.push({ name: city.name, buildings: stats.buildings.loaded, openMs, result, heap: stats.heapBytes });
    } finally {
      await close();
    }
  }
} finally {
  await server.close();
}

console.log(`\nViewer in headless Chromium (SwiftShader), 1280x720, ${seconds} s flight while playing\n`);
console.log('| city | buildings | open to first full frame s | FPS median | FPS p95 | frame ms median | cull+lod+animate ms | upload ms | draw calls | triangles median | triangles p95 |');
console.log('| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |');
for (const r of rows) {
  const f = r.result.frameMs;
  const engine = f.cull.median + f.lod.median + f.animate.median;
  console.log(`| ${r.name} | ${r.buildings} | ${(r.openMs / 1000).toFixed(2)} | ${r.result.fps.median.toFixed(1)} | ${r.result.fps.p95.toFixed(1)} | ` +
    `${f.total.median.toFixed(2)} | ${engine.toFixed(2)} | ${f.upload.median.toFixed(2)} | ${r.result.drawCalls.median} | ` +
    `${Math.round(r.result.triangles.median)} | ${Math.round(r.result.triangles.p95)} |`);
}
