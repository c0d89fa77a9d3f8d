// The page's one object per field version (web/session/derived-field.js): each derived value is made (or asked of
// the worker) once, on first request, and kept; a failed or empty worker reply is asked again; a field outliving
// its mesh starts its mesh-bound values over. The values are checked against the geometry functions they come
// from, called here on their own.
import assert from 'node:assert/strict';
import test from 'node:test';
import { grid, surfaceOf } from './fakes.mjs';
import { DerivedField } from '../../web/session/derived-field.js';
import { magnitudeScale } from '../../web/geometry/magnitudes.js';
import { findSingularities } from '../../web/geometry/singularities.js';
import { traceStreamlines } from '../../web/geometry/streamlines.js';
import { faceVectorsOfVertexField, oneFormOfVertexField } from '../../web/geometry/vertex-field.js';

const mesh = grid(8, 2, -1);

// A vortex about the origin, per vertex: a field with a singularity and streamlines that close.
function vortex(surface) {
  const V = new Float64Array(3 * surface.nV);
  for (let v = 0; v < surface.nV; v++) {
    const [x, y] = surface.vertex(v);
    V.set([-y, x, 0], 3 * v);
  }
  return V;
}

// A preview's snapshot: vertex vectors alone.
function preview(surface, extra = {}) {
  const snapshot = { version: 7, symmetry: 1, faceVectors: null, vertexVectors: vortex(surface), oneForm: null };
  return { ...snapshot, stats: { preview: true }, ...extra };
}

test('a preview’s face vectors, one-form, magnitudes and singularities are derived once, on first request', () => {
  const surface = surfaceOf(mesh);
  const field = new DerivedField(preview(surface), () => surface);
  assert.equal(field.faceVectors, null, 'nothing is derived before it is asked for');
  const faces = field.requireFaceVectors();
  assert.deepEqual(faces, faceVectorsOfVertexField(surface, field.vertexVectors));
  assert.equal(field.requireFaceVectors(), faces, 'kept: the same array the second time');
  assert.equal(field.faceVectors, faces, 'and in the field, so that it goes back to the worker with the others');
  const oneForm = field.requireOneForm();
  assert.deepEqual(oneForm, oneFormOfVertexField(surface, field.vertexVectors, 1));
  assert.equal(field.requireOneForm(), oneForm);
  assert.equal(field.requireVertexVectors(), field.vertexVectors);
  const scale = field.requireMagnitudes();
  assert.deepEqual(scale, magnitudeScale(field.vertexVectors));
  assert.equal(field.requireMagnitudes(), scale);
  const singularities = field.requireSingularities();
  assert.deepEqual(singularities, findSingularities(surface, faces, 1));
  assert.ok(singularities.length > 0, 'the vortex has its singularity');
  assert.equal(field.requireSingularities(), singularities);
});

test('arrays and a scale the worker sent are what the field gives', () => {
  const surface = surfaceOf(mesh);
  const faceVectors = new Float64Array(3 * surface.nF).fill(1), scale = { max: 3, top: 2 };
  const field = new DerivedField(preview(surface, { faceVectors, scale }), () => surface);
  assert.equal(field.requireFaceVectors(), faceVectors);
  assert.equal(field.requireMagnitudes(), scale);
});

test('a Hodge part is asked of the worker once, kept in the field’s scale, asked again after a failure', async () => {
  const surface = surfaceOf(mesh);
  const field = new DerivedField(preview(surface), () => surface);
  const asked = [];
  const reply = { faceVectors: new Float64Array(3), vertexVectors: new Float64Array(3), oneForm: new Float64Array(1) };
  const ask = (outcome) => () => {
    asked.push(outcome);
    if (outcome === 'fail') return Promise.reject(new Error('the worker restarted'));
    return Promise.resolve(outcome === 'empty' ? null : reply);
  };
  assert.equal(field.hodgePart('exact'), null);
  await assert.rejects(field.requireHodgePart('exact', ask('fail')), /restarted/);
  assert.equal(await field.requireHodgePart('exact', ask('empty')), null, 'a field the worker no longer holds');
  const first = field.requireHodgePart('exact', ask('ok'));
  const second = field.requireHodgePart('exact', ask('again'));
  assert.equal(second, first, 'one request while it is in flight');
  const part = await first;
  assert.deepEqual(asked, ['fail', 'empty', 'ok']);
  assert.equal(part.vertexVectors, reply.vertexVectors);
  assert.equal(part.scale, field.requireMagnitudes());
  assert.equal(field.hodgePart('exact'), part);
  assert.equal(field.hodgePart('coexact'), null, 'each part on its own');

  const shares = { energyShares: { exact: 0.5, coexact: 0.25, harmonic: 0.25 }, decomposeMs: 3 };
  assert.equal(field.energyShares(), null);
  assert.equal(await field.requireEnergyShares(() => Promise.resolve(shares)), shares);
  assert.equal(field.energyShares(), shares.energyShares);
  await field.requireEnergyShares(() => assert.fail('asked twice'));
});

test('streamlines are traced once per component and spacing, or kept as the worker sent them', () => {
  const surface = surfaceOf(mesh);
  const field = new DerivedField(preview(surface), () => surface);
  const options = { component: 'whole', spacing: 0.3, lift: 0 };
  assert.equal(field.streamlines(options), null);
  const lines = field.requireStreamlines(options);
  const plain = { spacing: 0.3, lift: 0, symmetry: 1, faceVectors: null };
  assert.deepEqual(lines, traceStreamlines(surface, field.vertexVectors, plain));
  assert.ok(lines.length > 0);
  assert.equal(field.requireStreamlines(options), lines, 'kept');
  assert.notEqual(field.traceStreamlines(options), lines, 'traced again when asked to, whatever is kept');
  const fromWorker = [new Float32Array(6)];
  field.keepStreamlines({ component: 'whole', spacing: 0.5 }, fromWorker);
  assert.equal(field.requireStreamlines({ component: 'whole', spacing: 0.5, lift: 0 }), fromWorker);
});

test('a field outliving its mesh forgets what it derived on that mesh', async () => {
  let surface = surfaceOf(mesh);
  const field = new DerivedField(preview(surface), () => surface);
  const options = { component: 'whole', spacing: 0.3, lift: 0 };
  const lines = field.requireStreamlines(options);
  const reply = { faceVectors: new Float64Array(3), vertexVectors: new Float64Array(3), oneForm: new Float64Array(1) };
  await field.requireHodgePart('harmonic', () => Promise.resolve(reply));
  surface = surfaceOf(grid(8, 2, -1));
  assert.equal(field.streamlines(options), null);
  assert.equal(field.hodgePart('harmonic'), null);
  assert.notEqual(field.requireStreamlines(options), lines);
});
