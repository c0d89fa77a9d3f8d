// The texture's phases and what they let go (issue: the texture at the GPU's speed), on the default bunny:
// - a texture's phases (synthesisStats().phases) add up to its wall time, and name the kernel and the atlas;
// - the generated atlas is kept per mesh in the core's worker and IndexedDB: after a reload the same mesh's
//   texture takes it from there, and it is the same atlas (the same texture, pixel for pixel, with the same seed);
// - one edit on its own (nothing else changing) is answered by a full synthesis started at once: no preview,
//   no settle timer in its phases.
import { expect, test } from '@playwright/test';
import { fieldTurnedAt, openDesigner, openDesignerPage, readMesh, subdividedOff } from './helpers.mjs';

const OPTIONS = { resolution: 256, featureScale: 1, seed: 3 };

const phaseSum = (s) => Object.values(s.phases).reduce((a, b) => a + b, 0);

test.describe.serial('texture phases, a single edit, the atlas kept per mesh (bunny)', () => {
  let page, errors, first;

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser));
  });

  test.afterAll(async () => {
    await page?.close();
  });

  test('the first texture: its phases add up to its wall time', async () => {
    first = await page.evaluate(async (o) => {
      const t0 = performance.now();
      await window.tvf.synthesize(o);
      const measuredMs = performance.now() - t0; // the wall time, on its own
      const s = { ...(await window.tvf.synthesisIdle()), measuredMs };
      const png = await window.tvf.exportTexturePNG({ magnification: 1 });
      return { ...s, png: Array.from(new Uint8Array(await png.arrayBuffer())) };
    }, OPTIONS);
    console.log(JSON.stringify({ phases: first.phases, wallMs: first.wallMs, gpuMs: first.gpuMs }));
    expect(first.atlas.source).toBe('generated');
    expect(first.atlas.cache.cached).toBe(false);
    const keys = Object.keys(first.phases);
    expect(keys.some((k) => k.includes('kernel'))).toBe(true);
    expect(keys).toContain('atlas (worker: charts, packing, corners, seams)');
    expect(keys).toContain('to the view (copied on the GPU)');
    expect(keys).not.toContain('read-back'); // the result stays on the GPU
    expect(Math.abs(phaseSum(first) - first.wallMs)).toBeLessThan(0.1 * keys.length + 0.1);
    expect(Math.abs(phaseSum(first) - first.measuredMs)).toBeLessThan(0.1 * first.measuredMs);
    expect(first.phases['kernel: GPU']).toBeGreaterThan(0);
  });

  test('after a reload, the same mesh\'s atlas comes from the cache: the same texture', async () => {
    // The worker stores the atlas in IndexedDB after its reply: waited for here, in the same origin's database.
    const stored = await page.evaluate(async (key) => {
      const open = () => new Promise((resolve, reject) => {
        const r = indexedDB.open('tvf-atlas-cache', 1);
        // Should this open come first, it makes the store as the worker would (web/synthesis/atlas-cache.js).
        r.onupgradeneeded = () => r.result.createObjectStore('atlases', { keyPath: 'key' });
        r.onsuccess = () => resolve(r.result);
        r.onerror = () => reject(r.error);
      });
      for (let i = 0; i < 100; i++) {
        const db = await open();
        const entry = await new Promise((resolve) => {
          const r = db.transaction('atlases').objectStore('atlases').get(key);
          r.onsuccess = () => resolve(r.result);
          r.onerror = () => resolve(null);
        });
        db.close();
        if (entry) return entry.key;
        await new Promise((resolve) => setTimeout(resolve, 50));
      }
      return null;
    }, first.atlas.cache.key);
    expect(stored).toBe(first.atlas.cache.key);
    await page.reload();
    await openDesigner(page);
    const again = await page.evaluate(async (o) => {
      await window.tvf.synthesize(o);
      const s = await window.tvf.synthesisIdle();
      const png = await window.tvf.exportTexturePNG({ magnification: 1 });
      return { ...s, png: Array.from(new Uint8Array(await png.arrayBuffer())) };
    }, OPTIONS);
    expect(again.atlas.cache.cached).toBe(true);
    expect(again.atlas.cache.key).toBe(first.atlas.cache.key);
    expect(Object.keys(again.phases)).toContain('atlas (worker: kept for this mesh)');
    expect(again.atlas.charts).toBe(first.atlas.charts);
    expect(again.png).toEqual(first.png);
  });

  test('one edit on its own: a full synthesis at once, no preview, no settle timer', async () => {
    const r = await page.evaluate(async () => {
      const t = window.tvf;
      const before = t.synthesisStats();
      await new Promise((resolve) => setTimeout(resolve, 600)); // nothing else changed for a while
      const t0 = performance.now();
      await t.addVector(900, [1, 0.2, 0]);
      await t.settled();
      const s = await t.synthesisIdle();
      return { before, s, t0, t1: performance.now() };
    });
    console.log(JSON.stringify({ updatePhases: r.s.phases, wallMs: r.s.wallMs }));
    expect(r.s.fieldVersion).not.toBe(r.before.fieldVersion);
    expect(r.s.preview).toBe(false);
    expect(r.s.previewRuns).toBe(r.before.previewRuns); // no preview run, so no settle timer either
    expect(Object.keys(r.s.phases)).toContain("queue (behind the page's tasks)");
    expect(r.s.atlas.cache.key).toBe(first.atlas.cache.key); // the same atlas, held by the page
    expect(Object.keys(r.s.phases).some((k) => k.startsWith('atlas'))).toBe(false);
    // The run's clock starts at the field change (after the edit's solve) and ends with the texture shown.
    expect(r.s.startedAt).toBeGreaterThanOrEqual(r.t0);
    expect(r.s.shownAt).toBeLessThanOrEqual(r.t1);
    expect(Math.abs(phaseSum(r.s) - (r.t1 - r.s.startedAt))).toBeLessThan(0.1 * (r.t1 - r.t0));
  });

  // The synthesis draws in the view's own context: losing it loses the texture's targets too, and once it is
  // back the texture is made again, the same as before (the same field and seed).
  test('the view\'s context lost and restored: the texture is made again, the same', async () => {
    const r = await page.evaluate(async () => {
      const t = window.tvf;
      const bytes = async () => Array.from(new Uint8Array(await (await t.exportTexturePNG({ magnification: 1 })).arrayBuffer()));
      const before = { stats: t.synthesisStats(), png: await bytes() };
      const canvas = document.querySelector('tangent-field-designer').shadowRoot.querySelector('#viewport canvas');
      const lose = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
      await new Promise((resolve) => {
        // Restoring is allowed once the event has been dispatched (three.js prevents its default): a task later.
        canvas.addEventListener('webglcontextlost', () => setTimeout(resolve, 0), { once: true });
        lose.loseContext();
      });
      await new Promise((resolve) => {
        canvas.addEventListener('webglcontextrestored', () => resolve(), { once: true });
        lose.restoreContext();
      });
      await new Promise((resolve) => setTimeout(resolve, 50));
      const after = await t.synthesisIdle();
      return { before: before.stats, after, same: JSON.stringify(before.png) === JSON.stringify(await bytes()) };
    });
    expect(r.after.shownAt).toBeGreaterThan(r.before.shownAt);
    expect(r.after.fieldVersion).toBe(r.before.fieldVersion);
    expect(r.after.atlas.cache.cached).toBe(true);
    expect(r.same).toBe(true);
  });

  // After an update that came within a frame or two (web/synthesis/quick-edits.js followsWithin, FOLLOW_MS), the
  // next edit on its own has its field drawn with its texture in one frame: none drawn between the edit and the
  // texture shown, one after it; after a slower update the field is drawn first, as before; after the whole run
  // (whose next is local) the field's frame waits half the budget. The panels are shown with that frame: the
  // constraint list has the edit's row once the frame is drawn. The budget is raised
  // to 2 s here (tvf.debugTextureFollowMs), so that the wait is seen on a loaded machine too (the updates took
  // 87-191 ms alone, 350-470 ms beside the other runner). The edits: the field at
  // a face asked to turn by 2° (as long as it is), which moves a part of the texture only; the run before the
  // first was the whole one after the context's restore (above).
  test('an edit on its own after a quick update: its field and its texture drawn in one frame', async () => {
    const edit = async (face) => {
      const turned = await fieldTurnedAt(page, face, Math.PI / 90);
      return page.evaluate(async ({ face, turned }) => {
        const t = window.tvf;
        await new Promise((resolve) => setTimeout(resolve, 600));
        const before = t.synthesisStats();
        const frames = t.debugRecordFrames();
        const t0 = performance.now();
        await t.addVector(face, turned);
        await t.settled();
        const s = await t.synthesisIdle();
        await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
        const root = document.querySelector('tangent-field-designer').shadowRoot;
        const rows = root.querySelectorAll('#constraint-list li');
        return { before, s, t0, frames: frames.slice(), rows: rows.length, constraints: t.constraints().length };
      }, { face, turned });
    };
    await page.evaluate(() => window.tvf.debugTextureFollowMs(2000));
    const runs = [await edit(1200), await edit(2400), await edit(600)];
    await page.evaluate(() => window.tvf.debugTextureFollowMs(null));
    for (const r of runs) {
      const quick = !r.before.preview && (r.before.local ? r.before.wallMs < 2000 : r.before.localNext);
      const early = r.frames.filter((x) => x < r.s.shownAt);
      console.log(JSON.stringify({ before: r.before.wallMs, quick, wallMs: r.s.wallMs, waited: r.s.fieldFrameWaited,
        frames: r.frames.map((x) => Math.round(x - r.t0)), shownAt: Math.round(r.s.shownAt - r.t0) }));
      expect(r.s.fieldFrameWaited > 0, 'the field\'s frame waited for its texture').toBe(quick);
      // The wait ends at the texture, or at its deadline (twice the update before) when the texture comes later.
      const deadline = r.s.startedAt + r.s.fieldFrameWaited - 5;
      const tooEarly = early.filter((x) => x < deadline);
      if (quick) expect(tooEarly, 'frames drawn before the texture or the deadline').toEqual([]);
      else expect(early.length, 'the field drawn first').toBeGreaterThan(0);
      expect(r.frames.some((x) => x >= r.s.shownAt), 'the frame with the field and its texture').toBe(true);
      expect(r.rows, 'the constraint list shown with the frame').toBe(r.constraints);
    }
    expect(runs[0].before.local, 'the first edit comes after a whole run').toBe(false);
    expect(runs[0].s.fieldFrameWaited, 'after a whole run, half the budget').toBe(1000);
    expect(runs.some((r) => r.s.fieldFrameWaited > 0), 'an edit whose frame waited for its texture').toBe(true);
  });

  // On a big model (here forced: previewEdges 1) an edit brings a preview field, then the exact one: the texture
  // ends on the exact field, and synthesisIdle() resolves with it (the queue's own race is
  // tests/node/synthesis-idle.test.mjs's).
  test('a preview field, then the exact one: the texture ends on the exact field', async () => {
    const off = subdividedOff(await readMesh(page), 0);
    const r = await page.evaluate(async ({ off, o }) => {
      const t = window.tvf;
      await t.loadModel(new TextEncoder().encode(off), { name: 'bunny.off', format: 'off', previewEdges: 1, restore: false });
      await t.settled();
      await t.synthesize(o);
      const before = await t.synthesisIdle();
      await t.addVector(900, [1, 0.2, 0]);
      await t.settled();
      const after = await t.synthesisIdle();
      const again = await t.synthesize(o); // the current field, asked for: no newer than what the idle one showed
      return { before, after, again, exact: !t.stats().preview };
    }, { off, o: OPTIONS });
    expect(r.exact).toBe(true);
    expect(r.after.fieldVersion).toBeGreaterThan(r.before.fieldVersion);
    expect(r.after.fieldVersion).toBe(r.again.fieldVersion);
    expect(r.after.preview).toBe(false);
  });

  test('no console errors', () => {
    expect(errors.filter((e) => !/CONTEXT_LOST|context lost/i.test(e))).toEqual([]);
  });
});

// synthesis/atlas-ahead.js: a model's atlas is prepared in the core's worker once the model is shown, before any
// texture is asked for, so the first texture at the resolution a run would choose finds it made.
test('a model\'s atlas is prepared ahead: the first texture finds it kept', async ({ browser }) => {
  const { page, errors } = await openDesignerPage(browser);
  try {
    const r = await page.evaluate(async () => {
      const t = window.tvf;
      await t.settled();
      // The default model's atlas takes the worker ~0.1-0.3 s here, a step per request.
      await new Promise((resolve) => setTimeout(resolve, 2500));
      await t.synthesize({ seed: 3 });
      return { ahead: await t.synthesisIdle() };
    });
    const a = r.ahead;
    expect(a.atlas.source).toBe('generated');
    expect(a.atlas.cache.cached).toBe(true);
    expect(Object.keys(a.phases)).toContain('atlas (worker: kept for this mesh)');
    expect(Object.keys(a.phases)).not.toContain('atlas (worker: charts, packing, corners, seams)');
    expect(a.atlas.charts).toBeGreaterThan(0);
    expect(a.atlas.coverage).toBeGreaterThan(0.3);
    expect(errors).toEqual([]);
  } finally {
    await page.close();
  }
});
