// Line and cross fields (symmetry N ≥ 2) in the page, against the real wasm core in its worker: the Field
// panel's Symmetry selector and the element's `symmetry` attribute agree; a stroke on a line field gives unit
// representatives and singularities in halves that sum to the Euler characteristic (checked here from the
// arrays the page hands out, and against the core's own read-out); the core refuses a source at N = 2; a switch
// with a source present removes it in one announced step and undo brings it back under its id; the curvature
// alignment goes with even N only; texture synthesis and the exports refuse a line field for now. One page for
// the file (the default model, closed); the tests run in order.
import { mkdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test } from '@playwright/test';
import { dot, faceNormal, norm, openDesignerPage, readMesh, sub, surfacePoint, topFacePair } from './helpers.mjs';

const EMPTY = { boundary: 'free', gamma: 0, constraints: [] };
const EPS = 1e-9;
const PICTURES = resolve(dirname(fileURLToPath(import.meta.url)), '../../test-results/symmetry');

test.describe.serial('line and cross fields', () => {
  let page, errors, mesh, info, stroke;

  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const settings = () => evaluate(() => window.tvf.settings());
  const constraints = () => evaluate(() => window.tvf.constraints());
  const symmetryAttribute = () => evaluate(() => document.querySelector('tangent-field-designer').getAttribute('symmetry'));
  const selector = () => page.locator('#symmetry');
  // The message a promise made in the page rejects with ('' when it resolves).
  const rejection = (request) => evaluate(({ name, args }) => window.tvf[name](...args).then(() => '', (err) => err.message), request);
  const call = (name, ...args) => ({ name, args });

  // The selector, the attribute, the property and the core's stats all say N.
  async function expectSymmetry(n) {
    await expect.poll(async () => (await settings()).symmetry).toBe(n);
    await expect(selector()).toHaveValue(String(n));
    expect(await symmetryAttribute()).toBe(String(n));
    expect(await evaluate(() => document.querySelector('tangent-field-designer').symmetry)).toBe(n);
    expect(await evaluate(() => window.tvf.stats().symmetry)).toBe(n);
  }

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
    mesh = await readMesh(page);
    info = await evaluate(() => window.tvf.info());
  });
  test.afterAll(async () => {
    await page?.close();
  });

  test('the Symmetry selector makes a line field; the attribute, settings() and the point tools follow', async () => {
    expect(info.boundaryLoops, 'the default model is closed (the index sum below needs it)').toBe(0);
    await evaluate((d) => window.tvf.loadDesign(d), EMPTY);
    await expect(selector()).toHaveValue('1');
    await expect(page.locator('[data-tool="source"]')).toBeEnabled();
    await selector().selectOption('2');
    await expectSymmetry(2);
    expect(await settings()).toEqual({ boundary: 'free', gamma: 0, symmetry: 2, curvatureAlignment: 0,
      exactSingularities: false });
    for (const tool of ['source', 'sink', 'vortex']) {
      await expect(page.locator(`[data-tool="${tool}"]`)).toBeDisabled();
      await expect(page.locator(`[data-tool="${tool}"]`)).toHaveAttribute('title', /not for a line field/);
    }
    await expect(page.locator('[data-tool="stroke"]')).toBeEnabled();
    expect(await evaluate(() => window.tvf.saveDesign().symmetry)).toBe(2);
    expect(errors).toEqual([]);
  });

  test('a stroke on a line field: unit representatives along it, singularities in halves summing to χ', async () => {
    const [f0, f1] = topFacePair(mesh);
    stroke = [{ face: f0, bary: [0.2, 0.3, 0.5] }, { face: f1, bary: [0.5, 0.3, 0.2] }];
    await evaluate((points) => window.tvf.addStroke(points), stroke);
    const F = await evaluate(() => Array.from(window.tvf.faceVectors()));
    const nF = mesh.triangles.length / 3;
    expect(F.length).toBe(3 * nF);
    let worstLength = 0, worstNormal = 0;
    for (let f = 0; f < nF; f++) {
      const v = [F[3 * f], F[3 * f + 1], F[3 * f + 2]];
      worstLength = Math.max(worstLength, Math.abs(norm(v) - 1));
      worstNormal = Math.max(worstNormal, Math.abs(dot(v, faceNormal(mesh, f))));
    }
    expect(worstLength, 'every face vector is a unit representative').toBeLessThan(1e-6);
    expect(worstNormal, 'and tangent to its face').toBeLessThan(1e-6);
    // In the first face the line is the stroke's, with either sign.
    const heading = sub(surfacePoint(mesh, stroke[1]), surfacePoint(mesh, stroke[0]));
    const n0 = faceNormal(mesh, f0);
    const inPlane = sub(heading, n0.map((x) => x * dot(heading, n0)));
    const rep = [F[3 * f0], F[3 * f0 + 1], F[3 * f0 + 2]];
    expect(Math.abs(dot(rep, inPlane)) / norm(inPlane), '|cos| between the line and the stroke').toBeGreaterThan(0.95);

    const onPage = await evaluate(() => window.tvf.singularities());
    const core = (await evaluate(() => window.tvf.debugCoreReadout())).singularities;
    for (const { index } of onPage) expect(Math.abs(2 * index - Math.round(2 * index)), `index ${index} is a multiple of 1/2`).toBeLessThan(EPS);
    const sum = onPage.reduce((s, x) => s + x.index, 0);
    expect(Math.abs(sum - info.eulerCharacteristic), `Σ index = ${sum}, χ = ${info.eulerCharacteristic}`).toBeLessThan(EPS);
    const byVertex = (list) => [...list].sort((a, b) => a.vertex - b.vertex).map(({ vertex, index }) => [vertex, index]);
    expect(byVertex(onPage), "the page's singularities are the core's").toEqual(byVertex(core));
    expect(errors).toEqual([]);
  });

  test("a source at N = 2 is refused with the core's message, and nothing changes", async () => {
    const before = await constraints();
    const history = await evaluate(() => window.tvf.history());
    const message = await rejection(call('addSource', 0));
    expect(message).toMatch(/source/i);
    expect(message).toMatch(/vector/i);
    expect(await rejection(call('addVortex', 0))).toMatch(/vort/i);
    expect(await constraints()).toEqual(before);
    expect(await evaluate(() => window.tvf.history())).toEqual(history);
  });

  test('switching to Line with a source removes it in one announced step; undo brings it back; selector and attribute agree', async () => {
    await selector().selectOption('1');
    await expectSymmetry(1);
    const source = await evaluate(() => window.tvf.addSource(3, { strength: 2 }));
    const before = await constraints();
    expect(before.map((c) => c.type)).toEqual(['stroke', 'source']);

    await selector().selectOption('2');
    await expectSymmetry(2);
    expect(await constraints()).toEqual(before.filter((c) => c.type !== 'source'));
    await expect(page.locator('#status')).toHaveText('Line field: removed 1 source (undo restores it)');
    expect((await evaluate(() => window.tvf.history())).undo.at(-1)).toBe('symmetry: Line');

    expect(await evaluate(() => window.tvf.undo())).toBe(true);
    await expectSymmetry(1);
    expect(await constraints(), 'the source is back under its id, with its spec').toEqual(before);
    await expect(page.locator('[data-tool="source"]')).toBeEnabled();

    expect(await evaluate(() => window.tvf.redo())).toBe(true);
    await expectSymmetry(2);
    expect(await evaluate(() => window.tvf.undo())).toBe(true);
    await expectSymmetry(1);

    // The attribute works the same way (a cross field), and so does the API, which returns what it removed.
    await evaluate(() => document.querySelector('tangent-field-designer').setAttribute('symmetry', '4'));
    await expectSymmetry(4);
    expect((await constraints()).map((c) => c.type)).toEqual(['stroke']);
    await evaluate(() => window.tvf.undo());
    await expectSymmetry(1);
    const removed = await evaluate(() => window.tvf.setSymmetry(2));
    expect(removed).toEqual(before.filter((c) => c.id === source));
    await expectSymmetry(2);
    await evaluate(() => window.tvf.undo());
    await expectSymmetry(1);
    expect(await constraints()).toEqual(before);

    // An N the selector has no name for shows as such.
    await evaluate(() => window.tvf.setSymmetry(3));
    await expectSymmetry(3);
    await expect(page.locator('#symmetry option:checked')).toHaveText('N = 3');
    await evaluate(() => window.tvf.undo());
    await expectSymmetry(1);
    expect(errors).toEqual([]);
  });

  test('curvature alignment: even N only; off with an odd N in the same step, back with undo', async () => {
    await evaluate(() => window.tvf.loadDesign({ boundary: 'free', gamma: 0, constraints: [] }));
    await expect(page.locator('#curvature-align')).toBeDisabled();
    expect(await rejection(call('setCurvatureAlignment', 1))).not.toBe('');
    await selector().selectOption('4');
    await expectSymmetry(4);
    const plain = await evaluate(() => Array.from(window.tvf.faceVectors()));
    await expect(page.locator('#curvature-align')).toBeEnabled();
    await page.locator('#curvature-align').check();
    await expect.poll(async () => (await settings()).curvatureAlignment).toBe(1);
    expect(await evaluate(() => document.querySelector('tangent-field-designer').getAttribute('curvature-alignment'))).toBe('1');
    const aligned = await evaluate(() => Array.from(window.tvf.faceVectors()));
    expect(aligned.some((x, k) => Math.abs(x - plain[k]) > 1e-6), 'the alignment changes the field').toBe(true);

    await selector().selectOption('1');
    await expectSymmetry(1);
    expect((await settings()).curvatureAlignment).toBe(0);
    await expect(page.locator('#status')).toHaveText('Vector field: turned curvature alignment off (undo restores it)');
    await evaluate(() => window.tvf.undo());
    await expectSymmetry(4);
    expect((await settings()).curvatureAlignment).toBe(1);
    await expect(page.locator('#curvature-align')).toBeChecked();
    expect(errors).toEqual([]);
  });

  test('a line field exports as an anisotropy GLB and a cross-field file; texture synthesis refuses N = 3 by name', async () => {
    await evaluate(() => window.tvf.setSymmetry(2));
    await expectSymmetry(2);
    await expect(page.locator('#export-glb')).toHaveText('Anisotropy GLB');
    // (The Export section may be folded: the button's own hidden flag is what the symmetry sets.)
    expect(await page.locator('#export-rawfield').evaluate((b) => b.hidden)).toBe(false);
    const glb = await evaluate(() => window.tvf.exportGlb({ texture: false, size: 64 }).then((bytes) => {
      const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
      return JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + view.getUint32(12, true))));
    }));
    expect(glb.extensionsUsed).toContain('KHR_materials_anisotropy');
    expect(glb.meshes[0].primitives[0].attributes._FIELD).toBeDefined();
    expect(glb.extras.tangentFieldDesigner.design.symmetry).toBe(2);
    const faces = (await evaluate(() => window.tvf.info())).faces;
    const raw = await evaluate(() => window.tvf.exportRawField());
    const lines = raw.trim().split('\n');
    expect(lines[0]).toBe(`2 ${faces}`);
    expect(lines.length).toBe(faces + 1);
    // Each face's two directions are opposite unit vectors, the first the page's own representative.
    const fv = await evaluate(() => Array.from(window.tvf.faceVectors()));
    for (const f of [0, 7, faces - 1]) {
      const [x0, y0, z0, x1, y1, z1] = lines[f + 1].split(' ').map(Number);
      expect(Math.hypot(x0, y0, z0)).toBeCloseTo(1, 9);
      expect(Math.hypot(x0 + x1, y0 + y1, z0 + z1)).toBeLessThan(1e-9);
      expect(Math.hypot(x0 - fv[3 * f], y0 - fv[3 * f + 1], z0 - fv[3 * f + 2])).toBeLessThan(1e-9);
    }
    expect((await evaluate(() => window.tvf.exportFlowMap({ size: 64 }))).length ?? 1).toBeGreaterThan(0);

    await evaluate(() => window.tvf.setSymmetry(3));
    await expectSymmetry(3);
    expect(await rejection(call('synthesize'))).toMatch(/symmetry 3/);

    await evaluate(() => window.tvf.setSymmetry(1));
    await expectSymmetry(1);
    await expect(page.locator('#export-glb')).toHaveText('GLB');
    expect(await page.locator('#export-rawfield').evaluate((b) => b.hidden)).toBe(true);
    expect(await rejection(call('exportRawField'))).toMatch(/vector field/);
    const png = await evaluate(() => window.tvf.exportFlowMap({ size: 64 }).then((bytes) => bytes.length));
    expect(png).toBeGreaterThan(0);
  });

  // Pictures of the same stroke as a vector, line and cross field (arrows/glyphs, streamlines, singularity
  // labels) into test-results/symmetry/ (docs/images/symmetry-N.png are copies): each view must differ from the
  // others, since a glyph with N spokes is not an arrow.
  test('the same stroke as a vector, line and cross field draws three different pictures', async () => {
    mkdirSync(PICTURES, { recursive: true });
    await evaluate(() => window.tvf.setViews({ arrows: true, streamlines: true, singularities: true }));
    const shots = [];
    for (const n of [1, 2, 4]) {
      await evaluate((k) => window.tvf.setSymmetry(k), n);
      await expectSymmetry(n);
      await page.waitForTimeout(500);
      const shot = await page.locator('tangent-field-designer').screenshot({ path: resolve(PICTURES, `symmetry-${n}.png`) });
      shots.push(shot.toString('base64'));
    }
    expect(new Set(shots).size).toBe(3);
    expect(errors).toEqual([]);
  });
});
