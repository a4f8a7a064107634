// Trust: what a link or a data file can make the viewer show and do. A link naming a city on
// another origin is refused unless the site's config.json allows that origin (and nothing is
// requested from it); the page runs under the Content-Security-Policy that serve.mjs sends; names
// from OpenStreetMap cannot run formulas in a spreadsheet or reorder the text on screen.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';
import { parse as parseCsv } from 'csv-parse/sync';
import { contentSecurityPolicy, handleStatic } from '../../web/serve.mjs';
import { launchBrowser, openPage, waitForFunction, waitReady } from './lib/browser.mjs';
import { REPO, SITE, serveSite } from './lib/server.mjs';

const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
const SYNTH = path.join(DATA, 'synth');
const HOSTILE = path.join(DATA, 'hostile');
const HOSTILE_SOURCE = path.join(REPO, 'tests/e2e/data/hostile-names.geojson');

// A second origin (another port of 127.0.0.1) serving the synthetic city at /city, with CORS open
// as a data host would have it; it counts every request it gets.
async function serveOtherOrigin() {
  const empty = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-other-'));
  const requests = [];
  const server = http.createServer((req, res) => {
    requests.push(req.url);
    handleStatic(req, res, empty, { '/city': SYNTH });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const origin = `http://127.0.0.1:${server.address().port}`;
  return {
    origin,
    requests,
    close: () => new Promise((resolve) => {
      server.close(resolve);
      fs.rmSync(empty, { recursive: true, force: true });
    }),
  };
}

// A copy of the built site with its own config.json, as a deployment that allows other origins.
function siteWithConfig(config) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'quakeview-site-'));
  fs.cpSync(SITE, dir, { recursive: true });
  fs.writeFileSync(path.join(dir, 'config.json'), JSON.stringify(config));
  return dir;
}

// Records every Content-Security-Policy violation the page reports, from its first script on.
async function watchCsp(context) {
  await context.addInitScript(() => {
    window.__cspViolations = [];
    document.addEventListener('securitypolicyviolation', (e) => {
      window.__cspViolations.push(`${e.violatedDirective} blocked ${e.blockedURI || '(inline)'} at ${e.sourceFile}:${e.lineNumber}`);
    });
  });
}

before(() => {
  for (const dir of [SYNTH, HOSTILE]) {
    assert.ok(fs.existsSync(path.join(dir, 'tileset.json')), `test city missing: ${dir} (scripts/test.sh prepares it)`);
  }
});

test('a link to a city on another origin is refused with a message naming it, and nothing is requested from it', async () => {
  const server = await serveSite({});
  const other = await serveOtherOrigin();
  const { context, close } = await launchBrowser();
  try {
    const requested = [];
    context.on('request', (r) => requested.push(r.url()));
    const { page, problems } = await openPage(context,
      `${server.url}/?data=${encodeURIComponent(`${other.origin}/city/tileset.json`)}`);
    // The page settles and stays usable, with the reason on screen.
    assert.deepEqual(await waitReady(page, 30000), { ok: true });
    const errors = await page.evaluate(() => window.quakeview.errors());
    const refusal = errors.find((e) => e.includes(`a city from ${other.origin}, which this site does not allow`));
    assert.ok(refusal, JSON.stringify(errors));
    assert.match(refusal, /nothing was loaded from it/);
    assert.match(refusal, new RegExp(`\\{"dataOrigins": \\["${other.origin}"\\]\\}`));  // how to allow it
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.match(text, /== Errors ==/);
    assert.ok(text.includes(`a city from ${other.origin}`));
    await page.evaluate(() => window.quakeview.play());
    await page.waitForTimeout(500);
    // Not one request reached the other origin: neither in the browser's network events nor at its server.
    assert.deepEqual(requested.filter((u) => u.startsWith(other.origin)), []);
    assert.deepEqual(other.requests, []);
    assert.ok(requested.some((u) => u === `${server.url}/config.json`), 'the page read its configuration');
    assert.deepEqual(problems.filter((p) => !/Failed to load resource.*404/.test(p)), []);
  } finally {
    await close();
    await server.close();
    await other.close();
  }
});

test('an origin allowed in config.json loads, and the panel says where the city came from', async () => {
  const other = await serveOtherOrigin();
  const site = siteWithConfig({ dataOrigins: [other.origin, `${other.origin}/not-an-origin/`] });
  const { startServer } = await import('../../web/serve.mjs');
  const server = await startServer({ root: site, port: 0, host: '127.0.0.1' });
  const url = `http://127.0.0.1:${server.address().port}`;
  const { context, close } = await launchBrowser();
  try {
    await watchCsp(context);
    const { page, problems } = await openPage(context, `${url}/?data=${encodeURIComponent(`${other.origin}/city/tileset.json`)}`);
    assert.deepEqual(await waitReady(page), { ok: true });
    const manifest = JSON.parse(fs.readFileSync(path.join(SYNTH, 'tileset.json'), 'utf8'));
    const stats = await page.evaluate(() => window.quakeview.stats());
    assert.equal(stats.buildings.loaded, manifest.buildings);
    assert.ok(other.requests.includes('/city/tileset.json'));
    const text = await page.evaluate(() => window.quakeview.uiText());
    assert.ok(text.includes(`Data: "${manifest.name}" from ${other.origin} (allowed by this site's config.json)`), text);
    assert.match(text, /Shaking: SCENARIO/);
    // The bad entry of the configuration is reported, and is the only message.
    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.equal(errors.length, 1, JSON.stringify(errors));
    assert.match(errors[0], /config\.json: "dataOrigins" entry ".*not-an-origin\/" is not an origin/);
    // The server's policy lets the page read the allowed origin, and nothing else was blocked.
    assert.deepEqual(await page.evaluate(() => window.__cspViolations), []);
    assert.deepEqual(problems, []);
  } finally {
    await close();
    await new Promise((resolve) => server.close(resolve));
    await other.close();
    fs.rmSync(site, { recursive: true, force: true });
  }
});

test('an allowed origin whose server does not let the page read its files (no CORS) says so', async () => {
  const bare = http.createServer((req, res) => {
    res.writeHead(200, { 'Content-Type': 'application/json' });
    res.end('{"format":"quakeview-tileset"}');
  });
  await new Promise((resolve) => bare.listen(0, '127.0.0.1', resolve));
  const origin = `http://127.0.0.1:${bare.address().port}`;
  const site = siteWithConfig({ dataOrigins: [origin] });
  const { startServer } = await import('../../web/serve.mjs');
  const server = await startServer({ root: site, port: 0, host: '127.0.0.1' });
  const { context, close } = await launchBrowser();
  try {
    const { page } = await openPage(context,
      `http://127.0.0.1:${server.address().port}/?data=${encodeURIComponent(`${origin}/tileset.json`)}`);
    assert.deepEqual(await waitReady(page, 30000), { ok: true });
    const errors = await page.evaluate(() => window.quakeview.errors());
    assert.ok(errors.some((e) => /Access-Control-Allow-Origin/.test(e)), JSON.stringify(errors));
  } finally {
    await close();
    await new Promise((resolve) => server.close(resolve));
    bare.close();
    fs.rmSync(site, { recursive: true, force: true });
  }
});

test('the page runs under the site\'s Content-Security-Policy, with nosniff and the right MIME types', async () => {
  const server = await serveSite({ '/data': DATA });
  const { context, close } = await launchBrowser();
  try {
    await watchCsp(context);
    const responses = new Map();
    context.on('response', (r) => responses.set(new URL(r.url()).pathname, r));
    const { page, problems } = await openPage(context, `${server.url}/?data=/data/synth/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    // Exactly the documented policy, on the page itself.
    const document = await responses.get('/').allHeaders();
    assert.equal(document['content-security-policy'], contentSecurityPolicy([]));
    assert.match(document['content-security-policy'], /script-src 'self' 'wasm-unsafe-eval'(;|$)/);
    assert.doesNotMatch(document['content-security-policy'], /unsafe-inline|'unsafe-eval'/);
    assert.equal(document['x-content-type-options'], 'nosniff');
    // Use the page as a person would: play, select, search, filter, export (a download).
    await page.evaluate(() => window.quakeview.play());
    await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 60000 });
    const id = (await page.evaluate(() => window.quakeview.search('s', 1)))[0].id;
    assert.ok(await page.evaluate((i) => window.quakeview.select(i), id));
    await page.evaluate(() => window.quakeview.setFilters({ minDamage: 'slight' }));
    const download = page.waitForEvent('download');
    const csv = await page.evaluate(() => window.quakeview.exportList('csv'));
    assert.match(csv, /^# QuakeView building list [^\r\n,]*\r\nid,name,address/);
    await download;
    await page.mouse.click(800, 400);
    await page.waitForTimeout(1000);
    assert.deepEqual(await page.evaluate(() => window.__cspViolations), []);
    assert.deepEqual(problems, []);
    // Every file of the site and the city came with its type and nosniff.
    const expected = {
      '.html': /^text\/html/, '.js': /^text\/javascript/, '.css': /^text\/css/, '.wasm': /^application\/wasm$/,
      '.json': /^application\/json$/, '.qvt': /^application\/octet-stream$/, '.qvs': /^application\/octet-stream$/,
      '.qvh': /^application\/octet-stream$/, '.qvi': /^application\/octet-stream$/,
    };
    const seen = new Set();
    for (const [pathname, response] of responses) {
      if (response.status() !== 200) continue;
      const ext = pathname === '/' ? '.html' : path.extname(pathname);
      const headers = await response.allHeaders();
      assert.equal(headers['x-content-type-options'], 'nosniff', pathname);
      if (expected[ext]) {
        assert.match(headers['content-type'], expected[ext], pathname);
        seen.add(ext);
      }
    }
    assert.deepEqual([...seen].sort(), Object.keys(expected).sort());
  } finally {
    await close();
    await server.close();
  }
});

test('exports of hostile names are safe in a spreadsheet, parse with standard CSV and JSON parsers, and the screen shows them cleaned', async () => {
  const source = JSON.parse(fs.readFileSync(HOSTILE_SOURCE, 'utf8'));
  const names = new Map(source.features.map((f) => [`g:${f.properties.id}`, f.properties.name]));
  const server = await serveSite({ '/data': DATA });
  const { context, close } = await launchBrowser();
  try {
    const { page, problems } = await openPage(context, `${server.url}/?data=/data/hostile/tileset.json`);
    assert.deepEqual(await waitReady(page), { ok: true });
    await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 60000 });

    const csv = await page.evaluate(() => window.quakeview.exportList('csv'));
    // The first line is the export's provenance comment (docs/formats.md "Exports"); a name may hold '#'.
    assert.ok(csv.startsWith('# QuakeView building list'), csv.slice(0, 100));
    const rows = parseCsv(csv.slice(csv.indexOf('\r\n') + 2), { columns: true, relax_quotes: false });
    assert.equal(rows.length, names.size);
    const formula = /^[=+\-@\t\r]/;
    let neutralised = 0;
    for (const row of rows) {
      const original = names.get(row.id);
      assert.ok(original !== undefined, `unknown id ${row.id}`);
      // Text columns never start a formula; numeric ones are numbers (a minus sign included).
      for (const column of ['id', 'name', 'address', 'use', 'importance', 'damage_state']) {
        assert.doesNotMatch(row[column], formula, `${row.id} ${column} would run as a formula: ${JSON.stringify(row[column])}`);
      }
      if (formula.test(original)) {
        assert.equal(row.name, `'${original}`, row.id);
        neutralised += 1;
      } else {
        assert.equal(row.name, original, row.id);
      }
      assert.match(row.lon, /^-7[34]\.\d+$/, `${row.id} lon ${row.lon}`);
      assert.match(row.x_m, /^-?\d+\.\d+$/, `${row.id} x ${row.x_m}`);
      assert.ok(Number.isFinite(Number(row.peak_drift_ratio)), `${row.id} drift ${row.peak_drift_ratio}`);
    }
    assert.equal(neutralised, 6, 'the fixture plants six formula triggers (=, +, -, @, tab, CR)');

    const geojson = JSON.parse(await page.evaluate(() => window.quakeview.exportList('geojson')));
    assert.equal(geojson.features.length, names.size);
    for (const f of geojson.features) assert.equal(f.properties.name, names.get(f.properties.id), f.properties.id);

    // On screen the bidirectional override is gone (it would show "exe.fdp" reversed and turn the
    // rest of the line around) and the line break of a name is a space.
    const bidi = /[\u202A-\u202E\u2066-\u2069\u200E\u200F\u061C]/;
    const controls = /[\u0000-\u0009\u000B-\u001F\u007F-\u009F]/;
    assert.ok(await page.evaluate(() => window.quakeview.select('g:h9')));
    await page.waitForTimeout(500);
    let text = await page.evaluate(() => window.quakeview.uiText());
    assert.ok(text.includes('Clinic exe.fdp annex'), text);
    assert.doesNotMatch(text, bidi);
    assert.doesNotMatch(text, controls);
    assert.ok(await page.evaluate(() => window.quakeview.select('g:h8')));
    await page.waitForTimeout(500);
    text = await page.evaluate(() => window.quakeview.uiText());
    assert.ok(text.includes('Two lines'), text);
    assert.doesNotMatch(text, bidi);
    assert.doesNotMatch(text, controls);
    assert.deepEqual(problems, []);
  } finally {
    await close();
    await server.close();
  }
});
