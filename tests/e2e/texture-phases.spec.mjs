// The texture's phases and what they let go (issue: the texture at the GPU's speed), on the default bunny:
// - a texture's phases (synthesisStats().phases) add up to its wall time, and name the kernel and the atlas;
// - the generated atlas is kept per mesh in the core's worker and IndexedDB: after a reload the same mesh's
//   texture takes it from there, and it is the same atlas (the same texture, pixel for pixel, with the same seed);
// - one edit on its own (nothing else changing) is answered by a full synthesis started at once: no preview,
//   no settle timer in its phases.
import { expect, test } from '@playwright/test';
import { openDesigner, openDesignerPage } from './helpers.mjs';

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
      await window.tvf.synthesize(o);
      const s = await window.tvf.synthesisIdle();
      const png = await window.tvf.exportTexturePNG({ magnification: 1 });
      return { ...s, png: Array.from(new Uint8Array(await png.arrayBuffer())) };
    }, OPTIONS);
    console.log(JSON.stringify({ phases: first.phases, wallMs: first.wallMs, gpuMs: first.gpuMs }));
    expect(first.atlas.source).toBe('generated');
    expect(first.atlas.cache.cached).toBe(false);
    const keys = Object.keys(first.phases);
    expect(keys.some((k) => k.includes('kernel'))).toBe(true);
    expect(keys).toContain('atlas (worker: charts, packing, corners, seams)');
    expect(keys).toContain('read-back');
    expect(Math.abs(phaseSum(first) - first.wallMs)).toBeLessThan(0.1 * keys.length + 0.1);
    expect(first.phases['kernel: GPU']).toBeGreaterThan(0);
  });

  test('after a reload, the same mesh\'s atlas comes from the cache: the same texture', async () => {
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
      const version = t.synthesisStats().fieldVersion;
      await new Promise((resolve) => setTimeout(resolve, 600)); // nothing else changed for a while
      await t.addVector(900, [1, 0.2, 0]);
      await t.settled();
      const s = await t.synthesisIdle();
      return { version, s };
    });
    console.log(JSON.stringify({ updatePhases: r.s.phases, wallMs: r.s.wallMs }));
    expect(r.s.fieldVersion).not.toBe(r.version);
    expect(r.s.preview).toBe(false);
    expect(Object.keys(r.s.phases)).toContain('settle, queue');
    expect(r.s.phases['settle, queue']).toBeLessThan(400); // the settle timer (400 ms) did not run
    expect(r.s.atlas.cache.key).toBe(first.atlas.cache.key); // the same atlas, held by the page
    expect(Object.keys(r.s.phases).some((k) => k.startsWith('atlas'))).toBe(false);
  });

  test('no console errors', () => {
    expect(errors).toEqual([]);
  });
});
