// Big meshes open progressively (web/core/progressive-core.js): a preview field solved on a coarse copy first, the
// exact one behind it. Forced here on a small mesh (the default bunny subdivided once, `previewEdges: 1`) with the
// exact factorization held back, so the preview surely leads: the first field and every edit made meanwhile
// are marked `preview` in stats(), edits apply at once and are replayed on the exact core in order, a design
// saved during the preview is the design the exact core ends with, undo still works, and once the exact field
// has landed it equals a fresh exact solve of the same design to 1e-9 (the independent truth: a plain load).
import { expect, test } from '@playwright/test';
import { openDesignerPage, readMesh, stripStrokesInPage, subdividedOff } from './helpers.mjs';

test.describe.serial('progressive loading of big meshes', () => {
  let page, errors, off;

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
    page.on('console', (m) => {
      if (m.type() === 'warning' && !m.text().includes('GL Driver Message')) errors.push(m.text());
      if (m.type() === 'log') console.log(m.text());
    });
    off = subdividedOff(await readMesh(page), 1);
  });

  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page.close();
  });

  test('the preview leads; edits made meanwhile replay on the exact core; the exact field is a fresh solve', async () => {
    const loaded = await page.evaluate(async (off) => {
      const t = window.tvf;
      // The test measures a field without sharp features: the model's low-poly creases would hold it (the
      // exact field follows them, the preview's coarse core has none), the angle going with the load's settings.
      await t.setFeatures({ angle: 0 });
      t.debugDelayExact(10000); // the edits below all happen while the preview leads
      // The progress label names the load's phases as they come.
      const label = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#progress .label');
      const labels = [];
      const observer = new MutationObserver(() => labels.push(label.textContent));
      observer.observe(label, { childList: true, characterData: true, subtree: true });
      const info = await t.loadModel(new TextEncoder().encode(off), { name: 'bunny-sub1.off', format: 'off', previewEdges: 1, restore: false });
      observer.disconnect();
      return { info, first: t.stats(), labels };
    }, off);
    expect(loaded.labels.some((l) => new RegExp(`a preview of ${loaded.info.faces.toLocaleString('en')} faces`).test(l)), loaded.labels.join(' | ')).toBe(true);
    // Every fourth face's centre: the strip's course (the coarse preview does not take a zig-zag literally).
    const strokes = await page.evaluate(stripStrokesInPage, { starts: [100, 5000, 12000], crossings: 24, every: 4 });
    const r = await page.evaluate(async ({ off, strokes, loaded: { info, first } }) => {
      const t = window.tvf;
      const bytes = new TextEncoder().encode(off);
      const ids = [];
      const marks = [];
      for (const s of strokes) {
        ids.push(await t.addStroke(s));
        marks.push(t.stats().preview);
      }
      await t.remove(ids[1]);
      marks.push(t.stats().preview);
      const savedDuringPreview = t.saveDesign();
      const previewFaces = t.faceVectors();
      await t.settled();
      const exactStats = t.stats();
      const savedAfter = t.saveDesign();
      const exact = await t.debugCoreReadout();
      const exactFaces = t.faceVectors();
      // Undo and redo of the remove, on the exact core now.
      await t.undo();
      const afterUndo = t.constraints().length;
      await t.redo();
      const afterRedo = t.constraints().length;
      const redone = await t.debugCoreReadout();
      // The independent truth: the same mesh loaded plainly, the saved design applied, solved from scratch.
      t.debugDelayExact(0);
      await t.loadModel(bytes, { name: 'bunny-sub1.off', format: 'off', previewEdges: 0, restore: false });
      const plain = t.stats().preview;
      await t.loadDesign(savedDuringPreview);
      const fresh = await t.debugCoreReadout();
      const diff = (a, b) => {
        let d = 0, m = 0;
        for (let i = 0; i < a.length; i++) {
          d = Math.max(d, Math.abs(a[i] - b[i]));
          m = Math.max(m, Math.abs(b[i]));
        }
        return d / m;
      };
      // Mean angle between the preview's face vectors and the exact field's (same design).
      // Weighted by the exact field's magnitude: where it has decayed to nothing its direction means little.
      let angle = 0, n = 0;
      for (let f = 0; f < exactFaces.length / 3; f++) {
        const a = previewFaces.subarray(3 * f, 3 * f + 3), b = exactFaces.subarray(3 * f, 3 * f + 3);
        const la = Math.hypot(...a), lb = Math.hypot(...b);
        if (la < 1e-12 || lb < 1e-12) continue;
        angle += lb * Math.acos(Math.min(1, Math.max(-1, (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb))));
        n += lb;
      }
      return {
        edges: info.edges, faces: info.faces, first: first.preview, previewFaces: first.previewFaces, marks, exactPreview: exactStats.preview,
        savedSame: JSON.stringify(savedDuringPreview) === JSON.stringify(savedAfter), savedCount: savedDuringPreview.constraints.length,
        savedFaces: savedDuringPreview.constraints.map((c) => c.points[0].face), strokeStarts: [strokes[0][0].face, strokes[2][0].face],
        meshKept: JSON.stringify(savedDuringPreview.mesh) === JSON.stringify(savedAfter.mesh) && !!savedAfter.mesh,
        afterUndo, afterRedo, plain,
        exactVsFresh: diff(exact.oneForm, fresh.oneForm), redoneVsFresh: diff(redone.oneForm, fresh.oneForm),
        meanAngleDeg: (angle / n) * (180 / Math.PI),
      };
    }, { off, strokes, loaded });
    console.log('progressive:', JSON.stringify(r));
    expect(r.first).toBe(true);
    expect(r.previewFaces).toBeLessThan(0.3 * r.faces); // the preview's mesh is the coarse one
    expect(r.marks).toEqual([true, true, true, true]);
    expect(r.exactPreview).toBe(false);
    expect(r.plain).toBe(false);
    expect(r.savedCount).toBe(2);
    expect(r.savedFaces).toEqual(r.strokeStarts); // the fine mesh's faces, never the coarse one's
    expect(r.savedSame).toBe(true);
    expect(r.meshKept).toBe(true);
    expect(r.afterUndo).toBe(3);
    expect(r.afterRedo).toBe(2);
    expect(r.exactVsFresh).toBeLessThan(1e-9);
    expect(r.redoneVsFresh).toBeLessThan(1e-9);
    expect(r.meanAngleDeg).toBeLessThan(30); // a preview, 4x coarser here: it resembles the field (21 deg measured), no more
  });

  test('an exact load that fails after its preview was shown brings the previous model back, design and all', async () => {
    // The open model is the bunny subdivided once (22k edges) with 2 strokes; this one is subdivided twice (88k).
    const bigger = subdividedOff(await readMesh(page), 1);
    const before = await page.evaluate(() => ({ faces: window.tvf.info().faces, design: window.tvf.saveDesign() }));
    const r = await page.evaluate(async (off) => {
      const t = window.tvf;
      const el = document.querySelector('tangent-field-designer');
      const failed = new Promise((resolve) => el.addEventListener('error', (e) => resolve(e.detail), { once: true }));
      // 50 MB: the open model's factor fits (~25 MB), the new one's (~100 MB) does not; the preview's core has no limit.
      await t.debugSetFactorMemoryLimit(5e7);
      t.debugDelayExact(6000); // the refusal comes after the preview is shown (before it, the load itself fails)
      const info = await t.loadModel(new TextEncoder().encode(off), { name: 'other.off', format: 'off', previewEdges: 1, restore: false });
      const shown = { faces: info.faces, preview: t.stats().preview };
      const error = await failed;
      t.debugDelayExact(0);
      await t.settled();
      for (let i = 0; i < 100 && t.info().faces === shown.faces; i++) await new Promise((r) => setTimeout(r, 100));
      await t.debugSetFactorMemoryLimit(0);
      return { shown, error, faces: t.info().faces, preview: t.stats().preview, design: t.saveDesign() };
    }, bigger);
    expect(r.shown.preview).toBe(true);
    expect(r.error.code).toBe('model');
    expect(r.error.message).toMatch(/other\.off.*too large/);
    expect(r.faces).toBe(before.faces);
    expect(r.preview).toBe(false);
    expect(r.design.constraints).toEqual(before.design.constraints);
  });
  // Chromium reads a response body or a file on the thread that asks: a big model read on the page blocked it for
  // up to a second. A big URL or File (4 MB and more; here an OFF file padded with a comment) is read on a
  // worker, a small one and bytes passed in on the page. The autosave key of the bytes read there is the one
  // the same bytes find when passed in (the design comes back either way).
  test('a big model file is read on a worker thread, and its autosave is found again from the same bytes', async () => {
    const r = await page.evaluate(async () => {
      const t = window.tvf;
      const m = t.mesh();
      const lines = [`OFF\n# ${'padding '.repeat(600_000)}\n${m.positions.length / 3} ${m.triangles.length / 3} 0`];
      for (let v = 0; v < m.positions.length; v += 3) lines.push(`${m.positions[v]} ${m.positions[v + 1]} ${m.positions[v + 2]}`);
      for (let f = 0; f < m.triangles.length; f += 3) lines.push(`3 ${m.triangles[f]} ${m.triangles[f + 1]} ${m.triangles[f + 2]}`);
      const bytes = new TextEncoder().encode(lines.join('\n') + '\n');
      const url = URL.createObjectURL(new Blob([bytes]));
      await t.loadModel(url, { name: 'padded.off', restore: false });
      const fromUrl = t.perf().modelRead;
      await t.addVector(10, [1, 0, 0]);
      await t.autosaveIdle();
      await t.loadModel(new File([bytes], 'padded.off'), { restore: true });
      const fromFile = { read: t.perf().modelRead, constraints: t.constraints().length };
      await t.loadModel(bytes, { name: 'padded.off', restore: true });
      const fromBytes = { read: t.perf().modelRead, constraints: t.constraints().length };
      await t.loadModel('models/bunny.glb', { restore: false });
      const small = t.perf().modelRead;
      return { size: bytes.length, fromUrl, fromFile, fromBytes, small };
    });
    expect(r.size).toBeGreaterThan(4 << 20);
    expect(r.fromUrl.thread).toBe('worker');
    expect(r.fromFile.read.thread).toBe('worker');
    expect(r.fromBytes.read.thread).toBe('page');
    expect(r.small.thread).toBe('page');
    expect(r.fromFile.constraints).toBe(1);
    expect(r.fromBytes.constraints).toBe(1);
  });

  // A big model's mesh arrives ahead of its field, and its buffers go to the GPU then, allocated empty and
  // filled slice by slice in tasks of their own (views/mesh-staging.js), instead of inside the task that first
  // draws them. The picture must be the one a plain load of the same mesh and design draws, pixel for pixel
  // up to the field's last digits: buffers allocated but never filled draw nothing, a slice missed or shifted
  // draws torn triangles.
  test("a big model's mesh is uploaded ahead of its field and draws what a plain load draws", async () => {
    const r = await page.evaluate(async (off) => {
      const t = window.tvf;
      const bytes = new TextEncoder().encode(off);
      const pixels = async () => {
        const bitmap = await createImageBitmap(await t.screenshot({ width: 320, height: 240 }));
        const ctx = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
        ctx.drawImage(bitmap, 0, 0);
        return ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
      };
      const design = async () => {
        await t.addSource(40);
        await t.addVector(900, [1, 0.2, 0]);
        await t.settled();
      };
      await t.loadModel(bytes, { name: 'bunny-sub1.off', format: 'off', previewEdges: 1, restore: false });
      const uploads = t.perf().meshUploads;
      await design();
      const staged = await pixels();
      await t.loadModel(bytes, { name: 'bunny-sub1.off', format: 'off', previewEdges: 0, restore: false });
      const plainAhead = 'surface' in t.perf().loadPhases; // a small model's mesh comes with its field
      await design();
      const plain = await pixels();
      let differing = 0, model = 0;
      for (let i = 0; i < plain.length; i += 4) {
        const d = Math.max(...[0, 1, 2].map((c) => Math.abs(plain[i + c] - staged[i + c])));
        if (d > 8) differing++;
        if (Math.abs(plain[i] - plain[0]) + Math.abs(plain[i + 1] - plain[1]) + Math.abs(plain[i + 2] - plain[2]) > 24) model++;
      }
      return { uploads, plainAhead, differing, model, pixels: plain.length / 4 };
    }, off);
    console.log('mesh staging:', JSON.stringify(r));
    expect(r.uploads).toBeGreaterThanOrEqual(8); // 4 buffers, each allocated, then filled
    expect(r.plainAhead).toBe(false);
    expect(r.model).toBeGreaterThan(0.1 * r.pixels); // the model is in the picture
    expect(r.differing).toBeLessThan(0.002 * r.pixels);
  });

  test("a big model's picking comes after its first field, and then hits what a plain load's hits", async () => {
    const r = await page.evaluate(async (off) => {
      const t = window.tvf;
      const bytes = new TextEncoder().encode(off);
      const view = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#view').getBoundingClientRect();
      const grid = () => {
        const out = [];
        for (let i = 1; i < 12; i++)
          for (let j = 1; j < 12; j++) out.push(t.pick(view.left + (view.width * i) / 12, view.top + (view.height * j) / 12)?.face ?? -1);
        return out;
      };
      t.debugDelayExact(3000); // the exact core factors after the picking parts are sent, and later than this
      await t.loadModel(bytes, { name: 'bunny-sub1.off', format: 'off', previewEdges: 1, restore: false });
      const preview = t.stats().preview;
      for (let k = 0; k < 100 && !('picking' in t.perf().loadPhases); k++) await new Promise((r) => setTimeout(r, 50));
      const pickingBeforeExact = 'picking' in t.perf().loadPhases && t.stats().preview;
      const progressive = grid();
      await t.settled();
      t.debugDelayExact(0);
      await t.loadModel(bytes, { name: 'bunny-sub1.off', format: 'off', previewEdges: 0, restore: false });
      const plain = grid();
      return { preview, pickingBeforeExact, progressive, plain, hits: plain.filter((f) => f >= 0).length };
    }, off);
    console.log('picking:', JSON.stringify({ ...r, progressive: undefined, plain: undefined }));
    expect(r.preview).toBe(true);
    expect(r.pickingBeforeExact).toBe(true);
    expect(r.hits).toBeGreaterThan(20); // the grid has hits and misses
    expect(r.hits).toBeLessThan(121);
    expect(r.progressive).toEqual(r.plain);
  });

  // What a big model's preview and picking need from its mesh alone is kept per mesh (worker/preview-cache.js,
  // worker/picking-cache.js): opened again, the preview takes its coarse mesh and map, the page its bounds tree,
  // from IndexedDB, and shows the same preview field and picks the same faces as when they were made; a
  // damaged entry of either is ignored (made anew, the same results) and replaced.
  test('a big model opened again takes its preview parts and its picking tree from the cache', async () => {
    const r = await page.evaluate(async (off) => {
      const t = window.tvf;
      const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
      // The mesh of the tests above, scaled: a mesh nothing is kept for yet.
      const lines = off.split('\n');
      const [nV, nF] = lines[1].split(' ').map(Number);
      for (let v = 2; v < 2 + nV; v++) lines[v] = lines[v].split(' ').map((x) => 1.25 * Number(x)).join(' ');
      const bytes = new TextEncoder().encode(lines.join('\n'));
      const view = t.shadowRoot.querySelector('#view').getBoundingClientRect();
      const grid = () => {
        const out = [];
        for (let i = 1; i < 10; i++)
          for (let j = 1; j < 10; j++) out.push(t.pick(view.left + (view.width * i) / 10, view.top + (view.height * j) / 10)?.face ?? -1);
        return out;
      };
      const store = (name, storeName, change) =>
        new Promise((resolve) => {
          const req = indexedDB.open(name, 1);
          req.onupgradeneeded = () => req.result.createObjectStore(storeName, { keyPath: 'key' });
          req.onsuccess = () => {
            const s = req.result.transaction(storeName, 'readwrite').objectStore(storeName);
            const all = s.getAll();
            all.onsuccess = () => {
              const entry = all.result.find((e) => e.key.endsWith(`-v${nV}-f${nF}`));
              if (entry && change) change(entry), s.put(entry);
              req.result.close();
              resolve(!!entry);
            };
          };
          req.onerror = () => resolve(false);
        });
      const stored = async () => {
        for (let k = 0; k < 100; k++) {
          if ((await store('tvf-preview-cache', 'previews')) && (await store('tvf-picking-cache', 'trees'))) return true;
          await sleep(50);
        }
        return false;
      };
      const open = async () => {
        t.debugDelayExact(2000); // the preview is read before the exact field lands
        await t.loadModel(bytes, { name: 'scaled.off', format: 'off', previewEdges: 1, restore: false });
        const out = { preview: t.stats().preview, kept: t.perf().previewTimings?.kept, faces: Array.from(t.faceVectors()) };
        for (let k = 0; k < 100 && !('picking' in t.perf().loadPhases); k++) await sleep(50);
        Object.assign(out, { treeKept: t.perf().pickingTreeKept, grid: grid() });
        t.debugDelayExact(0);
        await t.settled();
        return out;
      };
      const first = await open();
      const madeStored = await stored();
      const again = await open();
      await store('tvf-preview-cache', 'previews', (e) => (e.vertexFace[0] = 1e9));
      await store('tvf-picking-cache', 'trees', (e) => (e.bvh.indirectBuffer[0] = 1e9));
      const damaged = await open();
      const replaced = (await stored()) && (await open());
      return { first, madeStored, again, damaged, replaced, nF };
    }, off);
    const { first, again, damaged, replaced } = r;
    const hits = first.grid.filter((f) => f >= 0).length;
    console.log('kept preview parts:', JSON.stringify({ hits, runs: [first, again, damaged, replaced].map((o) => [o.preview, o.kept, o.treeKept]) }));
    expect(first.preview).toBe(true);
    expect([first.kept, first.treeKept]).toEqual([false, false]);
    expect(r.madeStored).toBe(true);
    expect([again.preview, again.kept, again.treeKept]).toEqual([true, true, true]);
    expect([damaged.preview, damaged.kept, damaged.treeKept]).toEqual([true, false, false]);
    expect([replaced.preview, replaced.kept, replaced.treeKept]).toEqual([true, true, true]);
    expect(hits).toBeGreaterThan(15);
    expect(hits).toBeLessThan(81);
    for (const run of [again, damaged, replaced]) {
      expect(run.faces).toEqual(first.faces);
      expect(run.grid).toEqual(first.grid);
    }
  });

  // A big surface is drawn once per view and copied under the field (views/surface-layer.js): an edit that
  // changes only the field must not draw the surface again, an orbit must, and the picture, field included,
  // must be the one the scene draws directly. With software GL (as here) every surface takes the layer; on a GPU
  // it is forced on this small mesh by lowering the layer's size.
  test('a big surface is drawn once per view; an edit draws only the field over it, as a direct render would', async () => {
    await page.evaluate(installLayerComparison);
    const r = await page.evaluate(async (off) => {
      const t = window.tvf;
      const both = window.layerComparison;
      await t.loadModel(new TextEncoder().encode(off), { name: 'bunny-sub1.off', format: 'off', previewEdges: 0, restore: false });
      await t.addSource(40);
      const gl = document.createElement('canvas').getContext('webgl2');
      const info = gl.getExtension('WEBGL_debug_renderer_info');
      const renderer = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
      const byDefault = t.debugSurfaceLayer(); // before the comparison, which leaves the layer off
      const before = await both();
      const on = t.debugSurfaceLayer(1);
      await t.addVector(900, [1, 0.2, 0]);
      const afterEdit = t.debugSurfaceLayer();
      t.setCamera({ ...t.camera(), position: t.camera().position.map((x, i) => (i === 0 ? x + 0.3 : x)) });
      await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
      const afterOrbit = t.debugSurfaceLayer();
      const edited = await both();
      t.debugSurfaceLayer(Infinity);
      const canvas = t.shadowRoot.querySelector('canvas');
      return { before, edited, renderer, byDefault, on, afterEdit, afterOrbit, canvas: [canvas.width, canvas.height] };
    }, off);
    console.log('surface layer:', JSON.stringify(r));
    for (const c of [r.before, r.edited]) {
      expect(c.model).toBeGreaterThan(0.1 * c.pixels); // the model is in the picture
      expect(c.differing).toBeLessThan(0.01 * c.pixels);
      expect(c.inside).toBeLessThan(0.0005 * c.pixels);
    }
    // Software GL (SwiftShader, the tests' renderer) draws every surface into the layer by default.
    const software = /swiftshader|llvmpipe|softpipe/i.test(r.renderer);
    expect(r.byDefault.minFaces).toBe(software ? 1 : 200_000);
    if (software) expect(r.byDefault.drawn).toBeGreaterThan(0);
    // The copy covers the surface's rectangle, not the whole canvas (the comparisons above include what lies
    // outside it).
    const [width, height] = r.canvas;
    expect(r.on.rect).not.toBeNull();
    expect(r.on.rect.width * r.on.rect.height).toBeLessThan(0.9 * width * height);
    expect(r.on.rect.width * r.on.rect.height).toBeGreaterThan((r.before.model / r.before.pixels) * width * height);
    expect(r.afterEdit.drawn).toBe(r.on.drawn); // the edit's frames copied the layer
    expect(r.afterEdit.copied).toBeGreaterThan(r.on.copied);
    expect(r.afterOrbit.drawn).toBeGreaterThan(r.afterEdit.drawn); // the orbit drew the surface again
  });

  // The synthesized texture's model: its geometry staged ahead of its first frame, its texture copied on the
  // GPU (the same picture whichever way it was made), and drawn as the surface in the layer (a big textured frame
  // rasterized at every field change keeps the GPU process, and through it the page, busy): its picture is
  // drawn again when its texture changes, and not for frames that change the field alone, and it equals the
  // direct one.
  test('the synthesized texture: its geometry staged, and drawn in the layer once per texture and view', async () => {
    const bunny = subdividedOff(await readMesh(page), 0);
    await page.evaluate(installLayerComparison);
    const r = await page.evaluate(async (off) => {
      const t = window.tvf;
      const frames = () => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
      await t.loadModel(new TextEncoder().encode(off), { name: 'bunny.off', format: 'off', previewEdges: 0, restore: false });
      await t.addSource(40);
      // The textured model's geometry goes to the GPU ahead of its first frame, allocated and then filled a
      // slice per task (views/mesh-staging.js): no upload of a whole corner array, in the synthesis or after.
      const nF = t.mesh().triangles.length / 3;
      const wholeUploads = [], gl2 = WebGL2RenderingContext.prototype, bufferData = gl2.bufferData;
      gl2.bufferData = function (target, data, usage) {
        if (typeof data !== 'number' && data?.byteLength >= 24 * nF) wholeUploads.push(data.byteLength);
        return bufferData.call(this, target, data, usage);
      };
      try {
        await t.synthesize({ resolution: 512 });
        await frames();
      } finally {
        gl2.bufferData = bufferData;
      }
      const textured = await window.layerComparison();
      // The texture goes to the view as a copy made on the GPU, from an interleaved synthesis or a blocking one:
      // the same texture, the same picture.
      const sliced = await window.viewPixels();
      await t.synthesize({ interleave: false });
      const whole = await window.viewPixels();
      await t.synthesize({ interleave: true });
      let slicedDiffers = 0;
      for (let i = 0; i < whole.length; i++) if (whole[i] !== sliced[i]) slicedDiffers++;
      t.setTextureAutoUpdate(false);
      const on = t.debugSurfaceLayer(1);
      await t.addVector(900, [1, 0.2, 0]); // the field alone changes: the texture waits (no auto update)
      await frames();
      const afterEdit = t.debugSurfaceLayer();
      const version = t.synthesisStats().fieldVersion;
      t.setTextureAutoUpdate(true); // the texture follows the edit
      const stats = await t.synthesisIdle();
      await frames();
      const afterTexture = t.debugSurfaceLayer();
      const retextured = await window.layerComparison();
      t.debugSurfaceLayer(Infinity);
      return { wholeUploads, whole: whole.length, slicedDiffers, textured, on, afterEdit, afterTexture, retextured, resynthesized: stats.fieldVersion !== version, uploadMs: stats.uploadMs };
    }, bunny);
    console.log('textured surface layer:', JSON.stringify(r));
    expect(r.wholeUploads).toEqual([]);
    expect(r.whole).toBeGreaterThan(0);
    expect(r.slicedDiffers).toBe(0);
    // The stripes' edges are antialiased edges too (triangle edges cross them), resolved in linear light in the
    // layer: 1.2-1.5 % of the pixels, against 0.5 % for the plain surface; inside smooth parts nothing may differ.
    for (const c of [r.textured, r.retextured]) {
      expect(c.model).toBeGreaterThan(0.1 * c.pixels);
      expect(c.differing).toBeLessThan(0.02 * c.pixels);
      expect(c.inside).toBeLessThan(0.0005 * c.pixels);
    }
    expect(r.afterEdit.drawn).toBe(r.on.drawn); // the field's frames copied the textured picture
    expect(r.afterEdit.copied).toBeGreaterThan(r.on.copied);
    expect(r.resynthesized).toBe(true);
    expect(r.afterTexture.drawn).toBeGreaterThan(r.afterEdit.drawn); // the new texture drew it again
    expect(r.uploadMs).toBeGreaterThan(0);
  });
});

// window.layerComparison(): a picture of the view drawn directly and one with the surface from the layer
// (views/surface-layer.js), compared. Pixels that differ by more than 8 levels: all of them, and those inside a
// smooth part of the direct picture (its four neighbours within 24 levels). The layer is multisampled in
// linear light, the canvas in sRGB, so a silhouette's antialiased pixels differ by a few levels; nothing else
// may. Leaves the layer off. window.viewPixels(): the view's RGBA at 320x240.
function installLayerComparison() {
  const t = window.tvf;
  const pixels = async () => {
    const bitmap = await createImageBitmap(await t.screenshot({ width: 320, height: 240 }));
    const ctx = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
    ctx.drawImage(bitmap, 0, 0);
    return ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
  };
  const compare = (a, b, width = 320) => {
    const far = (i, j, to) => Math.abs(a[i] - to[j]) + Math.abs(a[i + 1] - to[j + 1]) + Math.abs(a[i + 2] - to[j + 2]);
    let differing = 0, inside = 0, model = 0;
    for (let i = 0; i < a.length; i += 4) {
      if (far(i, 0, a) > 24) model++;
      if (Math.max(...[0, 1, 2].map((c) => Math.abs(a[i + c] - b[i + c]))) <= 8) continue;
      differing++;
      if ([-4, 4, -4 * width, 4 * width].every((o) => a[i + o] !== undefined && far(i, i + o, a) <= 24)) inside++;
    }
    return { differing, inside, model, pixels: a.length / 4 };
  };
  window.viewPixels = pixels;
  window.layerComparison = async () => {
    t.debugSurfaceLayer(Infinity);
    const direct = await pixels();
    t.debugSurfaceLayer(1);
    const layered = await pixels();
    t.debugSurfaceLayer(Infinity);
    return compare(direct, layered);
  };
}
