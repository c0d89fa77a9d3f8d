// A big model's opening in steps, with the real wasm core (dist/wasm, built before the unit tests run): the exact
// worker's side (web/core/open-steps.js) sends the mesh read before it is checked, then the design; the preview
// worker's side (web/core/preview/: warm-up, prepare, open) takes them in that order and makes a preview field
// of vertex vectors on the fine mesh.
import assert from 'node:assert/strict';
import test from 'node:test';
import { loadCore } from '../../web/core/core-client.js';
import { openModelInSteps } from '../../web/core/open-steps.js';
import { Preview } from '../../web/core/preview/preview.js';
import { warmUpPreview } from '../../web/core/preview/warm-up.js';
import { SpareArrays } from '../../web/core/spare-arrays.js';
import { icosphere, offText, parseOff } from './fakes.mjs';

const DIST = new URL('../../dist/', import.meta.url).href;

function opening(core, bytes, previewEdges) {
  const sent = [];
  const steps = { bytes, format: 'off', settings: null, design: null, embedded: false, previewEdges };
  const out = openModelInSteps(core, steps, (value, list) => sent.push({ value, list }));
  return { ...out, sent };
}

test('opening in steps: the mesh read goes first, then the design; a small model sends nothing', async () => {
  const core = await loadCore(DIST);
  const mesh = icosphere(3);
  const bytes = new TextEncoder().encode(offText(mesh));
  const nE = mesh.edges.length / 2;

  const big = opening(core, bytes, nE); // just at the threshold: 1.5 faces per edge promise it
  assert.deepEqual(big.sent.map((s) => s.value.phase), ['read', 'opened']);
  const [read, opened] = big.sent.map((s) => s.value);
  assert.deepEqual(Array.from(read.mesh.positions), Array.from(mesh.positions));
  assert.deepEqual(Array.from(read.mesh.triangles), Array.from(mesh.triangles));
  assert.deepEqual(Object.keys(opened.mesh), [], 'the mesh is not sent twice');
  assert.equal(opened.info.edges, nE);
  assert.ok(big.ahead && Array.isArray(opened.design.constraints));
  for (const { list } of big.sent) assert.equal(new Set(list).size, list.length, 'each buffer transferred once');
  core.commitModel();
  assert.equal(core.info().edges, nE);

  const small = opening(core, bytes, nE + 1);
  assert.deepEqual(small.sent, [], 'below the threshold the model opens without a preview');
  assert.equal(small.ahead, false);
  const none = opening(core, bytes, 0);
  assert.deepEqual(none.sent, []);

  // A broken file fails at the read, and a non-manifold one at the check, each by name, with nothing sent.
  assert.throws(() => opening(core, new TextEncoder().encode('OFF\n3 1 0\n0 0 0\n'), 1), /load:/);
  const book = 'OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n';
  assert.throws(() => opening(core, new TextEncoder().encode(book), 1), /non-manifold/);
});

test('the preview worker: warmed up on a torus, then prepared on the mesh read and opened with the design', async () => {
  const core = await loadCore(DIST);
  await warmUpPreview(core);
  assert.ok(core.info().genus === 1, 'the warm-up leaves the torus loaded');

  const exact = await loadCore(DIST);
  const fine = parseOff(offText(icosphere(4)));
  const sent = opening(exact, new TextEncoder().encode(offText(fine)), 1).sent.map((s) => s.value);
  const prepared = await Preview.prepare(sent[0].mesh);
  assert.ok(prepared.coarse.triangles.length / 3 <= fine.triangles.length / 12, 'a quarter of the faces at most');
  const preview = Preview.open(core, prepared, sent[1].design, null);
  const snap = preview.snapshot(new SpareArrays(), {});
  assert.equal(snap.vertexVectors.length, fine.positions.length);
  assert.equal(snap.faceVectors, null, "a vector field's face vectors are the page's to derive");
  assert.equal(snap.oneForm, null);
  assert.deepEqual(snap.transfer, [snap.vertexVectors.buffer]);
  assert.ok(snap.stats.preview && snap.version < 0);
  assert.ok(snap.scale.max >= snap.scale.top && snap.scale.top >= 0);
  assert.deepEqual(snap.design.document.constraints, [], 'without the changed ids, the whole fine document');

  // An edit's reply carries its own entry, in fine terms (the fine faces of the stroke's points).
  const points = [10, 11, 12].map((face) => ({ face, bary: [0.2, 0.3, 0.5] }));
  const spec = { type: 'stroke', points, strength: 1, weight: 1e4 };
  const [coarseSpec] = preview.argsOnCoarse('add', [spec]);
  const id = core.addConstraintJson(coarseSpec);
  preview.afterOp('add', [spec], id);
  core.solve();
  const after = preview.snapshot(new SpareArrays(), {}, [id]);
  assert.deepEqual(after.design.ids, [id]);
  assert.equal(after.design.document, undefined);
  assert.deepEqual(after.design.changed.map(([k]) => k), [id]);
  assert.deepEqual(after.design.changed[0][1].points, points);

  // A prescribed singularity: placed and moved on the coarse vertex the fine one stands on, answered in fine
  // vertices; the features (angle and fine edge edits) stay in the fine document, the coarse core has none.
  core.remove(id);
  preview.afterOp('remove', [id], true);
  core.setSymmetry(4);
  const [v, w] = [prepared.coarse.fineVertex[5], prepared.coarse.fineVertex[200]];
  const placeArgs = preview.argsOnCoarse('addSingularity', [v, 0.25]);
  assert.deepEqual(placeArgs, [5, 0.25], 'a kept fine vertex is its coarse vertex');
  const sid = core.addSingularity(...placeArgs);
  preview.afterOp('addSingularity', [v, 0.25], sid);
  core.solve();
  const placed = preview.snapshot(new SpareArrays(), {}, [sid]);
  assert.deepEqual(placed.design.changed, [[sid, { index: 0.25, type: 'singularity', vertex: v }]]);
  core.moveSingularity(...preview.argsOnCoarse('moveSingularity', [sid, w]));
  preview.afterOp('moveSingularity', [sid, w], true);
  const [a, b] = [fine.triangles[0], fine.triangles[1]]; // an edge of the fine mesh
  core.setFeatures(...preview.argsOnCoarse('setFeatures', [{ angle: 30, add: [[a, b]], remove: [] }]));
  preview.afterOp('setFeatures', [{ angle: 30, add: [[a, b]], remove: [] }], true);
  core.solve();
  const whole = preview.snapshot(new SpareArrays(), {});
  assert.deepEqual(whole.design.document.singularities, [{ index: 0.25, vertex: w }]);
  assert.deepEqual(whole.design.specs, [{ index: 0.25, type: 'singularity', vertex: w }]);
  assert.deepEqual(whole.design.document.constraints, []);
  assert.equal(whole.design.document.featureAngle, 30);
  assert.deepEqual(whole.design.document.featureEdges, { add: [[a, b]], remove: [] });
  assert.deepEqual(core.features(), { angle: 0, add: [], remove: [] }, 'the coarse core has no features');
});
