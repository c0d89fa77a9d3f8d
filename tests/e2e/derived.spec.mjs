// The lean edit pipeline (docs/js-api.md, web/core-worker.js): after an edit the worker sends the field arrays
// and only the constraints the edit touched; the page derives the singularities itself when they are read or
// shown, keeps the design document from those changes, and has the streamlines view traced in the worker.
// These tests hold each of those against the core's own read-outs (derived by the core, eagerly, on request)
// after a sequence of edits of every kind, a refused edit, undo and redo, and against the page's own tracer.
// The field arrays the page holds are, after the first edits, the worker's refills of buffers the page handed
// back when a newer field replaced them (core-proxy.js recycle()).
import { expect, test } from '@playwright/test';
import { CENTRE, readMesh, topFacePair, openDesignerPage } from './helpers.mjs';

test.describe.serial('lazily derived read-outs', () => {
  let page, errors, mesh;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);

  // The page's synchronous reads next to what the core itself holds now.
  const compare = async (label) => {
    const { page: mine, core } = await evaluate(async () => {
      const core = await window.tvf.debugCoreReadout();
      const t = window.tvf;
      return {
        page: {
          design: t.saveDesign(),
          singularities: t.singularities(),
          vertexVectors: Array.from(t.vertexVectors()),
          faceVectors: Array.from(t.faceVectors()),
          oneForm: Array.from(t.oneForm()),
          constraints: t.constraints().map(({ id, ...spec }) => spec),
        },
        core: { ...core, vertexVectors: Array.from(core.vertexVectors), faceVectors: Array.from(core.faceVectors), oneForm: Array.from(core.oneForm) },
      };
    });
    expect(mine.design, `${label}: design`).toEqual(core.design);
    // constraints() lists by page id (kept across a delete and its undo), the design by the core's order.
    expect(mine.constraints, `${label}: constraints`).toHaveLength(core.design.constraints.length);
    expect(mine.constraints, `${label}: constraints`).toEqual(expect.arrayContaining(core.design.constraints));
    expect(mine.singularities, `${label}: singularities`).toEqual(core.singularities);
    // The same arrays bit for bit: the page's copies are of the field the core holds now.
    expect(mine.oneForm, `${label}: one-form`).toEqual(core.oneForm);
    expect(mine.vertexVectors, `${label}: vertex vectors`).toEqual(core.vertexVectors);
    expect(mine.faceVectors, `${label}: face vectors`).toEqual(core.faceVectors);
    return core;
  };

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
    mesh = await readMesh(page);
  });

  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page?.close();
  });

  test('after edits of every kind, a refused edit, undo and redo, the page holds what the core derives', async () => {
    const nV = mesh.positions.length / 3, nF = mesh.triangles.length / 3;
    await compare('loaded');
    const [f0, f1] = topFacePair(mesh);
    const stroke = await evaluate(([a, b, c]) => window.tvf.addStroke([{ face: a, bary: c }, { face: b, bary: c }], { strength: 2 }), [f0, f1, CENTRE]);
    await compare('stroke');
    const source = await evaluate((v) => window.tvf.addSource(v), Math.floor(nV / 3));
    await evaluate((v) => window.tvf.addSink(v, { strength: 0.5 }), Math.floor((2 * nV) / 3));
    await evaluate((f) => window.tvf.addVortex(f, { strength: -0.7 }), Math.floor(nF / 2));
    const vector = await evaluate((f) => window.tvf.addVector(f, [1, 0.2, 0.1], { weight: 100 }), Math.floor(nF / 5));
    const core = await compare('sources, vortex, vector');
    // Not a comparison of two empty lists: a source, a sink and a vortex on a stroked field are singular.
    expect(core.singularities.length).toBeGreaterThanOrEqual(3);
    await evaluate(([id, w]) => window.tvf.setWeight(id, w), [vector, 3]);
    // By now the worker copies every field array into a buffer the page gave back; the comparisons check that
    // what it refilled is the new field.
    const reused = await evaluate(async (args) => {
      await window.tvf.setStrength(...args);
      return window.tvf.perf().lastOp.workerParts.reusedArrays;
    }, [stroke, -1]);
    expect(reused).toBe(3);
    await compare('weight and strength');
    // A refused edit leaves the page on what the core holds.
    await expect(evaluate((id) => window.tvf.setWeight(id, 1e16), vector)).rejects.toThrow(/weight/);
    await compare('refused edit');
    await evaluate((id) => window.tvf.remove(id), source);
    await compare('remove');
    await evaluate(() => window.tvf.undo());
    await compare('undo of the remove');
    await evaluate(() => window.tvf.undo());
    await evaluate(() => window.tvf.redo());
    await compare('undo and redo');
    await evaluate(() => window.tvf.setGamma(0.5));
    await compare('γ');
    await evaluate(() => window.tvf.loadDesign(window.tvf.saveDesign()));
    await compare('the design loaded again');
  });

  test('a fresh load of the saved design gives the same read-outs as the edits did', async () => {
    const before = await evaluate(() => ({
      design: window.tvf.saveDesign(),
      singularities: window.tvf.singularities(),
      vertexVectors: Array.from(window.tvf.vertexVectors()),
    }));
    // The same design factored and solved from scratch (no updates): the lazily derived read-outs agree.
    await evaluate(async (design) => {
      await window.tvf.loadDesign({ ...design, constraints: [] });
      await window.tvf.loadDesign(design);
    }, before.design);
    const after = await evaluate(() => ({
      design: window.tvf.saveDesign(),
      singularities: window.tvf.singularities(),
      vertexVectors: Array.from(window.tvf.vertexVectors()),
    }));
    expect(after.design).toEqual(before.design);
    expect(after.singularities).toEqual(before.singularities);
    let diff = 0, size = 0;
    for (let i = 0; i < after.vertexVectors.length; i++) {
      diff = Math.max(diff, Math.abs(after.vertexVectors[i] - before.vertexVectors[i]));
      size = Math.max(size, Math.abs(before.vertexVectors[i]));
    }
    expect(diff / size).toBeLessThan(1e-8);
  });

  test('streamlines traced in the worker for the view equal those traced on the page', async () => {
    // Waits for the view's lines of a field newer than `after` (page field versions), traced in the worker.
    const workerLines = async (after) => {
      await expect
        .poll(() => evaluate(() => (window.tvf.perf().streamlines?.source === 'worker' ? window.tvf.perf().streamlines.fieldVersion : -1)))
        .toBeGreaterThan(after);
      return evaluate(() => ({
        fieldVersion: window.tvf.perf().streamlines.fieldVersion,
        view: window.tvf.streamlines(),
        page: window.tvf.debugTraceStreamlines(),
      }));
    };
    await evaluate(() => window.tvf.setViews({ streamlines: true }));
    const first = await workerLines(0);
    expect(first.view.length).toBeGreaterThan(5);
    expect(first.view).toEqual(first.page);
    // After an edit the view asks for the new field's lines.
    await evaluate((f) => window.tvf.addVortex(f, { strength: 2 }), topFacePair(mesh)[0]);
    const second = await workerLines(first.fieldVersion);
    expect(second.view).toEqual(second.page);
    expect(second.view).not.toEqual(first.view);
    await evaluate(() => window.tvf.setViews({ streamlines: false }));
  });
});
