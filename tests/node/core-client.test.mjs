// The wasm core's client (web/core/core-client.js and its call groups in web/core/client/), with the real core
// (dist/wasm, built before the unit tests run): the groups together make one class in which no call is defined
// twice (a later group would hide an earlier one's unseen), every call the worker makes is there, and each group's
// failures reach the caller as a CoreError naming the operation, the model left as it was.
import assert from 'node:assert/strict';
import test from 'node:test';
import { CoreClient, loadCore } from '../../web/core/core-client.js';
import { CoreError } from '../../web/core/core-error.js';
import { icosphereOff } from '../icosphere.mjs';

const DIST = new URL('../../dist/', import.meta.url).href;

// The calls of each class on CoreClient's prototype chain, nearest first.
function callsByClass() {
  const out = [];
  for (let proto = CoreClient.prototype; proto !== Object.prototype; proto = Object.getPrototypeOf(proto)) {
    out.push(Object.getOwnPropertyNames(proto).filter((name) => name !== 'constructor'));
  }
  return out;
}

test('core client: the call groups make one class, each call defined once', () => {
  const all = callsByClass().flat();
  const twice = all.filter((name, k) => all.indexOf(name) !== k);
  assert.deepEqual(twice, []);
  // What the worker's op modules, open-steps.js, preview/ and core-export.js call.
  const used = ['addConstraintJson', 'applyDeferredUpdates', 'applyDesignJson', 'commitModel', 'constraint',
    'constraintIds', 'curvatureAlignment', 'designJson', 'edges', 'faceVectors', 'factor', 'fieldJson', 'gamma',
    'hodge', 'info', 'loadModel', 'mesh', 'oneForm', 'openParsed', 'parsedMesh', 'pendingDesign', 'pendingInfo',
    'pendingMesh', 'readModel', 'reconstruct', 'remove', 'setBoundary', 'setCurvatureAlignment',
    'setDeferredUpdates', 'setFactorMemoryLimit', 'setGamma', 'setStrength', 'setSymmetry', 'setWeight',
    'singularities', 'solve', 'stats', 'symmetry', 'vertexVectors', 'warmUp', 'addSingularity', 'moveSingularity',
    'setFeatures', 'features', 'featureEdgePairs', 'constraintSpecs'];
  assert.deepEqual(used.filter((name) => !all.includes(name)), []);
});

// The message of the CoreError `fn` throws.
function refusal(fn) {
  try {
    fn();
  } catch (err) {
    assert.ok(err instanceof CoreError, `${err.name}: ${err.message}`);
    return err.message;
  }
  assert.fail('no error');
}

test('core client: each group reports a failure as a CoreError naming the operation', async () => {
  const core = await loadCore(DIST);
  assert.ok(core instanceof CoreClient);
  assert.match(refusal(() => core.loadModel(new TextEncoder().encode('OFF\n1 1 0\n'), 'off')), /^load: /);
  assert.equal(core.hasMesh, false);
  core.loadModel(new TextEncoder().encode(icosphereOff(1)), 'off');
  assert.equal(core.hasMesh, true);
  const nE = core.edges().length / 2;
  assert.equal(core.oneForm().length, nE);

  assert.match(refusal(() => core.setSymmetry(2.5)), /^symmetry must be a whole number from 1 to 6 \(got 2\.5\)$/);
  assert.match(refusal(() => core.setGamma(null)), /^gamma must be a number \(got null\)$/);
  assert.match(refusal(() => core.setBoundary({ angle: 'steep' })), /^boundary: /);
  assert.match(refusal(() => core.addConstraintJson({ type: 'vortex', face: 1e9, strength: 1 })), /^constraint: /);
  assert.match(refusal(() => core.remove(12345)), /^remove: /);
  assert.match(refusal(() => core.setWeight(12345, 1)), /^weight: /);
  assert.match(refusal(() => core.applyDesignJson('{')), /^design: /);
  assert.match(refusal(() => core.reconstruct(new Float64Array(1))), /^reconstruct: /);
  assert.deepEqual(core.constraintIds(), []);

  const id = core.addConstraintJson({ type: 'vector', face: 0, vector: [1, 0, 0], weight: 1 });
  core.solve();
  assert.equal(core.constraint(id).type, 'vector');
  assert.deepEqual(core.constraintIds(), [id]);
  assert.equal(core.oneForm().length, nE);
  core.applyDeferredUpdates();
});
