// The Midtown test city (../shared/data/osm/fixture-midtown-empire-state.osm, prepared by
// scripts/test.sh into $QUAKEVIEW_E2E_DATA/midtown) served with the site for one test file.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before } from 'node:test';
import { ARTIFACTS, REPO, serveSite } from './server.mjs';

export const DATA = process.env.QUAKEVIEW_E2E_DATA || path.join(REPO, 'build/e2e-data');
export const MIDTOWN = path.join(DATA, 'midtown');
export const ESB = 'w34633854';  // the Empire State Building
export const URL_PATH = '/?data=/data/midtown/tileset.json';

/// Registers the test file's before and after hooks. Once `before` has run, the returned object's
/// `server` serves the site with the test cities under /data, and `esb` is what
/// `quakeview-prep info --building w34633854 --json` says of the Empire State Building.
export function serveMidtown() {
  const midtown = { server: null, esb: null };
  before(async () => {
    assert.ok(fs.existsSync(path.join(MIDTOWN, 'tileset.json')), `test city missing: ${MIDTOWN} (scripts/test.sh prepares it)`);
    midtown.esb = JSON.parse(fs.readFileSync(path.join(DATA, 'midtown-esb.json'), 'utf8'));
    midtown.server = await serveSite({ '/data': DATA });
    fs.mkdirSync(ARTIFACTS, { recursive: true });
  });
  after(async () => {
    if (midtown.server) await midtown.server.close();
  });
  return midtown;
}
