#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// The README's picture of the app (docs/images/app.png): the page as it opens, with a curved stroke and a vortex
// on the default model, arrows, streamlines and singularities shown; taken in Debian's Chromium with software
// WebGL from the page served from dist/ (build it first: npm run build:wasm && npm run build:web). A picture
// maker, not a test.
//
// Usage: node scripts/app-picture.mjs [--out FILE] [--port P]
import { writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { openDesigner } from '../tests/e2e/helpers.mjs';
import { argument, requireBuiltPage, withServedPage } from './page-session.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const out = resolve(argument('--out', join(ROOT, 'docs/images/app.png')));
const port = Number(argument('--port', process.env.PORT || 8198));

requireBuiltPage('app-picture');

// Surface points under screen points given as fractions of the view's width and height.
function pickAll(page, fractions) {
  return page.evaluate((list) => {
    const rect = window.tvf.shadowRoot.querySelector('#view').getBoundingClientRect();
    const hits = list.map(([x, y]) => window.tvf.pick(rect.left + rect.width * x, rect.top + rect.height * y));
    return hits.filter(Boolean).map((h) => ({ face: h.face, bary: h.bary }));
  }, fractions);
}

await withServedPage('app-picture', port, async (browser, baseURL) => {
  const page = await browser.newPage({ baseURL, viewport: { width: 1280, height: 760 } });
  await openDesigner(page);
  await page.evaluate(() => window.tvf.shadowRoot.querySelector('#hint .close')?.click());
  await page.evaluate(() => window.tvf.setViews({ arrows: true, streamlines: true, singularities: true }));
  // An arc over the flank, left to right, rising then falling.
  const arc = Array.from({ length: 25 }, (_, k) => {
    const t = k / 24;
    return [0.36 + 0.28 * t, 0.62 - 0.16 * Math.sin(Math.PI * t)];
  });
  const stroke = await pickAll(page, arc);
  if (stroke.length < 10) throw new Error(`the stroke found the surface at ${stroke.length} points only`);
  await page.evaluate((points) => window.tvf.addStroke(points), stroke);
  const [vortexAt] = await pickAll(page, [[0.55, 0.74]]);
  if (!vortexAt) throw new Error('the vortex found no surface');
  await page.evaluate((face) => window.tvf.addVortex(face), vortexAt.face);
  await page.evaluate(() => window.tvf.settled());
  await page.waitForTimeout(1500); // the views' last frames
  writeFileSync(out, await page.screenshot());
  console.log(`app-picture: wrote ${out}`);
});
