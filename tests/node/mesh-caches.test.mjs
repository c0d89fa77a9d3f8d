// The worker caches of what depends on a mesh alone (web/core/worker/mesh-key.js, preview-cache.js,
// picking-cache.js): the key changes with any coordinate's last bit and with any index; a kept preview is the
// preview made anew (the same coarse mesh, the same map, the same fine faces' points found later); an entry
// that does not fit the mesh, or is damaged in any array, is refused.
import assert from 'node:assert/strict';
import test from 'node:test';
import { buildSerializedBVH } from '../../web/geometry/mesh-bvh-transfer.js';
import { Preview } from '../../web/core/preview/preview.js';
import { torus } from '../../web/core/preview/warm-up.js';
import { meshKey } from '../../web/core/worker/mesh-key.js';
import { restoredForm, storedForm } from '../../web/core/worker/kept-store.js';
import { usableBVH } from '../../web/core/worker/picking-cache.js';
import { usablePreviewParts } from '../../web/core/worker/preview-cache.js';

const fine = () => {
  const { positions, triangles } = torus(120, 60);
  return { positions, triangles };
};

test('the mesh key changes with any coordinate bit and any index, not with a copy', () => {
  const m = fine();
  const key = meshKey(m.positions, m.triangles);
  assert.equal(meshKey(m.positions.slice(), m.triangles.slice()), key);
  const moved = m.positions.slice();
  moved[1234] = moved[1234] * (1 + Number.EPSILON);
  assert.notEqual(moved[1234], m.positions[1234]);
  assert.notEqual(meshKey(moved, m.triangles), key);
  const flipped = m.triangles.slice();
  [flipped[30], flipped[31]] = [flipped[31], flipped[30]];
  assert.notEqual(meshKey(m.positions, flipped), key);
  assert.match(key, new RegExp(`-v${m.positions.length / 3}-f${m.triangles.length / 3}$`));
});

test('a kept preview is the preview made anew; damaged or foreign parts are refused', async () => {
  const m = fine();
  const made = await Preview.prepare(m);
  const parts = structuredClone(Preview.keptParts(made)); // as IndexedDB gives it back
  const nV = m.positions.length / 3;
  assert.equal(usablePreviewParts({ format: 1, ...parts }, nV), true);
  const again = await Preview.prepare(m, { format: 1, ...parts });
  assert.deepEqual(again.coarse.positions, made.coarse.positions);
  assert.deepEqual(again.coarse.triangles, made.coarse.triangles);
  assert.deepEqual(again.map.vertexFace, made.map.vertexFace);
  assert.deepEqual(again.map.vertexBary, made.map.vertexBary);
  assert.equal(again.timings.kept, true);
  // The faces' points, found only when asked (searched from the kept nearest vertices), are the same too.
  made.map.everyFaceOnCoarse();
  again.map.everyFaceOnCoarse();
  assert.deepEqual(again.map.faceFace, made.map.faceFace);
  assert.deepEqual(again.map.faceBary, made.map.faceBary);

  const damaged = (change) => {
    const e = { format: 1, ...structuredClone(parts) };
    change(e);
    return usablePreviewParts(e, nV);
  };
  assert.equal(usablePreviewParts({ format: 1, ...parts }, nV + 1), false); // another mesh's
  assert.equal(damaged((e) => (e.format = 2)), false);
  assert.equal(damaged((e) => (e.vertexFace[5] = parts.coarseTriangles.length / 3)), false);
  assert.equal(damaged((e) => (e.nearest[5] = -1)), false);
  assert.equal(damaged((e) => (e.fineVertex[0] = nV)), false);
  assert.equal(damaged((e) => (e.coarseTriangles[3] = parts.fineVertex.length)), false);
  assert.equal(damaged((e) => (e.vertexBary[7] = NaN)), false);
  assert.equal(damaged((e) => (e.vertexBary = new Float32Array(e.vertexBary))), false);
  assert.equal(damaged((e) => (e.coarseTriangles = e.coarseTriangles.subarray(1))), false);
});

test('a kept bounds tree is refused when it does not fit the mesh or is damaged', () => {
  const m = fine();
  const nV = m.positions.length / 3, nF = m.triangles.length / 3;
  const bvh = { ...buildSerializedBVH(m.positions, m.triangles), positions: null, index: null };
  const entry = () => ({ format: 1, bvh: structuredClone(bvh) });
  assert.equal(usableBVH(entry(), nV, nF), true);
  assert.equal(usableBVH(entry(), nV, nF + 1), false);
  const damaged = (change) => {
    const e = entry();
    change(e.bvh);
    return usableBVH(e, nV, nF);
  };
  assert.equal(damaged((b) => (b.indirectBuffer[2] = nF)), false);
  assert.equal(damaged((b) => (b.format = 0)), false);
  assert.equal(damaged((b) => (b.roots = [b.roots[0].slice(0, 40)])), false);
  // The root's first leaf reaches past the faces; an inner node's right child past the buffer.
  const nodes = (b, visit) => {
    const u32 = new Uint32Array(b.roots[0]), u16 = new Uint16Array(b.roots[0]);
    for (let n = 0; n < u32.length; n += 8) if (visit(n, u32, u16)) return;
  };
  assert.equal(damaged((b) => nodes(b, (n, u32, u16) => u16[2 * n + 15] === 0xffff && (u32[n + 6] = nF))), false);
  assert.equal(damaged((b) => nodes(b, (n, u32, u16) => u16[2 * n + 15] !== 0xffff && (u32[n + 6] = 1e6))), false);
  assert.equal(damaged((b) => (new Float32Array(b.roots[0])[0] = NaN)), false);
});

test('an entry stored with its big typed arrays as Blobs comes back the same, small ones and the rest as they were', async () => {
  const big = new Float64Array(20000).map((_, i) => Math.sin(i));
  const view = new Int32Array(new Int32Array(40000).map((_, i) => i * 7).buffer, 4 * 1000, 30000); // a view inside a buffer
  const entry = { key: 'k', madeAt: 3, atlas: { big, parts: [view, new Uint8Array([1, 2, 3])], name: 'x', n: 5, none: null } };
  const stored = storedForm(entry);
  assert.ok(stored.atlas.big.keptBlob instanceof Blob);
  assert.equal(stored.atlas.big.keptBlob.size, big.byteLength);
  assert.ok(stored.atlas.parts[0].keptBlob instanceof Blob);
  assert.ok(stored.atlas.parts[1] instanceof Uint8Array); // under the threshold: as it is
  assert.equal(big[5], Math.sin(5)); // the entry itself untouched
  const back = await restoredForm(stored);
  assert.ok(back.atlas.big instanceof Float64Array);
  assert.deepEqual(back.atlas.big, big);
  assert.ok(back.atlas.parts[0] instanceof Int32Array);
  assert.deepEqual(back.atlas.parts[0], view);
  assert.deepEqual(back.atlas.parts[1], new Uint8Array([1, 2, 3]));
  assert.deepEqual({ ...back, atlas: null }, { key: 'k', madeAt: 3, atlas: null });
  assert.deepEqual([back.atlas.name, back.atlas.n, back.atlas.none], ['x', 5, null]);
});

test("a picking tree's roots, ArrayBuffers, stored as Blobs come back as ArrayBuffers of the same bytes", async () => {
  const root = new Uint32Array(30000).map((_, i) => i * 2654435761).buffer;
  const small = new Uint8Array([9, 8, 7]).buffer;
  const stored = storedForm({ key: 'k', bvh: { roots: [root, small] } });
  assert.ok(stored.bvh.roots[0].keptBlob instanceof Blob);
  assert.ok(stored.bvh.roots[1] instanceof ArrayBuffer); // under the threshold: as it is
  const back = await restoredForm(stored);
  assert.ok(back.bvh.roots[0] instanceof ArrayBuffer);
  assert.deepEqual(new Uint32Array(back.bvh.roots[0]), new Uint32Array(root));
  assert.deepEqual(new Uint8Array(back.bvh.roots[1]), new Uint8Array([9, 8, 7]));
});
