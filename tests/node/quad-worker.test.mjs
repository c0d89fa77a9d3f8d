// The quad remeshing's worker op (web/quad/worker-ops.js) as the worker entry serves it (web/core-worker.js on a
// stand-in of the worker's global), with the real wasm core (dist/wasm, built before the unit tests run), and the
// page's controller (web/quad/controller.js) driving that op: a sphere's smoothest cross field becomes a closed
// quad mesh whose arrays agree with the core's statistics and with what the page derives from them (its
// irregular vertices are exactly the vertices whose valence is not 4), the stages come as progress messages, the
// arrays (and the wireframe's edges, valences and normals, derived there) are transferred; a field that is not a cross field is refused by the core with its reason and by the
// controller with the page's words before any worker is asked; the quad mesh goes stale with the next field.
import assert from 'node:assert/strict';
import test from 'node:test';
import { QUAD_REFUSAL, QuadController } from '../../web/quad/controller.js';
import { quadObj } from '../../web/quad/quad-files.js';
import { uniqueEdges, valences, vertexNormals } from '../../web/quad/quad-mesh.js';
import { icosphere, offText } from './fakes.mjs';
import { parseObj } from './quad-fixtures.mjs';
import { serveCoreWorker } from './worker-harness.mjs';

const DIST = new URL('../../dist/', import.meta.url).href;

const { posted, call } = await serveCoreWorker();

await call('init', DIST);
const mesh = icosphere(3);
await call('loadMesh', new TextEncoder().encode(offText(mesh)), 'off', null, null);
await call('setSymmetry', 4);
const cross = (await call('read')).value;
const input = () => ({
  positions: mesh.positions.slice(),
  triangles: mesh.triangles.slice(),
  faceDirections: cross.faceVectors.slice(),
});

// The CSR mesh's own consistency, and its agreement with the core's statistics.
function checkQuadMesh(value) {
  const { positions, faceStart, faceVertices, irregular, stats } = value;
  const nV = positions.length / 3, nF = faceStart.length - 1;
  assert.equal(stats.vertices, nV);
  assert.equal(stats.faces, nF);
  assert.equal(faceStart[0], 0);
  assert.equal(faceStart[nF], faceVertices.length);
  let quads = 0;
  for (let f = 0; f < nF; f++) {
    const n = faceStart[f + 1] - faceStart[f];
    assert.ok(n >= 3, `face ${f} has ${n} corners`);
    if (n === 4) quads++;
  }
  assert.equal(stats.quads, quads);
  assert.ok(Math.abs(stats.quadShare - quads / nF) < 1e-12);
  assert.ok(faceVertices.every((v) => v >= 0 && v < nV));
  assert.ok(positions.every(Number.isFinite));
  // The sphere is closed: every vertex is interior, and the irregular ones are those of valence other than 4.
  const valence = valences(value);
  const expected = [...valence.keys()].filter((v) => valence[v] !== 4);
  assert.deepEqual([...irregular].sort((a, b) => a - b), expected);
  assert.equal(stats.irregularVertices, irregular.length);
  return { nV, nF, quads };
}

test('the worker op: a cross field on a sphere becomes a quad mesh, its arrays as its statistics say', async () => {
  const before = posted.length;
  const { positions, triangles, faceDirections } = input();
  const reply = await call('quadRemesh', positions, triangles, faceDirections, { quads: 600, symmetry: 4 });
  const value = reply.value;
  console.log(`[ measured ] icosphere(3), 600 quads asked: ${JSON.stringify(value.stats)}`);
  const { nF } = checkQuadMesh(value);
  assert.ok(nF > 300 && nF < 1200, `about 600 faces asked, ${nF} made`);
  assert.ok(value.stats.quadShare >= 0.9, `quad share ${value.stats.quadShare}`);
  assert.equal(value.stats.fieldSingularities, 8, "the sphere's cross field has eight +1/4 singularities");
  assert.equal(value.stats.eulerCharacteristic, 2);
  assert.equal(value.stats.manifold, true);
  assert.ok(value.stats.edgeLength > 0 && value.stats.ms >= 0);
  const transferred = ['positions', 'faceStart', 'faceVertices', 'irregular'].map((k) => value[k].buffer);
  const { edges, valence, normals } = value.derived;
  transferred.push(edges.buffer, valence.buffer, normals.buffer);
  assert.deepEqual(reply.list, transferred, 'the four arrays and the three derived ones are transferred');
  // What the worker derives for the wireframe is what the page would derive from the four arrays.
  assert.deepEqual(edges, uniqueEdges(value));
  assert.deepEqual(valence, valences(value));
  assert.deepEqual(normals, vertexNormals(value));
  const progress = posted.slice(before).filter((p) => p.data.seq === reply.seq && p.data.progress);
  assert.ok(progress.length > 0, 'the stages are posted');
  let last = 0;
  for (const { data } of progress) {
    assert.equal(typeof data.progress.stage, 'string');
    assert.ok(data.progress.fraction >= last - 1e-12 && data.progress.fraction <= 1, 'fractions go up to 1');
    last = data.progress.fraction;
  }
  // The OBJ of the core's mesh reads back with the same counts.
  const obj = parseObj(quadObj(value));
  assert.equal(obj.vertices.length, value.stats.vertices);
  assert.equal(obj.faces.length, value.stats.faces);
  assert.equal(obj.faces.filter((f) => f.length === 4).length, value.stats.quads);
});

test('the worker op: the core refuses what is not a cross field, with its reason', async () => {
  const { positions, triangles, faceDirections } = input();
  await assert.rejects(call('quadRemesh', positions, triangles, faceDirections, { quads: 600, symmetry: 1 }),
    /cross field/);
});

test('the controller over the real op: the result, stale after the next field, a vector field refused', async () => {
  let version = 1, symmetry = 4, runs = 0;
  const stages = new Set(); // the stages the controller's state showed (what the panel draws)
  const controller = new QuadController({
    getInput: async () => ({ ...input(), symmetry, version }),
    symmetry: () => symmetry,
    fieldVersion: () => version,
    // The real op, served in this thread (as the worker would, without its thread): its progress messages are
    // handed on once it has replied.
    startRun: (data, options, onProgress) => {
      runs++;
      const promise = call('quadRemesh', data.positions, data.triangles, data.faceDirections, options).then((reply) => {
        for (const p of posted) if (p.data.seq === reply.seq && p.data.progress) onProgress(p.data.progress);
        return reply.value;
      });
      return { promise, cancel: () => false };
    },
    onChange: () => {
      const { stage } = controller.state();
      if (stage) stages.add(stage);
    },
  });
  assert.equal(controller.state().target.quads, 5000, 'about 5,000 quads by default');
  const result = await controller.remesh({ quads: 400 });
  checkQuadMesh(result);
  const state = controller.state();
  assert.deepEqual(state.target, { quads: 400 });
  assert.equal(state.hasResult, true);
  assert.equal(state.running, false);
  assert.equal(state.stale, false);
  assert.deepEqual(state.stats, result.stats);
  assert.ok([...stages].some((stage) => stage !== 'starting'), `the core's stages shown: ${[...stages]}`);
  // What the API hands out is a copy: changing it changes nothing the controller exports.
  result.positions.fill(0);
  assert.notEqual(parseObj(controller.exportObj()).vertices[0].join(), '0,0,0');
  assert.ok(new Uint8Array(controller.exportGlb(), 0, 4).every((b, k) => b === 'glTF'.charCodeAt(k)));

  controller.fieldChanged();
  assert.equal(controller.state().stale, false, 'the same field version');
  version = 2;
  controller.fieldChanged();
  assert.equal(controller.state().stale, true);

  symmetry = 1;
  await assert.rejects(controller.remesh(), (err) => err.message === QUAD_REFUSAL);
  assert.equal(controller.state().error, QUAD_REFUSAL);
  assert.equal(controller.state().hasResult, true, 'the last quad mesh stays');
  assert.equal(runs, 1, 'no run for a vector field');
  await assert.rejects(controller.remesh({ quads: -3 }), /quads must be a whole number/);
  controller.modelChanged();
  assert.equal(controller.state().hasResult, false);
  assert.throws(() => controller.exportObj(), /no quad mesh yet/);
});
