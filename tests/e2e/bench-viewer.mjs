// Viewer benchmark in a headless browser, 1280x720, default settings (on these software renderers:
// the weak-device preset). Not part of the test run (timings are not tests); prints markdown tables.
// - The flight (default): page open to the first full frame (quakeview.ready), then the
//   ?bench=SECONDS flight (an overview of the whole city, then a low pass through the densest
//   area, playing), measured inside the engine (engine/scene/src/Bench.cpp).
// - The overview poses (--poses overview): the camera looks at the centre of the city's bounds
//   from 1.8 km at a pitch of 56 degrees, at eight headings (0, 45, ..., 315); each is held until
//   nothing is left to load, then measured for --pose-seconds (default 5, at least 6 frames):
//   FPS from the page's requestAnimationFrame intervals, triangles and draw calls of each frame
//   (stats().lastFrame).
// Every table gives the triangles and the pixels per frame beside the FPS, and the browser and
// WebGL renderer it ran on. Last, the reference (tests/e2e/bench/reference.html): a bare WebGL2 page
// drawing 30,000 and 100,000 small triangles in the same browser, measured in the same run, so that
// the viewer's rows can be read against what this machine draws at that moment.
//
//   node tests/e2e/bench-viewer.mjs NAME=CITY_DIR [NAME=CITY_DIR ...] [--seconds 20]
//        [--browser chromium|firefox] [--poses overview [--pose-seconds 5] [--flight]] [--params 'aa=0']
//
// --browser: Debian's Chromium (SwiftShader, the default) or Firefox ESR (llvmpipe); the same as
// QUAKEVIEW_BROWSER=firefox. --poses overview measures the poses instead of the flight; add
// --flight for both. --params adds URL parameters to every page (e.g. 'aa=0' or 'quality=high').
import fs from 'node:fs';
import path from 'node:path';

const args = process.argv.slice(2);
let seconds = 20;
let poseSeconds = 5;
let poses = null;
let flight = null;
let params = '';
const cities = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--seconds') seconds = Number(args[++i]);
  else if (args[i] === '--pose-seconds') poseSeconds = Number(args[++i]);
  else if (args[i] === '--browser') process.env.QUAKEVIEW_BROWSER = args[++i];
  else if (args[i] === '--poses') poses = args[++i];
  else if (args[i] === '--flight') flight = true;
  else if (args[i] === '--params') params = args[++i].replace(/^[?&]/, '');
  else {
    const [name, dir] = args[i].split('=');
    if (!dir) throw new Error(`expected NAME=CITY_DIR, got ${args[i]}`);
    cities.push({ name, dir: path.resolve(dir) });
  }
}
if (cities.length === 0 || (poses !== null && poses !== 'overview') || !(seconds > 0) || !(poseSeconds > 0)) {
  console.error('usage: node tests/e2e/bench-viewer.mjs NAME=CITY_DIR [...] [--seconds 20] ' +
    '[--browser chromium|firefox] [--poses overview [--pose-seconds 5] [--flight]] [--params aa=0]');
  process.exit(2);
}
if (flight === null) flight = poses === null;

// lib/browser.mjs reads QUAKEVIEW_BROWSER when it is loaded: after --browser.
const { BROWSER, launchBrowser, openPage, settle, waitForFunction, waitReady } = await import('./lib/browser.mjs');
const { serveSite } = await import('./lib/server.mjs');
const BROWSER_NAME = BROWSER === 'firefox' ? 'Firefox ESR' : 'Chromium';

/// The overview poses: 1.8 km from the centre of the city's bounds, pitch 56 degrees.
const OVERVIEW = { distance: 1800, pitchDeg: 56, headings: [0, 45, 90, 135, 180, 225, 270, 315] };

function cityCentre(dir) {
  const tileset = JSON.parse(fs.readFileSync(path.join(dir, 'tileset.json'), 'utf8'));
  const [minX, minY, maxX, maxY] = tileset.bounds;
  return { x: (minX + maxX) / 2, y: (minY + maxY) / 2 };
}

const pixelsText = (s) => `${s.canvas.width}×${s.canvas.height} (${s.pixels}${s.samples !== s.pixels ? `, ${s.samples} samples` : ''})`;

// Frames for `ms` and at least `minFrames` intervals (or, with `untilBench`, until the ?bench
// flight has its result), at most 10 minutes, measured in the page: {frames, fps: {median,
// atP95FrameTime}, frameMs: {median, p95}, triangles: {median, p95}, drawCalls: {median},
// responding: {median, min}} (responding: the share of the buildings in view that follow their
// response, stats().buildings.animated / visible). Nothing is compiled from a string in the page
// (the site's CSP forbids it).
async function measureFrames(page, ms, minFrames = 6, untilBench = false) {
  return page.evaluate(({ ms, minFrames, untilBench }) => new Promise((resolve) => {
    const done = untilBench ? () => window.quakeview.benchResult !== null : null;
    const times = [], triangles = [], drawCalls = [], responding = [];
    const start = performance.now();
    const q = (v, p) => {
      const s = [...v].sort((a, b) => a - b);
      return s.length ? s[Math.min(s.length - 1, Math.max(0, Math.ceil(p * s.length) - 1))] : NaN;
    };
    const tick = (t) => {
      times.push(t);
      const s = window.quakeview.stats();
      triangles.push(s.lastFrame.triangles);
      drawCalls.push(s.lastFrame.drawCalls);
      if (s.buildings.visible > 0) responding.push(s.buildings.animated / s.buildings.visible);
      const elapsed = t - start;
      const more = done ? !done() : elapsed < ms || times.length <= minFrames;
      if (more && elapsed < 600000) {
        requestAnimationFrame(tick);
        return;
      }
      const intervals = times.slice(1).map((x, i) => x - times[i]);
      resolve({
        frames: intervals.length,
        fps: { median: 1000 / q(intervals, 0.5), atP95FrameTime: 1000 / q(intervals, 0.95) },
        frameMs: { median: q(intervals, 0.5), p95: q(intervals, 0.95) },
        triangles: { median: q(triangles, 0.5), p95: q(triangles, 0.95) },
        drawCalls: { median: q(drawCalls, 0.5) },
        responding: { median: q(responding, 0.5), min: responding.length ? Math.min(...responding) : NaN },
      });
    };
    requestAnimationFrame(tick);
  }), { ms, minFrames, untilBench });
}

const mounts = { '/reference': path.join(path.dirname(new URL(import.meta.url).pathname), 'bench') };
cities.forEach((c, i) => { mounts[`/city${i}`] = c.dir; });
const server = await serveSite(mounts);
const extra = params ? `&${params}` : '';
const flightRows = [];
const poseRows = [];
const referenceRows = [];
try {
  for (const [i, city] of cities.entries()) {
    if (flight) {
      const { context, close } = await launchBrowser();
      try {
        // Page open to first full frame: a fresh page, no cache.
        const t0 = Date.now();
        const { page } = await openPage(context, `${server.url}/?data=/city${i}/tileset.json&bench=${seconds}${extra}`);
        const ready = await waitReady(page, 180000);
        const openMs = Date.now() - t0;
        if (!ready.ok) throw new Error(`${city.name}: ${ready.message}`);
        const stats = await page.evaluate(() => window.quakeview.stats());
        // The flight starts at the frame that resolves ready; its frames measured in the page too
        // (requestAnimationFrame intervals: the engine's benchResult has no percentile of them).
        const frames = await measureFrames(page, 0, 0, true);
        const result = await page.evaluate(() => window.quakeview.benchDone);
        const after = await page.evaluate(() => window.quakeview.stats());
        flightRows.push({ name: city.name, buildings: stats.buildings.loaded, openMs, result, frames, stats: after });
      } finally {
        await close();
      }
    }
    if (poses === 'overview') {
      const centre = cityCentre(city.dir);
      const { context, close } = await launchBrowser();
      try {
        const { page } = await openPage(context, `${server.url}/?data=/city${i}/tileset.json${extra}`);
        const ready = await waitReady(page, 180000);
        if (!ready.ok) throw new Error(`${city.name}: ${ready.message}`);
        for (const headingDeg of OVERVIEW.headings) {
          const camera = { x: centre.x, y: centre.y, distance: OVERVIEW.distance, pitchDeg: OVERVIEW.pitchDeg, headingDeg };
          const ok = await page.evaluate((c) => window.quakeview.setCamera(c), camera);
          if (!ok) throw new Error(`${city.name}: setCamera(${JSON.stringify(camera)}) refused`);
          await settle(page);
          const m = await measureFrames(page, poseSeconds * 1000);
          const stats = await page.evaluate(() => window.quakeview.stats());
          poseRows.push({ name: city.name, headingDeg, m, stats });
        }
      } finally {
        await close();
      }
    }
  }
  // The reference: what this browser draws of bare small triangles, now.
  const { context, close } = await launchBrowser();
  try {
    for (const n of [30000, 100000]) {
      const { page } = await openPage(context, `${server.url}/reference/reference.html?n=${n}`);
      await waitForFunction(page, () => document.title.startsWith('drawing') || document.title.startsWith('error'), null, { timeout: 60000 });
      const title = await page.evaluate(() => document.title);
      if (!title.startsWith('drawing')) throw new Error(`reference page: ${title}`);
      await page.waitForTimeout(1000);
      const intervals = await page.evaluate((ms) => new Promise((resolve) => {
        const times = [];
        const tick = (t) => {
          times.push(t);
          if (t - times[0] < ms || times.length < 8) requestAnimationFrame(tick);
          else resolve(times.slice(1).map((x, i) => x - times[i]));
        };
        requestAnimationFrame(tick);
      }), poseSeconds * 1000);
      const sorted = [...intervals].sort((a, b) => a - b);
      const at = (p) => sorted[Math.min(sorted.length - 1, Math.max(0, Math.ceil(p * sorted.length) - 1))];
      referenceRows.push({ n, frames: intervals.length, median: at(0.5), p95: at(0.95) });
      await page.close();
    }
  } finally {
    await close();
  }
} finally {
  await server.close();
}

const rendererOf = (rows) => [...new Set(rows.map((r) => r.stats.renderer))].join('; ');
if (flightRows.length > 0) {
  console.log(`\nViewer in headless ${BROWSER_NAME} (${rendererOf(flightRows)}), 1280x720, ${seconds} s flight while playing` +
    `${params ? `, ?${params}` : ''}\n`);
  console.log('| city | browser | buildings | open to first full frame s | FPS median | FPS at p95 frame time | frame ms median | frame ms p95 | engine CPU ms (cull+lod+animate) | upload ms | draw calls | triangles median | triangles p95 | in view responding, median (min) | pixels per frame | quality (step) |');
  console.log('| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |');
  for (const r of flightRows) {
    const f = r.result.frameMs;
    const engine = f.cull.median + f.lod.median + f.animate.median;
    const m = r.frames;
    console.log(`| ${r.name} | ${BROWSER_NAME} | ${r.buildings} | ${(r.openMs / 1000).toFixed(2)} | ${m.fps.median.toFixed(1)} | ` +
      `${m.fps.atP95FrameTime.toFixed(1)} | ${m.frameMs.median.toFixed(1)} | ${m.frameMs.p95.toFixed(1)} | ${engine.toFixed(2)} | ` +
      `${f.upload.median.toFixed(2)} | ${r.result.drawCalls.median} | ${Math.round(r.result.triangles.median)} | ` +
      `${Math.round(r.result.triangles.p95)} | ${(100 * m.responding.median).toFixed(0)} % (${(100 * m.responding.min).toFixed(0)} %) | ` +
      `${pixelsText(r.stats)} | ${r.stats.quality} (${r.stats.qualityStep}) |`);
  }
  console.log('\n(FPS and frame ms from the page\'s requestAnimationFrame intervals over the flight; engine CPU, ' +
    'draw calls and triangles from its benchResult; quality: the preset and governor step at the end.)');
}
if (poseRows.length > 0) {
  console.log(`\nOverview poses in headless ${BROWSER_NAME} (${rendererOf(poseRows)}), 1280x720: ${OVERVIEW.distance} m from the ` +
    `centre of the city's bounds, pitch ${OVERVIEW.pitchDeg}°, each heading held until loaded, then ${poseSeconds} s measured` +
    `${params ? `, ?${params}` : ''}\n`);
  console.log('| city | browser | heading ° | frames | FPS median | FPS at p95 frame time | frame ms median | frame ms p95 | triangles median | triangles p95 | pixels per frame | draw calls | quality (step) |');
  console.log('| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | --- |');
  for (const r of poseRows) {
    const m = r.m;
    console.log(`| ${r.name} | ${BROWSER_NAME} | ${r.headingDeg} | ${m.frames} | ${m.fps.median.toFixed(2)} | ${m.fps.atP95FrameTime.toFixed(2)} | ${m.frameMs.median.toFixed(1)} | ` +
      `${m.frameMs.p95.toFixed(1)} | ${Math.round(m.triangles.median)} | ${Math.round(m.triangles.p95)} | ${pixelsText(r.stats)} | ` +
      `${m.drawCalls.median} | ${r.stats.quality} (${r.stats.qualityStep}) |`);
  }
  const byCity = new Map();
  for (const r of poseRows) byCity.set(r.name, [...(byCity.get(r.name) || []), r.m.fps.median]);
  for (const [name, fps] of byCity) {
    const s = [...fps].sort((a, b) => a - b);
    console.log(`\n${name}: FPS over the ${s.length} poses: min ${s[0].toFixed(2)}, median ${((s[(s.length - 1) >> 1] + s[s.length >> 1]) / 2).toFixed(2)}, max ${s[s.length - 1].toFixed(2)}`);
  }
}
if (referenceRows.length > 0) {
  console.log(`\nReference in headless ${BROWSER_NAME}, same run: a bare WebGL2 page (tests/e2e/bench/reference.html), ` +
    `1280x720, no antialiasing, one draw call of small triangles (about 4 x 7 pixels) a frame\n`);
  console.log('| browser | triangles | frames | FPS median | FPS at p95 frame time | frame ms median | frame ms p95 |');
  console.log('| --- | ---: | ---: | ---: | ---: | ---: | ---: |');
  for (const r of referenceRows) {
    console.log(`| ${BROWSER_NAME} | ${r.n} | ${r.frames} | ${(1000 / r.median).toFixed(1)} | ${(1000 / r.p95).toFixed(1)} | ` +
      `${r.median.toFixed(1)} | ${r.p95.toFixed(1)} |`);
  }
}
