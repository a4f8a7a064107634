// The situation report in the browser: `quakeview.report()` is byte for byte the document
// `quakeview-prep report` writes for the same city (scripts/test.sh writes them beside the test
// cities), its headline is the panel's numbers, the panel's "Report (HTML)" downloads it, and
// printed by the browser (A4 and Letter) it is a few readable pages whose PNGs are kept in the
// artifacts for a person to look at. Runs in Chromium and in Firefox ESR.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { launchBrowser, openPage, openSection, panelItemInView, waitForFunction, waitReady } from './lib/browser.mjs';
import { ARTIFACTS, REPO, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const DEMO = process.env.QUAKEVIEW_DEMO_DATA || path.join(REPO, 'build/demo-data/default');
const CITIES = { actual: path.join(DATA, 'actual'), manhattan: path.join(DATA, 'manhattan'), demo: DEMO };
let server;

before(async () => {
  for (const [name, dir] of Object.entries(CITIES)) {
    assert.ok(fs.existsSync(path.join(dir, 'tileset.json')), `test city missing: ${dir} (scripts/test.sh prepares it)`);
    assert.ok(fs.existsSync(path.join(DATA, `${name}-report.html`)), `the tool's report of ${name} is missing`);
  }
  fs.mkdirSync(ARTIFACTS, { recursive: true });
  const mounts = {};
  for (const [name, dir] of Object.entries(CITIES)) mounts[`/${name}`] = dir;
  server = await serveSite(mounts);
});
after(() => server?.close());

// The expected-count text the report prints (one decimal under 10, whole numbers with commas above).
function countText(value) {
  if (Math.abs(value) < 0.05) return '0';
  if (Math.abs(value) < 10) return value.toFixed(1);
  return Math.round(value).toLocaleString('en-US');
}

// Prints `html` alone to PDF in `paper` format, keeps the PDF and its pages as PNGs (pdftoppm) in the
// artifacts, and returns {pages, text} (pdftotext).
async function printReport(context, html, name, paper) {
  const page = await context.newPage();
  try {
    await page.setContent(html);
    const pdf = Buffer.from(await page.pdf({ format: paper, printBackground: true }));
    const file = path.join(ARTIFACTS, `report-${name}-${paper}.pdf`);
    fs.writeFileSync(file, pdf);
    execFileSync('pdftoppm', ['-r', '60', '-png', file, path.join(ARTIFACTS, `report-${name}-${paper}`)]);
    const text = execFileSync('pdftotext', ['-layout', file, '-']).toString('utf8');
    const pages = (text.match(/\f/g) || []).length;
    return { pages, text };
  } finally {
    await page.close();
  }
}

test('report() is the tool\'s report, its headline the panel\'s, and "Report (HTML)" downloads it', async (t) => {
  const { context, close, browser } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/actual/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const html = await page.evaluate(() => window.quakeview.report());
    const tool = fs.readFileSync(path.join(DATA, 'actual-report.html'), 'utf8');
    assert.equal(html, tool, 'the viewer\'s report is the tool\'s, byte for byte');
    await waitForFunction(page, () => window.quakeview.consequences()?.city != null, null, { timeout: 30000 });
    const c = await page.evaluate(() => window.quakeview.consequences());
    assert.match(html, /class="banner actual">ACTUAL EVENT/);
    assert.ok(html.includes(`Buildings damaged (moderate or worse)</div><div class="v">${countText(c.city.moderateOrWorse.expected)}</div>`),
      `the headline is the panel's ${c.city.moderateOrWorse.expected}`);
    assert.ok(html.includes(`Deaths</div><div class="v">${countText(c.city.deaths.expected)}</div>`));
    for (const d of c.districts) assert.ok(html.includes(`<td class="l">${d.name}</td>`), `district ${d.name}`);
    for (const time of ['2 AM (night) &#9664; assumed above', '2 PM (day)', '5 PM (commute)']) assert.ok(html.includes(time), time);
    assert.doesNotMatch(html, /<script/i, 'hostile building names stay text');

    // The panel's button (beside "Save image (PNG)" at the end of the consequences section, scrolled
    // into the panel as a person would): the same document as a file named for the city and the event.
    if (browser === 'chromium') {
      await openSection(page, 'All consequences: city, view, districts');
      const button = await panelItemInView(page, 'Report (HTML)');
      const downloadPromise = page.waitForEvent('download', { timeout: 20000 });
      await page.mouse.click(button.x + button.width / 2, button.y + button.height / 2);
      const download = await downloadPromise;
      assert.match(download.suggestedFilename(), /^quakeview-actual-event-test-actual-qvtest2026-report\.html$/);
      assert.equal(fs.readFileSync(await download.path(), 'utf8'), html);
      t.diagnostic(`downloaded as ${download.suggestedFilename()}`);
    }
    t.diagnostic(`${browser}: report ${html.length} bytes`);
    assert.deepEqual(problems, []);
  } finally {
    await close();
  }
});

test('the Manhattan and demo reports equal the tool\'s and print to a few pages of A4 and Letter', async (t) => {
  const { context, close, browser } = await launchBrowser();
  try {
    for (const name of ['manhattan', 'demo']) {
      const { page, problems } = await openPage(context, `${server.url}/?data=/${name}/tileset.json`);
      assert.deepEqual(await waitReady(page), { ok: true });
      const html = await page.evaluate(() => window.quakeview.report());
      assert.equal(html, fs.readFileSync(path.join(DATA, `${name}-report.html`), 'utf8'), `${name}: the tool's report`);
      const c = await page.evaluate(() => window.quakeview.consequences());
      assert.deepEqual(problems, []);
      await page.close();
      if (browser !== 'chromium') continue;  // printing a document alone: Chromium's PDF (Firefox prints the page: images.test.mjs)
      for (const paper of ['A4', 'Letter']) {
        const { pages, text } = await printReport(context, html, name, paper);
        t.diagnostic(`${name} ${paper}: ${pages} pages`);
        assert.ok(pages >= 2 && pages <= 8, `${name} ${paper}: ${pages} pages`);
        assert.match(text, /Earthquake situation report/);
        assert.match(text, /SCENARIO/);
        assert.match(text, /The impact at a glance/);
        assert.match(text, /Casualties by time of day/);
        assert.match(text, /Essential facilities/);
        assert.match(text, /not a safety assessment/);
        assert.ok(text.includes(countText(c.city.moderateOrWorse.expected)), `${name}: the damaged count is printed`);
      }
    }
  } finally {
    await close();
  }
});
