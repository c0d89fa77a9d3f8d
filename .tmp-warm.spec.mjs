import { test } from '@playwright/test';
import { openDesigner } from './tests/e2e/helpers.mjs';
for (const w of [-1, 2, 3, 4]) test('warm ' + w, async ({ page }) => {
  const t0 = Date.now();
  await page.goto('/?warmup=' + w);
  await page.waitForFunction(() => window.tvf && window.tvf.ready); await page.evaluate(() => window.tvf.ready);
  const t1 = Date.now();
  const s = await page.evaluate(() => window.tvf.stats());
  const r = [];
  for (let i = 0; i < 3; i++) { await page.evaluate(() => window.tvf.addStroke([{face: 0, bary:[0.3,0.3,0.4]},{face: 1, bary:[0.3,0.3,0.4]}])); const t = await page.evaluate(() => window.tvf.stats()); r.push([t.updateMs, t.solveMs]); }
  await page.evaluate(() => window.tvf.setGamma(0)); const f = await page.evaluate(() => window.tvf.stats());
  console.log(w, 'ready', t1 - t0, 'warm', JSON.stringify(await page.evaluate(() => window.__tvfWarm)), 'first factor', s.factorMs.toFixed(1), 'solve', s.solveMs.toFixed(1), 'strokes', JSON.stringify(r), 'refactor', f.factorMs.toFixed(1), f.solveMs.toFixed(1));
});
