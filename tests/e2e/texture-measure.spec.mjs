// The exported GLB measured as any glTF viewer shows it (its own TEXCOORD_0 and embedded image, image row 0 =
// v 0), at the page's default synthesis settings (tests/e2e/surface-texture-metrics.mjs):
// - the measure itself, calibrated on an analytic stripe texture painted over the bunny's generated atlas, whose
//   stripes are level sets of a linear function (truth: their tangent) and which is continuous across seams;
// - the default bunny with a stroke-designed field;
// - with TVF_MEASURE=1 and scripts/fetch-meshes.sh run: held-out CGAL models (knot2 has genus 1; others with
//   TVF_MEASURE_MODELS=refined_elephant,camel,..., low-poly ones made by scripts/decimate-off.mjs among them),
//   reported for docs/benchmarks.md and held to its targets (slow under software WebGL: not part of `npm test`);
//   TVF_MEASURE_SYMMETRY=2 measures a line field, TVF_MEASURE_EXEMPLAR_SIZE=32|128|... another size of
//   the stripes exemplar, TVF_MEASURE_SYNTHESIS='{"passes":4}' (JSON) options for the synthesis (default: none).
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { expect, test } from '@playwright/test';
import bunny from 'bunny';
import { generateAtlas } from '../../web/synthesis/atlas.js';
import createTvfCore from '../../build-wasm/tvf_core.mjs';
import { surfacePointsAlongScreenLine, openDesignerPage, synthesisReadback } from './helpers.mjs';
import { neighbourhoodEnergy, randomCoordinates } from './synthesis-metrics.mjs';
import { pixelLength, readGlb, seamJumpRatio, stripeAlignment } from './surface-texture-metrics.mjs';


test('the surface stripe measure on an analytic texture over a generated atlas (calibration)', async () => {
  const Module = await createTvfCore();
  const positions = Float64Array.from(bunny.positions.flat());
  const triangles = Int32Array.from(bunny.cells.flat());
  const R = 512;
  const { cornerUVs } = generateAtlas(Module, positions, triangles, { resolution: R, gutter: 2 });
  const nF = triangles.length / 3;
  // Stripes: intensity = sin(2π p·a / period) at every texel's surface point (texels of a face and a 2-texel
  // ring around it, extrapolated with the face's own map, as a gutter).
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) for (let k = 0; k < 3; k++) (lo[k] = Math.min(lo[k], positions[i + k])), (hi[k] = Math.max(hi[k], positions[i + k]));
  const diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const a = [0.6, 0.64, 0.48];
  const period = diag / 40;
  const pixels = new Uint8Array(R * R * 4);
  const glbFaces = { positions: new Float32Array(9 * nF), uvs: new Float32Array(6 * nF), indices: new Uint32Array(3 * nF) };
  const field = new Float64Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    const P = [0, 1, 2].map((k) => [0, 1, 2].map((c) => positions[3 * triangles[3 * f + k] + c]));
    const Q = [0, 1, 2].map((k) => [cornerUVs[6 * f + 2 * k] * R, cornerUVs[6 * f + 2 * k + 1] * R]);
    for (let k = 0; k < 3; k++) {
      glbFaces.positions.set(P[k], 9 * f + 3 * k);
      // glTF: image row 0 is v = 0; the image below is written with row y at atlas v = (y + 0.5) / R.
      glbFaces.uvs.set([cornerUVs[6 * f + 2 * k], cornerUVs[6 * f + 2 * k + 1]], 6 * f + 2 * k);
      glbFaces.indices[3 * f + k] = 3 * f + k;
    }
    const e1 = P[1].map((x, c) => x - P[0][c]), e2 = P[2].map((x, c) => x - P[0][c]);
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const nl = Math.hypot(...n);
    const nn = n.map((x) => x / nl);
    const an = a[0] * nn[0] + a[1] * nn[1] + a[2] * nn[2];
    const ap = a.map((x, c) => x - an * nn[c]);
    field.set([nn[1] * ap[2] - nn[2] * ap[1], nn[2] * ap[0] - nn[0] * ap[2], nn[0] * ap[1] - nn[1] * ap[0]], 3 * f);
    const t = [Q[1][0] - Q[0][0], Q[2][0] - Q[0][0], Q[1][1] - Q[0][1], Q[2][1] - Q[0][1]];
    const det = t[0] * t[3] - t[1] * t[2];
    if (!(Math.abs(det) > 1e-12)) continue;
    const x0 = Math.max(0, Math.floor(Math.min(Q[0][0], Q[1][0], Q[2][0])) - 2), x1 = Math.min(R - 1, Math.ceil(Math.max(Q[0][0], Q[1][0], Q[2][0])) + 2);
    const y0 = Math.max(0, Math.floor(Math.min(Q[0][1], Q[1][1], Q[2][1])) - 2), y1 = Math.min(R - 1, Math.ceil(Math.max(Q[0][1], Q[1][1], Q[2][1])) + 2);
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const dx = x + 0.5 - Q[0][0], dy = y + 0.5 - Q[0][1];
        const l1 = (t[3] * dx - t[1] * dy) / det, l2 = (-t[2] * dx + t[0] * dy) / det;
        const inside = l1 >= 0 && l2 >= 0 && l1 + l2 <= 1;
        const o = 4 * (y * R + x);
        if (pixels[o + 3] === 255 && !inside) continue; // a face's own texels win over another's gutter
        const p = [0, 1, 2].map((c) => P[0][c] + l1 * e1[c] + l2 * e2[c]);
        const v = Math.round(127.5 + 127 * Math.sin((2 * Math.PI * (p[0] * a[0] + p[1] * a[1] + p[2] * a[2])) / period));
        pixels.set([v, v, v, inside ? 255 : 254], o);
      }
  }
  for (let i = 3; i < pixels.length; i += 4) pixels[i] = pixels[i] ? 255 : 0;
  const glb = { ...glbFaces, image: { width: R, height: R, pixels } };
  const align = stripeAlignment(glb, field, period);
  const seams = seamJumpRatio(glb, triangles);
  console.log(JSON.stringify({ calibration: { meanDegrees: align.meanDegrees, shareWithin10: align.shareWithin10, faces: align.faces, seamRatio: seams.ratio, seamEdges: seams.seamEdges } }));
  // texture-quality.md: a perfect analytic texture scores ~3° / 93% at 1024², 5-10° at 256².
  expect(align.meanDegrees).toBeLessThan(6);
  expect(align.shareWithin10).toBeGreaterThan(0.85);
  expect(seams.seamEdges).toBeGreaterThan(100);
  expect(seams.ratio).toBeLessThan(1.3);
  expect(seams.ratio).toBeGreaterThan(0.7);
});

// Loads a model (or keeps the default), draws a stroke across the view, synthesizes at the page's defaults,
// exports the GLB and measures it. Returns the report.
// exemplarSize: the procedural stripes' size (their period a quarter of it); symmetry: the field's N, set before
// the stroke (a line or cross field's texture follows its combed representatives).
async function measureModel(page, testInfo, { name, bytes, exemplarSize = 64, symmetry = 1 }) {
  if (bytes) await page.evaluate(([b, n]) => window.tvf.loadModel(new Uint8Array(b), { name: n }), [bytes, name]);
  // The measure is taken without sharp features (docs/texture-synthesis.md): most models start without them, but
  // one whose sharp folds run on long lines (knot2's faceted tube) starts with them.
  if (bytes) await page.evaluate(() => window.tvf.setFeatures({ angle: 0 }));
  await page.evaluate(() => window.tvf.setViews({ arrows: false }));
  if (symmetry !== 1) await page.evaluate(async (n) => (await window.tvf.setSymmetry(n), window.tvf.settled()), symmetry);
  const points = await surfacePointsAlongScreenLine(page, { x0: 0.3, dx: 0.013, y: 0.5, count: 30 });
  expect(points.length).toBeGreaterThan(5);
  await page.evaluate((pts) => window.tvf.addStroke(pts), points);
  await page.evaluate((size) => window.tvf.setExemplar({ procedural: 'stripes', size }), exemplarSize);
  const stats = await page.evaluate((o) => window.tvf.synthesize(o), JSON.parse(process.env.TVF_MEASURE_SYNTHESIS || '{}'));
  // The GLB comes back as base64: a number array of a 10 MB file (refined_elephant) took minutes.
  const data = await page.evaluate(async () => {
    const glb = await window.tvf.exportGlb();
    let s = '';
    for (let i = 0; i < glb.length; i += 0x8000) s += String.fromCharCode(...glb.subarray(i, i + 0x8000));
    const m = window.tvf.mesh();
    return { glb: btoa(s), triangles: Array.from(m.triangles), faceVectors: Array.from(window.tvf.faceVectors()) };
  });
  data.glb = Buffer.from(data.glb, 'base64');
  const glb = readGlb(new Uint8Array(data.glb.buffer, data.glb.byteOffset, data.glb.byteLength));
  const magnification = glb.image.width / stats.atlas.resolution;
  const period = (exemplarSize / 4) * stats.featureScale * magnification * pixelLength(glb);
  const align = stripeAlignment(glb, Float64Array.from(data.faceVectors), period);
  const seams = seamJumpRatio(glb, Int32Array.from(data.triangles));
  await page.screenshot({ path: testInfo.outputPath(`${name}.png`) });
  // The model alone (the pictures in docs/images): the hint dismissed, the view's middle clipped.
  await page.evaluate(() => document.querySelector('tangent-field-designer').shadowRoot.querySelector('#hint .close')?.click());
  const box = await page.evaluate(() => {
    const r = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view').getBoundingClientRect();
    const side = Math.min(r.width, r.height) * 0.8;
    return { x: r.left + (r.width - side) / 2, y: r.top + (r.height - side) / 2, width: side, height: side };
  });
  await page.screenshot({ path: testInfo.outputPath(`${name}-view.png`), clip: box });
  writeFileSync(testInfo.outputPath(`${name}.glb`), data.glb);
  if (process.env.TVF_DIAGNOSE) {
    // Everything scripts/texture-diagnose.mjs needs to split the deviation by cause, and GLBs at other
    // export resolutions (the measure's own floor shrinks with the image's resolution).
    const extra = await page.evaluate(async (sizes) => {
      const m = window.tvf.mesh();
      const rb = await window.tvf.synthesisReadback();
      const glbs = {};
      for (const r of sizes) glbs[r] = Array.from(await window.tvf.exportGlb({ textureResolution: r }));
      return { positions: Array.from(m.positions), triangles: Array.from(m.triangles), faceVectors: Array.from(window.tvf.faceVectors()), vertexVectors: Array.from(window.tvf.vertexVectors()), singularities: window.tvf.singularities(), cornerUVs: Array.from(rb.cornerUVs), glbs };
    }, (process.env.TVF_DIAGNOSE_SIZES || '2048').split(',').map(Number));
    for (const [r, bytes] of Object.entries(extra.glbs)) writeFileSync(testInfo.outputPath(`${name}-${r}.glb`), Buffer.from(bytes));
    delete extra.glbs;
    writeFileSync(testInfo.outputPath(`${name}-diag.json`), JSON.stringify({ ...extra, stats, period }));
  }
  // LH05's neighbourhood energy of the synthesized coordinates (in the atlas, neighbours inside the charts and
  // their gutters), against the same atlas with random coordinates: comparable with the flat square's (docs/benchmarks.md).
  const readback = await synthesisReadback(page, ['coords', 'jacobian', 'exemplar']);
  const rb = { R: readback.resolution, m: readback.exemplarSize };
  const coords = readback.coords, jac = readback.jacobian, ex = readback.exemplar;
  const energy = neighbourhoodEnergy(coords, jac, rb.R, rb.R, ex, rb.m);
  const energyRandom = neighbourhoodEnergy(randomCoordinates(coords, rb.m), jac, rb.R, rb.R, ex, rb.m);
  const report = {
    model: name,
    faces: data.triangles.length / 3,
    exemplarSize,
    symmetry,
    atlas: { resolution: stats.atlas.resolution, charts: stats.atlas.charts, coverage: stats.atlas.coverage, ms: Math.round(stats.atlas.ms) },
    featureScale: +stats.featureScale.toFixed(3),
    stripeMeanDegrees: +align.meanDegrees.toFixed(2),
    shareWithin10: +align.shareWithin10.toFixed(3),
    seamJump: +seams.seamJump.toFixed(1),
    interiorJump: +seams.interiorJump.toFixed(1),
    seamRatio: +seams.ratio.toFixed(3),
    neighbourhoodEnergy: +energy.toFixed(1),
    neighbourhoodEnergyRandom: +energyRandom.toFixed(1),
    synthesisMs: Math.round(stats.totalMs),
    levelMs: stats.levels?.map((l) => Math.round(l.ms)),
    wallMs: Math.round(stats.wallMs),
  };
  console.log(JSON.stringify(report));
  writeFileSync(testInfo.outputPath(`${name}-report.json`), JSON.stringify(report, null, 1));
  return report;
}

test.describe.serial('exported GLB at the default settings', () => {
  let page, errors;
  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
  });
  test.afterAll(async () => {
    await page?.close();
  });

  test('default bunny with a stroke: stripes on the field, seams continuous', async ({}, testInfo) => {
    // At the defaults: the default model, a curved surface of facets, starts without sharp features.
    expect(await page.evaluate(() => window.tvf.features().angle)).toBe(0);
    const r = await measureModel(page, testInfo, { name: 'bunny' });
    expect(r.stripeMeanDegrees).toBeLessThan(BUNNY_LIMITS.mean);
    expect(r.shareWithin10).toBeGreaterThan(BUNNY_LIMITS.share);
    expect(r.seamRatio).toBeLessThan(BUNNY_LIMITS.seam);
    // Coherent patches continued across the atlas: far below random coordinates (measured 0.026 of it).
    expect(r.neighbourhoodEnergy).toBeLessThan(0.05 * r.neighbourhoodEnergyRandom);
  });

  const MESHES = new URL('../../bench-data/meshes/', import.meta.url);
  // TVF_MEASURE_MODELS=a,b,... measures other fetched models (bench-data/meshes/NAME.off) instead.
  const heldOut = process.env.TVF_MEASURE_MODELS?.split(',').filter(Boolean) ?? ['knot2', 'lion-head', 'homer'];
  for (const name of heldOut) {
    test(`held-out model ${name} (TVF_MEASURE=1)`, async ({}, testInfo) => {
      const file = new URL(`${name}.off`, MESHES);
      test.skip(!process.env.TVF_MEASURE || !existsSync(file), 'set TVF_MEASURE=1 and run scripts/fetch-meshes.sh');
      test.setTimeout(600_000);
      await page.evaluate(() => window.tvf.clearTexture());
      const exemplarSize = Number(process.env.TVF_MEASURE_EXEMPLAR_SIZE ?? 64);
      const symmetry = Number(process.env.TVF_MEASURE_SYMMETRY ?? 1);
      const bytes = Array.from(readFileSync(file));
      const r = await measureModel(page, testInfo, { name, bytes, exemplarSize, symmetry });
      expect(r.stripeMeanDegrees, 'stripes against the field (degrees)').toBeLessThan(TARGETS.mean);
      expect(r.shareWithin10, 'share of the surface within 10°').toBeGreaterThan(TARGETS.share);
      expect(r.seamRatio, 'seam jump ÷ interior jump').toBeLessThan(TARGETS.seam);
      // Coherent patches, as on the bunny (docs/benchmarks.md: knot2 129.4 against 6119 for random coordinates).
      expect(r.neighbourhoodEnergy).toBeLessThan(0.05 * r.neighbourhoodEnergyRandom);
    });
  }

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});

// Measured 4.93° / 0.90 / 1.04 at 0.84 x the shape complexity tiles (auto-settings.js), 5.02–5.35° / 0.89–0.91 /
// 0.95–1.03 at 0.66 x (the previous fixed 6 tiles across √area measured 6.72° / 0.85 / 1.00); following the
// Whitney field per texel, 5.10° / 0.896 / 0.95. The targets are 6° / 0.85 / 1.3
// (docs/texture-synthesis.md, "Exported GLB").
const BUNNY_LIMITS = { mean: 6, share: 0.87, seam: 1.15 };
// The targets every held-out model meets (docs/benchmarks.md, "Texture": knot2 3.8° / 96.7 % / 1.09, lion-head
// 5.46° / 89.1 % / 1.16, homer 5.03° / 90.5 % / 1.06; camel's 88.2 % the least margin of the seven).
const TARGETS = { mean: 6, share: 0.85, seam: 1.3 };
