// What a synthesis run follows (web/synthesis/run-inputs.js): a vector field's Whitney reconstruction from its
// 1-form, and a big model's preview, which the page knows by its vertex vectors alone, by those as they are
// (deriving its 1-form on the page held an armadillo-sub2 update 140 ms in one task).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { checkSynthesisOptions } from '../../web/synthesis/options.js';
import { fieldInputSteps, runOptions, stepped } from '../../web/synthesis/run-inputs.js';

const fieldInput = (model, atlas) => stepped(fieldInputSteps(model, atlas), false, () => false);

const surface = { positions: new Float64Array(9), edgeRows: new Int32Array(3) };

test('a vector field with a 1-form is followed by its Whitney reconstruction', async () => {
  const oneForm = new Float64Array([1, 2, 3]);
  const { symmetry, input } = await fieldInput({ symmetry: 1, surface, oneForm }, {});
  assert.equal(symmetry, 1);
  assert.equal(input.whitney.oneForm, oneForm);
  assert.equal(input.whitney.rows, surface.edgeRows);
});

test("a preview's vertex vectors are followed as they are", async () => {
  const vertexVectors = new Float64Array([1, 0, 0, 0, 1, 0, 0, 0, 1]);
  const { symmetry, input } = await fieldInput({ symmetry: 1, surface, vertexVectors }, {});
  assert.equal(symmetry, 1);
  assert.equal(input, vertexVectors);
});

test('localDegrees is an option a run takes, an angle from 0 (every run whole) to 180', () => {
  for (const localDegrees of [0, 1, 180]) assert.doesNotThrow(() => checkSynthesisOptions({ localDegrees }));
  for (const localDegrees of [-1, 181, NaN, '1', null])
    assert.throws(() => checkSynthesisOptions({ localDegrees }), /localDegrees must be a number of degrees/);
  const synth = runOptions({ localDegrees: 0.5, resolution: 'auto' }, {}, { stats: {} }, 64, false);
  assert.equal(synth.localDegrees, 0.5);
  assert.equal(synth.resolution, undefined);
});
