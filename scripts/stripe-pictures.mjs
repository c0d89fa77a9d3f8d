#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// The stripe profiles' picture of docs/stripes.md (docs/images/stripe-profiles.png): the default model's
// curvature-aligned line field drawn as stripes and wood rings, its cross field as grid lines, bricks and a
// weave, side by side; taken in Debian's Chromium with software WebGL from the page served from dist/ (build it
// first: npm run build:wasm && npm run build:web). A picture maker, not a test: what the stripes read back is
// tests/e2e/stripes.spec.mjs's.
//
// Usage: node scripts/stripe-pictures.mjs [--out DIR] [--port P] [--size PX]
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { openDesigner } from '../tests/e2e/helpers.mjs';
import { argument, requireBuiltPage, withServedPage } from './page-session.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const out = resolve(argument('--out', join(ROOT, 'docs/images')));
const port = Number(argument('--port', process.env.PORT || 8197));
const size = Number(argument('--size', 360));
// [symmetry, profile] in the order shown.
const PROFILES = [[2, 'stripes'], [2, 'wood'], [4, 'grid'], [4, 'bricks'], [4, 'weave']];

requireBuiltPage('stripe-pictures');

// One picture of the model per profile (PNG bytes), the panels, hint and view buttons out of the way.
async function profilePictures(page) {
  await openDesigner(page);
  await page.evaluate(() => {
    const style = document.createElement('style');
    style.textContent = '#side-panel, #constraints-panel, #hint, #view-presets { display: none !important; }';
    window.tvf.shadowRoot.append(style);
  });
  await page.evaluate(() => window.tvf.setViews({ arrows: false, singularities: false }));
  const shots = [];
  for (const [symmetry, profile] of PROFILES) {
    await page.evaluate(async ([n, p]) => {
      if (window.tvf.settings().symmetry !== n) {
        await window.tvf.setSymmetry(n);
        await window.tvf.setCurvatureAlignment(1);
      }
      await window.tvf.settled();
      await window.tvf.setStripes({ visible: true, profile: p });
      await window.tvf.stripesIdle();
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    }, [symmetry, profile]);
    shots.push({ profile, png: await page.locator('#view').screenshot() });
  }
  return shots;
}

// The pictures side by side, each captioned, as one PNG.
async function composite(page, shots) {
  const cells = shots
    .map(({ profile, png }) => `<figure><img src="data:image/png;base64,${png.toString('base64')}">` +
      `<figcaption>${profile}</figcaption></figure>`)
    .join('');
  await page.setViewportSize({ width: shots.length * (size + 6) + 6, height: size + 40 });
  await page.setContent(`<style>body{margin:0;background:#1b1c20}#row{display:flex;gap:6px;padding:6px}
    figure{margin:0;color:#ddd;font:14px sans-serif;text-align:center}img{width:${size}px;height:${size}px;
    object-fit:cover;display:block}</style><div id="row">${cells}</div>`);
  return page.locator('#row').screenshot();
}

mkdirSync(out, { recursive: true });
await withServedPage('stripe-pictures', port, async (browser, baseURL) => {
  const page = await browser.newPage({ viewport: { width: 720, height: 720 }, baseURL });
  page.setDefaultTimeout(180_000);
  const shots = await profilePictures(page);
  const path = join(out, 'stripe-profiles.png');
  writeFileSync(path, await composite(page, shots));
  console.log(path);
});
