#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// A sweep of texture-synthesis settings on models, in Debian's Chromium with software WebGL, served from dist/
// (build it first: npm run build:wasm && npm run build:web). A measuring tool for the texture defaults
// (docs/texture-synthesis.md), not a test: it checks nothing and writes what scripts/texture-diagnose.mjs reads.
//
// Usage: node scripts/texture-sweep.mjs --sweep '[{"tiles": 12}, {"passes": 3, "label": "p3"}]'
//                                       [--models homer,lion-head] [--raw] [--out DIR] [--port P]
//   --sweep    a JSON list of settings, each synthesize()'s options plus `label` (the files' suffix; default c<i>),
//              `tiles` (featureScale for that many exemplar tiles across sqrt(area), as index.js's
//              defaultFeatureScale) and `exportResolution` (the GLB's textureResolution)
//   --models   meshes of bench-data/meshes (scripts/fetch-meshes.sh; default homer); `bunny`: the page's own
//   --raw      also the synthesized coordinates and Jacobians (RGBA32F) and the exemplar, for offline rendering
//   --out      where the files go (default bench-data/texture-sweep)
// Per model and setting: <model>-<label>.glb (the exported GLB), <model>-<label>-diag.json (mesh, field,
// singularities, atlas UVs and the synthesis stats) and, with --raw, <model>-<label>-{coords,jacobian,exemplar}.bin;
// one JSON line per setting on stdout.
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { openDesigner, surfacePointsAlongScreenLine } from '../tests/e2e/helpers.mjs';
import { withServedPage } from './page-session.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const MESHES = resolve(ROOT, 'bench-data/meshes');
const arg = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const configs = JSON.parse(arg('--sweep', '[]'));
const models = arg('--models', 'homer').split(',');
const raw = process.argv.includes('--raw');
const out = resolve(arg('--out', join(ROOT, 'bench-data/texture-sweep')));
const port = Number(arg('--port', process.env.PORT || 8195));

function die(message) {
  console.error(`texture-sweep: ${message}`);
  process.exit(1);
}
if (!configs.length) die('give --sweep a JSON list of settings, e.g. \'[{"tiles": 9}, {"featureScale": 1}]\'');
if (!existsSync(resolve(ROOT, 'dist/index.html'))) die('dist/ not found; run npm run build:wasm && npm run build:web');
for (const name of models) {
  if (name !== 'bunny' && !existsSync(join(MESHES, `${name}.off`))) die(`${name}.off not in bench-data/meshes`);
}

// The page's data for one synthesis: the GLB, the mesh and field, the atlas UVs.
function readResult(page, exportResolution) {
  return page.evaluate(async (r) => {
    const m = window.tvf.mesh();
    const rb = await window.tvf.synthesisReadback();
    const glb = Array.from(await window.tvf.exportGlb(r ? { textureResolution: r } : {}));
    return {
      glb,
      positions: Array.from(m.positions),
      triangles: Array.from(m.triangles),
      faceVectors: Array.from(window.tvf.faceVectors()),
      singularities: window.tvf.singularities(),
      cornerUVs: Array.from(rb.cornerUVs),
    };
  }, exportResolution);
}

// The synthesized coordinates and Jacobians and the exemplar, base64 (a page hands strings over cheaply).
function readRaw(page) {
  return page.evaluate(async () => {
    const rb = await window.tvf.synthesisReadback();
    const b64 = (a) => {
      const u = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
      let s = '';
      for (let i = 0; i < u.length; i += 0x8000) s += String.fromCharCode.apply(null, u.subarray(i, i + 0x8000));
      return btoa(s);
    };
    return { coords: b64(rb.coords), jacobian: b64(rb.jacobian), exemplar: b64(rb.exemplar) };
  });
}

async function sweep(page, name) {
  await openDesigner(page);
  if (name !== 'bunny') {
    const bytes = Array.from(readFileSync(join(MESHES, `${name}.off`)));
    await page.evaluate(([b, n]) => window.tvf.loadModel(new Uint8Array(b), { name: n }), [bytes, name]);
  }
  await page.evaluate(() => window.tvf.setViews({ arrows: false }));
  const points = await surfacePointsAlongScreenLine(page, { x0: 0.3, dx: 0.013, y: 0.5, count: 30 });
  await page.evaluate((pts) => window.tvf.addStroke(pts), points);
  await page.evaluate(() => window.tvf.setExemplar('stripes'));
  for (const [i, cfg] of configs.entries()) {
    const { exportResolution, label = `c${i}`, tiles, ...opts } = cfg;
    if (tiles) {
      const s = await page.evaluate((o) => window.tvf.synthesize(o), { ...opts, featureScale: 'auto' });
      opts.featureScale = (s.atlas.resolution * Math.sqrt(s.atlas.coverage)) / (tiles * s.exemplarSize);
    }
    const stats = await page.evaluate((o) => window.tvf.synthesize(o), opts);
    const { glb, ...data } = await readResult(page, exportResolution);
    writeFileSync(join(out, `${name}-${label}.glb`), Buffer.from(glb));
    if (raw) {
      const bins = await readRaw(page);
      for (const [k, b64] of Object.entries(bins)) {
        writeFileSync(join(out, `${name}-${label}-${k}.bin`), Buffer.from(b64, 'base64'));
      }
    }
    writeFileSync(join(out, `${name}-${label}-diag.json`), JSON.stringify({ ...data, stats }));
    const { featureScale, resolution } = stats;
    console.log(JSON.stringify({ name, label, cfg, totalMs: Math.round(stats.totalMs), featureScale, resolution }));
  }
}

mkdirSync(out, { recursive: true });
await withServedPage('texture-sweep', port, async (browser, baseURL) => {
  for (const name of models) {
    const page = await browser.newPage({ viewport: { width: 1024, height: 720 }, baseURL });
    page.setDefaultTimeout(1_800_000);
    await sweep(page, name);
    await page.close();
  }
});
