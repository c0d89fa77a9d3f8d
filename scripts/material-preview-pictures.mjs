#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// The material-preview pictures of docs/export.md (docs/images/material-preview-{brushed-metal,satin}.png), taken
// in Debian's Chromium with software WebGL from the page served from dist/ (build it first: npm run build:wasm &&
// npm run build:web). A picture maker, not a test: what the preview reads back is tests/e2e/export.spec.mjs's.
//
// Usage: node scripts/material-preview-pictures.mjs [--out DIR] [--port P]
//   --out   where the pictures go (default docs/images)
import { mkdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { openDesigner } from '../tests/e2e/helpers.mjs';
import { argument, requireBuiltPage, withServedPage } from './page-session.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const out = resolve(argument('--out', join(ROOT, 'docs/images')));
const port = Number(argument('--port', process.env.PORT || 8196));
const PRESETS = ['brushed metal', 'satin'];

requireBuiltPage('material-preview-pictures');

// A source at the lowest and a sink at the highest vertex of the default model: a field that sweeps over the
// whole surface, so the highlights wrap around it.
async function sweepingField(page) {
  const [low, high] = await page.evaluate(() => {
    const { positions } = window.tvf.mesh();
    let lo = 0, hi = 0;
    for (let v = 0; v < positions.length / 3; v++) {
      if (positions[3 * v + 1] < positions[3 * lo + 1]) lo = v;
      if (positions[3 * v + 1] > positions[3 * hi + 1]) hi = v;
    }
    return [lo, hi];
  });
  const constraints = [
    { type: 'source', vertex: low, strength: 1 },
    { type: 'sink', vertex: high, strength: 1 },
  ];
  await page.evaluate((c) => window.tvf.loadDesign({ constraints: c }), constraints);
}

async function pictures(page) {
  await openDesigner(page);
  await sweepingField(page);
  await page.evaluate(() => window.tvf.setViews({ arrows: false }));
  // The picture is of the model: panels, the first-visit hint and the view buttons out of the way.
  await page.evaluate(() => {
    const style = document.createElement('style');
    style.textContent = '#side-panel, #constraints-panel, #hint, #view-presets { display: none !important; }';
    window.tvf.shadowRoot.append(style);
  });
  for (const preset of PRESETS) {
    await page.evaluate((p) => window.tvf.materialPreview(p), preset);
    const path = join(out, `material-preview-${preset.replace(' ', '-')}.png`);
    await page.locator('#view').screenshot({ path });
    console.log(path);
  }
}

mkdirSync(out, { recursive: true });
await withServedPage('material-preview-pictures', port, async (browser, baseURL) => {
  const page = await browser.newPage({ viewport: { width: 1024, height: 720 }, baseURL });
  page.setDefaultTimeout(180_000);
  await pictures(page);
});
