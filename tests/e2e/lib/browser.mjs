// Launches Debian's Chromium headless with SwiftShader WebGL2 through playwright-core (never a
// downloaded browser), and collects what a page logs, so tests can assert there were no errors.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

export const CHROMIUM = process.env.QUAKEVIEW_CHROMIUM || '/usr/bin/chromium';

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

/// options.webgl === false launches with WebGL disabled (to test the fallback message).
/// options.viewport {width, height} (CSS px, default 1280 x 720) and options.deviceScaleFactor
/// (default 1) size the page; options.touch === true emulates a touch device (hasTouch and
/// isMobile: touch events, page.touchscreen, a mobile viewport).
export async function launchBrowser(options = {}) {
  if (!fs.existsSync(CHROMIUM)) {
    throw new Error(`Chromium not found at ${CHROMIUM}: run scripts/setup.sh (Debian package chromium)`);
  }
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-chromium-'));
  const args = [...BASE_FLAGS];
  if (options.webgl === false) args.push('--disable-webgl', '--disable-3d-apis');
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
  return { context, close };
}

/// Opens a page and records console errors, page errors and failed requests.
export async function openPage(context, url, { timeoutMs = 60000 } = {}) {
  const page = await context.newPage();
  const problems = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') problems.push(`console.error: ${msg.text()}`);
  });
  page.on('pageerror', (err) => problems.push(`page error: ${err.message}`));
  page.setDefaultTimeout(timeoutMs);
  await page.goto(url, { waitUntil: 'load' });
  return { page, problems };
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
