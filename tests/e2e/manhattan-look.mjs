import fs from 'node:fs';
import { launchBrowser, openPage, waitReady, settle, waitForFunction } from './lib/browser.mjs';
import { serveSite } from './lib/server.mjs';
const server = await serveSite({ '/nyc': '/work/main/build/bench-data/nyc' });
const { context, close, browser } = await launchBrowser();
try {
  const { page } = await openPage(context, `${server.url}/?data=/nyc/tileset.json`);
  console.log(await waitReady(page, 120000));
  await settle(page);
  await page.screenshot({ path: `/tmp/nyc-opening-${browser}.png` });
  console.log('opening', JSON.stringify((await page.evaluate(() => window.quakeview.stats())).buildings), await page.evaluate(() => window.quakeview.time()));
  await waitForFunction(page, () => window.quakeview.searchReady(), null, { timeout: 120000 });
  await page.evaluate(() => window.quakeview.setFilters({ minProbability: { state: 'slight', percent: 10 } }));
  const list = await page.evaluate(() => window.quakeview.filteredList(8));
  console.log('P(>= slight) >= 10 %:', list.total, 'buildings');
  for (const b of list.buildings) console.log(' ', b.label, '|', b.use, '|', (100 * b.probabilityAtLeast.slight).toFixed(1), '% slight+,', (100 * b.probabilityAtLeast.moderate).toFixed(1), '% moderate+ | state', b.damageState);
  await page.evaluate(() => window.quakeview.setFilters({ criticalOnly: true }));
  const crit = await page.evaluate(() => window.quakeview.filteredList(1000));
  console.log('critical:', crit.total);
  const hospital = crit.buildings.find((b) => b.use === 'hospital' && b.name) || crit.buildings[0];
  console.log('hospital:', hospital.label, hospital.x, hospital.y);
  await page.evaluate((h) => window.quakeview.setCamera({ x: h.x, y: h.y, distance: 2000, headingDeg: 20, pitchDeg: 55 }), hospital);
  await settle(page);
  await page.evaluate(() => window.quakeview.pause());
  await page.evaluate((id) => window.quakeview.select(id), hospital.id);
  await page.waitForTimeout(1500);
  await page.screenshot({ path: `/tmp/nyc-critical-${browser}.png` });
  console.log(JSON.stringify((await page.evaluate(() => window.quakeview.stats())).lastFrame));
} finally {
  await close();
  await server.close();
}
