// Small screens and touch: a phone (390 x 844 CSS px at a device pixel ratio of 3) and a tablet
// (768 x 1024 at 2), both with touch emulation, on the Midtown cut of the NYC data prepared by
// scripts/test.sh. Taps press the panel's buttons and select buildings; the phone's panel starts
// folded and its building window is a bottom sheet; the canvas is not drawn at the device's ratio
// of 3. Screenshots of each state go to tests/e2e/artifacts/touch-*.png.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { launchBrowser, openPage, waitForFunction, settle, swipe, waitReady } from './lib/browser.mjs';
import { ESB, URL_PATH, serveMidtown } from './lib/midtown.mjs';
import { ARTIFACTS } from './lib/server.mjs';

const midtown = serveMidtown();

const layout = (page) => page.evaluate(() => window.quakeview.uiLayout());
const panelOf = (l) => l.windows.find((w) => w.title === 'QuakeView');
const centre = (r) => ({ x: r.x + r.width / 2, y: r.y + r.height / 2 });

// Taps the panel's title bar (left of its middle, away from the collapse arrow and any button)
// and waits until the panel is folded or open as wanted.
async function tapPanelHeader(page, wantOpen) {
  const panel = panelOf(await layout(page));
  assert.ok(panel, 'the panel is drawn');
  await page.touchscreen.tap(panel.x + Math.min(120, panel.width / 2), panel.y + 8);
  await waitForFunction(page, (open) => {
    const p = window.quakeview.uiLayout().windows.find((w) => w.title === 'QuakeView');
    return p && p.collapsed === !open;
  }, wantOpen, { timeout: 20000, polling: 100 });
}

// The "Pause (Space)" button's rectangle, scrolled into the panel's visible part by swiping the
// panel up when it is below it.
async function pauseButton(page) {
  for (let attempt = 0; attempt < 8; ++attempt) {
    const l = await layout(page);
    const panel = panelOf(l);
    const button = l.items.find((i) => i.window === 'QuakeView' && i.label === 'Pause (Space)');
    assert.ok(button, `the panel shows the Pause button: ${JSON.stringify(l.items.map((i) => i.label))}`);
    const titleBar = 20;
    if (button.y >= panel.y + titleBar && button.y + button.height <= panel.y + panel.height) return button;
    const up = button.y + button.height > panel.y + panel.height ? -1 : 1;
    const x = panel.x + panel.width / 2;
    const y = panel.y + panel.height / 2;
    await swipe(page, { x, y }, { x, y: y + up * Math.min(200, panel.height / 3) });
    await page.waitForTimeout(300);
  }
  assert.fail('the Pause button could not be scrolled into view');
}

// Waits until the time has stopped advancing: the same over half a second.
async function timeStops(page) {
  const t0 = await page.evaluate(() => window.quakeview.time());
  await page.waitForTimeout(600);
  const t1 = await page.evaluate(() => window.quakeview.time());
  return t1 === t0;
}

// Looks down on the Empire State Building (a view that fits a portrait screen) and returns where
// its upper part (200 m up, inside its 443 m tower) appears.
async function lookAtEsb(page, distance) {
  assert.ok(await page.evaluate(({ x, y, d }) => window.quakeview.setCamera({ x, y, distance: d, headingDeg: 20, pitchDeg: 55, fovDeg: 45 }),
    { x: midtown.esb.x_m, y: midtown.esb.y_m, d: distance }));
  await settle(page);
  const [x, y] = await page.evaluate(({ x, y }) => window.quakeview.worldToScreen(x, y, 200), { x: midtown.esb.x_m, y: midtown.esb.y_m });
  return { x, y };
}

const inside = (p, r) => p.x >= r.x && p.x <= r.x + r.width && p.y >= r.y && p.y <= r.y + r.height;

test('on a phone, taps open the folded panel, press Pause and select a building shown above a bottom sheet; the canvas is not drawn at 3x', async () => {
  const { context, close } = await launchBrowser({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, touch: true });
  try {
    const { page, problems } = await openPage(context, `${midtown.server.url}${URL_PATH}`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await settle(page);

    // The canvas: a 390 x 844 CSS screen at 3 would be 1170 x 2532; at most 1.5x is drawn.
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.equal(stats.canvas.devicePixelRatio, 3);
    assert.equal(stats.canvas.cssWidth, 390);
    assert.ok(stats.canvas.pixelRatio <= 1.5 && stats.canvas.pixelRatio >= 1, JSON.stringify(stats.canvas));
    assert.ok(stats.canvas.width <= 585 && stats.canvas.height <= 1266, JSON.stringify(stats.canvas));

    // Folded at the start: the title bar is there, the controls are not, and it fits the screen.
    let l = await layout(page);
    let panel = panelOf(l);
    assert.ok(panel.collapsed, JSON.stringify(panel));
    assert.ok(panel.x >= 0 && panel.x + panel.width <= 390, JSON.stringify(panel));
    assert.ok(!(await page.evaluate(() => window.quakeview.uiText())).includes('[Pause (Space)]'));
    await page.screenshot({ path: path.join(ARTIFACTS, 'touch-phone-folded.png') });

    // A tap on its title bar opens it, no wider than the screen.
    await tapPanelHeader(page, true);
    l = await layout(page);
    panel = panelOf(l);
    assert.ok(panel.x >= 0 && panel.x + panel.width <= 390, `panel within the screen: ${JSON.stringify(panel)}`);
    assert.ok(panel.y + panel.height <= 844, JSON.stringify(panel));
    await page.screenshot({ path: path.join(ARTIFACTS, 'touch-phone-open.png') });

    // A tap on "Pause (Space)" stops the time.
    assert.ok(await page.evaluate(() => window.quakeview.playing()), 'the animation plays at the start');
    const pause = await pauseButton(page);
    await page.touchscreen.tap(centre(pause).x, centre(pause).y);
    await waitForFunction(page, () => !window.quakeview.playing(), null, { timeout: 20000, polling: 100 });
    assert.ok(await timeStops(page), 'the time stops advancing');

    // Folded again, a tap on the Empire State Building selects it, without moving the camera.
    await tapPanelHeader(page, false);
    const at = await lookAtEsb(page, 1600);
    l = await layout(page);
    assert.ok(at.x > 20 && at.x < 370 && at.y > 60 && at.y < 800, `ESB on screen: ${JSON.stringify(at)}`);
    assert.ok(!l.windows.some((w) => inside(at, w)), `ESB not under a window: ${JSON.stringify(l.windows)}`);
    const cameraBefore = await page.evaluate(() => window.quakeview.getCamera());
    await page.touchscreen.tap(at.x, at.y);
    await waitForFunction(page, (id) => window.quakeview.selection() === id, ESB, { timeout: 20000, polling: 100 });
    await page.waitForTimeout(500);
    const cameraAfter = await page.evaluate(() => window.quakeview.getCamera());
    assert.deepEqual(cameraAfter, cameraBefore, 'a tap does not pan the camera');

    // The building window is a bottom sheet: full width, on the bottom 40 %, the building above it.
    l = await layout(page);
    const sheet = l.windows.find((w) => w.title === `Building ${ESB}`);
    assert.ok(sheet, `the building window is shown: ${JSON.stringify(l.windows.map((w) => w.title))}`);
    assert.equal(sheet.x, 0);
    assert.equal(sheet.width, 390);
    assert.ok(Math.abs(sheet.y + sheet.height - 844) < 1, JSON.stringify(sheet));
    assert.ok(sheet.height <= 844 * 0.4 + 1 && sheet.height > 150, JSON.stringify(sheet));
    const [, shownY] = await page.evaluate(({ x, y }) => window.quakeview.worldToScreen(x, y, 200), { x: midtown.esb.x_m, y: midtown.esb.y_m });
    assert.ok(shownY < sheet.y, `the building (${shownY}) above the sheet (${sheet.y})`);
    await page.screenshot({ path: path.join(ARTIFACTS, 'touch-phone-sheet.png') });

    // A one-finger swipe on the city pans it and selects nothing else.
    const before = await page.evaluate(() => window.quakeview.getCamera());
    await swipe(page, { x: 200, y: 250 }, { x: 120, y: 330 });
    await page.waitForTimeout(300);
    const panned = await page.evaluate(() => window.quakeview.getCamera());
    assert.ok(Math.hypot(panned.x - before.x, panned.y - before.y) > 10, `the swipe panned: ${JSON.stringify([before, panned])}`);
    assert.equal(await page.evaluate(() => window.quakeview.selection()), ESB);

    // A tap on a building selected from a sheet-hidden spot brings it above the sheet.
    await page.evaluate(() => window.quakeview.select(''));
    const low = await lookAtEsb(page, 1600);
    await page.evaluate(({ x, y, d }) => window.quakeview.setCamera({ x, y: y + 500, distance: d }), { x: midtown.esb.x_m, y: midtown.esb.y_m, d: 1600 });
    await settle(page);
    const [, hiddenY] = await page.evaluate(({ x, y }) => window.quakeview.worldToScreen(x, y, 200), { x: midtown.esb.x_m, y: midtown.esb.y_m });
    assert.ok(hiddenY > 844 * 0.6, `set-up: the building low on the screen (${hiddenY}, was ${low.y})`);
    assert.ok(await page.evaluate((id) => window.quakeview.select(id), ESB));
    await waitForFunction(page, ({ x, y, limit }) => {
      const p = window.quakeview.worldToScreen(x, y, 200);
      return p && p[1] < limit;
    }, { x: midtown.esb.x_m, y: midtown.esb.y_m, limit: 844 * 0.6 }, { timeout: 20000, polling: 100 });

    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('on a tablet, a tap presses Pause in the open panel and a tap selects a building', async () => {
  const { context, close } = await launchBrowser({ viewport: { width: 768, height: 1024 }, deviceScaleFactor: 2, touch: true });
  try {
    const { page, problems } = await openPage(context, `${midtown.server.url}${URL_PATH}`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await settle(page);

    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.ok(stats.canvas.pixelRatio <= 2 && stats.canvas.width <= 1536, JSON.stringify(stats.canvas));

    // Open as on a desktop, within the screen.
    let l = await layout(page);
    let panel = panelOf(l);
    assert.ok(!panel.collapsed);
    assert.ok(panel.x >= 0 && panel.x + panel.width <= 768, JSON.stringify(panel));
    await page.screenshot({ path: path.join(ARTIFACTS, 'touch-tablet-open.png') });

    const pause = await pauseButton(page);
    await page.touchscreen.tap(centre(pause).x, centre(pause).y);
    await waitForFunction(page, () => !window.quakeview.playing(), null, { timeout: 20000, polling: 100 });
    assert.ok(await timeStops(page), 'the time stops advancing');

    // The panel folds with a tap on its title bar, and opens again.
    await tapPanelHeader(page, false);
    await page.screenshot({ path: path.join(ARTIFACTS, 'touch-tablet-folded.png') });
    const at = await lookAtEsb(page, 1400);
    l = await layout(page);
    assert.ok(!l.windows.some((w) => inside(at, w)), `ESB not under a window: ${JSON.stringify([at, l.windows])}`);
    await page.touchscreen.tap(at.x, at.y);
    await waitForFunction(page, (id) => window.quakeview.selection() === id, ESB, { timeout: 20000, polling: 100 });
    await page.waitForTimeout(300);
    l = await layout(page);
    const inspection = l.windows.find((w) => w.title === `Building ${ESB}`);
    assert.ok(inspection && inspection.x + inspection.width <= 768, JSON.stringify(l.windows));
    await page.screenshot({ path: path.join(ARTIFACTS, 'touch-tablet-selected.png') });
    await tapPanelHeader(page, true);

    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
