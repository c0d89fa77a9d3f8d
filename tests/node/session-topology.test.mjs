// The field's topology as the session edits it (web/session/field-topology.js and the commands AddSingularity,
// MoveSingularity, SetFeatures; a singularity's removal is RemoveConstraint's): each edit one request and one
// history step, undo and redo, the refusals, the page ids, the design document the save, load and autosave
// carry, and the reads (singularities with their page ids, the summary, the features in use). Driven through a
// real Session over the fake core of fakes.mjs, which checks singularities and feature edges as the core does;
// the truth each test checks against is what the fake core holds afterwards.
import assert from 'node:assert/strict';
import test from 'node:test';
import { icosphereOff } from '../icosphere.mjs';
import { FakeCore } from './fakes.mjs';
import { Session } from '../../web/session/session.js';
import { deserializeCommand } from '../../web/session/commands/index.js';
import { CREASED_FEATURE_ANGLE } from '../../web/session/constraint-table.js';
import { isEmptyDesign } from '../../web/session/documents.js';
import { pointSpec } from '../../web/session/specs.js';

const MODEL = new TextEncoder().encode(icosphereOff(1)); // 42 vertices, 120 edges, 80 faces: chi = 2

async function open(core = new FakeCore(), options = {}) {
  const s = new Session({ assetBase: 'http://localhost/', ...options });
  s.proxy = core;
  await s.loadModel(MODEL, { name: 'ico.off' });
  return s;
}

// The core's prescribed singularities, in its order: the independent record.
const coreSingularities = (core) =>
  core.ids.map((id) => core.specs.get(id)).filter((spec) => spec.type === 'singularity');

// The page lists exactly the core's constraints under its page ids, and its design document is the core's.
function assertMirrorsCore(s, core) {
  const list = s.constraintList();
  assert.equal(list.length, core.ids.length);
  for (const { id, ...spec } of list) assert.deepEqual(spec, core.specs.get(s.table.coreIdOf(id)), `page id ${id}`);
  const { schema, mesh, ...doc } = core.document();
  const { schema: _s, mesh: _m, ...mirror } = s.design;
  assert.deepEqual(mirror, doc, 'the mirrored document is the core’s');
  assert.deepEqual(s.topology.features().angle, core.features.angle);
}

// The edits' requests since `from` (the loader's warm-up request comes when it will).
const requests = (core, from) => core.log.slice(from).map(([op]) => op).filter((op) => op !== 'warmUp');

// The k-th edge of the core's mesh, and a vertex pair that is not an edge.
const edge = (core, k) => [core.mesh.edges[2 * k], core.mesh.edges[2 * k + 1]];
function nonEdge(core) {
  const E = core.mesh.edges, keys = new Set();
  for (let k = 0; k < E.length; k += 2) keys.add(`${E[k]},${E[k + 1]}`);
  for (let b = 1; ; b++) if (!keys.has(`0,${b}`)) return [0, b];
}

test('a new design starts at the model’s suggested feature angle; a chosen one carries to the next model', async () => {
  assert.equal(CREASED_FEATURE_ANGLE, 35);
  const core = new FakeCore();
  const s = await open(core);
  const loads = () => core.log.filter(([op]) => op === 'loadMesh').map(([, [, , settings]]) => settings.featureAngle);
  assert.deepEqual(loads(), ['auto'], 'the first model takes its own suggestion');
  assert.equal(core.features.angle, 35);
  assert.equal(s.design.featureAngle, 35);
  // A faceted curved model next: the angle left at the last model's suggestion follows the new model's.
  core.suggestedFeatureAngle = 0;
  await s.loadModel(MODEL, { name: 'faceted.off' });
  assert.deepEqual(loads(), ['auto', 'auto']);
  assert.equal(core.features.angle, 0);
  assert.equal(s.design.featureAngle, undefined, 'a document without an angle means 0');
  // An angle the user chose carries.
  await s.topology.setFeatures({ angle: 25 });
  core.suggestedFeatureAngle = 35;
  await s.loadModel(MODEL, { name: 'creased.off' });
  assert.deepEqual(loads(), ['auto', 'auto', 25]);
  assert.equal(core.features.angle, 25);
  // Set back to this model's suggestion, it follows the next model's again.
  await s.topology.setFeatures({ angle: 35 });
  core.suggestedFeatureAngle = 0;
  await s.loadModel(MODEL, { name: 'faceted-again.off' });
  assert.deepEqual(loads(), ['auto', 'auto', 25, 'auto']);
  assert.equal(core.features.angle, 0);
  s.dispose();
});

test('features: the angle and edge edits are undoable steps; a design without an angle means 0', async () => {
  const core = new FakeCore();
  const s = await open(core);
  assert.equal(core.features.angle, 35);
  assert.equal(isEmptyDesign(s.design), true, 'an untouched new design is not worth an autosave');
  await s.replaceDesign({ constraints: [] }, 'load design');
  assert.equal(core.features.angle, 0);
  assert.deepEqual(s.topology.features(), { angle: 0, add: [], remove: [], edges: [] });
  await s.loadModel(MODEL, { name: 'next.off' });
  const [, [, , next]] = core.log.findLast(([op]) => op === 'loadMesh');
  assert.equal(next.featureAngle, 0, 'the next model takes the design’s angle, as the other settings');
  s.dispose();
});

test('placing a singularity: one request, a page id, listed as a constraint, flagged prescribed; undo and redo', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const before = core.log.length;
  const id = await s.topology.addSingularity(7, 1);
  assert.deepEqual(requests(core, before), ['addSingularity']);
  assert.deepEqual(coreSingularities(core), [{ type: 'singularity', vertex: 7, index: 1 }]);
  assert.deepEqual(s.constraintList(), [{ id, type: 'singularity', vertex: 7, index: 1 }]);
  assert.deepEqual(s.design.singularities, [{ vertex: 7, index: 1 }], 'the document lists it apart');
  assert.deepEqual(s.design.constraints, []);
  assert.deepEqual(s.currentSingularities(), [{ vertex: 7, index: 1, prescribed: true, id }]);
  assert.deepEqual(s.topology.summary(), {
    mode: 'free',
    eulerCharacteristic: 2,
    prescribedIndex: 1,
    freeIndex: 1,
    exact: false,
  });
  assert.deepEqual(s.history.labels().undo, [`add singularity #${id}`]);
  assertMirrorsCore(s, core);

  await s.step(false);
  assert.deepEqual(coreSingularities(core), []);
  assert.equal(s.design.singularities, undefined);
  assert.deepEqual(s.topology.summary().mode, 'none');
  const coreIdBefore = core.nextId;
  await s.step(true);
  assert.deepEqual(s.constraintList(), [{ id, type: 'singularity', vertex: 7, index: 1 }], 'the same page id');
  assert.ok(s.table.coreIdOf(id) >= coreIdBefore, 'under a fresh core id');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('a cross field takes 8 x +1/4 on the sphere exactly; every prescribed one is named by its page id', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 4);
  const vertices = [0, 5, 9, 13, 20, 30, 33, 41];
  const ids = [];
  for (const v of vertices) ids.push(await s.topology.addSingularity(v, 0.25));
  const summary = s.topology.summary();
  assert.equal(summary.mode, 'exact');
  assert.equal(summary.freeIndex, 0);
  assert.equal(summary.prescribedIndex, summary.eulerCharacteristic);
  const found = s.currentSingularities();
  assert.deepEqual(found.map(({ vertex }) => vertex), vertices);
  assert.deepEqual(found.map(({ id }) => id), ids);
  assert.ok(found.every(({ prescribed, index }) => prescribed && index === 0.25));
  assertMirrorsCore(s, core);
  s.dispose();
});

test('moving keeps the page id, the core id and the index; undo moves it back', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const a = await s.topology.addSingularity(3, 1);
  const b = await s.topology.addSingularity(4, -1);
  const coreId = s.table.coreIdOf(a);
  const before = core.log.length;
  assert.equal(await s.topology.moveSingularity(a, 11), true);
  assert.deepEqual(requests(core, before), ['moveSingularity']);
  assert.equal(s.table.coreIdOf(a), coreId);
  assert.deepEqual(core.specs.get(coreId), { type: 'singularity', vertex: 11, index: 1 });
  assert.deepEqual(s.design.singularities, [{ vertex: 11, index: 1 }, { vertex: 4, index: -1 }]);
  assert.deepEqual(core.specs.get(s.table.coreIdOf(b)).vertex, 4, 'the other stays where it was');
  assertMirrorsCore(s, core);
  await s.step(false);
  assert.deepEqual(core.specs.get(coreId).vertex, 3);
  assertMirrorsCore(s, core);
  await s.step(true);
  assert.deepEqual(core.specs.get(coreId).vertex, 11);
  // A move onto the vertex it is at changes nothing and is not recorded.
  const depth = s.history.undoStack.length;
  await s.topology.moveSingularity(a, 11);
  assert.equal(s.history.undoStack.length, depth);
  s.dispose();
});

test('removing one: undo brings back its vertex and index under the same page id; others are refused', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const source = await s.addConstraint(pointSpec('source', 2, 1));
  const a = await s.topology.addSingularity(3, -1);
  await s.topology.removeSingularity(a);
  assert.deepEqual(coreSingularities(core), []);
  assert.equal(s.history.labels().undo.at(-1), `delete singularity #${a}`);
  await s.step(false);
  assert.deepEqual(s.constraintList().find(({ id }) => id === a), { id: a, type: 'singularity', vertex: 3, index: -1 });
  assert.deepEqual(core.log.at(-1), ['add', [{ type: 'singularity', vertex: 3, index: -1 }]]);
  assertMirrorsCore(s, core);
  await assert.rejects(s.topology.removeSingularity(source), /constraint 1 is a source, not a singularity/);
  await assert.rejects(s.topology.moveSingularity(source, 4), /constraint 1 is a source, not a singularity/);
  s.dispose();
});

test('refusals reject with the core’s reason, leave the design as it was and are not recorded', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const a = await s.topology.addSingularity(3, 1);
  await s.topology.setFeatures({ add: [edge(core, 0)] });
  const design = structuredClone(s.design), list = s.constraintList(), depth = s.history.undoStack.length;
  const [x, y] = nonEdge(core);
  const cases = [
    [() => s.topology.addSingularity(3, -1), /vertex 3 already has one/],
    [() => s.topology.addSingularity(5, 0.5), /index 0.5 is not a nonzero multiple of 1\/1/],
    [() => s.topology.addSingularity(500, 1), /vertex 500 does not exist/],
    [() => s.topology.moveSingularity(a, 900), /vertex 900 does not exist/],
    [() => s.topology.setFeatures({ add: [[x, y]] }), new RegExp(`${x}-${y} is not an edge of the mesh`)],
    [() => s.topology.setFeatures({ angle: 200 }), /angle 200 is out of range/],
    [() => s.topology.setFeatures({ nonsense: 1 }), /unknown key "nonsense"/],
  ];
  for (const [edit, reason] of cases) {
    await assert.rejects(edit(), reason);
    assert.deepEqual(s.design, design);
    assert.deepEqual(s.constraintList(), list);
    assert.equal(s.history.undoStack.length, depth);
  }
  assertMirrorsCore(s, core);
  s.dispose();
});

test('features: any subset of the keys, one step each, undone to the features before', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.topology.setFeatures({ angle: 20 });
  assert.deepEqual(core.features, { angle: 20, add: [], remove: [] });
  const [e0, e1, e2] = [0, 1, 2].map((k) => edge(core, k));
  await s.topology.setFeatures({ add: [e0, Int32Array.from(e1)] });
  await s.topology.setFeatures({ remove: new Set([e2]) });
  assert.deepEqual(core.features, { angle: 20, add: [e0, e1], remove: [e2] });
  assert.deepEqual(s.design.featureEdges, { add: [e0, e1], remove: [e2] });
  assert.deepEqual(s.topology.features().edges, [e0, e1], 'the edges the core says are in use');
  assert.deepEqual(s.history.labels().undo, ['feature angle 20', 'feature edges', 'feature edges']);
  assertMirrorsCore(s, core);
  const depth = s.history.undoStack.length;
  await s.topology.setFeatures({ angle: 20 });
  assert.equal(s.history.undoStack.length, depth, 'no change, no step');
  await s.step(false);
  await s.step(false);
  assert.deepEqual(core.features, { angle: 20, add: [], remove: [] });
  await s.step(false);
  assert.deepEqual(core.features, { angle: 35, add: [], remove: [] });
  assertMirrorsCore(s, core);
  s.dispose();
});

test('save and load carry singularities and features; unsaved edits see them', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 4);
  await s.topology.addSingularity(3, 0.25);
  await s.topology.addSingularity(8, -0.25);
  await s.topology.setFeatures({ angle: 50, add: [edge(core, 4)] });
  const saved = JSON.parse(JSON.stringify(s.design)); // as saveDesign() gives it and a file keeps it
  assert.deepEqual(saved.singularities, [{ vertex: 3, index: 0.25 }, { vertex: 8, index: -0.25 }]);
  assert.equal(saved.featureAngle, 50);
  assert.equal(isEmptyDesign({ ...saved, constraints: [], featureEdges: undefined, featureAngle: 0, symmetry: 1 }), false,
    'a design with prescribed singularities is worth an autosave');
  s.markSaved();
  await s.topology.moveSingularity(1, 9);
  assert.equal(s.hasUnsavedEdits(), true);
  await s.step(false);
  assert.equal(s.hasUnsavedEdits(), false);

  const core2 = new FakeCore({ firstId: 900 });
  const s2 = await open(core2);
  await s2.replaceDesign(saved, 'load design');
  assert.deepEqual(coreSingularities(core2), coreSingularities(core));
  assert.deepEqual(core2.features, core.features);
  assert.deepEqual(s2.constraintList().map(({ id, ...spec }) => spec), s.constraintList().map(({ id, ...spec }) => spec));
  assertMirrorsCore(s2, core2);
  // Undo of the load puts the new design's features back.
  await s2.step(false);
  assert.deepEqual(core2.features, { angle: 35, add: [], remove: [] });
  assert.deepEqual(coreSingularities(core2), []);
  s.dispose();
  s2.dispose();
});

test('the new commands serialize and replay on another session to the same design and page ids', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const a = await s.topology.addSingularity(3, 1);
  await s.topology.addSingularity(5, 1);
  await s.topology.moveSingularity(a, 6);
  await s.topology.setFeatures({ angle: 10, add: [edge(core, 7)] });
  await s.topology.removeSingularity(a);
  const json = JSON.parse(JSON.stringify(s.history.serialize()));
  assert.deepEqual(json.undo.map((c) => c.type),
    ['AddSingularity', 'AddSingularity', 'MoveSingularity', 'SetFeatures', 'RemoveConstraint']);
  for (const c of json.undo) assert.deepEqual(deserializeCommand(c).serialize(), c);

  const core2 = new FakeCore({ firstId: 5000 });
  const s2 = await open(core2);
  for (const c of json.undo) await s2.execute(() => deserializeCommand(c));
  assert.deepEqual(s2.constraintList(), s.constraintList());
  assert.deepEqual(s2.topology.features(), s.topology.features());
  assertMirrorsCore(s2, core2);
  while (await s2.step(false));
  assert.deepEqual(core2.ids, []);
  assert.deepEqual(core2.features.angle, 35);
  s.dispose();
  s2.dispose();
});

test('a new symmetry takes the singularities it cannot keep in the same step; undo brings them back', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 4);
  const quarter = await s.topology.addSingularity(3, 0.25);
  const half = await s.topology.addSingularity(9, -0.5);
  const notices = [];
  s.on('flash', ({ text }) => notices.push(text));
  const removed = await s.setSetting('symmetry', 2);
  assert.deepEqual(removed, [{ id: quarter, type: 'singularity', vertex: 3, index: 0.25 }]);
  assert.deepEqual(coreSingularities(core), [{ type: 'singularity', vertex: 9, index: -0.5 }], 'the -1/2 stays');
  assert.match(notices.at(-1), /Line field: removed 1 singularity \(undo restores it\)/);
  await s.step(false);
  assert.equal(core.symmetry, 4);
  assert.deepEqual(s.constraintList().map(({ id, vertex, index }) => [id, vertex, index]),
    [[quarter, 3, 0.25], [half, 9, -0.5]]);
  assertMirrorsCore(s, core);
  s.dispose();
});

test('a +/- pair is one step and one request each way; a refusal of either adds neither', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 4);
  const before = core.log.length, depth = s.history.undoStack.length;
  const [plus, minus] = await s.topology.addSingularityPair([3, 0.25], [9, -0.25]);
  assert.deepEqual(requests(core, before), ['addSingularities']);
  assert.equal(s.history.undoStack.length, depth + 1);
  assert.deepEqual(s.constraintList().map(({ id, vertex, index }) => [id, vertex, index]), [[plus, 3, 0.25], [minus, 9, -0.25]]);
  assert.equal(s.topology.summary().prescribedIndex, 0, 'the total index is unchanged');
  await s.step(false);
  assert.deepEqual(requests(core, before), ['addSingularities', 'removeConstraints']);
  assert.deepEqual(coreSingularities(core), []);
  await s.step(true);
  assert.deepEqual(s.constraintList().map(({ id }) => id), [plus, minus], 'the same page ids');
  assertMirrorsCore(s, core);
  await assert.rejects(s.topology.addSingularityPair([20, 0.25], [9, -0.25]), /vertex 9 already has one/);
  assert.deepEqual(coreSingularities(core).map(({ vertex }) => vertex), [3, 9], 'the refused pair’s first singularity was taken back');
  assert.equal(s.history.undoStack.length, depth + 1);
  assertMirrorsCore(s, core);
  const json = JSON.parse(JSON.stringify(s.history.serialize()));
  const pair = json.undo.find((c) => c.type === 'AddSingularityPair');
  assert.deepEqual(deserializeCommand(pair).serialize(), pair);
  s.dispose();
});
