// Weak devices: a software WebGL renderer (SwiftShader in headless Chromium, llvmpipe in headless
// Firefox: both browsers of these tests render on the CPU) is detected and the viewer starts in the
// weak-device preset, without antialiasing, saying so in the Performance panel; ?aa=1 and
// ?quality= override it; the frame-time governor lowers detail when frames stay slow.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, openSection, waitReady } from './lib/browser.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const SYNTH = path.join(DATA, 'synth');

let server;
before(async () => {
  assert.ok(fs.existsSync(path.join(SYNTH, 'tileset.json')), `test city missing: ${SYNTH} (scripts/test.sh prepares it)`);
  server = await serveSite({ '/data': DATA });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});
after(async () => server && server.close());

test('a software renderer starts in the weak-device preset, says so, and the governor lowers detail on slow frames', async () => {
  const { context, close, browser } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/data/synth/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.equal(stats.softwareRenderer, true, `renderer ${stats.renderer}`);
    assert.match(stats.renderer, browser === 'firefox' ? /llvmpipe/i : /SwiftShader/i);
    assert.equal(stats.antialias, false);
    assert.equal(stats.maxPixelRatio, 1);
    assert.equal(stats.quality, 'Low (weak devices)');
    assert.equal(stats.governor, true);
    assert.equal(typeof stats.triangles, 'number');
    // Pixels per frame: the drawing buffer, one sample a pixel without antialiasing.
    const canvasPixels = stats.canvas.width * stats.canvas.height;
    assert.ok(canvasPixels > 0, `canvas ${stats.canvas.width}x${stats.canvas.height}`);
    assert.equal(stats.pixels, canvasPixels, `pixels ${stats.pixels} of a ${stats.canvas.width}x${stats.canvas.height} canvas`);
    assert.equal(stats.samples, stats.pixels, 'no antialiasing: one sample a pixel');
    // The panel says so in one line, and in the Performance section.
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /Software rendering: the weak-device preset is on \(Performance\)\./);
    await openSection(page, 'Performance');
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, new RegExp(`triangles \\d+ · pixels ${stats.canvas.width}×${stats.canvas.height} \\(no MSAA\\)`));
    assert.match(text, /Software rendering detected \(.+\): weak-device preset\./);
    assert.match(text, /Use full quality/);
    assert.match(text, /antialiasing off, pixel ratio capped at 1\.0/);

    // These renderers draw this city at a few frames per second: once two seconds of frames have
    // a median above 50 ms, detail goes one step down, and the panel says why.
    const deadline = Date.now() + 20000;
    let s = stats;
    while (Date.now() < deadline && s.qualityStep === 0) {
      await page.waitForTimeout(500);
      s = await page.evaluate(() => window.quakeview.stats());
    }
    const medianFrameMs = 1000 / s.fps;
    if (medianFrameMs > 60) {
      assert.ok(s.qualityStep >= 1, `frames of ${medianFrameMs.toFixed(0)} ms lowered the detail step: ${s.qualityStep}`);
      const now = await page.evaluate(() => window.quakeview.uiText());
      assert.match(now, /detail step [1-3] of 3 below the preset \(lowered: median frame \d+ ms > 50 ms\)/);
    } else {
      console.log(`frames of ${medianFrameMs.toFixed(0)} ms: fast enough that the governor holds step ${s.qualityStep}`);
    }
    await page.screenshot({ path: path.join(ARTIFACTS, `weak-device-${browser}.png`) });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('?aa=1 keeps full quality on a software renderer; ?quality= fixes a preset with the governor off', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/data/synth/tileset.json&aa=1`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const full = await page.evaluate(() => window.quakeview.stats());
    assert.equal(full.softwareRenderer, true);
    assert.equal(full.antialias, true);
    assert.equal(full.maxPixelRatio, 0);
    assert.equal(full.quality, 'High (desktop)');
    // Antialiased: each pixel filled with several samples (MSAA).
    assert.equal(full.pixels, full.canvas.width * full.canvas.height);
    const perPixel = full.samples / full.pixels;
    assert.ok(Number.isInteger(perPixel) && perPixel >= 2, `samples ${full.samples} for ${full.pixels} pixels`);
    assert.deepEqual(problems, []);
    await page.close();

    const { page: fixed } = await openPage(context, `${server.url}/?data=/data/synth/tileset.json&quality=balanced`);
    assert.deepEqual(await waitReady(fixed), { ok: true });
    await fixed.waitForTimeout(3000);
    const balanced = await fixed.evaluate(() => window.quakeview.stats());
    assert.equal(balanced.quality, 'Balanced');
    assert.equal(balanced.governor, false);
    assert.equal(balanced.qualityStep, 0, 'no governor step with a fixed preset');
    assert.equal(balanced.antialias, true);
    await fixed.close();

    // ?aa=0: antialiasing off whatever the preset, one sample a pixel.
    const { page: plain } = await openPage(context, `${server.url}/?data=/data/synth/tileset.json&quality=high&aa=0`);
    assert.deepEqual(await waitReady(plain), { ok: true });
    const noAa = await plain.evaluate(() => window.quakeview.stats());
    assert.equal(noAa.antialias, false);
    assert.equal(noAa.pixels, noAa.canvas.width * noAa.canvas.height);
    assert.equal(noAa.samples, noAa.pixels);
  } finally {
    await close();
  }
});
