// The symmetry N of the field (web/session/commands/set-symmetry.js) and the curvature alignment, driven
// through a real Session whose core link is the fake that speaks the worker's protocol (fakes.mjs; it refuses
// sources, sinks, vortices and edges for N ≥ 2, as the core does). The truth each test checks against is what
// the fake core holds afterwards.
import assert from 'node:assert/strict';
import test from 'node:test';
import { icosphereOff } from '../icosphere.mjs';
import { FakeCore } from './fakes.mjs';
import { Session } from '../../web/session/session.js';
import { deserializeCommand, SetSymmetry } from '../../web/session/commands/index.js';
import { ConstraintTable } from '../../web/session/constraint-table.js';
import { isEmptyDesign } from '../../web/session/documents.js';
import { edgeSpec, pointSpec, strokeSpec, vectorSpec } from '../../web/session/specs.js';
import { countedTypes, symmetryName } from '../../web/session/symmetry.js';

const MODEL = new TextEncoder().encode(icosphereOff(1)); // 42 vertices, 80 faces

async function open(core = new FakeCore()) {
  const s = new Session({ assetBase: 'http://localhost/' });
  s.proxy = core;
  await s.loadModel(MODEL, { name: 'ico.off' });
  return s;
}

const coreSpecs = (core) => core.ids.map((id) => core.specs.get(id));
const byJson = (list) => list.map((x) => JSON.stringify(x)).sort();

function assertMirrorsCore(s, core) {
  const list = s.constraintList();
  assert.equal(list.length, core.ids.length, 'the page lists as many constraints as the core holds');
  for (const { id, ...spec } of list) assert.deepEqual(spec, core.specs.get(s.table.coreIdOf(id)), `page id ${id}`);
  assert.deepEqual(s.design.constraints, coreSpecs(core), 'the mirrored document is the core’s, in its order');
  const { boundary, gamma, symmetry, curvatureAlignment } = core;
  assert.deepEqual(s.settings(), { boundary, gamma, symmetry, curvatureAlignment, exactSingularities: false });
  assert.equal(s.field.symmetry, core.symmetry, 'the field says which N its vectors are representatives of');
}

const stroke = strokeSpec(
  [
    { face: 1, bary: [1 / 3, 1 / 3, 1 / 3] },
    { face: 2, bary: [0.2, 0.3, 0.5] },
  ],
  { strength: 1, weight: 100 },
);

// Page ids 1..6: a stroke, two sources, a vector, a vortex, an edge.
async function mixed(core = new FakeCore()) {
  const s = await open(core);
  const specs = [stroke, pointSpec('source', 5, 2), pointSpec('source', 9, 1), vectorSpec(3, [1, 0, 0], { weight: 10 }), pointSpec('vortex', 4, -1), edgeSpec([0, 1], 0.5, { weight: 7 })];
  for (const spec of specs) await s.addConstraint(spec);
  return { s, core, specs };
}

function flashes(s) {
  const seen = [];
  s.on('flash', ({ text }) => seen.push(text));
  return seen;
}

test('the words: names of N and counts of what was removed', () => {
  assert.deepEqual([1, 2, 4, 3].map(symmetryName), ['Vector', 'Line', 'Cross', 'N = 3']);
  const types = (...t) => t.map((type) => ({ type }));
  assert.equal(countedTypes(types('source', 'source', 'vortex')), '2 sources and 1 vortex');
  assert.equal(countedTypes(types('sink', 'edge', 'vortex', 'vortex', 'edge')), '1 sink, 2 edge constraints and 2 vortices');
  assert.equal(countedTypes(types('edge')), '1 edge constraint');
  assert.equal(countedTypes([]), '');
});

test('a line field: one step removes the sources, vortex and edge, keeps strokes and vectors, and says so', async () => {
  const { s, core, specs } = await mixed();
  const seen = flashes(s);
  const depth = s.history.undoStack.length;
  const removed = await s.setSetting('symmetry', 2);
  assert.equal(core.symmetry, 2);
  assert.deepEqual(s.constraintList().map((c) => c.id), [1, 4], 'the stroke and the vector carry over under their page ids');
  assert.deepEqual(coreSpecs(core), [specs[0], specs[3]]);
  assert.deepEqual(removed, [2, 3, 5, 6].map((id) => ({ id, ...specs[id - 1] })), 'resolves with what went, page ids included');
  assert.equal(s.history.undoStack.length, depth + 1, 'one undoable step');
  assert.equal(s.history.peekUndo().label, 'symmetry: Line');
  assert.deepEqual(seen, ['Line field: removed 2 sources, 1 vortex and 1 edge constraint (undo restores them)']);
  const sent = core.log.filter(([op]) => op === 'setSymmetry');
  assert.equal(sent.length, 1, 'one request to the worker');
  assert.equal(sent[0][1][0], 2);
  assert.equal(sent[0][1][1].remove.length, 4, 'the removals travel with the new N, to go before it');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('undo brings back N and the removed constraints exactly: same page ids, same specs; redo removes them again', async () => {
  const { s, core } = await mixed();
  const before = s.constraintList(), coreBefore = coreSpecs(core);
  await s.setSetting('symmetry', 4);
  const seen = flashes(s);
  assert.equal(await s.step(false), true);
  assert.equal(core.symmetry, 1);
  assert.deepEqual(s.constraintList(), before, 'every constraint back under its page id with its spec');
  assert.deepEqual(byJson(coreSpecs(core)), byJson(coreBefore), 'the core holds the same specs');
  assert.deepEqual(seen, ['Undo: restored 2 sources, 1 vortex and 1 edge constraint']);
  assertMirrorsCore(s, core);

  assert.equal(await s.step(true), true); // redo
  assert.equal(core.symmetry, 4);
  assert.deepEqual(s.constraintList().map((c) => c.id), [1, 4]);
  assertMirrorsCore(s, core);
  assert.equal(await s.step(false), true);
  assert.deepEqual(s.constraintList(), before);
  await s.setParameter('strength', 2, 3); // the restored page ids reach the right core constraints
  assert.equal(core.specs.get(s.table.coreIdOf(2)).strength, 3);
  assertMirrorsCore(s, core);
  s.dispose();
});

test('with nothing to remove the step is silent; the same N again is no step at all', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.addConstraint(stroke);
  const seen = flashes(s);
  assert.deepEqual(await s.setSetting('symmetry', 2), []);
  assert.deepEqual(seen, []);
  const depth = s.history.undoStack.length, calls = core.log.length;
  await s.setSetting('symmetry', 2);
  assert.equal(s.history.undoStack.length, depth, 'not recorded');
  assert.equal(core.log.length, calls, 'no refactorization for nothing');
  s.dispose();
});

test('at N ≥ 2 a source is refused with the core’s message and nothing is recorded', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 2);
  const depth = s.history.undoStack.length;
  await assert.rejects(s.addConstraint(pointSpec('source', 3, 1)), /sources are vector-field notions/);
  await assert.rejects(s.addConstraint(edgeSpec([0, 1], 1, { weight: 1 })), /edge values are vector-field notions/);
  assert.equal(s.history.undoStack.length, depth);
  assert.equal(await s.addConstraint(vectorSpec(3, [0, 1, 0], { weight: 10 })), 1, 'vectors work for every N');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('a symmetry the core refuses leaves the design, the page ids and N as they were', async () => {
  const { s, core } = await mixed();
  const before = s.constraintList(), depth = s.history.undoStack.length;
  await assert.rejects(s.setSetting('symmetry', 7), /symmetry 7 is out of range/);
  assert.equal(core.symmetry, 1);
  assert.deepEqual(s.constraintList(), before, 'the removed ones came back under their page ids');
  assert.equal(s.history.undoStack.length, depth);
  assertMirrorsCore(s, core);
  await s.setParameter('strength', 3, 4);
  assert.equal(core.specs.get(s.table.coreIdOf(3)).strength, 4);
  s.dispose();
});

test('curvature alignment: for even N only; a switch to an odd N turns it off in the same step, undo turns it on', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await assert.rejects(s.setSetting('curvatureAlignment', 0.5), /needs an even symmetry/);
  await s.setSetting('symmetry', 2);
  await s.setSetting('curvatureAlignment', 0.5);
  assert.equal(core.curvatureAlignment, 0.5);
  await s.setSetting('symmetry', 4);
  assert.deepEqual([core.symmetry, core.curvatureAlignment], [4, 0.5], 'an even N keeps it');
  const seen = flashes(s);
  await s.setSetting('symmetry', 1);
  assert.deepEqual([core.symmetry, core.curvatureAlignment], [1, 0]);
  assert.deepEqual(seen, ['Vector field: turned curvature alignment off (undo restores it)']);
  await s.step(false);
  assert.deepEqual([core.symmetry, core.curvatureAlignment], [4, 0.5]);
  await s.step(false);
  await s.step(false);
  assert.deepEqual([core.symmetry, core.curvatureAlignment], [2, 0]);
  assert.equal(s.history.peekUndo().label, 'symmetry: Line');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('SetSymmetry serializes through JSON; replayed on another session it rebuilds the same design and undoes', async () => {
  const { s } = await mixed();
  await s.setSetting('symmetry', 2);
  await s.setSetting('curvatureAlignment', 0.25);
  await s.setSetting('symmetry', 3);
  await s.step(false); // one on the redo stack too
  const json = JSON.parse(JSON.stringify(s.history.serialize()));
  const commands = [...json.undo, ...json.redo].filter((c) => c.type === 'SetSymmetry');
  assert.equal(commands.length, 2);
  for (const c of commands) assert.deepEqual(deserializeCommand(c).serialize(), c);
  assert.deepEqual(commands[0].removed.map((r) => r.uid), [2, 3, 5, 6]);

  const core2 = new FakeCore({ firstId: 7000 });
  const s2 = await open(core2);
  for (const c of json.undo) await s2.execute(() => deserializeCommand(c));
  assert.deepEqual(s2.constraintList(), s.constraintList());
  assert.deepEqual(s2.settings(), s.settings());
  assertMirrorsCore(s2, core2);
  while (await s2.step(false));
  assert.deepEqual(s2.constraintList(), []);
  assert.deepEqual(s2.settings(), { boundary: 'free', gamma: 0, symmetry: 1, curvatureAlignment: 0, exactSingularities: false });
  s.dispose();
  s2.dispose();
});

test('SetSymmetry alone: label, result and serialize name N and what it removes', () => {
  const c = new SetSymmetry({ symmetry: 1, curvatureAlignment: 0 }, { symmetry: 4, curvatureAlignment: 0 }, [{ uid: 3, spec: pointSpec('sink', 2, 1) }]);
  assert.equal(c.label, 'symmetry: Cross');
  assert.deepEqual(c.result, [{ id: 3, type: 'sink', vertex: 2, strength: 1 }]);
  assert.deepEqual(c.serialize(), {
    type: 'SetSymmetry',
    from: { symmetry: 1, curvatureAlignment: 0 },
    to: { symmetry: 4, curvatureAlignment: 0 },
    removed: [{ uid: 3, spec: { type: 'sink', vertex: 2, strength: 1 } }],
  });
});

test('a design document with symmetry and curvature alignment round-trips through the constraint table', () => {
  const t = new ConstraintTable();
  assert.deepEqual(t.settings(), { boundary: 'free', gamma: 0, symmetry: 1, curvatureAlignment: 0, exactSingularities: false }, 'the defaults before any model');
  const document = { schema: 'tvf-design/1', boundary: 'free', gamma: 0.5, symmetry: 2, curvatureAlignment: 0.3, constraints: [stroke] };
  t.apply({ ids: [11], document: structuredClone(document) });
  t.adoptUnmapped();
  assert.deepEqual(t.settings(), { boundary: 'free', gamma: 0.5, symmetry: 2, curvatureAlignment: 0.3, exactSingularities: false });
  assert.deepEqual(t.design, document, 'the design (save, autosave) is the core’s document, symmetry included');
  const key = t.key();
  t.apply({ ids: [11], document: { ...structuredClone(document), symmetry: 4 } });
  assert.notEqual(t.key(), key, 'a new N is an unsaved edit');
  t.apply({ ids: [11], document: structuredClone(document) });
  assert.equal(t.key(), key, 'back to the saved N is none');
  // A document without the keys (an older design) means a vector field without alignment.
  t.apply({ ids: [], document: { boundary: 'free', gamma: 0, constraints: [] } });
  assert.deepEqual(t.settings(), { boundary: 'free', gamma: 0, symmetry: 1, curvatureAlignment: 0, exactSingularities: false });
  assert.equal(isEmptyDesign(t.design), true);
  assert.equal(isEmptyDesign({ ...t.design, symmetry: 2 }), false, 'a line field with no constraint is still worth autosaving');
  assert.equal(isEmptyDesign({ ...t.design, symmetry: 2, curvatureAlignment: 1 }), false);
});

test('designs carry N: loading one sets it (undoably), saving one keeps it, Clear keeps it, a new model takes it', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.replaceDesign({ symmetry: 2, curvatureAlignment: 0.5, constraints: [stroke] }, 'load design');
  assert.deepEqual([core.symmetry, core.curvatureAlignment], [2, 0.5]);
  assert.equal(s.design.symmetry, 2, 'saveDesign() has it');
  assertMirrorsCore(s, core);
  await assert.rejects(s.replaceDesign({ symmetry: 2, constraints: [pointSpec('sink', 1, 1)] }, 'load design'), /sinks are vector-field notions/);
  await s.replaceDesign({ ...s.settings(), constraints: [] }, 'clear');
  assert.deepEqual([core.symmetry, core.curvatureAlignment, core.ids.length], [2, 0.5, 0]);
  await s.step(false);
  await s.step(false);
  assert.deepEqual([core.symmetry, core.curvatureAlignment], [1, 0]);
  assertMirrorsCore(s, core);
  await s.step(true);
  await s.loadModel(MODEL, { name: 'again.off' });
  const [, [, , settings]] = core.log.findLast(([op]) => op === 'loadMesh');
  // The feature angle goes too: 0, as the loaded design (which has none) means.
  const expected = {
    boundary: 'free',
    gamma: 0,
    symmetry: 2,
    curvatureAlignment: 0.5,
    exactSingularities: false,
    featureAngle: 0,
  };
  assert.deepEqual(settings, expected, 'the settings go to the next model');
  assertMirrorsCore(s, core);
  s.dispose();
});
