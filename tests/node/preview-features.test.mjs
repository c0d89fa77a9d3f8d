// A big model's preview and the design's sharp features, with the real wasm core (dist/wasm, built before the
// unit tests run) behind the worker's own ops (web/core/worker/): the preview core solves on a decimated stand-in
// whose creases are the decimation's, so it runs without features, while the fine design document it answers
// with keeps the design's angle and edge edits. The truth is the exact core, given the same model and edits.
import assert from 'node:assert/strict';
import test from 'node:test';
import { loadCore } from '../../web/core/core-client.js';
import { openModelInSteps } from '../../web/core/open-steps.js';
import { serve } from '../../web/core/worker/dispatch.js';
import { editOps } from '../../web/core/worker/edit-ops.js';
import { loadOps } from '../../web/core/worker/load-ops.js';
import { previewOps } from '../../web/core/worker/preview-ops.js';
import { settingOps } from '../../web/core/worker/setting-ops.js';
import { WorkerState } from '../../web/core/worker/state.js';
import { icosphere, offText } from './fakes.mjs';

const DIST = new URL('../../dist/', import.meta.url).href;

// A preview worker stand-in: the entry's groups that a preview worker serves, over a state the test can read.
function previewWorker() {
  const posted = [];
  const scope = { postMessage: (data, list = []) => posted.push({ data, list }) };
  const state = new WorkerState(scope);
  serve(scope, state, [loadOps(state), previewOps(state), editOps(state), settingOps(state)]);
  let seq = 0;
  const call = async (op, ...args) => {
    const mine = ++seq;
    await scope.onmessage({ data: { seq: mine, op, args } });
    const { data } = posted.find((p) => p.data.seq === mine && !p.data.progress);
    if (!data.ok) throw new Error(data.error);
    return data;
  };
  return { state, call };
}

// The features part of a design document, as the core writes it (absent: none).
const featuresOf = ({ featureAngle, featureEdges }) => ({ featureAngle, featureEdges });

test('the preview core runs without features; the fine document keeps the angle and the edge edits', async () => {
  const mesh = icosphere(4);
  const bytes = new TextEncoder().encode(offText(mesh));
  const [a, b, c] = mesh.triangles; // a fine face: its edges are fine mesh edges
  const d = mesh.triangles.at(-1); // a vertex away from them, for a prescribed singularity
  const design = { constraints: [], featureAngle: 35, featureEdges: { add: [[a, b]], remove: [[b, c]] } };
  // The exact worker's side: the model opened in steps with a new design's angle in the settings, as the page
  // opens one (session/model-loader.js); its 'read' and 'opened' progress are what the preview worker gets.
  const exact = await loadCore(DIST);
  const sent = [];
  const steps = { bytes, format: 'off', settings: { featureAngle: 35 }, design, embedded: false, previewEdges: 1 };
  openModelInSteps(exact, steps, (value) => sent.push(value));
  const [read, opened] = sent;
  assert.deepEqual(featuresOf(opened.design), featuresOf(design), 'the exact core took the features');
  exact.commitModel();

  const { state, call } = previewWorker();
  await call('init', DIST);
  await call('previewMesh', read.mesh);
  await call('openPreview', opened.design, steps.settings);
  assert.ok(state.preview, 'the worker serves a preview');
  assert.deepEqual(state.core.features(), { angle: 0, add: [], remove: [] }, 'the coarse core has no features');
  assert.equal('featureAngle' in JSON.parse(state.core.designJson()), false);

  // An edit: the coarse core stays without features, the fine document is the exact core's own.
  const sid = (await call('addSingularity', d, 1)).value;
  exact.addSingularity(d, 1);
  const angle = await call('setFeatures', { angle: 50, add: [[a, b], [c, a]], remove: [] });
  exact.setFeatures({ angle: 50, add: [[a, b], [c, a]], remove: [] });
  assert.equal(state.core.features().angle, 0, 'a new angle does not reach the coarse core');
  const doc = angle.snapshot.design.document;
  assert.equal(doc.featureAngle, 50);
  assert.deepEqual(doc.featureEdges, { add: [[a, b], [c, a]], remove: [] });
  assert.deepEqual(doc, JSON.parse(exact.designJson()), 'the fine document is the exact core\'s');
  assert.deepEqual(Object.keys(doc), Object.keys(JSON.parse(exact.designJson())), 'in the core\'s key order');
  assert.deepEqual(angle.snapshot.design.specs, [{ index: 1, type: 'singularity', vertex: d }]);
  assert.deepEqual(angle.snapshot.design.ids, [sid]);

  // Any part of the features alone (the others kept), and 0: none, which a document leaves out.
  const edges = (await call('setFeatures', { remove: [[b, c]] })).snapshot.design.document;
  assert.deepEqual(featuresOf(edges), { featureAngle: 50, featureEdges: { add: [[a, b], [c, a]], remove: [[b, c]] } });
  const off = (await call('setFeatures', { angle: 0, add: [], remove: [] })).snapshot.design.document;
  exact.setFeatures({ angle: 0 });
  assert.deepEqual(off, JSON.parse(exact.designJson()));
  assert.equal('featureAngle' in off || 'featureEdges' in off, false);

  // A whole design applied: its features go to the fine document, none to the coarse core.
  const applied = { ...doc, featureAngle: 20, featureEdges: { add: [], remove: [[a, b]] } };
  const whole = (await call('applyDesign', applied)).snapshot.design.document;
  exact.applyDesignJson(JSON.stringify(applied));
  assert.deepEqual(whole, JSON.parse(exact.designJson()));
  assert.deepEqual(featuresOf(whole), featuresOf(applied));
  assert.deepEqual(state.core.features(), { angle: 0, add: [], remove: [] });

  // An angle the core refuses is refused by the preview too, by the core's name for it, and changes nothing.
  await assert.rejects(call('setFeatures', { angle: 200 }), /feature angle must be a number of degrees in \[0, 180\]/);
  const after = (await call('setGamma', 0)).snapshot.design.document;
  assert.deepEqual(featuresOf(after), featuresOf(applied));
});
