// The texture's bookkeeping, without a GPU: the phase clock (web/synthesis/phase-clock.js) adds up to the wall
// time it measures and moves a split found afterwards without changing the total; the atlas cache's identity
// (web/synthesis/atlas-cache.js) changes with any byte of the input, and an entry of another input is never
// handed out.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { AtlasCache, inputHash } from '../../web/synthesis/atlas-cache.js';
import { PhaseClock } from '../../web/synthesis/phase-clock.js';

const busy = (ms) => {
  const end = performance.now() + ms;
  while (performance.now() < end);
};

test('phases add up to the wall time, and a move keeps the total', () => {
  const t0 = performance.now();
  const clock = new PhaseClock(t0);
  busy(3);
  clock.mark('a');
  busy(2);
  clock.mark('kernel: GPU');
  busy(1);
  clock.mark('a');
  const wall = performance.now() - t0;
  const sum = Object.values(clock.phases).reduce((x, y) => x + y, 0);
  assert.ok(Math.abs(sum - clock.wallMs) < 1e-9, `${sum} vs ${clock.wallMs}`);
  assert.ok(clock.wallMs <= wall && clock.wallMs >= 6, `wall ${clock.wallMs}`);
  assert.ok(clock.phases.a >= 4 && clock.phases['kernel: GPU'] >= 2);
  const before = { ...clock.phases };
  clock.move('kernel: GPU', 'waits', 1);
  clock.move('a', 'waits', 1e9); // at most what there is
  assert.equal(clock.phases.a, 0);
  assert.ok(Math.abs(clock.phases.waits - before.a - 1) < 1e-9);
  const after = Object.values(clock.phases).reduce((x, y) => x + y, 0);
  assert.ok(Math.abs(after - sum) < 1e-9);
  const { phases, wallMs } = clock.summary();
  assert.deepEqual(Object.keys(phases), ['a', 'kernel: GPU', 'waits']);
  assert.equal(wallMs, Math.round(10 * clock.wallMs) / 10);
});

const mesh = () => ({
  positions: new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]),
  triangles: new Uint32Array([0, 1, 2, 1, 3, 2]),
  cornerUVs: null,
});

test('the atlas identity follows every byte of the input and the settings', () => {
  const base = AtlasCache.identify(mesh(), { resolution: 512, gutter: 2 });
  assert.equal(base.key, AtlasCache.identify(mesh(), { resolution: 512, gutter: 2 }).key);
  const keys = new Set([base.key]);
  const moved = mesh();
  moved.positions[4] = Math.fround(1e-7); // one coordinate, by a little
  keys.add(AtlasCache.identify(moved, { resolution: 512, gutter: 2 }).key);
  const flipped = mesh();
  flipped.triangles.set([0, 2, 1], 0);
  keys.add(AtlasCache.identify(flipped, { resolution: 512, gutter: 2 }).key);
  keys.add(AtlasCache.identify({ ...mesh(), cornerUVs: new Float32Array(12) }, { resolution: 512, gutter: 2 }).key);
  keys.add(AtlasCache.identify(mesh(), { resolution: 1024, gutter: 2 }).key);
  keys.add(AtlasCache.identify(mesh(), { resolution: 512, gutter: 3 }).key);
  assert.equal(keys.size, 6);
  assert.notEqual(inputHash([new Uint8Array([1, 2, 3])]), inputHash([new Uint8Array([1, 2, 3, 0])]));
});

const prepared = (n) => ({
  cornerUVs: new Float32Array(6).fill(n),
  faceCharts: new Int32Array(1),
  corners: {
    uv: new Float32Array(6).fill(n),
    frames: new Float32Array(12).fill(n),
    faceArea: new Float32Array(1),
    gutter: { uv: new Float32Array(4).fill(n), source: new Int32Array(4), indices: new Uint32Array(6) },
  },
  seams: { map: new Float32Array(2).fill(n) },
  source: 'generated',
});

test('the cache hands out copies of its own input\'s atlas only', async () => {
  const cache = new AtlasCache({ persistent: false });
  const id = AtlasCache.identify(mesh(), { resolution: 512, gutter: 2 });
  assert.equal(await cache.get(id), null);
  const made = prepared(7);
  await cache.put(id, made);
  made.cornerUVs.fill(0); // the caller's arrays go elsewhere (transferred): the cache kept its own
  const got = await cache.get(id);
  assert.deepEqual(Array.from(got.cornerUVs), [7, 7, 7, 7, 7, 7]);
  made.corners.gutter.uv.fill(0);
  made.corners.frames.fill(0);
  assert.deepEqual(Array.from(got.corners.gutter.uv), [7, 7, 7, 7]);
  assert.equal(got.corners.frames[11], 7);
  got.cornerUVs.fill(1);
  assert.equal((await cache.get(id)).cornerUVs[0], 7);
  const other = AtlasCache.identify(mesh(), { resolution: 256, gutter: 2 });
  assert.equal(await cache.get(other), null);
  assert.equal(await cache.get({ key: id.key, sizes: [...id.sizes.slice(0, -1), 99] }), null); // stale format
});
