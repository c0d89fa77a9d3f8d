// The Hodge decomposition c = dα + δβ + h (Eq. 3) of the page's field (tvf.hodge(), the worker's `hodge` and
// `component` ops), checked against independent truth: the parts' sum, their orthogonality, curl and
// divergence computed here from the mesh and the arrays the page hands out; the known answers on a sphere (a
// source and a sink make an exact field, a vortex pair a coexact one, and a sphere has no harmonic fields); and
// the native CLI's `tvf design … --hodge` of the page's saved design. One page for the file; the tests run in
// order.
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { openDesignerPage, readMesh, relativeDifference, topFacePair } from './helpers.mjs';
import { icosphereOff } from '../icosphere.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const TVF = resolve(ROOT, 'build/tvf');
const BUNNY_GLB = resolve(ROOT, 'dist/models/bunny.glb');
const PARTS = ['exact', 'coexact', 'harmonic'];

const dotP = (P, a, b) => {
  let s = 0;
  for (let e = 0; e < P.length; e++) s += P[e] * a[e] * b[e];
  return s;
};
const norm2 = (a) => Math.sqrt(a.reduce((s, x) => s + x * x, 0));
const maxAbs = (a) => a.reduce((m, x) => Math.max(m, Math.abs(x)), 0);

// The discrete exterior derivatives from the core's edge list (2 vertices per edge, oriented lower → higher):
// curl per face (d1 c: the signed sum around the face) and divergence per vertex (d0ᵀ P c).
function edgeIndex(edges) {
  const index = new Map();
  for (let e = 0; e < edges.length / 2; e++) index.set(`${edges[2 * e]},${edges[2 * e + 1]}`, e);
  return index;
}
function curl(mesh, index, c) {
  const out = [];
  for (let f = 0; f < mesh.triangles.length / 3; f++) {
    let s = 0;
    for (let k = 0; k < 3; k++) {
      const i = mesh.triangles[3 * f + k], j = mesh.triangles[3 * f + ((k + 1) % 3)];
      const e = index.get(i < j ? `${i},${j}` : `${j},${i}`);
      s += i < j ? c[e] : -c[e];
    }
    out.push(s);
  }
  return out;
}
// sign: -1 at an edge's first vertex, +1 at its second; absolute: the sum of |P c| instead (the scale).
function divergence(mesh, P, c, absolute = false) {
  const out = new Array(mesh.positions.length / 3).fill(0);
  for (let e = 0; e < P.length; e++) {
    const x = P[e] * c[e];
    out[mesh.edges[2 * e]] += absolute ? Math.abs(x) : -x;
    out[mesh.edges[2 * e + 1]] += absolute ? Math.abs(x) : x;
  }
  return out;
}

test.describe.serial('the Hodge decomposition of the page\'s field', () => {
  let page, errors, mesh;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  // The decomposition and the field as plain arrays.
  const readHodge = () =>
    evaluate(async () => {
      const h = await window.tvf.hodge();
      const plain = {};
      for (const [k, v] of Object.entries(h)) plain[k] = ArrayBuffer.isView(v) ? Array.from(v) : v;
      plain.oneForm = Array.from(window.tvf.oneForm());
      plain.solveMs = window.tvf.stats().solveMs;
      return plain;
    });
  const readComponent = (name) =>
    evaluate(async (name) => {
      const c = await window.tvf.debugComponent(name);
      return { oneForm: Array.from(c.oneForm), faceVectors: Array.from(c.faceVectors), vertexVectors: Array.from(c.vertexVectors) };
    }, name);

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
    mesh = await readMesh(page);
  });
  test.afterAll(async () => {
    await page?.close();
  });

  let bunny; // the bunny's decomposition, for the CLI comparison
  test('bunny with a stroke, a vortex and a source: the parts sum to the field and are orthogonal', async ({}, testInfo) => {
    await evaluate(() => window.tvf.loadDesign({ boundary: 'free', gamma: 0, constraints: [] }));
    const [f0, f1] = topFacePair(mesh);
    await evaluate(([f0, f1]) => window.tvf.addStroke([{ face: f0, bary: [0.2, 0.3, 0.5] }, { face: f1, bary: [0.5, 0.3, 0.2] }]), [f0, f1]);
    const nF = mesh.triangles.length / 3, nV = mesh.positions.length / 3;
    await evaluate((f) => window.tvf.addVortex(f, { strength: 2 }), Math.floor(nF / 3));
    await evaluate((v) => window.tvf.addSource(v, { strength: 1.5 }), Math.floor((2 * nV) / 3));
    const h = await readHodge();
    bunny = h;
    const c = h.oneForm, P = h.innerProduct, nE = mesh.edges.length / 2;
    for (const k of [...PARTS, 'innerProduct']) expect(h[k].length, k).toBe(nE);
    expect(h.potential0.length).toBe(nV);
    expect(h.potential2.length).toBe(nF);
    expect(P.every((w) => w > 0)).toBe(true);
    expect(['star1', 'whitney-mass']).toContain(h.metric);

    // c = dα + δβ + h, edge by edge.
    const sum = c.map((_, e) => h.exact[e] + h.coexact[e] + h.harmonic[e]);
    expect(relativeDifference(sum, c)).toBeLessThanOrEqual(1e-10);
    // Pairwise orthogonal in the inner product, relative to |c|².
    const cc = dotP(P, c, c);
    expect(cc).toBeGreaterThan(0);
    for (const [a, b] of [['exact', 'coexact'], ['exact', 'harmonic'], ['coexact', 'harmonic']])
      expect(Math.abs(dotP(P, h[a], h[b])) / cc, `<${a}, ${b}>`).toBeLessThanOrEqual(1e-10);
    // Each part is a real part of this field, not zero: the design has a curl-free and a divergence-free source.
    expect(dotP(P, h.exact, h.exact) / cc).toBeGreaterThan(1e-3);
    expect(dotP(P, h.coexact, h.coexact) / cc).toBeGreaterThan(1e-3);
    // The shares as computed here from the arrays.
    for (const k of PARTS) expect(Math.abs(h.energyShares[k] - dotP(P, h[k], h[k]) / cc), k).toBeLessThanOrEqual(1e-12);
    expect(Math.abs(h.energyShares.exact + h.energyShares.coexact + h.energyShares.harmonic - 1)).toBeLessThanOrEqual(1e-10);

    // exact = d0 α is curl-free; coexact is divergence-free in P; the potentials give the parts.
    const index = edgeIndex(mesh.edges);
    expect(maxAbs(curl(mesh, index, h.exact)) / maxAbs(c)).toBeLessThanOrEqual(1e-10);
    expect(maxAbs(divergence(mesh, P, h.coexact)) / maxAbs(divergence(mesh, P, c, true))).toBeLessThanOrEqual(1e-10);
    const dAlpha = h.exact.map((_, e) => h.potential0[mesh.edges[2 * e + 1]] - h.potential0[mesh.edges[2 * e]]);
    expect(relativeDifference(dAlpha, h.exact)).toBeLessThanOrEqual(1e-10);
    // The harmonic part is both (up to the solves' round-off).
    expect(maxAbs(curl(mesh, index, h.harmonic)) / maxAbs(c)).toBeLessThanOrEqual(1e-8);

    testInfo.annotations.push({ type: 'decomposeMs', description: `bunny ${nE} edges: decomposeMs ${h.decomposeMs.toFixed(1)} (solveMs of the last edit ${h.solveMs?.toFixed?.(1)})` });
    console.log(`hodge on the bunny (${nV} vertices, ${nE} edges, ${nF} faces): decomposeMs ${h.decomposeMs.toFixed(1)} ms, metric ${h.metric}; last edit's solveMs ${h.solveMs}`);

    // Asked again for the same field: the worker's kept decomposition (the same numbers, no new solve).
    const again = await readHodge();
    expect(again.decomposeMs).toBe(h.decomposeMs);
    for (const k of PARTS) expect(relativeDifference(again[k], h[k]), k).toBe(0);
    expect(errors).toEqual([]);
  });

  test('the component op: the parts as the worker hands them to the views', async () => {
    const h = bunny;
    const whole = await readComponent('whole');
    const field = await evaluate(() => ({
      oneForm: Array.from(window.tvf.oneForm()),
      faceVectors: Array.from(window.tvf.faceVectors()),
      vertexVectors: Array.from(window.tvf.vertexVectors()),
    }));
    for (const k of ['oneForm', 'faceVectors', 'vertexVectors']) expect(relativeDifference(whole[k], field[k]), k).toBe(0);
    const parts = {};
    for (const name of PARTS) {
      parts[name] = await readComponent(name);
      expect(parts[name].oneForm).toEqual(h[name]); // exactly the decomposition's part
      expect(parts[name].faceVectors.length).toBe(field.faceVectors.length);
      expect(parts[name].vertexVectors.length).toBe(field.vertexVectors.length);
    }
    // The reconstruction is linear: the parts' vectors sum to the field's.
    for (const k of ['faceVectors', 'vertexVectors']) {
      const sum = field[k].map((_, i) => parts.exact[k][i] + parts.coexact[k][i] + parts.harmonic[k][i]);
      expect(relativeDifference(sum, field[k]), k).toBeLessThanOrEqual(1e-10);
    }
    const message = await evaluate(() => window.tvf.debugComponent('curl').then(() => '', (err) => err.message));
    expect(message).toMatch(/unknown component "curl"/);
    expect(errors).toEqual([]);
  });

  test('an edit drops the kept decomposition: the next one is of the new field', async () => {
    const before = bunny;
    await evaluate(() => window.tvf.addSink(0, { strength: 1.5 }));
    const h = await readHodge();
    expect(relativeDifference(h.oneForm, before.oneForm)).toBeGreaterThan(1e-6);
    const sum = h.oneForm.map((_, e) => h.exact[e] + h.coexact[e] + h.harmonic[e]);
    expect(relativeDifference(sum, h.oneForm)).toBeLessThanOrEqual(1e-10);
    expect(relativeDifference(h.exact, before.exact)).toBeGreaterThan(1e-6);
    // Undo: the first field again, decomposed again (the same numbers).
    await evaluate(() => window.tvf.undo());
    const back = await readHodge();
    // (Relative to |c|: the harmonic part is round-off here.)
    for (const k of PARTS) expect(norm2(back[k].map((x, e) => x - before[k][e])) / norm2(before.oneForm), k).toBeLessThanOrEqual(1e-9);
  });

  test('page ↔ CLI: `tvf design … --hodge` of the saved design gives the same parts', async ({}, testInfo) => {
    test.skip(!existsSync(TVF), 'the native CLI is not built (npm run build:native)');
    const h = bunny;
    const designPath = testInfo.outputPath('bunny.design.json');
    const fieldPath = testInfo.outputPath('bunny.field.json');
    writeFileSync(designPath, JSON.stringify(await evaluate(() => window.tvf.saveDesign())));
    execFileSync(TVF, ['design', BUNNY_GLB, designPath, '-o', fieldPath, '--hodge'], { stdio: 'pipe' });
    const cli = JSON.parse(readFileSync(fieldPath, 'utf8'));
    expect(relativeDifference(h.oneForm, cli.oneForm)).toBeLessThanOrEqual(1e-9);
    const scale = norm2(cli.oneForm);
    for (const k of PARTS) {
      const diff = norm2(h[k].map((x, e) => x - cli.hodge[k][e]));
      expect(diff / scale, k).toBeLessThanOrEqual(1e-9);
    }
    expect(h.metric).toBe(cli.hodge.metric);
    for (const k of PARTS) expect(Math.abs(h.energyShares[k] - cli.hodge.energyShares[k]), k).toBeLessThanOrEqual(1e-9);
  });

  test('on a sphere: a source and a sink make an exact field, a vortex pair a coexact one, nothing harmonic', async () => {
    const message = await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'ico.off', restore: false })
      .then(() => '', (err) => err.message), icosphereOff(3));
    expect(message).toBe('');
    const sphere = await readMesh(page);
    const nV = sphere.positions.length / 3, nF = sphere.triangles.length / 3;
    // Opposite points: vertex 0 and the vertex farthest from it; face 0 and the face farthest from it.
    const far = (n, point) => {
      let best = 0, bestD = -1;
      for (let i = 0; i < n; i++) {
        const d = point(i).reduce((s, x, k) => s + (x - point(0)[k]) ** 2, 0);
        if (d > bestD) (bestD = d), (best = i);
      }
      return best;
    };
    const vertexAt = (v) => sphere.positions.slice(3 * v, 3 * v + 3);
    const faceAt = (f) => [0, 1, 2].map((k) => [0, 1, 2].reduce((s, c) => s + sphere.positions[3 * sphere.triangles[3 * f + c] + k], 0) / 3);
    const designs = {
      exact: [{ type: 'source', vertex: 0, strength: 1 }, { type: 'sink', vertex: far(nV, vertexAt), strength: 1 }],
      coexact: [{ type: 'vortex', face: 0, strength: 1 }, { type: 'vortex', face: far(nF, faceAt), strength: -1 }],
    };
    for (const [kind, constraints] of Object.entries(designs)) {
      await evaluate((d) => window.tvf.loadDesign(d), { boundary: 'free', gamma: 0, constraints });
      const h = await readHodge();
      const other = kind === 'exact' ? 'coexact' : 'exact';
      expect(h.energyShares[kind], kind).toBeGreaterThanOrEqual(1 - 1e-8);
      expect(h.energyShares[other], `${kind}: ${other}`).toBeLessThanOrEqual(1e-8);
      expect(h.energyShares.harmonic, `${kind}: harmonic`).toBeLessThanOrEqual(1e-8);
      expect(norm2(h.harmonic) / norm2(h.oneForm), `${kind}: |h| / |c|`).toBeLessThanOrEqual(1e-10);
      expect(relativeDifference(h[kind], h.oneForm), kind).toBeLessThanOrEqual(1e-3);
    }
    expect(errors).toEqual([]);
  });
});
