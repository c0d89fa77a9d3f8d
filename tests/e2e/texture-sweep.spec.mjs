// Sweep of synthesis settings on models (TVF_SWEEP='[{"tiles": 12}, {"passes": 3, "label": "p3"}]',
// TVF_SWEEP_MODELS=homer,lion-head; TVF_SWEEP_RAW=1 adds the coordinates and Jacobians): per setting, the exported
// GLB and the bundle that scripts/texture-diagnose.mjs reads. Skipped without TVF_SWEEP: a measuring tool for the
// texture defaults (docs/texture-synthesis.md), not a test.
import { readFileSync, writeFileSync } from 'node:fs';
import { test } from '@playwright/test';
import { openDesigner, surfacePointsAlongScreenLine } from './helpers.mjs';

const MESHES = new URL('../../bench-data/meshes/', import.meta.url);
const models = (process.env.TVF_SWEEP_MODELS || 'homer').split(',');
const configs = JSON.parse(process.env.TVF_SWEEP || '[]');
test.skip(!configs.length, 'set TVF_SWEEP to a JSON list of settings, e.g. [{"tiles": 9}, {"featureScale": 1}]');

for (const name of models) {
  test(`sweep ${name}`, async ({ page }, testInfo) => {
    test.setTimeout(1_800_000);
    await openDesigner(page);
    if (name !== 'bunny') await page.evaluate(([b, n]) => window.tvf.loadModel(new Uint8Array(b), { name: n }), [Array.from(readFileSync(new URL(`${name}.off`, MESHES))), name]);
    await page.evaluate(() => window.tvf.setViews({ arrows: false }));
    const points = await surfacePointsAlongScreenLine(page, { x0: 0.3, dx: 0.013, y: 0.5, count: 30 });
    await page.evaluate((pts) => window.tvf.addStroke(pts), points);
    await page.evaluate(() => window.tvf.setExemplar('stripes'));
    for (const [i, cfg] of configs.entries()) {
      const { exportResolution, label = `c${i}`, tiles, ...opts } = cfg;
      if (tiles) {
        // featureScale for `tiles` exemplar tiles across sqrt(area), as index.js's defaultFeatureScale.
        const s = await page.evaluate((o) => window.tvf.synthesize(o), { ...opts, featureScale: 'auto' });
        opts.featureScale = (s.atlas.resolution * Math.sqrt(s.atlas.coverage)) / (tiles * s.exemplarSize);
      }
      const stats = await page.evaluate((o) => window.tvf.synthesize(o), opts);
      const data = await page.evaluate(async (r) => {
        const m = window.tvf.mesh();
        const rb = await window.tvf.synthesisReadback();
        const glb = Array.from(await window.tvf.exportGlb(r ? { textureResolution: r } : {}));
        return { glb, positions: Array.from(m.positions), triangles: Array.from(m.triangles), faceVectors: Array.from(window.tvf.faceVectors()), singularities: window.tvf.singularities(), cornerUVs: Array.from(rb.cornerUVs) };
      }, exportResolution);
      writeFileSync(testInfo.outputPath(`${name}-${label}.glb`), Buffer.from(data.glb));
      if (process.env.TVF_SWEEP_RAW) {
        // The synthesized coordinates and Jacobians (RGBA32F) and the exemplar, for offline rendering.
        const raw = await page.evaluate(async () => {
          const rb = await window.tvf.synthesisReadback();
          const b64 = (a) => {
            const u = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
            let s = '';
            for (let i = 0; i < u.length; i += 0x8000) s += String.fromCharCode.apply(null, u.subarray(i, i + 0x8000));
            return btoa(s);
          };
          return { resolution: rb.resolution, exemplarSize: rb.exemplarSize, coords: b64(rb.coords), jacobian: b64(rb.jacobian), exemplar: b64(rb.exemplar) };
        });
        for (const k of ['coords', 'jacobian', 'exemplar']) writeFileSync(testInfo.outputPath(`${name}-${label}-${k}.bin`), Buffer.from(raw[k], 'base64'));
      }
      delete data.glb;
      writeFileSync(testInfo.outputPath(`${name}-${label}-diag.json`), JSON.stringify({ ...data, stats }));
      console.log(JSON.stringify({ name, label, cfg, totalMs: Math.round(stats.totalMs), featureScale: stats.featureScale, resolution: stats.resolution }));
    }
  });
}
