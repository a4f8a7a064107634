// Keyboard and screen-reader use on the Midtown cut (the Empire State Building,
// ../shared/data/osm/fixture-midtown-empire-state.osm, prepared by scripts/test.sh): a building
// is found and selected with the keyboard alone, Tab reaches the panel's controls beyond the
// sliders with a visible focus, and the page's accessibility tree (the HTML copy of the panels
// beside the canvas and its live region) names the selection.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { launchBrowser, openPage, waitForFunction, waitReady } from './lib/browser.mjs';
import { decodePng } from './lib/pixels.mjs';
import { ESB, URL_PATH, serveMidtown } from './lib/midtown.mjs';
import { ARTIFACTS } from './lib/server.mjs';

const midtown = serveMidtown();

async function openCity(context) {
  const { page, problems } = await openPage(context, `${midtown.server.url}${URL_PATH}`);
  assert.deepEqual(await waitReady(page), { ok: true });
  await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 30000 });
  await page.evaluate(() => window.quakeview.pause());
  await page.focus('#canvas');
  return { page, problems };
}

// Pixels of the keyboard focus's frame: ImGui's navigation highlight in the app's colour
// (ImGuiCol_NavHighlight, App.cpp: 0.0, 0.25, 0.70), within a small distance for antialiasing.
function focusPixels(image) {
  const { data } = image;
  let n = 0;
  for (let i = 0; i < data.length; i += 4) {
    if (Math.hypot(data[i] - 0, data[i + 1] - 64, data[i + 2] - 178) < 30) ++n;
  }
  return n;
}

// Resolves after the engine has drawn a frame since the call (it runs on requestAnimationFrame, and
// its callback of the coming frame was registered before ours), so a key pressed before has been
// handled and what the UI shows is up to date. On this loaded software-rendered machine frames can
// take a second.
async function nextFrames(page) {
  await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
}

// Presses Tab until `accept(focus)` holds for the control showing the keyboard focus; returns the
// descriptions met on the way (quakeview.uiFocus(), "Export CSV, button").
async function tabUntil(page, accept, limit = 90) {
  const seen = [];
  for (let i = 0; i < limit; ++i) {
    await page.keyboard.press('Tab');
    await nextFrames(page);
    const focus = await page.evaluate(() => window.quakeview.uiFocus());
    seen.push(focus);
    if (focus && accept(focus)) return seen;
  }
  assert.fail(`Tab never reached the control; met: ${JSON.stringify(seen)}`);
  return seen;
}

test('keyboard only: / opens the search, typing does not turn the camera, Enter selects the first result', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    // "Find and filter" starts collapsed: '/' must open it.
    assert.match(await page.evaluate(() => window.quakeview.uiText()), /> Find and filter/);
    const before = await page.evaluate(() => window.quakeview.getCamera());
    await page.keyboard.press('/');
    // "Empire State" holds an e (Q/E turn the camera), an S (pans) and a space (plays).
    await page.keyboard.type('Empire State', { delay: 30 });
    await waitForFunction(page, () => /Search \(\/\): \[Empire State\]/.test(window.quakeview.uiText()), null, { timeout: 20000 });
    const typed = await page.evaluate(() => window.quakeview.getCamera());
    for (const k of Object.keys(before)) assert.equal(typed[k], before[k], `camera ${k} unchanged while typing`);
    assert.equal(await page.evaluate(() => window.quakeview.playing()), false, 'the space typed did not start playback');
    await page.screenshot({ path: path.join(ARTIFACTS, 'accessibility-search.png') });

    await page.keyboard.press('Enter');
    await waitForFunction(page, (id) => window.quakeview.selection() === id, ESB, { timeout: 10000 });
    // It flies there, as a click on the result does.
    await waitForFunction(page, (b) => {
      const c = window.quakeview.getCamera();
      return Math.abs(c.x - b.x) > 1 || Math.abs(c.y - b.y) > 1 || Math.abs(c.distance - b.distance) > 1;
    }, before, { timeout: 10000 });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('Tab reaches headers, checkboxes, buttons and the inspection window beyond the sliders, with a visible focus', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    assert.ok(await page.evaluate((id) => window.quakeview.select(id), ESB));
    await page.keyboard.press('/');  // opens "Find and filter" (its checkbox and list)
    await waitForFunction(page, () => /Search \(\/\): \[\]/.test(window.quakeview.uiText()), null, { timeout: 20000 });
    await nextFrames(page);
    await page.keyboard.press('Escape');  // leaves the search field
    await nextFrames(page);
    assert.equal(await page.evaluate(() => window.quakeview.uiFocus()), null, 'Escape hides the focus');

    const before = decodePng(await page.screenshot());
    const seen = await tabUntil(page, (f) => f.startsWith('Critical facilities only') && f.includes(', checkbox,'));
    assert.ok(seen.some((f) => f && f.endsWith(', section, expanded')), `a section header: ${JSON.stringify(seen)}`);
    assert.ok(seen.some((f) => f && f.startsWith('Play (Space), button') || f && f.startsWith('Pause (Space), button')),
      `the play button: ${JSON.stringify(seen)}`);
    assert.ok(seen.some((f) => f && f.includes(', drop-down,')), `a drop-down: ${JSON.stringify(seen)}`);
    // The focus is drawn: a frame in the highlight's dark blue around the checkbox's row, which the
    // screen did not hold before Tab.
    const png = await page.screenshot({ path: path.join(ARTIFACTS, 'accessibility-focus-checkbox.png') });
    const shown = focusPixels(decodePng(png));
    assert.ok(shown > focusPixels(before) + 100, `focus frame pixels: ${focusPixels(before)} before, ${shown} after`);

    // Space presses the focused checkbox.
    assert.equal((await page.evaluate(() => window.quakeview.filters())).criticalOnly, false);
    await page.keyboard.press('Space');
    await waitForFunction(page, () => window.quakeview.filters().criticalOnly === true, null, { timeout: 20000 });
    assert.equal(await page.evaluate(() => window.quakeview.playing()), false, 'Space pressed the checkbox, not Play');
    await page.keyboard.press('Space');
    await waitForFunction(page, () => window.quakeview.filters().criticalOnly === false, null, { timeout: 20000 });

    // On to Export and the inspection window's Close, which Enter presses.
    const more = await tabUntil(page, (f) => f.startsWith('Close (Esc), button'));
    assert.ok(more.some((f) => f && f.startsWith('Export CSV, button')), `Export: ${JSON.stringify(more)}`);
    await page.screenshot({ path: path.join(ARTIFACTS, 'accessibility-focus-close.png') });
    await page.keyboard.press('Enter');
    await waitForFunction(page, () => window.quakeview.selection() === null, null, { timeout: 20000 });
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the accessibility tree holds the panels as headings and names the selected building; the live region says it', async () => {
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openCity(context);
    const canvasLabel = await page.getAttribute('#canvas', 'aria-label');
    assert.match(canvasLabel, /Tab/);
    assert.doesNotMatch(canvasLabel, /uiText|quakeview\./, 'no JavaScript function in what a screen reader reads');

    await page.keyboard.press('/');
    await page.keyboard.type('Empire State', { delay: 30 });
    await page.keyboard.press('Enter');
    await waitForFunction(page, (id) => window.quakeview.selection() === id, ESB, { timeout: 10000 });
    const building = await page.evaluate((id) => window.quakeview.building(id), ESB);

    // The live region announces the selection with its damage.
    await waitForFunction(page, () => /^Selected: /.test(document.getElementById('qv-status').textContent), null,
      { timeout: 20000 });
    const status = await page.locator('#qv-status').textContent();
    assert.match(status, /^Selected: Empire State Building, /);
    assert.ok(status.includes(building.damageState === 'none' ? 'no damage' : `${building.damageState} damage`), status);

    // The accessibility tree, as a screen reader gets it.
    await waitForFunction(page, () => /Selected building: Empire State Building/.test(document.getElementById('qv-panel').textContent),
      null, { timeout: 20000 });
    const tree = await page.locator('body').ariaSnapshot();
    fs.writeFileSync(path.join(ARTIFACTS, 'accessibility-tree.yaml'), tree);
    assert.match(tree, /region "QuakeView panel"/);
    assert.match(tree, /heading "Selected building: Empire State Building" \[level=2\]/);
    assert.match(tree, /heading "Earthquake and data" \[level=2\]/);
    assert.match(tree, /SCENARIO/);
    assert.match(tree, /heading "Damage and colours( \(collapsed in the panel\))?" \[level=2\]/);
    assert.match(tree, /heading "Consequences" \[level=2\]/);
    assert.match(tree, /Damage state: /);
    assert.match(tree, /status.*Selected: Empire State Building/s);
    // The copy is not on screen: it takes no room beside the canvas.
    const box = await page.locator('#qv-panel').boundingBox();
    assert.ok(box.width <= 1 && box.height <= 1, JSON.stringify(box));

    // It follows the content, not the frame: once the flight to the building has ended and what it
    // brought into view has loaded (the totals in view, the animated count), it stays unchanged;
    // an outline rewritten every frame would never hold still for 600 ms.
    let still = false;
    for (let attempt = 0; attempt < 30 && !still; ++attempt) {
      const revision = await page.evaluate(() => window.quakeview.uiOutline().revision);
      await page.waitForTimeout(600);
      still = (await page.evaluate(() => window.quakeview.uiOutline().revision)) - revision <= 1;
    }
    assert.ok(still, 'paused and still, the outline does not change every frame');
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});
