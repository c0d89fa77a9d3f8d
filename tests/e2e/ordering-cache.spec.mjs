// The field's fill-reducing ordering kept per mesh in IndexedDB (web/core/worker/ordering-cache.js) with its
// symbolic factor: a model opened again, in the same page or after a reload, skips the whole analysis
// (stats().analysisReused, symbolicReused) and solves the same field, to round-off; another mesh is ordered
// anew; a damaged entry is ignored and replaced.
import { expect, test } from '@playwright/test';
import { icosphereOff } from '../icosphere.mjs';
import { openDesigner, openDesignerPage } from './helpers.mjs';

// Opens the OFF text, puts one vector on it and returns the stats and the 1-form.
async function openAndDesign(page, off, name) {
  return page.evaluate(
    async ({ off, name }) => {
      const t = window.tvf;
      await t.loadModel(new TextEncoder().encode(off).buffer, { name, restore: false });
      await t.settled();
      const { analysisReused: reused, symbolicReused } = t.stats();
      await t.addVector(7, [1, 0.3, 0]);
      await t.settled();
      return { reused, symbolicReused, oneForm: Array.from(await t.oneForm()) };
    },
    { off, name },
  );
}

// Waits until the worker has stored `count` orderings (it stores behind the load's reply).
async function storedOrderings(page, count) {
  return page.evaluate(async (count) => {
    for (let i = 0; i < 200; i++) {
      const entries = await new Promise((resolve) => {
        const r = indexedDB.open('tvf-ordering-cache', 1);
        r.onupgradeneeded = () => r.result.createObjectStore('orderings', { keyPath: 'key' });
        r.onsuccess = () => {
          const get = r.result.transaction('orderings').objectStore('orderings').getAll();
          get.onsuccess = () => (r.result.close(), resolve(get.result));
          get.onerror = () => (r.result.close(), resolve([]));
        };
        r.onerror = () => resolve([]);
      });
      const permutation = (p) => new Set(p).size === p.length;
      // Big arrays are kept as Blobs (kept-store.js storedForm): {keptBlob, type}.
      const restored = async (x) => (x?.keptBlob ? new globalThis[x.type](await x.keptBlob.arrayBuffer()) : x);
      const summary = async (e) => {
        const [perm, symbolic] = [await restored(e.perm), await restored(e.symbolic)];
        return { key: e.key, n: perm.length, permutation: permutation(perm), symbolic: symbolic?.length ?? 0 };
      };
      if (entries.length >= count) return Promise.all(entries.map(summary));
      await new Promise((resolve) => setTimeout(resolve, 50));
    }
    return [];
  }, count);
}

// Damages the kept entry of the n-edge mesh: its permutation no longer one, or its symbolic factor cut short.
function damageEntry(page, n, what) {
  return page.evaluate(
    ({ n, what }) =>
      new Promise((resolve, reject) => {
        const r = indexedDB.open('tvf-ordering-cache', 1);
        r.onsuccess = () => {
          const all = r.result.transaction('orderings').objectStore('orderings').getAll();
          all.onsuccess = async () => {
            // Read whole (big arrays are kept as Blobs), damaged, put back as plain arrays (which a store reads too).
            const restored = async (x) => (x?.keptBlob ? new globalThis[x.type](await x.keptBlob.arrayBuffer()) : x);
            const entries = await Promise.all(
              all.result.map(async (x) => ({ ...x, perm: await restored(x.perm), symbolic: await restored(x.symbolic) })),
            );
            const e = entries.find((x) => x.perm.length === n);
            if (what === 'perm') e.perm[1] = e.perm[0];
            else e.symbolic = e.symbolic.slice(0, e.symbolic.length - 1);
            const write = r.result.transaction('orderings', 'readwrite').objectStore('orderings');
            write.put(e).onsuccess = () => (r.result.close(), resolve());
          };
        };
        r.onerror = () => reject(r.error);
      }),
    { n, what },
  );
}

const maxRelative = (a, b) => {
  let d = 0, n = 0;
  for (let i = 0; i < a.length; i++) (d = Math.max(d, Math.abs(a[i] - b[i]))), (n = Math.max(n, Math.abs(a[i])));
  return d / n;
};

test('a model opened again takes its ordering from the cache and solves the same field', async ({ browser }) => {
  const { page, errors } = await openDesignerPage(browser);
  try {
    const off = icosphereOff(5); // big enough to factor by supernodes: a symbolic factor to keep
    const first = await openAndDesign(page, off, 'sphere.off');
    expect(first.reused).toBe(false);
    const stored = await storedOrderings(page, 2); // the default model's and this one's
    expect(stored.length).toBeGreaterThanOrEqual(2);
    const symbolicBytes = stored.find((e) => e.n === first.oneForm.length)?.symbolic;
    expect(symbolicBytes).toBeGreaterThan(0);

    const again = await openAndDesign(page, off, 'sphere.off');
    expect(again.reused).toBe(true);
    expect(again.symbolicReused).toBe(true);
    expect(maxRelative(again.oneForm, first.oneForm)).toBeLessThan(1e-12);

    // Another mesh: ordered anew.
    const other = await openAndDesign(page, icosphereOff(3), 'small.off');
    expect(other.reused).toBe(false);

    // After a reload, the same mesh again: the ordering from IndexedDB.
    await page.reload();
    await openDesigner(page);
    const reloaded = await openAndDesign(page, off, 'sphere.off');
    expect(reloaded.reused).toBe(true);
    expect(reloaded.symbolicReused).toBe(true);
    expect(maxRelative(reloaded.oneForm, first.oneForm)).toBeLessThan(1e-12);

    // A damaged symbolic factor (cut short): refused by the core, analyzed anew with the ordering, replaced.
    const n = first.oneForm.length;
    await damageEntry(page, n, 'symbolic');
    const cut = await openAndDesign(page, off, 'sphere.off');
    expect(cut.reused).toBe(true);
    expect(cut.symbolicReused).toBe(false);
    expect(maxRelative(cut.oneForm, first.oneForm)).toBeLessThan(1e-12);
    // The new analysis is stored behind the reply: waited for, whole again, then taken.
    const storedBytes = async () => (await storedOrderings(page, 1)).find((e) => e.n === n)?.symbolic;
    await expect.poll(storedBytes).toBe(symbolicBytes);
    expect((await openAndDesign(page, off, 'sphere.off')).symbolicReused).toBe(true);

    // A damaged ordering (not a permutation): refused by the core, the mesh ordered anew, the entry replaced.
    await damageEntry(page, n, 'perm');
    const damaged = await openAndDesign(page, off, 'sphere.off');
    expect(damaged.reused).toBe(false);
    expect(maxRelative(damaged.oneForm, first.oneForm)).toBeLessThan(1e-12);
    // The new ordering is stored behind the reply: waited for, a permutation again.
    await expect.poll(async () => (await storedOrderings(page, 1)).find((e) => e.n === n)?.permutation).toBe(true);
    expect((await openAndDesign(page, off, 'sphere.off')).reused).toBe(true);
    expect(errors).toEqual([]);
  } finally {
    await page.close();
  }
});
