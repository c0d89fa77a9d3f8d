// Texture synthesis along line fields (N = 2): the representatives the core hands out have arbitrary signs, so
// the synthesis combs them per atlas chart (web/geometry/chart-comb.js) before rasterizing the field per corner.
// - a flat square (one chart, TEXCOORD_0 = (x, y)) with a constant line field whose representatives (the core's)
//   come with mixed signs: the combed Jacobian has one sign over the chart and follows the line within 1° at every
//   texel, and the stripes come out as the vector field's along the same line, within 1°;
// - the default bunny with a line field from two strokes, synthesized at the page's defaults with the stripes
//   exemplar: stripe direction against the field mod 180° and the seam ratio, measured on the texture as the
//   export renders it (tests/e2e/surface-texture-metrics.mjs);
// - with TVF_MEASURE=1 (slow, not in `npm test`): the bunny and knot2 (scripts/fetch-meshes.sh) as vector, line
//   and cross fields, reported for docs/texture-synthesis.md and held to what it documents.
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { expect, test } from '@playwright/test';
import { flatSquareGlb } from '../node/export-fixtures.mjs';
import { surfacePointsAlongScreenLine, openDesignerPage, synthesisReadback } from './helpers.mjs';
import { coordinateCoherence, exemplarImage, orientationError, stripeOrientation } from './synthesis-metrics.mjs';
import { decodePng, pixelLength, seamJumpRatio, stripeAlignment } from './surface-texture-metrics.mjs';

const STRIPE_PERIOD_PX = 16; // the 'stripes' exemplar: 64² with a period of 16 pixels
const MAGNIFICATION = 2; // pixels per atlas texel, as the GLB export renders the texture by default

// The current texture as any viewer would show it: the model's faces (unindexed) with the atlas UVs and the
// texture rendered as the export renders it (image row 0 = v 0), in the shape readGlb gives.
async function texturedModel(page) {
  const d = await page.evaluate(async (magnification) => {
    const png = await window.tvf.exportTexturePNG({ magnification });
    const rb = await window.tvf.synthesisReadback();
    const m = window.tvf.mesh();
    return {
      png: Array.from(new Uint8Array(await png.arrayBuffer())),
      cornerUVs: Array.from(rb.cornerUVs),
      positions: Array.from(m.positions),
      triangles: Array.from(m.triangles),
      faceVectors: Array.from(window.tvf.faceVectors()),
    };
  }, MAGNIFICATION);
  const nF = d.triangles.length / 3;
  const positions = new Float32Array(9 * nF), uvs = new Float32Array(6 * nF), indices = new Uint32Array(3 * nF);
  for (let c = 0; c < 3 * nF; c++) {
    const v = d.triangles[c];
    positions.set([d.positions[3 * v], d.positions[3 * v + 1], d.positions[3 * v + 2]], 3 * c);
    uvs.set([d.cornerUVs[2 * c], d.cornerUVs[2 * c + 1]], 2 * c);
    indices[c] = c;
  }
  return { glb: { positions, uvs, indices, image: decodePng(Uint8Array.from(d.png)) }, triangles: Int32Array.from(d.triangles), faceVectors: Float64Array.from(d.faceVectors) };
}

// Per-face stripe errors (degrees, mod 180°, NaN where unmeasured) taken mod 90°: area-weighted mean and share
// within 10°.
function modQuarter(glb, errors) {
  const P = glb.positions;
  let sum = 0, within = 0, total = 0;
  errors.forEach((e, f) => {
    if (Number.isNaN(e)) return;
    const p = (k) => [0, 1, 2].map((c) => P[9 * f + 3 * k + c]);
    const [a, b, c] = [p(0), p(1), p(2)];
    const u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    const area = Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]) / 2;
    const d = Math.min(e, 90 - e);
    sum += area * d;
    total += area;
    if (d <= 10) within += area;
  });
  return { meanDegrees: sum / total, shareWithin10: within / total };
}

// Strokes across the view at the given heights (fractions of the view), then the stripes synthesized at the
// page's defaults and measured. Returns the report.
async function strokesAndMeasure(page, testInfo, { name, symmetry, heights, bytes = null }) {
  if (bytes) await page.evaluate(([b, n]) => window.tvf.loadModel(new Uint8Array(b), { name: n, restore: false }), [bytes, name]);
  await page.evaluate(() => window.tvf.setViews({ arrows: false }));
  await page.evaluate((n) => window.tvf.setSymmetry(n), symmetry);
  for (const y of heights) {
    const points = await surfacePointsAlongScreenLine(page, { x0: 0.3, dx: 0.013, y, count: 30 });
    expect(points.length).toBeGreaterThan(5);
    await page.evaluate((pts) => window.tvf.addStroke(pts), points);
  }
  await page.evaluate(() => window.tvf.setExemplar('stripes'));
  // The page's defaults (options given earlier stay until changed).
  const stats = await page.evaluate(() => window.tvf.synthesize({ resolution: 'auto', featureScale: 'auto' }));
  const { glb, triangles, faceVectors } = await texturedModel(page);
  const period = STRIPE_PERIOD_PX * stats.featureScale * MAGNIFICATION * pixelLength(glb);
  let align = stripeAlignment(glb, faceVectors, period);
  // A cross field: the stripes follow one of its two families, either of them, so the error is taken mod 90°.
  if (symmetry === 4) align = modQuarter(glb, align.errors);
  const seams = seamJumpRatio(glb, triangles);
  const report = {
    model: name,
    symmetry,
    faces: triangles.length / 3,
    resolution: stats.resolution,
    featureScale: +stats.featureScale.toFixed(3),
    stripeMeanDegrees: +align.meanDegrees.toFixed(2),
    shareWithin10: +align.shareWithin10.toFixed(3),
    seamRatio: +seams.ratio.toFixed(3),
    combCutEdges: stats.combCutEdges ?? null,
    combMs: stats.combMs === undefined ? null : Math.round(stats.combMs),
    synthesisMs: Math.round(stats.totalMs),
  };
  console.log(JSON.stringify(report));
  writeFileSync(testInfo.outputPath(`${name}-N${symmetry}-report.json`), JSON.stringify(report, null, 1));
  await page.screenshot({ path: testInfo.outputPath(`${name}-N${symmetry}.png`) });
  return report;
}

test.describe.serial('texture synthesis along line fields', () => {
  let page, errors;
  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
  });
  test.afterAll(async () => {
    await page?.close();
  });

  test('flat square: a constant line field with scrambled representatives is followed within 1°, one sign over the chart', async ({}, testInfo) => {
    await page.evaluate((bytes) => window.tvf.loadModel(new Uint8Array(bytes), { name: 'flat-square.glb', restore: false }), Array.from(flatSquareGlb(16)));
    await page.evaluate(() => window.tvf.setExemplar('stripes'));
    // At 120° the core's representatives come with mixed signs: a face's is the one within 90° of its frame's
    // first edge, and the square's faces start at edges along 0°, 45° and 90°.
    const theta = 120, t = (theta * Math.PI) / 180;
    const run = async (symmetry) => {
      const design = { boundary: 'free', gamma: 0, symmetry, constraints: [{ type: 'vector', face: 40, vector: [Math.cos(t), Math.sin(t), 0], weight: 1e4 }] };
      await page.evaluate((d) => window.tvf.loadDesign(d, { ignoreFingerprint: true }), design);
      const reps = await page.evaluate(() => [...window.tvf.faceVectors(), ...window.tvf.vertexVectors()]);
      const stats = await page.evaluate(() => window.tvf.synthesize({ resolution: 256, featureScale: 2 }).then(() => window.tvf.synthesisIdle()));
      const b = await synthesisReadback(page, ['coords', 'jacobian', 'exemplar']);
      const r = { R: b.resolution, m: b.exemplarSize };
      const coords = b.coords, jac = b.jacobian;
      const orientation = stripeOrientation(exemplarImage(coords, b.exemplar, r.m), r.R, r.R);
      // The direction the synthesis follows at every texel: the Jacobian's first row (atlas step → exemplar x)
      // is the field's direction in UV = (x, y); its sign and its angle to the line.
      let plus = 0, minus = 0, worst = 0;
      for (let i = 0; i < jac.length; i += 4) {
        if (coords[i + 3] === 0) continue;
        const d = jac[i] * Math.cos(t) + jac[i + 2] * Math.sin(t);
        if (d > 0) plus++;
        else if (d < 0) minus++;
        worst = Math.max(worst, (Math.acos(Math.min(1, Math.abs(d) / Math.hypot(jac[i], jac[i + 2]))) * 180) / Math.PI);
      }
      return { stats, reps, orientation, signs: [plus, minus], worst, coherence: coordinateCoherence(coords, jac, r.R, r.R, r.m) };
    };
    const vector = await run(1);
    const line = await run(2);
    let negated = 0;
    for (let i = 0; i < line.reps.length; i += 3) if (line.reps[i] * Math.cos(t) + line.reps[i + 1] * Math.sin(t) < 0) negated++;
    const report = {
      negatedRepresentatives: `${negated}/${line.reps.length / 3}`,
      lineStripeError: +orientationError(line.orientation.degrees, theta).toFixed(3),
      vectorStripeError: +orientationError(vector.orientation.degrees, theta).toFixed(3),
      lineVsVector: +orientationError(line.orientation.degrees, vector.orientation.degrees).toFixed(3),
      worstTexelDegrees: +line.worst.toFixed(4),
      jacobianSigns: line.signs,
      anisotropy: +line.orientation.anisotropy.toFixed(3),
      coherence: +line.coherence.toFixed(3),
      combCutEdges: line.stats.combCutEdges,
    };
    console.log(JSON.stringify(report));
    writeFileSync(testInfo.outputPath('flat-square-report.json'), JSON.stringify(report, null, 1));
    expect(line.stats.symmetry).toBe(2);
    expect(line.stats.atlas.source).toBe('TEXCOORD_0');
    expect(negated / (line.reps.length / 3), 'the representatives come with mixed signs').toBeGreaterThan(0.1);
    expect(line.stats.combCutEdges, 'a field without singularities needs no cut').toBe(0);
    expect(Math.min(...line.signs), 'the combed field has one sign over the chart').toBe(0);
    expect(line.worst, 'every texel follows the line (degrees)').toBeLessThan(1);
    // The stripes: as the vector field's along the same line, within 1° (the synthesis's own error at 120° on
    // this 256² atlas, about 2.3° for both, is synthesis.spec.mjs's to bound).
    expect(report.lineVsVector, 'line-field stripes vs vector-field stripes (degrees)').toBeLessThan(1);
    expect(report.lineStripeError).toBeLessThan(5);
    expect(line.orientation.anisotropy).toBeGreaterThan(0.8);
    expect(line.coherence).toBeGreaterThanOrEqual(0.6);
  });

  test('default bunny, a line field from two strokes: stripes along it (mod 180°), seams continuous', async ({}, testInfo) => {
    await page.evaluate(() => window.tvf.clearTexture());
    await page.evaluate(() => window.tvf.loadModel('models/bunny.glb', { restore: false }));
    const r = await strokesAndMeasure(page, testInfo, { name: 'bunny', symmetry: 2, heights: [0.45, 0.6] });
    expect(r.stripeMeanDegrees).toBeLessThan(6);
    expect(r.shareWithin10).toBeGreaterThan(0.85);
    expect(r.seamRatio).toBeLessThan(1.3);
  });

  test('with Line selected the Texture panel offers line textures: stripes and brushed', async () => {
    await page.evaluate(() => window.tvf.clearTexture());
    await page.evaluate(() => window.tvf.setSymmetry(2));
    const names = await page.evaluate(() => [...document.querySelector('tangent-field-designer').shadowRoot.querySelectorAll('#tex-exemplar option')].map((o) => o.value));
    expect(names).toEqual(expect.arrayContaining(['stripes', 'brushed']));
    const info = await page.evaluate(() => window.tvf.setExemplar('brushed'));
    expect(info).toMatchObject({ label: 'brushed', size: 64 });
    await page.evaluate(() => window.tvf.setExemplar('stripes'));
  });

  test('N = 3 is refused by name', async () => {
    await page.evaluate(() => window.tvf.clearTexture());
    await page.evaluate(() => window.tvf.setSymmetry(3));
    const message = await page.evaluate(() => window.tvf.synthesize().then(() => 'resolved', (e) => e.message));
    expect(message).toMatch(/texture synthesis follows vector, line and cross fields \(N = 1, 2, 4\)/);
    await page.evaluate(() => window.tvf.setSymmetry(1));
  });

  const MESHES = new URL('../../bench-data/meshes/', import.meta.url);
  // docs/texture-synthesis.md, "Line and cross fields": mean stripe error (degrees), share within 10°, seam ratio.
  const DOCUMENTED = {
    'bunny 1': [4.69, 0.917, 0.98],
    'knot2 1': [3.83, 0.96, 1.1],
    'knot2 2': [3.86, 0.957, 1.08],
    'bunny 4': [6.27, 0.849, 1.1],
    'knot2 4': [5.1, 0.902, 1.06],
  };
  // What reruns on the loaded machine spread by (the one-stroke bunny: 5.02–5.35°, 89–91 %, seams 0.95–1.03,
  // texture-measure.spec.mjs), with room to spare; a regression of the synthesis or the comb goes past it.
  const MARGIN = { mean: 1, share: 0.04, seam: 0.15 };
  for (const [name, symmetry] of [['bunny', 1], ['knot2', 1], ['knot2', 2], ['bunny', 4], ['knot2', 4]]) {
    test(`measured: ${name}, N = ${symmetry} (TVF_MEASURE=1)`, async ({}, testInfo) => {
      const file = name === 'bunny' ? null : new URL(`${name}.off`, MESHES);
      test.skip(!process.env.TVF_MEASURE || (file && !existsSync(file)), 'set TVF_MEASURE=1 and run scripts/fetch-meshes.sh');
      test.setTimeout(600_000);
      await page.evaluate(() => window.tvf.clearTexture());
      if (!file) await page.evaluate(() => window.tvf.loadModel('models/bunny.glb', { restore: false }));
      const bytes = file ? Array.from(readFileSync(file)) : null;
      const r = await strokesAndMeasure(page, testInfo, { name, symmetry, heights: [0.45, 0.6], bytes });
      const [mean, share, seam] = DOCUMENTED[`${name} ${symmetry}`];
      expect(r.stripeMeanDegrees, 'stripes against the field (degrees)').toBeLessThan(mean + MARGIN.mean);
      expect(r.shareWithin10, 'share of the surface within 10°').toBeGreaterThan(share - MARGIN.share);
      expect(r.seamRatio, 'seam jump ÷ interior jump').toBeLessThan(seam + MARGIN.seam);
      // A line or cross field is combed per chart; a vector field needs no comb.
      if (symmetry === 1) expect(r.combCutEdges).toBeNull();
      else expect(r.combCutEdges).toEqual(expect.any(Number));
    });
  }

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});
