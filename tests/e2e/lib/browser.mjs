// Launches the browser the end-to-end tests run in, never a downloaded one, and collects what a page
// logs, so tests can assert there were no errors. QUAKEVIEW_BROWSER chooses the engine:
// - "chromium" (default): Debian's Chromium, WebGL2 on SwiftShader, driven by playwright-core;
// - "firefox": Debian's Firefox ESR, WebGL2 on Mesa's llvmpipe, driven by puppeteer-core over
//   WebDriver BiDi (playwright-core drives only its own patched Firefox, a download).
// Tests are written against the subset of Playwright's Page API below; for Firefox the puppeteer
// page is wrapped so the same test file runs unchanged in either engine:
//   page.evaluate(fn, arg), page.waitForTimeout(ms),
//   page.screenshot({path}) -> Buffer, page.mouse.{move(x, y, {steps}), down(), up(), click(x, y),
//   wheel(dx, dy)}, page.keyboard.{press, down, up, type}, page.focus(selector),
//   page.locator(selector).{innerText(), isVisible()}, page.waitForEvent('download', {timeout}) ->
//   {suggestedFilename(), path()}, page.on('console' | 'pageerror'), page.setDefaultTimeout(ms),
//   page.goto(url, {waitUntil: 'load'}), page.close(), page.touchscreen.tap(x, y) (with
//   options.touch), page.pdf({format}) -> Buffer, page.emulateMedia({media}); context.newPage().
// One-finger swipes, which Playwright's API lacks, go through swipe(page, from, to) below in
// either engine. Waiting for a condition in the page goes through waitForFunction(page, fn, arg,
// options) below in either engine, never the drivers' own waitForFunction: both inject the
// predicate in ways a strict Content-Security-Policy can block (Firefox ESR 140 refuses
// puppeteer's `Function()` under the page's `script-src 'self' 'wasm-unsafe-eval'`).
//
// Touch emulation (launchBrowser({viewport, deviceScaleFactor, touch: true})):
// - Chromium: Playwright's viewport, deviceScaleFactor, hasTouch and isMobile; swipes are the
//   DevTools protocol's Input.dispatchTouchEvent.
// - Firefox: puppeteer's page.setViewport({width, height, deviceScaleFactor, isMobile, hasTouch})
//   as the default viewport. Over WebDriver BiDi it becomes browsingContext.setViewport with
//   devicePixelRatio, which Firefox ESR honours (window.devicePixelRatio, the canvas and the
//   screenshots are at that ratio: no `layout.css.devPixelsPerPx` needed); isMobile has no BiDi
//   equivalent and is ignored (Firefox has no mobile viewport mode, and the page sizes itself to
//   the viewport anyway); hasTouch asks for emulation.setTouchOverride, which Firefox ESR 153
//   does not implement (puppeteer tolerates that), so the preferences
//   dom.w3c_touch_events.enabled = 1 (the TouchEvent API) and dom.maxtouchpoints.testing.value = 1
//   (navigator.maxTouchPoints) make the page see a touch screen (the media query
//   `(pointer: coarse)` still does not match in headless Firefox; the viewer does not use it).
//   Taps and swipes are BiDi input.performActions with pointerType "touch", which Firefox
//   delivers as touch events (and pointer events), as a touch screen would.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

export const CHROMIUM = process.env.QUAKEVIEW_CHROMIUM || '/usr/bin/chromium';
export const FIREFOX = process.env.QUAKEVIEW_FIREFOX || '/usr/bin/firefox-esr';
/// The engine the tests run in: 'chromium' or 'firefox'.
export const BROWSER = (process.env.QUAKEVIEW_BROWSER || 'chromium').toLowerCase();
if (!['chromium', 'firefox'].includes(BROWSER)) {
  throw new Error(`QUAKEVIEW_BROWSER=${process.env.QUAKEVIEW_BROWSER}: expected chromium or firefox`);
}

const BASE_FLAGS = [
  '--no-sandbox',
  '--disable-gpu',
  '--enable-unsafe-swiftshader',
  '--use-angle=swiftshader',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
  '--disable-quic',
  '--disable-default-apps',
  '--disable-extensions',
];

/// options.webgl === false launches without WebGL2, as on an office machine without a GPU: Chromium
/// without its software renderer, Firefox with its default preferences (its WebGL needs a GPU or
/// webgl.force-enabled).
/// options.viewport {width, height} (CSS px, default 1280 x 720) and options.deviceScaleFactor
/// (default 1) size the page; options.touch === true emulates a touch device (hasTouch and
/// isMobile: touch events, page.touchscreen, swipe(); in Firefox without a mobile viewport, see
/// the top of this file).
/// Resolves to {context, close, browser} where browser is 'chromium' or 'firefox'.
export async function launchBrowser(options = {}) {
  return BROWSER === 'firefox' ? launchFirefox(options) : launchChromium(options);
}

async function launchChromium(options) {
  if (!fs.existsSync(CHROMIUM)) {
    throw new Error(`Chromium not found at ${CHROMIUM}: run scripts/setup.sh (Debian package chromium)`);
  }
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-chromium-'));
  // Without WebGL: a machine with no GPU where Chromium's software fallback is gone (no SwiftShader
  // flags, software rasterizer off), as the page meets it on a virtual desktop.
  const args = options.webgl === false
    ? [...BASE_FLAGS.filter((f) => !/swiftshader/.test(f)), '--disable-software-rasterizer']
    : [...BASE_FLAGS];
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args,
    viewport: options.viewport || { width: 1280, height: 720 },
    deviceScaleFactor: options.deviceScaleFactor || 1,
    hasTouch: options.touch === true,
    isMobile: options.touch === true,
  });
  const close = async () => {
    await context.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  };
  return { context, close, browser: 'chromium' };
}

// Headless Firefox has WebGL2 only on llvmpipe through EGL, and only with WebGL force-enabled
// (../shared/TOOLCHAIN.md; needs Debian's libgl1-mesa-dri, libegl1 and libegl-mesa0). Downloads go
// without a dialog into a folder of the test run, which waitForEvent('download') watches.
async function launchFirefox(options) {
  if (!fs.existsSync(FIREFOX)) {
    throw new Error(`Firefox not found at ${FIREFOX}: run scripts/setup.sh (Debian package firefox-esr)`);
  }
  const { default: puppeteer } = await import('puppeteer-core');
  const downloads = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-firefox-downloads-'));
  const prefs = {
    'browser.download.dir': downloads,
    'browser.download.folderList': 2,
    'browser.download.useDownloadDir': true,
    'browser.download.always_ask_before_handling_new_types': false,
    'browser.download.start_downloads_in_tmp_dir': false,
    'browser.download.alwaysOpenPanel': false,
    'browser.download.panel.shown': true,
    'browser.helperApps.neverAsk.saveToDisk': 'text/csv,application/geo+json,application/json,text/plain,application/octet-stream',
  };
  if (options.webgl !== false) prefs['webgl.force-enabled'] = true;
  const touch = options.touch === true;
  if (touch) {
    // BiDi's emulation.setTouchOverride is not in Firefox ESR 153: these give the page a touch screen.
    prefs['dom.w3c_touch_events.enabled'] = 1;
    prefs['dom.maxtouchpoints.testing.value'] = 1;
  }
  const viewport = options.viewport || { width: 1280, height: 720 };
  const browser = await puppeteer.launch({
    browser: 'firefox',
    executablePath: FIREFOX,
    headless: true,
    defaultViewport: {
      width: viewport.width,
      height: viewport.height,
      deviceScaleFactor: options.deviceScaleFactor || 1,
      isMobile: touch,
      hasTouch: touch,
    },
    extraPrefsFirefox: prefs,
    env: { ...process.env, MOZ_WEBGL_FORCE_EGL: '1' },
    // Firefox says "RenderCompositorSWGL failed mapping default framebuffer" on stderr, harmlessly.
    dumpio: false,
  });
  const context = {
    newPage: async () => wrapPuppeteerPage(await browser.newPage(), downloads),
  };
  const close = async () => {
    await browser.close();
    fs.rmSync(downloads, { recursive: true, force: true });
  };
  return { context, close, browser: 'firefox' };
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// A puppeteer Page seen through Playwright's API (the subset listed at the top of this file).
function wrapPuppeteerPage(page, downloads) {
  let defaultTimeout = 30000;
  // Chromium (over CDP) acknowledges an input event only once the page has handled it, and the
  // engine handles input in its next animation frame; WebDriver BiDi returns as soon as the event
  // is dispatched. Waiting two animation frames after each action gives Firefox the same order:
  // what a test reads after an action sees its effect.
  const settled = async (result) => {
    await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
    return result;
  };
  const mouse = {
    move: async (x, y, opts) => settled(await page.mouse.move(x, y, opts)),
    down: async (opts) => settled(await page.mouse.down(opts)),
    up: async (opts) => settled(await page.mouse.up(opts)),
    click: async (x, y, opts) => settled(await page.mouse.click(x, y, opts)),
    // Playwright: wheel(deltaX, deltaY); puppeteer: wheel({deltaX, deltaY}). WebDriver BiDi takes
    // whole pixels only (Firefox refuses 840.5 as "invalid argument").
    wheel: async (deltaX, deltaY) =>
      settled(await page.mouse.wheel({ deltaX: Math.round(deltaX), deltaY: Math.round(deltaY) })),
  };
  // Playwright's key names are the DOM `code`/`key` names; puppeteer's US layout knows the space
  // bar only as ' '.
  const keyName = (key) => (key === 'Space' ? ' ' : key);
  const keyboard = {
    press: async (key, opts) => settled(await page.keyboard.press(keyName(key), opts)),
    down: async (key, opts) => settled(await page.keyboard.down(keyName(key), opts)),
    up: async (key) => settled(await page.keyboard.up(keyName(key))),
    type: async (text, opts) => settled(await page.keyboard.type(text, opts)),
  };
  // Playwright: touchscreen.tap(x, y); puppeteer's is the same, a BiDi touch press and release.
  const touchscreen = {
    tap: async (x, y) => settled(await page.touchscreen.tap(x, y)),
  };
  const wrapped = {
    raw: page,
    mouse,
    keyboard,
    touchscreen,
    // One finger down at `from`, through `points`, up: see swipe() below.
    swipe: async (from, points, stepMs) => {
      const finger = await page.touchscreen.touchStart(from.x, from.y);
      for (const p of points) {
        await finger.move(p.x, p.y);
        await sleep(stepMs);
      }
      await finger.end();
      return settled();
    },
    evaluate: (fn, arg) => (arg === undefined ? page.evaluate(fn) : page.evaluate(fn, arg)),
    // Kept for code written against Playwright's API: the CSP-proof poller below.
    waitForFunction: (fn, arg, options = {}) => waitForFunction(wrapped, fn, arg, { timeout: defaultTimeout, ...options }),
    waitForTimeout: (ms) => sleep(ms),
    screenshot: async (options = {}) => Buffer.from(await page.screenshot(options)),
    // Printing: browsingContext.print over BiDi; the print media type through puppeteer.
    pdf: async (options = {}) => Buffer.from(await page.pdf(options)),
    emulateMedia: async ({ media }) => page.emulateMediaType(media),
    focus: (selector) => page.focus(selector),
    goto: (url, options = {}) => page.goto(url, { timeout: defaultTimeout, waitUntil: options.waitUntil || 'load' }),
    close: () => page.close(),
    url: () => page.url(),
    setDefaultTimeout: (ms) => {
      defaultTimeout = ms;
      page.setDefaultTimeout(ms);
    },
    on: (event, handler) => {
      page.on(event, handler);
      return wrapped;
    },
    locator: (selector) => ({
      innerText: () => page.$eval(selector, (e) => e.innerText),
      isVisible: () => page.$eval(selector, (e) => {
        const style = window.getComputedStyle(e);
        const box = e.getBoundingClientRect();
        return style.display !== 'none' && style.visibility !== 'hidden' && box.width > 0 && box.height > 0;
      }),
    }),
    // Resolves when a new file has fully arrived in the download folder (Firefox writes NAME.part
    // first, then renames it).
    waitForEvent: async (event, options = {}) => {
      if (event !== 'download') throw new Error(`waitForEvent('${event}') is not adapted for Firefox`);
      const before = new Set(fs.readdirSync(downloads));
      const deadline = Date.now() + (options.timeout ?? defaultTimeout);
      while (Date.now() < deadline) {
        const fresh = fs.readdirSync(downloads).filter((f) => !before.has(f) && !f.endsWith('.part'));
        const partial = fs.readdirSync(downloads).some((f) => f.endsWith('.part'));
        if (fresh.length > 0 && !partial) {
          const file = path.join(downloads, fresh[0]);
          return { suggestedFilename: () => fresh[0], path: async () => file };
        }
        await sleep(100);
      }
      throw new Error(`no download arrived in ${downloads} within ${options.timeout ?? defaultTimeout} ms`);
    },
  };
  return wrapped;
}

/// Resolves to fn(arg)'s value once it is truthy, evaluating fn in the page every
/// `options.polling` ms (a number; default 50) until `options.timeout` ms (default 30000) have
/// passed, then rejects naming the condition. Each poll is one page.evaluate from the test side:
/// nothing is compiled from a string in the page, so it works under the viewer's strict
/// Content-Security-Policy in every engine and version (Playwright's and puppeteer's own
/// waitForFunction inject the predicate in the page; puppeteer's `Function()` is blocked by
/// `script-src 'self' 'wasm-unsafe-eval'` in Firefox ESR 140). An error thrown by fn rejects.
export async function waitForFunction(page, fn, arg, options = {}) {
  const timeout = options.timeout ?? 30000;
  const interval = typeof options.polling === 'number' ? options.polling : 50;
  const deadline = Date.now() + timeout;
  for (;;) {
    const value = await (arg === undefined || arg === null ? page.evaluate(fn) : page.evaluate(fn, arg));
    if (value) return value;
    if (Date.now() >= deadline) {
      const what = String(fn).replace(/\s+/g, ' ').slice(0, 240);
      throw new Error(`waitForFunction: not true after ${timeout} ms: ${what}`);
    }
    await sleep(Math.min(interval, Math.max(0, deadline - Date.now())));
  }
}

const cdpSessions = new WeakMap();

/// A one-finger swipe on a page of a touch context (launchBrowser({touch: true})): the finger goes
/// down at `from` {x, y} (CSS px), moves in `steps` equal steps `stepMs` apart to `to`, and comes
/// up there. Chromium: the DevTools protocol's Input.dispatchTouchEvent (Playwright's touchscreen
/// only taps); Firefox: puppeteer's touchscreen.touchStart, then move and end (WebDriver BiDi
/// touch actions). Resolves once the page has received the finger's release.
export async function swipe(page, from, to, { steps = 8, stepMs = 30 } = {}) {
  const points = [];
  for (let i = 1; i <= steps; ++i) {
    points.push({ x: from.x + (to.x - from.x) * i / steps, y: from.y + (to.y - from.y) * i / steps });
  }
  if (typeof page.swipe === 'function') return page.swipe(from, points, stepMs);  // Firefox
  if (!cdpSessions.has(page)) cdpSessions.set(page, await page.context().newCDPSession(page));
  const cdp = cdpSessions.get(page);
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [{ x: from.x, y: from.y }] });
  for (const p of points) {
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [{ x: p.x, y: p.y }] });
    await page.waitForTimeout(stepMs);
  }
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
}

/// Opens a page and records console errors, page errors and failed requests.
export async function openPage(context, url, { timeoutMs = 60000 } = {}) {
  const page = await context.newPage();
  const problems = [];
  page.on('console', (msg) => {
    if (msg.type() !== 'error') return;
    // A city without a scenario catalogue answers its scenarios.json with HTTP 404, which is how
    // the viewer learns it has none, and a scenario not run yet has no scenario-N.json
    // (docs/formats.md); the browser still logs the failed request.
    const from = typeof msg.location === 'function' ? msg.location()?.url || '' : '';
    if (/\/(scenarios|scenario-[0-9]+)\.json$/.test(from) && /Failed to load resource.*404/.test(msg.text())) return;
    problems.push(`console.error: ${msg.text()}`);
  });
  page.on('pageerror', (err) => problems.push(`page error: ${err.message}`));
  page.setDefaultTimeout(timeoutMs);
  // Either engine: the driver's own waitForFunction injects code the page's CSP may block.
  page.waitForFunction = (fn, arg, options = {}) => waitForFunction(page, fn, arg, { timeout: timeoutMs, ...options });
  await page.goto(url, { waitUntil: 'load' });
  return { page, problems };
}

/// Waits until the view has nothing left to load (no tile pending) for four polls in a row, 250 ms
/// apart: after a camera move or a flight, what it brought into view is there.
export async function settle(page) {
  await page.evaluate(() => { window.__calm = 0; });
  await waitForFunction(page, () => {
    const s = window.quakeview.stats();
    window.__calm = s && s.tiles.pending === 0 ? (window.__calm || 0) + 1 : 0;
    return window.__calm >= 4;
  }, null, { timeout: 60000, polling: 250 });
}

/// Opens the control panel's section `label` ("Performance", "Damage and colours", ...) with a
/// click on its header, as a person would (the panel opens compact: most sections are folded), and
/// waits until the panel shows it open. Does nothing when it is open already.
export async function openSection(page, label) {
  const escaped = label.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
  const isOpen = (l) => new RegExp(`^v ${l}$`, 'm').test(window.quakeview.uiText());
  // The panel's content may still be moving (results arriving): a click that missed is tried again
  // where the header is then.
  for (let attempt = 0; ; ++attempt) {
    if (await page.evaluate(isOpen, escaped)) return;
    const layout = await page.evaluate(() => window.quakeview.uiLayout());
    const header = layout.items.find((i) => i.window === 'QuakeView' && i.label === label);
    if (!header) throw new Error(`no section header "${label}" in the panel`);
    // Scrolled out of the panel (its content taller than the window, e.g. while messages show):
    // the wheel over the panel brings it in, as a person would scroll.
    const panel = layout.windows.find((w) => w.title === 'QuakeView');
    const centreY = header.y + header.height / 2;
    if (panel && (centreY < panel.y + 20 || centreY > panel.y + panel.height - 10)) {
      if (attempt >= 6) throw new Error(`the section header "${label}" stays outside the panel (at y ${Math.round(centreY)})`);
      await page.mouse.move(panel.x + panel.width / 2, panel.y + panel.height / 2);
      await page.mouse.wheel(0, centreY - (panel.y + panel.height / 2));
      await page.waitForTimeout(300);
      continue;
    }
    await page.mouse.click(header.x + 40, centreY);
    try {
      await waitForFunction(page, isOpen, escaped, { timeout: 3000, polling: 100 });
      return;
    } catch (e) {
      if (attempt >= 8) throw new Error(`the section "${label}" did not open after ${attempt + 1} attempts: ${e.message}`);
    }
  }
}

/// The panel's control labelled `label` (uiLayout's item), scrolled into the panel first with the
/// wheel as a person would; throws when the panel has no such control.
export async function panelItemInView(page, label) {
  let item = null;
  for (let attempt = 0; attempt < 8; ++attempt) {
    const layout = await page.evaluate(() => window.quakeview.uiLayout());
    item = layout.items.find((i) => i.window === 'QuakeView' && i.label === label);
    const panel = layout.windows.find((w) => w.title === 'QuakeView');
    if (!item || !panel) throw new Error(`the panel has no "${label}"`);
    const centreY = item.y + item.height / 2;
    if (centreY > panel.y + 20 && centreY < panel.y + panel.height - 10) break;
    await page.mouse.move(panel.x + panel.width / 2, panel.y + panel.height / 2);
    await page.mouse.wheel(0, centreY - (panel.y + panel.height / 2));
    await page.waitForTimeout(300);
  }
  return item;
}

/// Waits for quakeview.ready; resolves to {ok: true} or {ok: false, message}.
export async function waitReady(page, timeoutMs = 90000) {
  return page.evaluate(async (ms) => {
    const timeout = new Promise((_, reject) => setTimeout(() => reject(new Error(`quakeview.ready not settled after ${ms} ms`)), ms));
    try {
      await Promise.race([window.quakeview.ready, timeout]);
      return { ok: true };
    } catch (e) {
      return { ok: false, message: String(e && e.message) };
    }
  }, timeoutMs);
}
