// The core worker's entry (web/core-worker.js) served on a stand-in of the worker's global, with the real wasm
// core (dist/wasm, built before the unit tests run): the composed groups answer a model's bytes, its load, an
// edit and the read-outs of the field version they name, the exports' refusal and the synthesis ops.
import assert from 'node:assert/strict';
import test from 'node:test';
import { fnv1a } from '../../web/core/model-bytes.js';
import { icosphere, offText } from './fakes.mjs';
import { serveCoreWorker } from './worker-harness.mjs';

const DIST = new URL('../../dist/', import.meta.url).href;

// The entry serves `self`: here a stand-in that keeps what the worker posts (worker-harness.mjs).
const { posted, call, callMarked } = await serveCoreWorker();
// The page's count of requests that rank above a background one, as a cross-origin isolated page shares it.
const interrupts = new Int32Array(new SharedArrayBuffer(4));

test('the worker entry: a load, an edit, and read-outs of the version they name', async () => {
  assert.deepEqual((await call('init', DIST, interrupts)).value, { crossOriginIsolated: false });
  await assert.rejects(call('add', {}), /no mesh loaded/);

  const mesh = icosphere(3);
  const text = new TextEncoder().encode(offText(mesh));
  const read = (await call('readBytes', new Blob([text]))).value;
  assert.deepEqual(new Uint8Array(read.bytes), text);
  assert.equal(read.digest, fnv1a(text));

  const load = await call('loadMesh', new Uint8Array(read.bytes), 'off', null, null);
  assert.equal(load.value.info.faces, mesh.triangles.length / 3);
  assert.deepEqual(Array.from(load.value.surface.triangles), Array.from(mesh.triangles));
  const v1 = load.snapshot.version;
  assert.deepEqual(load.snapshot.design.document.constraints, []);

  const points = [10, 11, 12].map((face) => ({ face, bary: [0.2, 0.3, 0.5] }));
  const edit = await call('add', { type: 'stroke', points, strength: 1, weight: 1e4 });
  const v2 = edit.snapshot.version;
  assert.equal(v2, v1 + 1);
  assert.deepEqual(edit.snapshot.design.changed.map(([id]) => id), [edit.value]);
  assert.ok(posted.some((p) => p.data.deferredUpdate?.seq === edit.seq), 'the factor took the update after');

  // The snapshot's field is the core's, bit for bit.
  const held = (await call('read')).value;
  assert.equal(held.version, v2);
  assert.deepEqual(edit.snapshot.vertexVectors, held.vertexVectors);
  assert.deepEqual(edit.snapshot.faceVectors, held.faceVectors);

  const lines = (await call('streamlines', v2, 0.2, 0)).value;
  assert.ok(lines.length > 0 && lines.every((l) => l instanceof Float32Array));
  assert.deepEqual((await call('streamlines', v2, 0.2, 0)).value, lines);
  assert.equal((await call('streamlines', v1, 0.2, 0)).value, null, "an earlier version's read-out");

  const hodge = await call('hodge', v2);
  assert.equal(hodge.value.exact.length, mesh.edges.length / 2);
  assert.equal(hodge.list.length, 6, 'the parts are transferred');
  const harmonic = (await call('component', v2, 'harmonic')).value;
  assert.equal(harmonic.vertexVectors.length, mesh.positions.length);
  const shares = (await call('hodgeShares', v2)).value;
  assert.deepEqual(shares.energyShares, hodge.value.energyShares);

  await assert.rejects(call('exportRawField'), /holds line and cross fields; this is a vector field/);
});

// A stripe pattern gives way to a request the page sent after it (an edit, an export): the core's steps read
// the shared count, the op replies {interrupted: true} and the last pattern stays; asked again at the new count
// (as the page does once that request is served), it is made.
test('a stripe pattern gives way to a request sent after it', async () => {
  const { version } = (await call('read')).value;
  const options = { frequency: 3, adaptSpacing: true };
  const made = await callMarked(Atomics.load(interrupts, 0), 'stripes', version, 'whole', options);
  assert.ok(made.value.phase.length > 0 && made.value.stats.residual < 1e-3);
  const sentAt = Atomics.load(interrupts, 0);
  Atomics.add(interrupts, 0, 1); // an edit sent behind the next request, before that request runs
  const given = await callMarked(sentAt, 'stripes', version, 'whole', { ...options, frequency: 4 });
  assert.deepEqual(given.value, { interrupted: true });
  const again = await callMarked(Atomics.load(interrupts, 0), 'stripes', version, 'whole', { ...options, frequency: 4 });
  assert.ok(again.value.phase.length > 0 && again.value.stats.residual < 1e-3);
  assert.notDeepEqual(Array.from(again.value.phase.slice(0, 30)), Array.from(made.value.phase.slice(0, 30)));
  // A page that cannot share the count (no mark): never interrupted.
  Atomics.add(interrupts, 0, 1);
  assert.ok((await call('stripes', version, 'whole', options)).value.phase.length > 0);
});

test('the synthesis ops the entry composes: an exemplar analysed in the worker', async () => {
  const { value, list } = await call('analyzeExemplar', { procedural: 'stripes', size: 32, seed: 1 });
  assert.equal(value.size, 32);
  assert.equal(value.rgba8.length, 32 * 32 * 4);
  assert.ok(list.length > 0 && list.includes(value.rgba8.buffer));
});
