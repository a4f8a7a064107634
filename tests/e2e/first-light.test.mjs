// First light: the test scene renders in headless Chromium (SwiftShader WebGL2) served over HTTP,
// the control panel shows, nothing logs an error; without WebGL the page explains why.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, waitReady } from './lib/browser.mjs';
import { colourAt, colourDistance, decodePng, luminanceStats } from './lib/pixels.mjs';
import { ARTIFACTS, serveSite } from './lib/server.mjs';

let server;
before(async () => {
  server = await serveSite();
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => server && server.close());

test('the test scene renders prisms, the panel and no console errors', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?scene=test`);
    const ready = await waitReady(page);
    assert.deepEqual(ready, { ok: true });
    await page.waitForTimeout(500);
    const png = await page.screenshot({ path: path.join(ARTIFACTS, 'first-light.png') });
    const image = decodePng(png);

    // Not blank: a flat canvas (all sky, all black) has almost no variance.
    const { variance } = luminanceStats(image);
    assert.ok(variance > 100, `canvas looks blank (luminance variance ${variance.toFixed(1)})`);

    // The prisms are where the camera says they are: the tower's middle and the courtyard block's
    // roof differ clearly from the bare ground next to them.
    const at = (x, y, z) => page.evaluate(([a, b, c]) => window.quakeview.worldToScreen(a, b, c), [x, y, z]);
    // (Bare ground south of the tower, between the courtyard block and the L: on screen whatever
    // side of the canvas the panel leaves free.)
    const groundAt = await at(0, -110, 0);
    assert.ok(groundAt[0] > 0 && groundAt[0] < image.width && groundAt[1] > 0 && groundAt[1] < image.height, `ground ${groundAt}`);
    const ground = colourAt(image, ...groundAt);
    for (const [name, point] of [['tower', [0, 0, 70]], ['slab', [-60, 45, 20]], ['courtyard roof', [-80, -75, 9.6]]]) {
      const [px, py] = await at(...point);
      assert.ok(px > 0 && px < image.width && py > 0 && py < image.height, `${name} is off screen`);
      const c = colourAt(image, px, py);
      assert.ok(colourDistance(c, ground) > 40, `${name} at (${px.toFixed(0)}, ${py.toFixed(0)}) looks like ground: ${c} vs ${ground}`);
    }
    // The courtyard's hole shows the ground through it.
    const hole = colourAt(image, ...(await at(-58, -53, 0)), 1);
    assert.ok(colourDistance(hole, ground) < 40, `courtyard hole is not open: ${hole} vs ground ${ground}`);

    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.equal(stats.buildings.loaded, 6);
    assert.equal(stats.drawCalls, 7);
    assert.ok(stats.fps > 0, 'fps is reported');
    assert.ok(stats.heapBytes > 0 && stats.heapReservedBytes >= stats.heapBytes);
    for (const key of ['cull', 'lod', 'animate', 'upload', 'render', 'total']) {
      assert.equal(typeof stats.frameMs[key], 'number', `frameMs.${key}`);
    }

    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /== QuakeView ==/);
    assert.match(text, /FPS: \d+\.\d\s+frame: \d+\.\d\d ms/);
    assert.match(text, /draw calls 7/);
    assert.deepEqual(await page.evaluate(() => window.quakeview.errors()), []);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('dragging the canvas pans the camera and the wheel zooms', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?scene=test`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const before = await page.evaluate(() => window.quakeview.getCamera());
    await page.mouse.move(800, 500);
    await page.mouse.down();
    await page.mouse.move(800, 420, { steps: 4 });
    await page.mouse.up();
    await page.waitForTimeout(200);
    const panned = await page.evaluate(() => window.quakeview.getCamera());
    assert.ok(Math.hypot(panned.x - before.x, panned.y - before.y) > 5, 'a drag moves the looked-at point');
    await page.mouse.wheel(0, -300);
    await page.waitForTimeout(200);
    const zoomed = await page.evaluate(() => window.quakeview.getCamera());
    assert.ok(zoomed.distance < panned.distance * 0.8, `wheel zooms in (${panned.distance} -> ${zoomed.distance})`);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('without WebGL, the page opens the 2D view and says why, with what an administrator can do', async () => {
  const { context, close } = await launchBrowser({ webgl: false });
  try {
    const { page, problems } = await openPage(context, `${server.url}/?scene=test`);
    const ready = await waitReady(page, 30000);
    assert.deepEqual(ready, { ok: true });
    const notice = await page.locator('#qv-map2d-notice').innerText();
    assert.match(notice, /The 3D view is off: this browser gives the page no WebGL2/);
    assert.match(notice, /An administrator turns the 3D view on/);
    assert.ok(await page.locator('#qv-map2d-notice').isVisible());
    assert.equal(await page.locator('#error').isVisible(), false);
    assert.equal(await page.locator('#loading').isVisible(), false);
    await page.screenshot({ path: path.join(ARTIFACTS, 'no-webgl.png') });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
