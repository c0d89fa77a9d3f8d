// Field-guided texture synthesis (web/synthesis/) end to end in the page, on a generated flat square with UVs
// (TEXCOORD_0 = (x, y)): a constant field at angle θ set through window.tvf, stripes synthesized on the GPU
// (software WebGL here: atlases stay at 256²), read back and measured in the test process
// (tests/e2e/synthesis-metrics.mjs): stripe orientation from the structure tensor, coordinate coherence,
// neighbourhood energy and colour histograms against a random-coordinates baseline.
import { writeFileSync } from 'node:fs';
import { expect, test } from '@playwright/test';
import bunny from 'bunny';
import { checkAtlasUVs, generateAtlas, rasterCoverage } from '../../web/synthesis/atlas.js';
import createTvfCore from '../../build-wasm/tvf_core.mjs';
import { flatSquareGlb } from '../node/export-fixtures.mjs';
import { Surface } from '../../web/geometry/surface.js';
import { defaultFeatureScale, defaultResolution, defaultTiles, shapeComplexity, shapeMeasures } from '../../web/synthesis/auto-settings.js';
import { seamIndirection } from '../../web/synthesis/seams.js';
import { icosphereOff } from '../icosphere.mjs';
import { surfacePointsAlongScreenLine, openDesignerPage, synthesisReadback } from './helpers.mjs';
import {
  colourAt,
  colourHistogram,
  coordinateCoherence,
  encodePng,
  exemplarImage,
  fieldAlignment,
  seamJumps,
  stripePeriods,
  histogramDistance,
  neighbourhoodEnergy,
  orientationError,
  randomCoordinates,
  stripeOrientation,
} from './synthesis-metrics.mjs';

const RESOLUTION = 256;
const FEATURE_SCALE = 2; // exemplar 64² with stripes every 16 px: a stripe period of 32 texels

// The face of the flat square containing (x, y).
function faceAt(mesh, x, y) {
  const P = mesh.positions, T = mesh.triangles;
  for (let f = 0; f < T.length / 3; f++) {
    const [a, b, c] = [0, 1, 2].map((k) => [P[3 * T[3 * f + k]], P[3 * T[3 * f + k] + 1]]);
    const d = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
    const l0 = ((b[1] - c[1]) * (x - c[0]) + (c[0] - b[0]) * (y - c[1])) / d;
    const l1 = ((c[1] - a[1]) * (x - c[0]) + (a[0] - c[0]) * (y - c[1])) / d;
    if (l0 >= 0 && l1 >= 0 && l0 + l1 <= 1) return f;
  }
  throw new Error(`no face at (${x}, ${y})`);
}

async function readback(page) {
  const names = ['coords', 'jacobian', 'colour', 'exemplar', 'cornerUVs'];
  const r = await synthesisReadback(page, names);
  return { ...r, ...Object.fromEntries(names.map((name) => [name, Array.from(r[name])])) };
}

// The face whose centroid is nearest to (x, y) (flat square).
function faceNear(mesh, x, y) {
  const P = mesh.positions, T = mesh.triangles;
  let best = -1, bd = Infinity;
  for (let f = 0; f < T.length / 3; f++) {
    const cx = (P[3 * T[3 * f]] + P[3 * T[3 * f + 1]] + P[3 * T[3 * f + 2]]) / 3;
    const cy = (P[3 * T[3 * f] + 1] + P[3 * T[3 * f + 1] + 1] + P[3 * T[3 * f + 2] + 1]) / 3;
    const d = Math.hypot(cx - x, cy - y);
    if (d < bd) (bd = d), (best = f);
  }
  return best;
}

function pngSize(bytes) {
  const b = Buffer.from(bytes);
  expect(b.subarray(0, 8).toString('hex')).toBe('89504e470d0a1a0a');
  return { width: b.readUInt32BE(16), height: b.readUInt32BE(20) };
}

// 1 per texel whose RGBA32F values differ between a and b.
function changedTexels(a, b) {
  const out = new Uint8Array(a.length / 4);
  for (let t = 0; t < out.length; t++) out[t] = [0, 1, 2, 3].some((k) => a[4 * t + k] !== b[4 * t + k]) ? 1 : 0;
  return out;
}

// Per texel, how far the field turned between two Jacobians of the same atlas (degrees; 0 outside the charts):
// the angle of the rotation J1 J0⁻¹ (each J = k [e1; e2] G, G the atlas's map: only the frame turns).
function fieldTurnDegrees(J0, J1) {
  const turn = new Float64Array(J0.length / 4);
  for (let t = 0; t < turn.length; t++) {
    const [a, b, c, d] = J0.subarray(4 * t, 4 * t + 4); // column-major: [[a, c], [b, d]]
    const det = a * d - b * c;
    if (det === 0) continue;
    const [p, q, r, u] = J1.subarray(4 * t, 4 * t + 4);
    const m00 = (p * d - r * b) / det, m01 = (r * a - p * c) / det;
    const m10 = (q * d - u * b) / det, m11 = (u * a - q * c) / det;
    turn[t] = (Math.abs(Math.atan2(m10 - m01, m00 + m11)) * 180) / Math.PI;
  }
  return turn;
}

// 1 within `radius` texels (a square) of any texel of the R x R grid whose value exceeds `above`.
function widenedMask(values, R, above, radius) {
  const out = new Uint8Array(R * R);
  for (let y = 0; y < R; y++)
    for (let x = 0; x < R; x++) {
      if (!(values[y * R + x] > above)) continue;
      for (let yy = Math.max(0, y - radius); yy <= Math.min(R - 1, y + radius); yy++)
        out.fill(1, yy * R + Math.max(0, x - radius), yy * R + Math.min(R - 1, x + radius) + 1);
    }
  return out;
}

// The texture read back (r) against the page's current field: the mean stripe error of fieldAlignment's windows
// and the patches' coherence.
async function textureAgainstField(page, r) {
  const R = r.resolution;
  const m = await page.evaluate(() => ({
    P: Array.from(window.tvf.mesh().positions),
    T: Array.from(window.tvf.mesh().triangles),
    vv: Array.from(window.tvf.vertexVectors()),
  }));
  const jumps = seamJumps(r.coords, r.jacobian, R, r.exemplar, r.exemplarSize, m.T, r.cornerUVs);
  const image = exemplarImage(r.coords, r.exemplar, r.exemplarSize);
  const windows = fieldAlignment(image, R, jumps.covered, m.P, m.T, r.cornerUVs, m.vv, { win: 16, step: 8 });
  return {
    windows: windows.length,
    meanErrorDegrees: windows.reduce((a, w) => a + w.errorDegrees, 0) / windows.length,
    coherence: coordinateCoherence(r.coords, r.jacobian, R, R, r.exemplarSize),
  };
}

// In the page: a vector constraint at the face under the view's point (x, y) (fractions of the view), asking for
// the field there turned by `degrees` in the face's plane, as long as it is. Resolves with its id.
function turnFieldAt(x, y, degrees = 90, weight = 1e4) {
  const view = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
  const rect = view.getBoundingClientRect();
  const { face } = window.tvf.pick(rect.left + x * rect.width, rect.top + y * rect.height);
  const { positions: P, triangles: T } = window.tvf.mesh(), vv = window.tvf.vertexVectors();
  const at = (a, k) => [0, 1, 2].map((d) => a[3 * k + d]);
  const [a, b, c] = [0, 1, 2].map((k) => T[3 * face + k]);
  const u = at(P, b).map((x, d) => x - at(P, a)[d]), w = at(P, c).map((x, d) => x - at(P, a)[d]);
  const m = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
  const n = m.map((x) => x / Math.hypot(...m));
  const v = [0, 1, 2].map((d) => (vv[3 * a + d] + vv[3 * b + d] + vv[3 * c + d]) / 3);
  const nv = [n[1] * v[2] - n[2] * v[1], n[2] * v[0] - n[0] * v[2], n[0] * v[1] - n[1] * v[0]];
  const t = (degrees * Math.PI) / 180;
  return window.tvf.addVector(face, v.map((x, d) => Math.cos(t) * x + Math.sin(t) * nv[d]), { weight });
}

test.describe.serial('texture synthesis on a flat square', () => {
  let page, errors, mesh;

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
    const glb = Array.from(flatSquareGlb(16));
    await page.evaluate((bytes) => window.tvf.loadModel(new Uint8Array(bytes), { name: 'flat-square.glb' }), glb);
    mesh = await page.evaluate(() => {
      const m = window.tvf.mesh();
      return { positions: Array.from(m.positions), triangles: Array.from(m.triangles) };
    });
    const exemplar = await page.evaluate(() => window.tvf.setExemplar('stripes'));
    expect(exemplar).toMatchObject({ label: 'stripes', size: 64 });
  });

  test.afterAll(async () => {
    await page?.close();
  });

  for (const theta of [0, 30, 60, 90]) {
    test(`stripes follow a constant field at ${theta}°`, async ({}, testInfo) => {
      const t = (theta * Math.PI) / 180;
      const face = faceAt(mesh, 0.5 + 1e-3, 0.5 + 2e-3);
      const design = { boundary: 'free', gamma: 0, constraints: [{ type: 'vector', face, vector: [Math.cos(t), Math.sin(t), 0], weight: 1e4 }] };
      await page.evaluate((d) => window.tvf.loadDesign(d), design);
      // The first angle switches the texture on; after that every field change resynthesizes by itself.
      const stats =
        theta === 0
          ? await page.evaluate((o) => window.tvf.synthesize(o), { resolution: RESOLUTION, featureScale: FEATURE_SCALE })
          : await page.evaluate(() => window.tvf.synthesisIdle());
      expect(stats.atlas.source).toBe('TEXCOORD_0');
      expect(stats.resolution).toBe(RESOLUTION);
      expect(stats.levels.length).toBeGreaterThanOrEqual(4);
      expect(stats.passes).toBeGreaterThanOrEqual(2);
      expect(stats.subpasses).toBeGreaterThanOrEqual(4);

      const r = await readback(page);
      const R = r.resolution, m = r.exemplarSize;
      const coords = Float32Array.from(r.coords), jac = Float32Array.from(r.jacobian), ex = Uint8Array.from(r.exemplar);
      // The image is made here from the coordinates (bilinear exemplar reads), not taken from the page.
      const image = exemplarImage(coords, ex, m);
      const orientation = stripeOrientation(image, R, R);
      const error = orientationError(orientation.degrees, theta);
      const coherence = coordinateCoherence(coords, jac, R, R, m);
      const random = randomCoordinates(coords, m);
      const energy = neighbourhoodEnergy(coords, jac, R, R, ex, m);
      const energyRandom = neighbourhoodEnergy(random, jac, R, R, ex, m);
      const hist = histogramDistance(colourHistogram(Uint8Array.from(r.colour)), colourHistogram(ex));
      const histRandom = histogramDistance(colourHistogram(colourAt(random, ex, m)), colourHistogram(ex));
      const report = {
        theta,
        stripeOrientation: +orientation.degrees.toFixed(2),
        errorDegrees: +error.toFixed(2),
        anisotropy: +orientation.anisotropy.toFixed(3),
        coherence: +coherence.toFixed(3),
        neighbourhoodEnergy: +energy.toFixed(1),
        neighbourhoodEnergyRandom: +energyRandom.toFixed(1),
        histogramDistance: +hist.toFixed(3),
        histogramDistanceRandom: +histRandom.toFixed(3),
        totalMs: Math.round(stats.totalMs),
        levels: stats.levels.map((l) => `${l.size}²/s${l.stackLevel}: ${Math.round(l.ms)} ms`),
      };
      console.log(JSON.stringify(report));
      writeFileSync(testInfo.outputPath(`stripes-${theta}.png`), encodePng(image, R, R));
      writeFileSync(testInfo.outputPath(`report-${theta}.json`), JSON.stringify(report, null, 1));
      await page.screenshot({ path: testInfo.outputPath(`page-${theta}.png`) });

      expect(error, 'stripe orientation vs field angle (degrees)').toBeLessThan(5);
      expect(orientation.anisotropy, 'a clearly oriented texture').toBeGreaterThan(0.8);
      expect(coherence, 'share of neighbour pairs with continuous coordinates').toBeGreaterThanOrEqual(0.6);
      // Random coordinates have the exemplar's colour histogram by construction (they sample it uniformly); what
      // they lose is structure: their neighbourhoods disagree with the exemplar's.
      expect(energy, 'neighbourhood energy vs. random coordinates').toBeLessThan(0.02 * energyRandom);
      expect(hist, 'colour histogram distance to the exemplar').toBeLessThan(0.2);
    });
  }

  test('magnitude-driven scale: larger features where the field is stronger', async ({}, testInfo) => {
    // Two vector constraints along +x, weak on the left and strong on the right: the magnitude grows with x.
    const design = {
      boundary: 'free',
      gamma: 0,
      constraints: [
        { type: 'vector', face: faceNear(mesh, 0.1, 0.5), vector: [0.5, 0, 0], weight: 1e4 },
        { type: 'vector', face: faceNear(mesh, 0.9, 0.5), vector: [2, 0, 0], weight: 1e4 },
      ],
    };
    await page.evaluate((d) => window.tvf.loadDesign(d), design);
    const field = await page.evaluate(() => ({ vv: Array.from(window.tvf.vertexVectors()), pos: Array.from(window.tvf.mesh().positions) }));
    const mags = [0, 0, 0, 0], counts = [0, 0, 0, 0];
    for (let v = 0; v < field.pos.length / 3; v++) {
      const q = Math.min(3, Math.floor(4 * field.pos[3 * v]));
      mags[q] += Math.hypot(field.vv[3 * v], field.vv[3 * v + 1], field.vv[3 * v + 2]);
      counts[q]++;
    }
    const magnitude = mags.map((m, q) => m / counts[q]);
    const periods = {};
    for (const exponent of [0, 1]) {
      await page.evaluate((o) => window.tvf.synthesize(o), { resolution: RESOLUTION, featureScale: 1, magnitudeExponent: exponent });
      const r = await readback(page);
      const image = exemplarImage(Float32Array.from(r.coords), Uint8Array.from(r.exemplar), r.exemplarSize);
      periods[exponent] = stripePeriods(image, r.resolution, r.resolution, 4);
      writeFileSync(testInfo.outputPath(`magnitude-exponent-${exponent}.png`), encodePng(image, r.resolution, r.resolution));
    }
    const report = { magnitudeByQuarter: magnitude.map((m) => +m.toFixed(3)), periodsExponent0: periods[0].map((p) => +p.toFixed(2)), periodsExponent1: periods[1].map((p) => +p.toFixed(2)) };
    console.log(JSON.stringify(report));
    writeFileSync(testInfo.outputPath('magnitude-report.json'), JSON.stringify(report, null, 1));
    for (let q = 1; q < 4; q++) expect(magnitude[q], 'the designed magnitude grows with x').toBeGreaterThan(magnitude[q - 1]);
    for (let q = 1; q < 4; q++) expect(periods[1][q], `stripe period, quarter ${q} vs ${q - 1}`).toBeGreaterThan(periods[1][q - 1]);
    expect(periods[1][3] / periods[1][0], 'period ratio across the square').toBeGreaterThan(1.5);
    expect(Math.max(...periods[0]) / Math.min(...periods[0]), 'direction only: one scale everywhere').toBeLessThan(1.3);
  });

  test('the field goes to the GPU a slice of faces per task: any slice gives the same texture', async () => {
    // The field changes between the runs with automatic updates off, so that a slice left unwritten would keep
    // the previous field's values and show.
    const design = { boundary: 'free', gamma: 0, constraints: [{ type: 'vector', face: faceNear(mesh, 0.5, 0.5), vector: [0.6, 0.8, 0], weight: 1e4 }] };
    const diff = await page.evaluate(async ({ R, design }) => {
      const run = async (extra) => {
        await window.tvf.synthesize({ resolution: R, featureScale: 1, magnitudeExponent: 1, ...extra });
        return window.tvf.synthesisReadback();
      };
      const before = await run({});
      window.tvf.setTextureAutoUpdate(false);
      await window.tvf.loadDesign(design);
      // 512 faces: the field in 19 slices of 28, the atlas's fixed data (sent once per atlas: a new one at R / 2,
      // then at R again) in 74 of 7, the last ones short.
      const whole = await run({ sliceFaces: 1 << 15 });
      await run({ resolution: R / 2, sliceFaces: 28 });
      const sliced = await run({ resolution: R, sliceFaces: 28 });
      await run({ sliceFaces: 1 << 15 });
      window.tvf.setTextureAutoUpdate(true);
      const count = (a, b) => a.reduce((n, v, k) => n + (v !== b[k]), 0);
      return {
        faces: window.tvf.mesh().triangles.length / 3,
        covered: whole.jacobian.reduce((n, v) => n + (v !== 0), 0),
        changed: count(before.jacobian, whole.jacobian),
        jacobian: count(whole.jacobian, sliced.jacobian),
        coords: count(whole.coords, sliced.coords),
      };
    }, { R: RESOLUTION, design });
    expect(diff.faces % 7 && diff.faces % 28).not.toBe(0);
    expect(diff.covered, 'the Jacobian covers the atlas').toBeGreaterThan(0.5 * RESOLUTION * RESOLUTION);
    expect(diff.changed, 'the new field changed the Jacobian').toBeGreaterThan(0.5 * RESOLUTION * RESOLUTION);
    expect(diff.jacobian, 'Jacobian texels that differ').toBe(0);
    expect(diff.coords, 'synthesized coordinates that differ').toBe(0);
    await expect(page.evaluate(() => window.tvf.synthesize({ sliceFaces: 0 }))).rejects.toThrow(/sliceFaces/);
  });

  test('exports: the atlas texture as PNG, the textured model in the one GLB that loads back with its UVs', async ({}, testInfo) => {
    const out = await page.evaluate(async () => {
      const png = await window.tvf.exportTexturePNG({ magnification: 2 });
      const glb = await window.tvf.exportGlb({ size: 256 });
      return { png: Array.from(new Uint8Array(await png.arrayBuffer())), pngType: png.type, glb: Array.from(glb) };
    });
    expect(out.pngType).toBe('image/png');
    expect(pngSize(out.png)).toEqual({ width: 2 * RESOLUTION, height: 2 * RESOLUTION });
    writeFileSync(testInfo.outputPath('texture.png'), Buffer.from(out.png));
    writeFileSync(testInfo.outputPath('textured.glb'), Buffer.from(out.glb));
    const glb = Buffer.from(out.glb);
    expect(glb.readUInt32LE(0)).toBe(0x46546c67);
    const json = JSON.parse(glb.subarray(20, 20 + glb.readUInt32LE(12)).toString('utf8'));
    const prim = json.meshes[0].primitives[0];
    expect(prim.attributes).toHaveProperty('TEXCOORD_0');
    expect(json.images[0].mimeType).toBe('image/png');
    expect(json.materials[0].pbrMetallicRoughness.baseColorTexture.index).toBe(0);
    expect(json.accessors[prim.indices].count).toBe(mesh.triangles.length);
    // Loaded back, its UVs are a valid atlas: synthesis runs in them instead of generating one.
    await page.evaluate((bytes) => window.tvf.loadModel(new Uint8Array(bytes), { name: 'textured.glb' }), out.glb);
    const info = await page.evaluate(() => window.tvf.info());
    expect(info.faces).toBe(mesh.triangles.length / 3);
    const stats = await page.evaluate(() => window.tvf.synthesize({ resolution: 64 }));
    expect(stats.atlas.source).toBe('TEXCOORD_0');
  });

  test('user image exemplar (PNG blob), and a readable error for a non-image', async () => {
    const r = await page.evaluate(async () => {
      // The weave pattern drawn on a canvas, as a PNG file a user would pick.
      const c = document.createElement('canvas');
      c.width = c.height = 96;
      const g = c.getContext('2d');
      for (let y = 0; y < 96; y += 8) for (let x = 0; x < 96; x += 8) {
        g.fillStyle = ((x + y) / 8) % 2 ? '#7a4a2a' : '#e0c090';
        g.fillRect(x, y, 8, 8);
      }
      const blob = await new Promise((res) => c.toBlob(res, 'image/png'));
      const info = await window.tvf.setExemplar(new File([blob], 'checker.png', { type: 'image/png' }), { size: 64 });
      let error = null;
      try {
        await window.tvf.setExemplar(new File([new Uint8Array([1, 2, 3])], 'broken.png', { type: 'image/png' }));
      } catch (err) {
        error = err.message;
      }
      const stats = await window.tvf.synthesize({ resolution: 64 });
      return { info, error, label: stats.exemplar.label };
    });
    expect(r.info).toMatchObject({ label: 'checker.png', size: 64 });
    expect(r.info.analysisMs).toBeGreaterThan(0);
    expect(r.error).toMatch(/broken\.png/);
    expect(r.label).toBe('checker.png');
  });

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});

test.describe.serial('texture synthesis on a curved model (the default bunny, generated atlas)', () => {
  let page, errors;

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
  });

  test.afterAll(async () => {
    await page?.close();
  });

  // Before any texture: the Texture panel's thumbnail already shows the exemplar a synthesis would use (the
  // default stripes), the same picture as once it is chosen explicitly.
  test('the exemplar thumbnail shows the default exemplar before the first synthesis', async () => {
    const thumbnail = () =>
      page.evaluate(() => {
        const c = document.querySelector('tangent-field-designer').shadowRoot.getElementById('tex-preview');
        return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);
      });
    const spread = (px) => {
      const grey = px.filter((_, i) => i % 4 === 0);
      const mean = grey.reduce((a, b) => a + b, 0) / grey.length;
      return Math.sqrt(grey.reduce((a, b) => a + (b - mean) ** 2, 0) / grey.length);
    };
    await expect.poll(async () => spread(await thumbnail()), { timeout: 20000 }).toBeGreaterThan(20);
    expect(await page.evaluate(() => window.tvf.synthesisStats())).toBeNull();
    const before = await thumbnail();
    await page.evaluate(() => window.tvf.setExemplar('stripes'));
    expect(await thumbnail()).toEqual(before);
  });

  test('stripes follow a stroke-designed field within 10°; seams continue across charts', async ({}, testInfo) => {
    // A stroke across the body, sampled from the surface under a horizontal screen line.
    const points = await surfacePointsAlongScreenLine(page, { x0: 0.38, dx: 0.012, y: 0.55, count: 20 });
    expect(points.length).toBeGreaterThan(10);
    await page.evaluate((pts) => window.tvf.addStroke(pts), points);
    await page.evaluate(() => window.tvf.setExemplar('stripes'));
    const base = await page.evaluate(() => {
      const m = window.tvf.mesh();
      return { positions: Array.from(m.positions), triangles: Array.from(m.triangles), vv: Array.from(window.tvf.vertexVectors()) };
    });
    const results = {};
    for (const seams of [false, true]) {
      const stats = await page.evaluate((o) => window.tvf.synthesize(o), { resolution: RESOLUTION, featureScale: 0.5, seams });
      expect(stats.atlas.source).toBe('generated');
      const r = await readback(page);
      const R = r.resolution, m = r.exemplarSize;
      const coords = Float32Array.from(r.coords), jac = Float32Array.from(r.jacobian), ex = Uint8Array.from(r.exemplar), uv = Float32Array.from(r.cornerUVs);
      const jumps = seamJumps(coords, jac, R, ex, m, base.triangles, uv);
      const image = exemplarImage(coords, ex, m);
      const windows = fieldAlignment(image, R, jumps.covered, base.positions, base.triangles, uv, base.vv, { win: 16, step: 8 });
      const errs = windows.map((w) => w.errorDegrees).sort((a, b) => a - b);
      results[seams ? 'seams' : 'noSeams'] = {
        totalMs: Math.round(stats.totalMs),
        charts: stats.atlas.charts,
        seamEdges: jumps.seamEdges,
        seamJump: +jumps.seam.toFixed(1),
        localVariation: +jumps.local.toFixed(1),
        windows: errs.length,
        meanErrorDegrees: +(errs.reduce((a, b) => a + b, 0) / errs.length).toFixed(2),
        medianErrorDegrees: +errs[errs.length >> 1].toFixed(2),
      };
      writeFileSync(testInfo.outputPath(`bunny-atlas-${seams ? 'seams' : 'no-seams'}.png`), encodePng(image, R, R));
      await page.evaluate(() => window.tvf.setViews({ arrows: false }));
      await page.screenshot({ path: testInfo.outputPath(`bunny-${seams ? 'seams' : 'no-seams'}.png`) });
    }
    console.log(JSON.stringify(results));
    writeFileSync(testInfo.outputPath('bunny-report.json'), JSON.stringify(results, null, 1));
    const { seams, noSeams } = results;
    expect(seams.windows, 'windows inside charts with clear stripes').toBeGreaterThanOrEqual(10);
    expect(seams.meanErrorDegrees, 'stripes vs field on the surface (mean over windows)').toBeLessThan(10);
    expect(seams.medianErrorDegrees).toBeLessThan(10);
    // Following the seam indirection makes the two sides of a seam one texture: the colour jump across seams
    // drops to the order of the colour change between neighbouring texels.
    expect(seams.seamJump, 'colour jump across seams, with vs. without indirection').toBeLessThan(0.5 * noSeams.seamJump);
    expect(seams.seamJump).toBeLessThan(2 * seams.localVariation);
  });

  // The Jacobian comes from the atlas's map of faces (drawn once) and one full-screen pass per field
  // (web/synthesis/atlas-raster.js). Checked against the field itself: at every texel centre inside a face, J from
  // the face's frame and its corners' field interpolated there (in double precision here); and a field sent in
  // slices that cross the per-corner textures' rows gives the same Jacobian as sent whole.
  test('the Jacobian is the field at each texel of its face, whole or sent in slices', async () => {
    const points = await surfacePointsAlongScreenLine(page, { x0: 0.4, dx: 0.012, y: 0.6, count: 16 });
    expect(points.length).toBeGreaterThan(4);
    const run = async (sliceFaces) => {
      // Whole runs: the Jacobian drawn for every face (a local run draws it only where the field moved).
      const o = { resolution: RESOLUTION, featureScale: 0.5, sliceFaces, localDegrees: 0 };
      await page.evaluate((o) => window.tvf.synthesize(o), o);
      return (await synthesisReadback(page, ['jacobian'])).jacobian;
    };
    const before = await run(1 << 17);
    await page.evaluate(() => window.tvf.setTextureAutoUpdate(false));
    await page.evaluate((pts) => window.tvf.addStroke(pts.slice().reverse()), points);
    const sliced = await run(1000); // 3,000 corners a slice: the 4,095-texel rows are crossed
    const whole = await run(1 << 17);
    await page.evaluate(() => window.tvf.setTextureAutoUpdate(true));
    const { cornerUVs } = await synthesisReadback(page, ['cornerUVs']);
    const m = await page.evaluate(() => {
      const mesh = window.tvf.mesh();
      return { P: Array.from(mesh.positions), T: Array.from(mesh.triangles), E: Array.from(window.tvf.edges()), w: Array.from(window.tvf.oneForm()) };
    });
    // A vector field's texture follows its Whitney reconstruction (Eq. 4): per face, sum over its edges i -> j of
    // the 1-form's value times b_i grad b_j - b_j grad b_i.
    const edgeOf = new Map();
    for (let e = 0; e < m.E.length / 2; e++) edgeOf.set(`${m.E[2 * e]},${m.E[2 * e + 1]}`, e);
    const oneFormAlong = (i, j) => (i < j ? m.w[edgeOf.get(`${i},${j}`)] : -m.w[edgeOf.get(`${j},${i}`)]);
    const count = (a, b) => a.reduce((n, v, k) => n + (v !== b[k]), 0);
    expect(m.T.length / 3, 'faces: more corners than one texture row holds').toBeGreaterThan(1365);
    expect(count(sliced, whole), 'Jacobian texels that differ, sliced against whole').toBe(0);
    expect(count(before, whole), 'the stroke changed the Jacobian').toBeGreaterThan(RESOLUTION * RESOLUTION);

    const R = RESOLUTION, sub = (a, b) => a.map((x, k) => x - b[k]), dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const at = (arr, i) => [arr[3 * i], arr[3 * i + 1], arr[3 * i + 2]];
    const pairs = []; // [GPU J, reference J with k = 1]
    for (let f = 0; f < m.T.length / 3; f++) {
      const uv = cornerUVs.subarray(6 * f, 6 * f + 6);
      const [a, b, c] = [0, 1, 2].map((k) => at(m.P, m.T[3 * f + k]));
      const du1 = uv[2] - uv[0], dv1 = uv[3] - uv[1], du2 = uv[4] - uv[0], dv2 = uv[5] - uv[1];
      const det = du1 * dv2 - du2 * dv1;
      const e1 = sub(b, a), e2 = sub(c, a);
      const G1 = [0, 1, 2].map((k) => (e1[k] * dv2 - e2[k] * dv1) / det);
      const G2 = [0, 1, 2].map((k) => (e2[k] * du1 - e1[k] * du2) / det);
      const nn = cross(e1, e2), n = nn.map((x) => x / Math.hypot(...nn)), n2 = dot(nn, nn);
      const corners = [a, b, c];
      const grad = [0, 1, 2].map((k) => cross(nn, sub(corners[(k + 2) % 3], corners[(k + 1) % 3])).map((x) => x / n2));
      const w = [0, 1, 2].map((k) => oneFormAlong(m.T[3 * f + k], m.T[3 * f + ((k + 1) % 3)]));
      const x0 = Math.floor(Math.min(uv[0], uv[2], uv[4]) * R), x1 = Math.ceil(Math.max(uv[0], uv[2], uv[4]) * R);
      const y0 = Math.floor(Math.min(uv[1], uv[3], uv[5]) * R), y1 = Math.ceil(Math.max(uv[1], uv[3], uv[5]) * R);
      for (let y = y0; y < y1; y++)
        for (let x = x0; x < x1; x++) {
          const pu = (x + 0.5) / R - uv[0], pv = (y + 0.5) / R - uv[1];
          const b1 = (pu * dv2 - du2 * pv) / det, b2 = (du1 * pv - pu * dv1) / det, b0 = 1 - b1 - b2;
          if (Math.min(b0, b1, b2) < 1e-3) continue; // on or near an edge: either face may own the texel
          const bary = [b0, b1, b2];
          const F = [0, 1, 2].map((d) =>
            [0, 1, 2].reduce((t, k) => t + w[k] * (bary[k] * grad[(k + 1) % 3][d] - bary[(k + 1) % 3] * grad[k][d]), 0));
          const v = F.map((x, k) => x - n[k] * dot(F, n)), mag = Math.hypot(...v);
          if (mag < 1e-6 * Math.hypot(...F) || mag === 0) continue;
          const u1 = v.map((x) => x / mag), u2 = cross(n, u1);
          const o = 4 * (y * R + x);
          pairs.push([whole.subarray(o, o + 4), [dot(u1, G1), dot(u2, G1), dot(u1, G2), dot(u2, G2)]]);
        }
    }
    expect(pairs.length, 'texels strictly inside faces').toBeGreaterThan(0.4 * R * R);
    // J = k [e1; e2] G with one k for the whole atlas (magnitude exponent 0): fitted, then every texel against it.
    const num = pairs.reduce((s, [g, r]) => s + g.reduce((t, x, i) => t + x * r[i], 0), 0);
    const k = num / pairs.reduce((s, [, r]) => s + r.reduce((t, x) => t + x * x, 0), 0);
    const rel = pairs.map(([g, r]) => Math.hypot(...g.map((x, i) => x - k * r[i])) / Math.hypot(...r.map((x) => k * x)));
    rel.sort((p, q) => p - q);
    const q = (p) => rel[Math.floor(p * (rel.length - 1))];
    console.log(JSON.stringify({ texels: rel.length, p50: q(0.5), p90: q(0.9), p99: q(0.99), p999: q(0.999), max: q(1) }));
    expect(q(0.5), 'relative difference from the reference, median').toBeLessThan(1e-3);
    expect(q(0.99), 'relative difference from the reference, 99th percentile').toBeLessThan(2e-2);
  });

  // A run after one with the same atlas, exemplar and options synthesizes again only the texels whose field moved
  // by more than localDegrees, and two texels round them (web/synthesis/local-update.js); the Jacobian itself is
  // drawn again only round the faces whose field turned by more than a quarter of it (raster-delta.js), the rest
  // left to the texels. Checked here against the Jacobians of whole runs before and after an edit: the field's turn
  // at each texel is the rotation J_after J_before⁻¹ (the atlas's map is the same), and a texel whose coordinates
  // stayed must have turned by at most the threshold; every texel two texels from any turned by more than a
  // quarter of it must have stayed, every texel turned clearly more must have been made again; the local run's
  // Jacobian is within a quarter of it of the whole one; and the texture follows the new field as a whole
  // synthesis does.
  test('after an edit only the texels whose field moved are synthesized again, the texture as good', async () => {
    await page.evaluate(() => window.tvf.setTextureAutoUpdate(false));
    // A design constrained over the whole body (strokes a little apart), in which an edit moves the field nearby.
    for (const y of [0.3, 0.38, 0.7, 0.76]) {
      const pts = await surfacePointsAlongScreenLine(page, { x0: 0.25, dx: 0.02, y, count: 20 });
      await page.evaluate((p) => window.tvf.addStroke(p), pts);
    }
    const opts = { resolution: RESOLUTION, featureScale: 0.5, seams: false };
    const synthesize = (o) => page.evaluate((o) => window.tvf.synthesize(o), o);
    const names = ['coords', 'jacobian', 'colour', 'exemplar', 'cornerUVs'];
    const whole = await synthesize({ ...opts, localDegrees: 0 });
    expect([whole.local, whole.localReason]).toEqual([false, 'off']);
    const before = await synthesisReadback(page, names);
    const same = await synthesize({ ...opts, localDegrees: 1 });
    expect(same.local, 'the same atlas, exemplar and options: a local run').toBe(true);
    const sum = (a) => a.reduce((n, v) => n + v, 0);
    const unchanged = changedTexels(before.coords, (await synthesisReadback(page, ['coords'])).coords);
    expect(sum(unchanged), 'texels made again with no field change').toBe(0);

    // One face on the back asked to turn its field by 10°: the field turns round it, less far away.
    await page.evaluate(`(${turnFieldAt})(0.5, 0.46, 10)`);
    const local = await synthesize(opts);
    expect(local.local).toBe(true);
    expect(local.localDrawnShare, 'the share of the finest level the passes were drawn over').toBeLessThan(0.9);
    const faces = await page.evaluate(() => window.tvf.mesh().triangles.length / 3);
    expect(local.raster.whole, 'the Jacobian drawn again round the faces that moved only').toBe(false);
    expect(local.raster.faces).toBeGreaterThan(0);
    expect(local.raster.faces, "faces whose Jacobian was kept").toBeLessThan(faces);
    const after = await synthesisReadback(page, names);
    const R = after.resolution;
    const localQuality = await textureAgainstField(page, after);
    await synthesize({ ...opts, localDegrees: 0 });
    const exact = await synthesisReadback(page, names);
    const wholeQuality = await textureAgainstField(page, exact);
    const rasterTurn = fieldTurnDegrees(after.jacobian, exact.jacobian);
    const rasterScale = after.jacobian.reduce((m, v, i) => Math.max(m, Math.abs(v - exact.jacobian[i]) /
      Math.max(1e-9, Math.hypot(...exact.jacobian.subarray(i & ~3, (i & ~3) + 4)))), 0);
    const turn = fieldTurnDegrees(before.jacobian, exact.jacobian);
    const redone = changedTexels(before.coords, after.coords);
    const near = widenedMask(turn, R, 0.24, 2);
    let keptTurned = 0, farRedone = 0, mustRedo = 0, redoneOfMust = 0, inside = 0, maxKeptTurn = 0;
    for (let t = 0; t < R * R; t++) {
      if (after.coords[4 * t + 3] === 0) continue;
      inside++;
      if (!redone[t]) maxKeptTurn = Math.max(maxKeptTurn, turn[t]);
      if (!redone[t] && turn[t] > 1.01) keptTurned++;
      if (redone[t] && !near[t]) farRedone++;
      if (turn[t] > 1.01) (mustRedo++, (redoneOfMust += redone[t]));
    }
    const share = sum(redone) / inside;
    const maxRasterTurn = Math.max(...rasterTurn);
    console.log(JSON.stringify({ inside, redoneShare: +share.toFixed(3), mustRedo, redoneOfMust, maxKeptTurn,
      rasterFaces: local.raster.faces, maxRasterTurn, rasterScale, drawnShare: local.localDrawnShare }));
    expect(maxRasterTurn, 'the local run\'s Jacobian against the whole one (degrees)').toBeLessThan(0.26);
    expect(rasterScale, 'the same, the largest difference relative to the Jacobian').toBeLessThan(0.01);
    expect(mustRedo, 'the edit turned the field by over 1° somewhere').toBeGreaterThan(0.02 * inside);
    expect(share, 'a share of the texels made again, not all').toBeLessThan(0.8);
    expect(keptTurned, 'texels kept although their field turned by over 1°').toBe(0);
    expect(farRedone, 'texels made again more than two texels from any whose field turned').toBe(0);
    expect(redoneOfMust / mustRedo, 'texels whose field turned by over 1° made again').toBeGreaterThan(0.99);

    // As good as a whole synthesis of the same field: the stripes against the field, and the patches' coherence.
    console.log(JSON.stringify({ localQuality, wholeQuality }));
    expect(localQuality.meanErrorDegrees).toBeLessThan(wholeQuality.meanErrorDegrees + 1);
    expect(localQuality.coherence).toBeGreaterThan(wholeQuality.coherence - 0.05);
    // Another seed is another texture: made whole.
    const reseeded = await synthesize({ ...opts, localDegrees: 1, seed: 7 });
    expect([reseeded.local, reseeded.localReason]).toEqual([false, 'first run of this atlas, exemplar and options']);
    await synthesize({ ...opts, seed: 1 });
    await page.evaluate(() => window.tvf.setTextureAutoUpdate(true));
  });

  // A run cancelled half-way by the next edit leaves the texels it had begun to the run after it: a level's moved
  // texels are flagged as never synthesized until the level is done (local-update.js). Checked exactly: an edit B
  // is made and undone (the texture made for each), then made again, and its run is cancelled in its finest level
  // by the undo. The runs after the undo must then make again what the first undo's run made, from the same
  // inputs, so the texture must be the one of that first undo; left half-made, the finest level's texels round B
  // would still be B's (a third of the texels differed so, with that flag left out). The field after the second undo equals the first one's to
  // round-off only (the factor's updates), which can move a coordinate across an exemplar pixel here and there.
  test('a run cancelled half-way by the next edit leaves no texel half-made', async () => {
    await page.evaluate(() => window.tvf.setTextureAutoUpdate(false));
    // A finer atlas than the other tests': with software GL a draw of its finest level is a slice of its own.
    const opts = { resolution: 2 * RESOLUTION, featureScale: 1, seams: false, localDegrees: 1 };
    const synthesize = (o) => page.evaluate((o) => window.tvf.synthesize(o), o);
    await synthesize(opts);
    await page.evaluate(`(${turnFieldAt})(0.45, 0.52)`);
    expect((await synthesize(opts)).local).toBe(true);
    await page.evaluate(() => window.tvf.undo());
    const undone = await synthesize(opts);
    const expected = (await synthesisReadback(page, ['coords'])).coords;

    await page.evaluate(() => window.tvf.setTextureAutoUpdate(true));
    const seen = await page.evaluate(`(async () => {
      const task = () => new Promise((resolve) => setTimeout(resolve, 0));
      await window.tvf.redo();
      let p = null;
      for (let k = 0; k < 100000 && !((p = window.tvf.synthesisProgress()) && p.fraction >= 0.3); k++) await task();
      await window.tvf.undo();
      await window.tvf.synthesisIdle();
      return p;
    })()`);
    const stats = await page.evaluate(() => window.tvf.synthesisStats());
    const differ = changedTexels(expected, (await synthesisReadback(page, ['coords'])).coords);
    const inside = expected.filter((_, i) => i % 4 === 3 && expected[i] !== 0).length;
    const share = differ.reduce((n, v) => n + v, 0) / inside;
    console.log(JSON.stringify({ seen, cancelled: stats.cancelledRuns, differShare: share }));
    expect(seen.preview, "the redo's run was a whole one").toBe(false);
    expect(stats.cancelledRuns.count).toBe(undone.cancelledRuns.count + 1);
    // The finest level's work is the last 72 % of a run's (its upsampling first).
    expect(stats.cancelledRuns.lastAt, "the redo's run cancelled in its finest level").toBeGreaterThan(0.28);
    expect(stats.cancelledRuns.lastAt).toBeLessThan(0.95);
    expect(stats.local).toBe(true);
    expect(share, 'texels that differ from the first undo').toBeLessThan(0.002);
  });

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});

// The atlas logic on its own (no page): when TEXCOORD_0 is used, and what the generated atlas guarantees.
test.describe('atlas choice and generation (node)', () => {
  const grid = (n) => {
    const positions = [], triangles = [], uv = [];
    for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) positions.push(i / n, j / n, 0);
    for (let j = 0; j < n; j++)
      for (let i = 0; i < n; i++) {
        const a = j * (n + 1) + i;
        for (const t of [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]) {
          triangles.push(...t);
          for (const v of t) uv.push(positions[3 * v], positions[3 * v + 1]);
        }
      }
    return { positions: Float64Array.from(positions), triangles: Int32Array.from(triangles), uv: Float32Array.from(uv) };
  };

  let Module;
  test.beforeAll(async () => {
    Module = await createTvfCore();
  });

  test('TEXCOORD_0 is used only when it is a non-overlapping atlas inside [0, 1]', () => {
    const g = grid(8);
    expect(checkAtlasUVs(Module, g.triangles, g.uv).ok).toBe(true);
    expect(checkAtlasUVs(Module, g.triangles, null).reason).toMatch(/no TEXCOORD_0/);
    const tiled = g.uv.map((x) => 4 * x); // a repeating texture layout
    expect(checkAtlasUVs(Module, g.triangles, tiled).reason).toMatch(/outside \[0, 1\]/);
    // Every quad on the same half square (a mirrored/stacked layout): each texel is claimed by 64 quads.
    const stacked = Float32Array.from({ length: g.uv.length }, (_, i) => 0.5 * [0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1][i % 12]);
    const r = checkAtlasUVs(Module, g.triangles, stacked);
    expect(r.ok).toBe(false);
    expect(r.reason).toMatch(/overlap/);
  });

  test('the generated atlas of the bunny: no overlaps, inside the square, seams indirected into charts', () => {
    const positions = Float64Array.from(bunny.positions.flat());
    const triangles = Int32Array.from(bunny.cells.flat());
    const { cornerUVs, stats } = generateAtlas(Module, positions, triangles, { resolution: 512, gutter: 2 });
    expect(stats.charts).toBeGreaterThan(5);
    expect(cornerUVs.every((x) => x >= 0 && x <= 1)).toBe(true);
    const check = checkAtlasUVs(Module, triangles, cornerUVs, { resolution: 512 });
    expect(check.ok).toBe(true);
    expect(check.stats.overlap).toBe(0);
    expect(check.stats.coverage).toBeGreaterThan(0.5);
    expect(stats.flippedFaces).toBe(0);
    const seams = seamIndirection({ positions, triangles }, cornerUVs, 256);
    expect(seams.seamEdges).toBeGreaterThan(100);
    const covered = rasterCoverage(cornerUVs, 256);
    let into = 0;
    for (let t = 0; t < 256 * 256; t++) {
      if (!seams.map[4 * t + 2]) continue;
      expect(covered[t], 'only texels outside every triangle are redirected').toBe(0);
      const x = Math.floor(seams.map[4 * t]), y = Math.floor(seams.map[4 * t + 1]);
      // The target (a point, in texels), or a texel next to it, lies inside a chart.
      let hit = false;
      for (let dy = -1; dy <= 1 && !hit; dy++) for (let dx = -1; dx <= 1; dx++) if (covered[Math.min(255, Math.max(0, y + dy)) * 256 + Math.min(255, Math.max(0, x + dx))]) hit = true;
      into += hit;
    }
    expect(into).toBeGreaterThan(0.98 * seams.redirected);
    console.log(JSON.stringify({ charts: stats.charts, coverage: +check.stats.coverage.toFixed(3), density: [stats.densityP05, stats.densityP95], ms: stats.ms, seamEdges: seams.seamEdges, redirected: seams.redirected }));
  });
});

// The default feature size follows the model's curvature (web/synthesis/auto-settings.js): checked against the analytic
// area-mean |mean curvature| of a sphere (1 / r) and of an open cylinder (1 / 2r).
test.describe('default feature size from the shape (node)', () => {
  const fromOff = (text) => {
    const lines = text.split('\n').filter((l) => l && !l.startsWith('#') && l !== 'OFF');
    const nv = Number(lines[0].split(' ')[0]);
    const positions = Float64Array.from(lines.slice(1, 1 + nv).flatMap((l) => l.split(' ').map(Number)));
    const triangles = Int32Array.from(lines.slice(1 + nv).flatMap((l) => l.split(' ').slice(1).map(Number)));
    return { positions, triangles };
  };
  const cylinder = (r, length, around, along) => {
    const positions = [], triangles = [];
    for (let j = 0; j <= along; j++)
      for (let i = 0; i < around; i++) {
        const a = (2 * Math.PI * i) / around;
        positions.push(r * Math.cos(a), r * Math.sin(a), (length * j) / along);
      }
    for (let j = 0; j < along; j++)
      for (let i = 0; i < around; i++) {
        const a = j * around + i, b = j * around + ((i + 1) % around);
        triangles.push(a, b, b + around, a, b + around, a + around);
      }
    return { positions: Float64Array.from(positions), triangles: Int32Array.from(triangles) };
  };

  test('shape complexity: sqrt(area) x mean |H| of a sphere and a cylinder, scale-free, 0 when flat', () => {
    const sphere = fromOff(icosphereOff(4));
    const complexity = (positions, triangles) => shapeComplexity(new Surface(positions, triangles, null));
    const s = complexity(sphere.positions, sphere.triangles);
    expect(Math.abs(s - Math.sqrt(4 * Math.PI))).toBeLessThan(0.01 * Math.sqrt(4 * Math.PI));
    expect(Math.abs(complexity(sphere.positions.map((x) => 37 * x), sphere.triangles) - s)).toBeLessThan(1e-9 * s);
    // Open cylinder, r = 0.1, length 4: H = 1 / (2r), area 2 pi r L.
    const c = cylinder(0.1, 4, 64, 400);
    const truth = Math.sqrt(2 * Math.PI * 0.1 * 4) / (2 * 0.1);
    expect(Math.abs(complexity(c.positions, c.triangles) - truth)).toBeLessThan(0.02 * truth);
    const flat = { positions: Float64Array.from([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]), triangles: Int32Array.from([0, 1, 2, 0, 2, 3]) };
    expect(complexity(flat.positions, flat.triangles)).toBe(0);
  });

  test("the facets' fold: the icosahedron's angle between every two faces, less on finer spheres", () => {
    const fold = (levels) => {
      const m = fromOff(icosphereOff(levels));
      return shapeMeasures(new Surface(m.positions, m.triangles, null)).foldDegrees;
    };
    // The regular icosahedron's faces meet at 138.19°: their normals 41.81° apart, on every edge.
    expect(fold(0)).toBeCloseTo(180 - (Math.acos(-Math.sqrt(5) / 3) * 180) / Math.PI, 9);
    // Each subdivision about halves the angle between neighbouring faces.
    expect(fold(3)).toBeLessThan(fold(2));
    expect(fold(3)).toBeGreaterThan(fold(2) / 2.5);
    const flat = { positions: Float64Array.from([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]), triangles: Int32Array.from([0, 1, 2, 0, 2, 3]) };
    expect(shapeMeasures(new Surface(flat.positions, flat.triangles, null)).foldDegrees).toBe(0);
  });

  test('a coarse curved model gets finer features where its facets fold sharply, on a larger atlas', () => {
    // Measured (docs/texture-synthesis.md): the default bunny (complexity 13.8, folds 11.1°), homer (18.3, 8.2°)
    // and lion-head-7000 (16.2, 9.0°) keep the curvature's tiles; refined_elephant-5500 (20.5, 12.5°) and
    // camel-6000 (24.7, 13.4°) get 40, on 2048².
    expect(defaultTiles(13.8, 11.1)).toBe(defaultTiles(13.8));
    expect(defaultTiles(18.3, 8.2)).toBe(defaultTiles(18.3));
    expect(defaultTiles(16.2, 9.0)).toBe(defaultTiles(16.2));
    expect(defaultTiles(20.5, 12.5)).toBe(40);
    expect(defaultTiles(24.7, 13.4)).toBe(40);
    expect(defaultTiles(18, 10)).toBeGreaterThan(defaultTiles(18));
    expect(defaultTiles(18, 10)).toBeLessThan(40);
    expect(defaultResolution(3674, 13.8, 11.1)).toBe(512);
    expect(defaultResolution(5500, 20.5, 12.5)).toBe(2048);
    // A big model is never taken past 1024² by its face count alone, nor by folds it does not have.
    expect(defaultResolution(800000, 19, 3.4)).toBe(1024);
    expect(defaultFeatureScale(2048, 0.62, 64, 20.5, 12.5)).toBeCloseTo((2048 * Math.sqrt(0.62)) / (40 * 64), 9);
  });

  test('more curved shapes get smaller features, within the tile and texel limits', () => {
    const fs = (complexity) => defaultFeatureScale(1024, 0.6, 64, complexity);
    // A sphere and the flat square keep 6 tiles across sqrt(area): R sqrt(coverage) / (6 m).
    expect(fs(3.5)).toBeCloseTo((1024 * Math.sqrt(0.6)) / (6 * 64), 9);
    expect(fs(0)).toBe(fs(3.5));
    expect(fs(14)).toBeLessThan(fs(10));
    expect(fs(18)).toBeLessThan(fs(14));
    // A thin tube (complexity 34) stops at 16 tiles; a small atlas keeps >= 0.625 texels per exemplar pixel.
    expect(fs(34)).toBeCloseTo(fs(60), 9);
    expect(fs(34)).toBeCloseTo((1024 * Math.sqrt(0.6)) / (16 * 64), 9);
    expect(defaultFeatureScale(256, 0.6, 64, 30)).toBe(0.625);
    // Whatever the exemplar's size, a tile of >= 40 texels: a 128-pixel exemplar may take 0.3125 texels per pixel
    // and so as many tiles as a 64-pixel one; a 16-pixel one needs 2.5.
    expect(defaultFeatureScale(256, 0.6, 128, 30)).toBe(40 / 128);
    expect(defaultFeatureScale(1024, 0.6, 128, 34) * 128).toBeCloseTo(fs(34) * 64, 9);
    expect(defaultFeatureScale(256, 0.6, 16, 30)).toBe(2.5);
  });

  test('the atlas resolution follows the face count, and the curvature where the face count gives too few texels', () => {
    // 16 texels per face at 60 % coverage: 3,674 faces 512², 9,856 faces 1024², capped at 1024².
    expect([3674, 9856, 60000, 800000].map((n) => defaultResolution(n))).toEqual([512, 1024, 1024, 1024]);
    // Curvature: a tile of 40 texels at 0.8 of the curvature's tiles, at 55 % coverage. The bunny (complexity
    // 13.8: 11.6 tiles) stays at 512²; a coarse model as curved as the elephant (19: 16 tiles) or a knotted tube
    // (34) gets 1024²; a small sphere's or square's 6 tiles (0.8 x 6 x 40 texels over 0.74) need 512², not 256².
    expect(defaultResolution(3674, 13.8)).toBe(512);
    expect(defaultResolution(5500, 19)).toBe(1024);
    expect(defaultResolution(5000, 34)).toBe(1024);
    expect(defaultResolution(1000)).toBe(256);
    expect(defaultResolution(1000, 3.5)).toBe(512);
    expect(defaultResolution(1000, 0)).toBe(512);
  });
});
