// Field-guided texture synthesis (web/synthesis/) end to end in the page, on a generated flat square with UVs
// (TEXCOORD_0 = (x, y)): a constant field at angle θ set through window.tvf, stripes synthesized on the GPU
// (software WebGL here: atlases stay at 256²), read back and measured in the test process
// (tests/e2e/synthesis-metrics.mjs): stripe orientation from the structure tensor, coordinate coherence,
// neighbourhood energy and colour histograms against a random-coordinates baseline.
import { writeFileSync } from 'node:fs';
import { expect, test } from '@playwright/test';
import { flatSquareGlb } from '../../web/synthesis/glb.js';
import { openDesigner, trackErrors } from './helpers.mjs';
import {
  colourAt,
  colourHistogram,
  coordinateCoherence,
  encodePng,
  exemplarImage,
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
  return page.evaluate(async () => {
    const r = await window.tvf.synthesisReadback();
    return { ...r, coords: Array.from(r.coords), jacobian: Array.from(r.jacobian), colour: Array.from(r.colour), exemplar: Array.from(r.exemplar), cornerUVs: [] };
  });
}

test.describe.serial('texture synthesis on a flat square', () => {
  let page, errors, mesh;

  test.beforeAll(async ({ browser }) => {
    page = await browser.newPage();
    errors = trackErrors(page);
    await openDesigner(page);
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

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});
