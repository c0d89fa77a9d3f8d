// Quad meshes from the designed cross field in the page (issue 46, item 2; web/quad/, docs/js-api.md "Quad
// meshes"), against the real wasm core on a worker of its own and the real WebGL view. On a small sphere's cross
// field the Quad mesh panel's Remesh makes a quad mesh whose statistics, as the panel shows them, are sane (nearly
// all quads, closed, as many field singularities as the page counts); its wireframe is on the canvas (the pixels
// differ from the same view with Show off); its OBJ (the API's, and the panel's download, the same text) reads
// back with the counts of the statistics, its GLB holds every vertex and the triangles. An edit leaves it drawn
// and marks it stale. While a remesh runs a stroke drawn with the mouse is taken; Cancel in the panel then leaves
// the panel idle, no new result and no worker of its own, and the next remesh runs (and ends its worker). A vector
// or line field is refused with "Quad meshes need a cross field", by the API and in the panel. A cube's sharp
// edges, as the design's features, become chains of quad edges (every quad in one side), and an open square's
// boundary the quad mesh's (a regular grid, its four corners quad vertices).
import { readFile } from 'node:fs/promises';
import { expect, test } from '@playwright/test';
import { icosphereOff } from '../icosphere.mjs';
import { cubeQuads, parseObj } from '../node/quad-fixtures.mjs';
import { openDesignerPage, readCanvasRgb } from './helpers.mjs';

// A quad mesh's polygons fanned into triangles, as an OFF text.
function trianglesOff({ positions, faceStart, faceVertices }) {
  const lines = [];
  for (let f = 0; f + 1 < faceStart.length; f++)
    for (let k = faceStart[f] + 1; k + 1 < faceStart[f + 1]; k++)
      lines.push(`3 ${faceVertices[faceStart[f]]} ${faceVertices[k]} ${faceVertices[k + 1]}`);
  const points = [];
  for (let v = 0; v < positions.length; v += 3) points.push(`${positions[v]} ${positions[v + 1]} ${positions[v + 2]}`);
  return `OFF\n${points.length} ${lines.length} 0\n${points.join('\n')}\n${lines.join('\n')}\n`;
}

// A remesh target on the small sphere that the test relies on to keep the core at work until a stroke has been
// drawn and taken (it checks that the remesh still runs before Cancel, and logs how long it had run then).
const BIG_TARGET = 1_000_000;

// Share of pixels whose colour differs by more than `threshold` (sum over R, G, B).
function differingShare(a, b, threshold = 48) {
  let n = 0;
  for (let i = 0; i < a.length; i += 3)
    if (Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]) > threshold) n++;
  return n / (a.length / 3);
}

test.describe.serial('quad meshes in the page', () => {
  let page, errors;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  // The message remesh(options) rejects with, exactly as the page has it.
  const refusal = (options) =>
    page.evaluate((o) => window.tvf.remesh(o).then(() => 'resolved', (err) => err.message), options);
  const quadState = () => evaluate(() => window.tvf.quadMesh());
  // Two animation frames: the view's requested render has been drawn.
  const frames = () => evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  let first = null; // the statistics of the panel's remesh
  // The page's core workers (core-worker.js): the element's, and a remesh's while it runs. Each runs the wasm
  // core with its own pthread helpers, nested workers that end with it; they are not counted, because
  // Playwright may never report a nested worker's end once its parent's end has come first (its end arrives
  // on the parent's session, then gone), and such a helper would stay in page.workers() for good.
  const isCore = (w) => new URL(w.url()).pathname.endsWith('/core-worker.js');
  const coreWorkers = () => page.workers().filter(isCore);
  // The next core worker the page starts (a remesh's), with `ended` set once it is gone. Its end is listened for
  // in the predicate, as the worker is reported: a short remesh's worker can end in the same batch of messages,
  // before a listener added once the wait has resolved (a CI run waited 30 s for an end that had come).
  const remeshWorkerStarts = () => {
    const watched = { ended: false };
    const predicate = (w) => {
      if (!isCore(w)) return false;
      w.once('close', () => (watched.ended = true));
      return true;
    };
    return page.waitForEvent('worker', { predicate, timeout: 60_000 }).then(() => watched);
  };

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
    // A closed genus-0 sphere of 1,280 triangles: its smoothest cross field has eight +1/4 singularities.
    await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'ball.off', restore: false }),
      icosphereOff(3));
    await evaluate(() => window.tvf.setSymmetry(4));
    await evaluate(() => window.tvf.setViews({ arrows: false, singularities: false }));
    await page.locator('#quad-panel summary').click();
  });
  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page.close();
  });

  test('Remesh in the panel: sane statistics, the wireframe drawn, the OBJ as the statistics count', async () => {
    await expect(page.locator('#quad-status')).toHaveText('No quad mesh yet.');
    await expect(page.locator('#quad-target-mode')).toHaveValue('quads');
    await expect(page.locator('#quad-target')).toHaveValue('5000');
    await page.locator('#quad-target').fill('800');
    await page.locator('#quad-target').dispatchEvent('change');
    expect((await quadState()).target).toEqual({ quads: 800 });
    const t0 = Date.now();
    await page.locator('#quad-remesh').click();
    await expect.poll(async () => (await quadState()).hasResult, { timeout: 120_000 }).toBe(true);
    const state = await quadState();
    const s = (first = state.stats);
    const ms = Date.now() - t0;
    console.log(`[ measured ] icosphere(3), 800 quads asked, ${ms} ms from the click: ${JSON.stringify(s)}`);
    expect(state.running).toBe(false);
    expect(state.error).toBeNull();
    expect(state.stale).toBe(false);
    expect(s.quadShare).toBeGreaterThanOrEqual(0.9);
    expect(s.faces).toBeGreaterThan(400);
    expect(s.faces).toBeLessThan(1600);
    expect(s.manifold).toBe(true);
    expect(s.eulerCharacteristic).toBe(2);
    expect(s.fieldSingularities).toBe(await evaluate(() => window.tvf.singularities().length));
    expect(s.flippedFaces).toBe(0);
    expect(s.hausdorffRelative).toBeLessThan(0.05);
    // The panel shows those numbers; idle: no bar, Cancel disabled, the exports enabled.
    const shown = await page.locator('#quad-stats').innerText();
    const count = (n) => n.toLocaleString('en-US');
    const quadPercent = (100 * s.quadShare).toFixed(2);
    expect(shown).toContain(`Quads: ${count(s.quads)} of ${count(s.faces)} faces (${quadPercent} %)`);
    expect(shown).toContain(`Irregular vertices: ${s.irregularVertices} (field singularities: ${s.fieldSingularities}`);
    expect(shown).toContain(`median ${s.edgeAngleMedianDeg.toFixed(1)}°, p90 ${s.edgeAngleP90Deg.toFixed(1)}°`);
    await expect(page.locator('#quad-running')).toBeHidden();
    await expect(page.locator('#quad-cancel')).toBeDisabled();
    await expect(page.locator('#quad-export-obj')).toBeEnabled();

    // The wireframe: the same view with Show off differs.
    await frames();
    const withMesh = await readCanvasRgb(page);
    await page.locator('#quad-show').uncheck();
    await frames();
    const without = await readCanvasRgb(page);
    await page.locator('#quad-show').check();
    await frames();
    const again = await readCanvasRgb(page);
    const share = differingShare(withMesh, without);
    console.log(`[ measured ] the wireframe changes ${(100 * share).toFixed(2)} % of the canvas's pixels`);
    expect(share).toBeGreaterThan(0.005);
    expect(differingShare(withMesh, again)).toBeLessThan(0.001);

    // The OBJ: as many vertices, faces and quads as the statistics say.
    const obj = parseObj(await evaluate(() => window.tvf.exportQuadObj()));
    expect(obj.vertices.length).toBe(s.vertices);
    expect(obj.faces.length).toBe(s.faces);
    expect(obj.faces.filter((f) => f.length === 4).length).toBe(s.quads);
    // The panel's OBJ button downloads the same text.
    const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#quad-export-obj').click()]);
    expect(download.suggestedFilename()).toBe('ball.quad.obj');
    const downloaded = await readFile(await download.path(), 'utf8');
    expect(downloaded).toBe(await evaluate(() => window.tvf.exportQuadObj()));
    // The GLB: its triangulated copy, with every vertex.
    const glb = await evaluate(() => {
      const bytes = new DataView(window.tvf.exportQuadGlb());
      const length = bytes.getUint32(12, true);
      const doc = JSON.parse(new TextDecoder().decode(new Uint8Array(bytes.buffer, 20, length)));
      return { magic: bytes.getUint32(0, true), total: bytes.getUint32(8, true), size: bytes.byteLength, doc };
    });
    expect(glb.magic).toBe(0x46546c67);
    expect(glb.total).toBe(glb.size);
    const primitive = glb.doc.meshes[0].primitives[0];
    expect(glb.doc.accessors[primitive.attributes.POSITION].count).toBe(s.vertices);
    expect(glb.doc.accessors[primitive.indices].count).toBe(3 * obj.faces.reduce((n, f) => n + f.length - 2, 0));
  });

  test('an edit: the quad mesh stays drawn and is marked stale; remeshing is no edit', async () => {
    const history = await evaluate(() => window.tvf.history());
    expect(history.undo.some((label) => /remesh|quad/i.test(label))).toBe(false);
    await evaluate(() => window.tvf.addVector(0, [0, 0, 1]));
    await expect.poll(async () => (await quadState()).stale).toBe(true);
    await expect(page.locator('#quad-status')).toHaveText('The design changed since; Remesh again.');
    const state = await quadState();
    expect(state.hasResult).toBe(true);
    expect(state.stats).toEqual(first);
    expect(state.visible).toBe(true);
  });

  test('Cancel while a stroke is drawn: the panel idle again, no new result; the next remesh runs', async () => {
    // The page's core workers now: the element's; a remesh starts one of its own.
    const idleCores = coreWorkers().length;
    // A big target keeps the core busy long enough to draw meanwhile.
    const started = Date.now();
    let remeshWorker = remeshWorkerStarts();
    await evaluate((quads) => {
      window.__remesh = window.tvf.remesh({ quads }).then(() => 'resolved', (err) => err.message);
    }, BIG_TARGET);
    await expect(page.locator('#quad-cancel')).toBeEnabled();
    await expect(page.locator('#quad-running')).toBeVisible();
    const cancelled = await remeshWorker;
    expect(coreWorkers().length).toBe(idleCores + 1);
    console.log(`[ measured ] the page's core workers: ${idleCores} idle, ${coreWorkers().length} while remeshing`);
    // Once the core is at work (its first stage posted), a stroke drawn with the mouse is taken at once.
    await expect.poll(async () => (await quadState()).stage, { timeout: 60_000 }).not.toBe('starting');
    const before = (await evaluate(() => window.tvf.constraints())).length;
    const line = await evaluate(() => {
      const view = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view');
      const r = view.getBoundingClientRect();
      const cx = r.left + r.width / 2, cy = r.top + r.height / 2, half = 60, n = 24;
      for (const dy of [0, 30, -30, 60]) {
        let all = true;
        for (let k = 0; k <= n && all; k++) all = !!window.tvf.pick(cx - half + (2 * half * k) / n, cy + dy);
        if (all) return { x0: cx - half, x1: cx + half, y: cy + dy };
      }
      return null;
    });
    expect(line, 'a screen line across the sphere').not.toBeNull();
    const t0 = Date.now();
    await page.getByRole('button', { name: 'Stroke', exact: true }).click();
    await page.mouse.move(line.x0, line.y);
    await page.mouse.down();
    await page.mouse.move(line.x1, line.y, { steps: 12 });
    await page.mouse.up();
    await expect.poll(async () => (await evaluate(() => window.tvf.constraints())).length).toBe(before + 1);
    console.log(`[ measured ] a stroke drawn during the remesh: its constraint after ${Date.now() - t0} ms`);
    expect((await quadState()).running, 'the remesh still runs').toBe(true);
    await page.getByRole('button', { name: 'Orbit', exact: true }).click();
    await page.locator('#quad-cancel').click();
    expect(await evaluate(() => window.__remesh)).toBe('the quad remeshing was cancelled');
    console.log(`[ measured ] ${BIG_TARGET} quads asked: cancelled after ${Date.now() - started} ms, still running`);
    const state = await quadState();
    expect(state.running).toBe(false);
    expect(state.stage).toBeNull();
    expect(state.error).toBeNull();
    expect(state.stats).toEqual(first); // no new result: the earlier (stale) one stays
    await expect(page.locator('#quad-running')).toBeHidden();
    await expect(page.locator('#quad-cancel')).toBeDisabled();
    expect(await evaluate(() => window.tvf.cancelRemesh())).toBe(false);
    await expect.poll(() => cancelled.ended, { message: "the remesh's worker is gone" }).toBe(true);
    expect(coreWorkers().length).toBe(idleCores);

    // The next remesh, through the API: the arrays as the statistics count them, and the mesh no longer stale.
    remeshWorker = remeshWorkerStarts();
    const result = await evaluate(async () => {
      const r = await window.tvf.remesh({ quads: 600 });
      return { nV: r.positions.length / 3, nF: r.faceStart.length - 1, corners: r.faceVertices.length,
        irregular: r.irregular.length, stats: r.stats };
    });
    expect(result.nV).toBe(result.stats.vertices);
    expect(result.nF).toBe(result.stats.faces);
    expect(result.irregular).toBe(result.stats.irregularVertices);
    expect(result.stats.quadShare).toBeGreaterThanOrEqual(0.9);
    const finished = await remeshWorker;
    await expect.poll(() => finished.ended, { message: 'a finished remesh ends its worker' }).toBe(true);
    expect(coreWorkers().length).toBe(idleCores);
    const after = await quadState();
    expect(after.stale).toBe(false);
    expect(after.target).toEqual({ quads: 600 });
    await expect(page.locator('#quad-target')).toHaveValue('600');
  });

  test('a vector or line field is refused: "Quad meshes need a cross field"', async () => {
    for (const n of [1, 2]) {
      await evaluate((n) => window.tvf.setSymmetry(n), n);
      expect(await refusal(undefined)).toBe('Quad meshes need a cross field');
    }
    await page.locator('#quad-remesh').click();
    await expect(page.locator('#quad-status')).toHaveText('Quad meshes need a cross field');
    expect((await quadState()).running).toBe(false);
    expect(await refusal({ quads: 0 })).toMatch(/^remesh: quads must be a whole number/);
  });

  test("a cube's sharp edges (the design's features) and a square's boundary become chains of quad edges",
    async () => {
      await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'cube.off', restore: false }),
        trianglesOff(cubeQuads(8)));
      await evaluate(() => window.tvf.setSymmetry(4));
      await evaluate(() => window.tvf.setFeatures({ angle: 35 }));
      // The side is 2: at 0.6 each side's lines make it 3 x 3 quads, none folded over an edge of the cube.
      const cube = await evaluate(() => window.tvf.remesh({ edgeLength: 0.6 }));
      expect(cube.stats).toMatchObject({ featureCurves: 12, releasedFeatureCurves: 0, quads: 54, faces: 54,
        valence3: 8, eulerCharacteristic: 2 });
      const straddling = [];
      for (let f = 0; f + 1 < cube.faceStart.length; f++) {
        const corners = Array.from(cube.faceVertices.slice(cube.faceStart[f], cube.faceStart[f + 1]));
        const flat = [0, 1, 2].some((axis) => [-1, 1].some((side) =>
          corners.every((v) => Math.abs(cube.positions[3 * v + axis] - side) < 1e-9)));
        if (!flat) straddling.push(f);
      }
      expect(straddling).toEqual([]);
      // An open square, 2 a side, its field following its boundary: at 0.45 a regular 4 x 4 grid whose
      // boundary is the square's.
      const n = 8, positions = [], faceVertices = [];
      for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) positions.push((2 * i) / n, (2 * j) / n, 0);
      for (let j = 0; j < n; j++)
        for (let i = 0; i < n; i++) faceVertices.push(j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1,
          (j + 1) * (n + 1) + i);
      const grid = { positions, faceStart: Array.from({ length: n * n + 1 }, (_, f) => 4 * f), faceVertices };
      await evaluate((text) => window.tvf.loadModel(new TextEncoder().encode(text), { name: 'square.off', restore: false }),
        trianglesOff(grid));
      await evaluate(() => window.tvf.setSymmetry(4));
      await evaluate(() => window.tvf.setBoundary('tangential'));
      const open = await evaluate(() => window.tvf.remesh({ edgeLength: 0.45 }));
      expect(open.stats).toMatchObject({ faces: 16, quads: 16, irregularVertices: 0, eulerCharacteristic: 1,
        boundaryEdges: 16 });
      const onBoundary = (x) => Math.abs(x) < 1e-9 || Math.abs(x - 2) < 1e-9;
      let corners = 0;
      for (let v = 0; v < open.positions.length; v += 3)
        corners += onBoundary(open.positions[v]) && onBoundary(open.positions[v + 1]) ? 1 : 0;
      expect(corners).toBe(4);
    });
});
