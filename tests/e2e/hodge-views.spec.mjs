// The Views panel's Component choice (the Hodge decomposition c = dα + δβ + h drawn by every view) on the real
// page: setViews({component}) and the panel's select agree; on a design with only a source and a sink the
// curl-free part is the whole field and the divergence-free part vanishes, as the arrows draw them; the energy
// shares the panel shows sum to 100 %; with the whole field nothing is asked of the worker.
import { expect, test } from '@playwright/test';
import { openDesignerPage, readMesh } from './helpers.mjs';

test.describe.serial('Hodge component views', () => {
  let page, errors;
  const evaluate = (fn, arg) => page.evaluate(fn, arg);
  const settle = () => evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const select = () => page.locator('tangent-field-designer #view-component');
  const requests = () => evaluate(() => window.tvf.perf().hodgeViews?.requests ?? { component: 0, hodgeShares: 0 });
  const arrows = () => evaluate(() => window.tvf.arrowInstances());
  const lengths = (v) => Array.from({ length: v.length / 3 }, (_, i) => Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
  const sum = (a) => a.reduce((x, y) => x + y, 0);

  // The part `name` of the current field has arrived and is drawn.
  async function showComponent(name) {
    await evaluate((name) => window.tvf.setViews({ component: name }), name);
    await expect.poll(() => evaluate(() => JSON.stringify(window.tvf.perf().hodgeViews))).toContain(`"drawn":{"component":"${name}"`);
    await settle();
  }

  test.beforeAll(async ({ browser }) => {
    ({ page, errors } = await openDesignerPage(browser, { viewport: { width: 1024, height: 720 } }));
  });

  test.afterAll(async () => {
    expect(errors).toEqual([]);
    await page?.close();
  });

  test('whole field by default; nothing asked of the worker', async () => {
    expect((await evaluate(() => window.tvf.views())).component).toBe('whole');
    await expect(select()).toHaveValue('whole');
    expect(await select().locator('option').allTextContents()).toEqual(['Whole field', 'Curl-free (gradient)', 'Divergence-free (rotation)', 'Harmonic']);
    const mesh = await readMesh(page);
    const nV = mesh.positions.length / 3;
    await evaluate(async ([a, b]) => {
      // The test measures a field without sharp features: the default model's low-poly creases would hold it.
      await window.tvf.setFeatures({ angle: 0 });
      await window.tvf.addSource(a);
      await window.tvf.addSink(b);
    }, [Math.floor(nV / 3), Math.floor((2 * nV) / 3)]);
    expect((await evaluate(() => window.tvf.constraints())).map((c) => c.type)).toEqual(['source', 'sink']);
    // Streamlines on: their worker trace marks the version drawn (perf().streamlines.fieldVersion).
    await evaluate(() => window.tvf.setViews({ arrows: true, arrowsScaled: true, streamlines: true }));
    await settle();
    expect(await requests()).toEqual({ component: 0, hodgeShares: 0 });
    await expect(page.locator('tangent-field-designer #component-shares')).toBeHidden();
  });

  test('curl-free equals the whole field of a source and a sink; divergence-free vanishes', async () => {
    await expect.poll(() => evaluate(() => window.tvf.perf().streamlines?.source)).toBe('worker');
    await settle();
    const whole = await arrows();
    expect(whole.vectors.length).toBeGreaterThan(300);
    const wholeLengths = lengths(whole.vectors), top = Math.max(...wholeLengths);

    await showComponent('exact');
    await expect(select()).toHaveValue('exact');
    const exact = await arrows();
    expect(exact.anchors).toEqual(whole.anchors);
    let worst = 0;
    for (let i = 0; i < whole.vectors.length; i++) worst = Math.max(worst, Math.abs(exact.vectors[i] - whole.vectors[i]));
    console.log(`curl-free vs whole: ${whole.vectors.length / 3} arrows, largest difference ${(worst / top).toExponential(2)} of the longest`);
    expect(worst / top).toBeLessThan(1e-6);

    await showComponent('coexact');
    await expect(select()).toHaveValue('coexact');
    const coexact = await arrows();
    // The vanishing part draws (next to) nothing in the whole field's scale.
    const ratio = sum(lengths(coexact.vectors)) / sum(wholeLengths);
    console.log(`divergence-free: ${coexact.vectors.length / 3} arrows, total length ${ratio.toExponential(2)} of the whole field's`);
    expect(ratio).toBeLessThan(1e-3);

    // Its streamlines are traced in the worker for the part: few or none where the whole field has many.
    await expect.poll(() => evaluate(() => window.tvf.perf().streamlines?.component)).toBe('coexact');
  });

  test('the energy shares shown sum to 100 %', async () => {
    const shares = page.locator('tangent-field-designer #component-shares');
    await expect(shares).toBeVisible();
    await expect(shares).not.toHaveClass(/stale/);
    const texts = await shares.locator('[data-share]').allTextContents();
    const values = texts.map((t) => parseFloat(t));
    console.log(`energy shares shown: ${texts.join(' / ')}`);
    expect(values.every(Number.isFinite)).toBe(true);
    expect(Math.abs(sum(values) - 100)).toBeLessThan(0.25);
    expect(values[0]).toBeGreaterThan(99); // a source and a sink: curl-free
  });

  test('the select and setViews agree; an unknown component is refused', async () => {
    await select().selectOption('harmonic');
    await expect.poll(() => evaluate(() => window.tvf.views().component)).toBe('harmonic');
    await evaluate(() => window.tvf.setViews({ component: 'exact' }));
    await expect(select()).toHaveValue('exact');
    const err = await evaluate(() => {
      try {
        window.tvf.setViews({ component: 'curl' });
        return null;
      } catch (e) {
        return e.message;
      }
    });
    expect(err).toMatch(/unknown component "curl".*'whole', 'exact', 'coexact', 'harmonic'/);
    expect((await evaluate(() => window.tvf.views())).component).toBe('exact');
  });

  test('back to the whole field: drawn at once, nothing more asked, not even after an edit', async () => {
    await showComponent('exact');
    const before = await requests();
    expect(before.component).toBeGreaterThan(0);
    expect(before.hodgeShares).toBeGreaterThan(0);
    await evaluate(() => window.tvf.setViews({ component: 'whole' }));
    await expect(select()).toHaveValue('whole');
    await expect(page.locator('tangent-field-designer #component-shares')).toBeHidden();
    await evaluate(() => window.tvf.addSource(7));
    await settle();
    expect(await requests()).toEqual(before);
    // The arrows are the new whole field's.
    const drawn = await arrows();
    expect(drawn.vectors.length).toBeGreaterThan(300);
  });
});
