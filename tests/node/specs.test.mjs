// Constraint specs (web/session/specs.js) against the design format (docs/design-format.md): the builders
// make exactly the documented objects, with plain arrays that survive JSON and postMessage, and check nothing
// (the core validates).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import { edgeSpec, pointSpec, strokeSpec, vectorSpec } from '../../web/session/specs.js';

// The example design of docs/design-format.md (its first json block).
const doc = readFileSync(new URL('../../docs/design-format.md', import.meta.url), 'utf8');
const example = JSON.parse(/```json\n([\s\S]*?)```/.exec(doc)[1]);
const byType = (type) => example.constraints.find((c) => c.type === type);

const json = (x) => JSON.parse(JSON.stringify(x));

test('the builders make the constraints of the documented example', () => {
  const stroke = byType('stroke'), vector = byType('vector'), edge = byType('edge');
  const built = [
    strokeSpec(stroke.points, { strength: stroke.strength, weight: stroke.weight }),
    vectorSpec(vector.face, vector.vector, { weight: vector.weight }),
    edgeSpec(edge.edge, edge.value, { weight: edge.weight }),
    pointSpec('source', byType('source').vertex, byType('source').strength),
    pointSpec('sink', byType('sink').vertex, byType('sink').strength),
    pointSpec('vortex', byType('vortex').face, byType('vortex').strength),
  ];
  assert.deepEqual(built, example.constraints);
});

test('typed arrays become plain arrays with the same numbers, and survive JSON and structured cloning', () => {
  const bary = Float64Array.of(0.2, 0.3, 0.5);
  const points = [{ face: 12, bary }, { face: 40, bary: Float32Array.of(0.25, 0.25, 0.5) }];
  const stroke = strokeSpec(points, { strength: 2, weight: 10 });
  assert.deepEqual(stroke, {
    type: 'stroke',
    points: [
      { face: 12, bary: [0.2, 0.3, 0.5] },
      { face: 40, bary: [0.25, 0.25, 0.5] },
    ],
    strength: 2,
    weight: 10,
  });
  assert.ok(stroke.points.every((p) => Array.isArray(p.bary)));
  const vector = vectorSpec(7, Float64Array.of(1, -2, 0.5), { weight: 1 });
  const edge = edgeSpec(Int32Array.of(3, 9), 0.25, { weight: 1 });
  assert.ok(Array.isArray(vector.vector) && Array.isArray(edge.edge));
  for (const spec of [stroke, vector, edge]) {
    assert.deepEqual(json(spec), spec);
    assert.deepEqual(structuredClone(spec), spec);
  }
  bary[0] = 0.9;
  assert.equal(stroke.points[0].bary[0], 0.2, 'a copy: the caller may reuse its buffer');
});

test('options left out are left out of the JSON, so the core applies the documented defaults', () => {
  assert.deepEqual(json(vectorSpec(1, [1, 0, 0], {})), { type: 'vector', face: 1, vector: [1, 0, 0] });
  assert.deepEqual(json(strokeSpec([{ face: 0, bary: [1, 0, 0] }], {})), { type: 'stroke', points: [{ face: 0, bary: [1, 0, 0] }] });
  assert.deepEqual(json(pointSpec('sink', 5)), { type: 'sink', vertex: 5 });
});

test('point constraints: sources and sinks sit on a vertex, vortices in a face', () => {
  assert.deepEqual(pointSpec('source', 3, 1), { type: 'source', vertex: 3, strength: 1 });
  assert.deepEqual(pointSpec('sink', 3, 1), { type: 'sink', vertex: 3, strength: 1 });
  assert.deepEqual(pointSpec('vortex', 3, -1), { type: 'vortex', face: 3, strength: -1 });
});

test('nothing is checked or clamped: out-of-range values reach the core as given', () => {
  assert.equal(vectorSpec(0, [1, 0, 0], { weight: 1e20 }).weight, 1e20);
  assert.equal(edgeSpec([3, 3], 1e13, { weight: -1 }).value, 1e13);
  assert.deepEqual(edgeSpec([3, 3], 0, {}).edge, [3, 3]);
  assert.equal(strokeSpec('not a list', {}).points, 'not a list');
  assert.deepEqual(strokeSpec([{ face: -1 }], {}).points, [{ face: -1, bary: undefined }]);
  assert.equal(vectorSpec(0, null, {}).vector, null);
  assert.equal(pointSpec('source', 1.5, NaN).vertex, 1.5);
});
