// Triangles bounded by the screen, not by the city: the overview of the demo's 100,000-building
// city (the first view a user gets) must draw no more triangles per frame than a budget. On the
// software renderers many administrators have (SwiftShader, WARP, llvmpipe) the frame time is the
// triangles and the pixels, so this bound is what keeps the viewer usable there.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, settle, waitReady } from './lib/browser.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

// Budgets of triangles per frame at the overview, 1280x720 CSS px at a pixel ratio of 1. A
// 1280x720 view has 921,600 pixels; SwiftShader on 2 cores fills on the order of 2-3 million small
// triangles a second (../shared/TOOLCHAIN.md, issue 18: 100k triangles ran at 22.5 FPS without
// antialiasing), so:
// - the default view (on a software renderer: the weak-device preset, no antialiasing), and that
//   preset with the frame-time governor off (?quality=low), get 150,000 triangles, about one for every six pixels, for some 15-20 FPS at the overview;
// - ?quality=high (antialiased, full detail) gets 400,000, still well under the 1.0 M the
//   overview drew when every building of the coarse root was drawn whatever its size on screen.
const BUDGET_DEFAULT_TRIANGLES = 150000;
const BUDGET_HIGH_TRIANGLES = 400000;

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const DEMO = path.join(DATA, 'demo');

let server;
before(async () => {
  assert.ok(fs.existsSync(path.join(DEMO, 'tileset.json')), `test city missing: ${DEMO} (scripts/test.sh prepares it)`);
  server = await serveSite({ '/data': DATA });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => server && server.close());

// The triangles of the settled overview: the most any of a few frames after everything in view has
// loaded drew (stats().lastFrame), and the median over recent frames (stats().triangles).
async function overviewTriangles(page) {
  await settle(page);
  return page.evaluate(() => new Promise((resolve) => {
    const frames = [];
    const tick = () => {
      frames.push(window.quakeview.stats().lastFrame.triangles);
      if (frames.length < 5) {
        requestAnimationFrame(tick);
        return;
      }
      const s = window.quakeview.stats();
      resolve({ triangles: Math.max(...frames), median: s.triangles, stats: s, camera: window.quakeview.getCamera() });
    };
    requestAnimationFrame(tick);
  }));
}

function describe(label, budget, m) {
  const s = m.stats;
  const camera = Object.entries(m.camera).map(([k, v]) => `${k} ${Number(v).toFixed(1)}`).join(', ');
  return `${label}: the overview drew ${m.triangles} triangles a frame (median over recent frames ${Math.round(m.median)}), ` +
    `over the budget of ${budget}; camera {${camera}}; ${s.canvas.width}x${s.canvas.height} px, ` +
    `quality ${s.quality} step ${s.qualityStep}, ${s.drawCalls} draw calls, ${s.buildings.visible} buildings visible`;
}

for (const { label, query, budget } of [
  { label: 'default view (weak-device preset on a software renderer)', query: '', budget: BUDGET_DEFAULT_TRIANGLES },
  // The weak-device preset itself, the frame-time governor off: the budget holds without its help.
  { label: '?quality=low', query: '&quality=low', budget: BUDGET_DEFAULT_TRIANGLES },
  { label: '?quality=high', query: '&quality=high', budget: BUDGET_HIGH_TRIANGLES },
]) {
  test(`the demo's overview, ${label}, draws at most ${budget} triangles a frame`, async () => {
    const { context, close, browser } = await launchBrowser();
    try {
      const { page, problems } = await openPage(context, `${server.url}/?data=/data/demo/tileset.json${query}`);
      assert.deepEqual(await waitReady(page, 300000), { ok: true });
      const m = await overviewTriangles(page);
      console.log(`${label}: ${m.triangles} triangles (median ${Math.round(m.median)}), ${m.stats.drawCalls} draw calls, ` +
        `quality ${m.stats.quality} step ${m.stats.qualityStep}, budget ${budget}`);
      await page.screenshot({ path: path.join(ARTIFACTS, `triangle-budget-${query ? query.split('=')[1] : 'default'}-${browser}.png`) });
      assert.ok(m.triangles > 0, `${label}: the overview drew nothing`);
      assert.ok(m.triangles <= budget, describe(label, budget, m));
      assert.deepEqual(problems, []);
    } finally {
      await close();
    }
  });
}
