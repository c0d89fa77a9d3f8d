// The edits (web/session/commands/), their history (history.js) and the page's mirror of the design with its
// page ids (constraint-table.js), driven through a real Session whose core link is a fake that speaks the
// worker's protocol (fakes.mjs: snapshots as core-worker.js sends them, fresh core ids on every add). The truth
// each test checks against is what the fake core holds afterwards, not what the page believes.
import assert from 'node:assert/strict';
import test from 'node:test';
import { icosphereOff } from '../icosphere.mjs';
import { FakeCore } from './fakes.mjs';
import { Session } from '../../web/session/session.js';
import { History } from '../../web/session/history.js';
import { deserializeCommand, AddConstraint } from '../../web/session/commands/index.js';
import { ConstraintTable } from '../../web/session/constraint-table.js';
import { pointSpec, strokeSpec, vectorSpec } from '../../web/session/specs.js';

const MODEL = new TextEncoder().encode(icosphereOff(1)); // 42 vertices, 80 faces

async function open(core = new FakeCore(), options = {}) {
  const s = new Session({ assetBase: 'http://localhost/', ...options });
  s.proxy = core;
  await s.loadModel(MODEL, { name: 'ico.off' });
  return s;
}

// What the core holds, in its order (the independent record).
const coreSpecs = (core) => core.ids.map((id) => core.specs.get(id));

// Every page id names the constraint the core holds under the core id it maps to, and the page lists exactly
// the core's constraints.
function assertMirrorsCore(s, core) {
  const list = s.constraintList();
  assert.equal(list.length, core.ids.length, 'the page lists as many constraints as the core holds');
  for (const { id, ...spec } of list) assert.deepEqual(spec, core.specs.get(s.table.coreIdOf(id)), `page id ${id}`);
  assert.deepEqual(s.design.constraints, coreSpecs(core), 'the mirrored document is the core’s, in its order');
  const { boundary, gamma, symmetry, curvatureAlignment } = core;
  assert.deepEqual(s.settings(), { boundary, gamma, symmetry, curvatureAlignment, exactSingularities: false });
}

const pageIds = (s) => s.constraintList().map((c) => c.id);

const specs = {
  vector: vectorSpec(3, [1, 0, 0], { weight: 10 }),
  source: pointSpec('source', 5, 2),
  stroke: strokeSpec(
    [
      { face: 1, bary: [1 / 3, 1 / 3, 1 / 3] },
      { face: 2, bary: [0.2, 0.3, 0.5] },
    ],
    { strength: 1, weight: 100 },
  ),
};

async function withThree(core = new FakeCore()) {
  const s = await open(core);
  const ids = [await s.addConstraint(specs.vector), await s.addConstraint(specs.source), await s.addConstraint(specs.stroke)];
  return { s, core, ids };
}

test('adds get page ids 1, 2, 3 and the core holds exactly the specs sent', async () => {
  const { s, core, ids } = await withThree();
  assert.deepEqual(ids, [1, 2, 3]);
  assert.deepEqual(coreSpecs(core), [specs.vector, specs.source, specs.stroke]);
  assertMirrorsCore(s, core);
  s.dispose();
});

test('remove and its undo keep the page id while the core hands out a new id', async () => {
  const { s, core } = await withThree();
  const coreIdBefore = s.table.coreIdOf(2);
  await s.remove(2);
  assert.deepEqual(pageIds(s), [1, 3]);
  assert.ok(!core.specs.has(coreIdBefore), 'the core no longer holds it');
  assertMirrorsCore(s, core);

  assert.equal(await s.step(false), true); // undo the delete
  assert.deepEqual(pageIds(s), [1, 2, 3]);
  assert.notEqual(s.table.coreIdOf(2), coreIdBefore, 're-added under a fresh core id');
  assert.deepEqual(s.constraintList()[1], { id: 2, ...specs.source });
  assertMirrorsCore(s, core);

  assert.equal(await s.step(true), true); // redo the delete
  assert.deepEqual(pageIds(s), [1, 3]);
  assertMirrorsCore(s, core);
  s.dispose();
});

test('undoing every edit empties the core; redoing them restores the same page ids and specs', async () => {
  const { s, core } = await withThree();
  const full = s.constraintList();
  while (await s.step(false));
  assert.deepEqual(core.ids, []);
  assert.deepEqual(s.constraintList(), []);
  assert.equal(await s.step(false), false, 'nothing left to undo');
  while (await s.step(true));
  assert.deepEqual(s.constraintList(), full);
  assertMirrorsCore(s, core);
  assert.equal(await s.step(true), false, 'nothing left to redo');
  s.dispose();
});

test('a redone add sends the spec as the core stored it (defaults filled in)', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.addConstraint({ type: 'vector', face: 7, vector: [0, 1, 0] }); // no weight: the core's default
  await s.step(false);
  await s.step(true);
  const adds = core.log.filter(([op]) => op === 'add');
  assert.equal(adds.length, 2);
  assert.deepEqual(adds[1][1][0], core.specs.get(s.table.coreIdOf(1)));
  assert.ok('weight' in adds[1][1][0], 'the redo carries the weight the core chose');
  s.dispose();
});

test('setting a parameter to its current value is not recorded; a change is, and undoes', async () => {
  const { s, core } = await withThree();
  const depth = s.history.undoStack.length;
  await s.setParameter('weight', 1, specs.vector.weight);
  assert.equal(s.history.undoStack.length, depth, 'no history entry for a non-change');

  await s.setParameter('weight', 1, 50);
  assert.equal(s.history.undoStack.length, depth + 1);
  assert.equal(core.specs.get(s.table.coreIdOf(1)).weight, 50);
  await s.step(false);
  assert.equal(core.specs.get(s.table.coreIdOf(1)).weight, specs.vector.weight);
  await s.setParameter('strength', 2, -4);
  assert.equal(core.specs.get(s.table.coreIdOf(2)).strength, -4);
  assert.equal(s.history.redoStack.length, 0, 'a new edit drops the redo stack');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('a parameter the constraint lacks is refused before anything reaches the core', async () => {
  const { s, core } = await withThree();
  const calls = core.log.length, depth = s.history.undoStack.length;
  await assert.rejects(s.setParameter('weight', 2, 3), /source has no weight/);
  assert.equal(core.log.length, calls);
  assert.equal(s.history.undoStack.length, depth);
  await assert.rejects(s.remove(99), /no constraint with id 99/);
  s.dispose();
});

test('an edit the core refuses is not recorded and the page shows what the core holds', async () => {
  const { s, core } = await withThree();
  const settings = [];
  s.on('settings', (x) => settings.push(x));
  const before = s.constraintList(), depth = s.history.undoStack.length;
  await assert.rejects(s.addConstraint(vectorSpec(3, [1, 0, 0], { weight: 1e20 })), /weight \S+ is out of range/);
  await assert.rejects(s.setSetting('gamma', -1), /gamma -1 is out of range/);
  assert.equal(s.history.undoStack.length, depth);
  assert.deepEqual(s.constraintList(), before);
  const defaults = { boundary: 'free', gamma: 0, symmetry: 1, curvatureAlignment: 0, exactSingularities: false };
  assert.deepEqual(settings, [defaults, defaults]);
  // The failure's snapshot is the session's field now: the core's latest version.
  assert.equal(s.field.version, core.version);
  assertMirrorsCore(s, core);
  s.dispose();
});

test('boundary and γ settings go to the core and undo to the previous values', async () => {
  const { s, core } = await withThree();
  await s.setSetting('gamma', 2.5);
  await s.setSetting('boundary', { angle: 0.5 });
  assert.deepEqual(s.settings(), {
    boundary: { angle: 0.5 },
    gamma: 2.5,
    symmetry: 1,
    curvatureAlignment: 0,
    exactSingularities: false,
  });
  assertMirrorsCore(s, core);
  await s.step(false);
  assert.equal(core.boundary, 'free');
  await s.step(false);
  assert.equal(core.gamma, 0);
  assert.deepEqual(pageIds(s), [1, 2, 3], 'a refactorization keeps the constraints and their ids');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('replacing the design gives its constraints new page ids; undo brings back the previous ids and specs', async () => {
  const { s, core } = await withThree();
  const before = s.constraintList();
  const coreIdsBefore = [...core.ids];
  const design = {
    gamma: 0.5,
    constraints: [
      { type: 'vortex', face: 4, strength: -1 },
      { type: 'sink', vertex: 7, strength: 1 },
    ],
  };
  await s.replaceDesign(design, 'load design');
  const loaded = pageIds(s);
  assert.equal(loaded.length, 2);
  assert.ok(loaded.every((id) => !before.some((c) => c.id === id)), 'no page id of the previous design is reused');
  assert.deepEqual(coreSpecs(core), design.constraints);
  assert.equal(core.gamma, 0.5);
  assertMirrorsCore(s, core);

  await s.step(false);
  assert.deepEqual(s.constraintList(), before);
  assert.ok(core.ids.every((id) => !coreIdsBefore.includes(id)), 'the core re-added them under fresh ids');
  assert.equal(core.gamma, 0);
  assertMirrorsCore(s, core);

  await s.step(true);
  assert.deepEqual(pageIds(s), loaded, 'the redo reuses the ids the design was given');
  assertMirrorsCore(s, core);
  s.dispose();
});

test('a design the core refuses leaves the page ids on the previous constraints', async () => {
  const { s, core } = await withThree();
  const before = s.constraintList(), depth = s.history.undoStack.length;
  const coreIdsBefore = [...core.ids];
  await assert.rejects(s.replaceDesign({ constraints: [], foo: 1 }, 'load design'), /unknown key "foo"/);
  await assert.rejects(s.replaceDesign({ constraints: [{ type: 'sink', vertex: 1e6 }] }, 'load design'), /does not exist/);
  assert.deepEqual(s.constraintList(), before);
  assert.ok(core.ids.every((id) => !coreIdsBefore.includes(id)), 'the core put the old design back under fresh ids');
  assert.equal(s.history.undoStack.length, depth);
  assertMirrorsCore(s, core);
  await s.setParameter('weight', 3, 7); // the ids still reach the right core constraint
  assert.equal(core.specs.get(core.ids[2]).weight, 7);
  s.dispose();
});

test('a design for another mesh is refused unless its fingerprint is ignored', async () => {
  const { s, core } = await withThree();
  const design = { ...core.document(), mesh: { vertices: 1, faces: 1, hash: 'other' }, constraints: [{ type: 'source', vertex: 0, strength: 1 }] };
  await assert.rejects(s.replaceDesign(design, 'load design'), /another mesh/);
  await s.replaceDesign(design, 'load design', { ignoreFingerprint: true });
  const [, [sent]] = core.log.findLast(([op]) => op === 'applyDesign');
  assert.ok(!('mesh' in sent), 'the fingerprint was dropped before the core saw the design');
  assert.deepEqual(coreSpecs(core), design.constraints);
  assert.deepEqual(design.mesh, { vertices: 1, faces: 1, hash: 'other' }, "the caller's object is left alone");
  await assert.rejects(s.replaceDesign([], 'load design'), /must be a JSON object/);
  s.dispose();
});

test('edits run one at a time, in call order, even when fired together', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const sent = [pointSpec('source', 1, 1), pointSpec('sink', 2, 1), pointSpec('vortex', 3, 1), pointSpec('source', 4, 2)];
  const ids = await Promise.all([...sent.map((spec) => s.addConstraint(spec)), s.step(false)]);
  assert.deepEqual(ids, [1, 2, 3, 4, true]);
  assert.equal(core.maxInFlight, 1, 'never two requests in flight');
  assert.deepEqual(coreSpecs(core), sent.slice(0, 3));
  assertMirrorsCore(s, core);
  s.dispose();
});

test('an edit made on a previous model is dropped before it reaches the core', async () => {
  const core = new FakeCore();
  const s = await open(core);
  const serial = s.meshSerial;
  await s.loadModel(MODEL, { name: 'ico-again.off' });
  await assert.rejects(s.addConstraint(pointSpec('source', 1, 1), serial), /model changed/);
  assert.equal(core.log.filter(([op]) => op === 'add').length, 0);
  assert.equal(await s.addConstraint(pointSpec('source', 1, 1), s.meshSerial), 1, 'constraint numbers restart with a model');
  s.dispose();
});

test('the selection follows the constraint: cleared when it goes, kept across other edits', async () => {
  const { s } = await withThree();
  s.select(2);
  await s.setParameter('weight', 1, 20);
  assert.equal(s.selected, 2);
  await s.remove(2);
  assert.equal(s.selected, null);
  s.select(42);
  assert.equal(s.selected, null, 'no such constraint');
  s.dispose();
});

test('unsaved edits: an edit makes some, undoing back to the saved state makes none', async () => {
  const { s } = await withThree();
  s.markSaved();
  assert.equal(s.hasUnsavedEdits(), false);
  await s.setSetting('gamma', 1);
  assert.equal(s.hasUnsavedEdits(), true);
  await s.step(false);
  assert.equal(s.hasUnsavedEdits(), false);
  s.dispose();
});

test('signals: constraintschange only when the list changed, fieldchange after every edit', async () => {
  const { s } = await withThree();
  const seen = [];
  for (const type of ['constraintschange', 'fieldchange', 'history']) s.on(type, () => seen.push(type));
  await s.setSetting('gamma', 3);
  assert.deepEqual(seen.filter((t) => t !== 'history'), ['fieldchange']);
  seen.length = 0;
  await s.remove(1);
  assert.deepEqual(seen.filter((t) => t !== 'history'), ['fieldchange', 'constraintschange']);
  assert.ok(seen.includes('history'));
  // The event's list is the one it was sent with, also when read after a later edit, and a copy.
  const details = [];
  s.on('constraintschange', (detail) => details.push(detail));
  await s.setParameter('weight', 3, 40);
  await s.addConstraint(specs.vector);
  assert.equal(details.length, 2);
  assert.deepEqual(details[0].constraints.map((c) => [c.id, c.weight]), [[2, undefined], [3, 40]]);
  assert.deepEqual(details[1].constraints.map((c) => c.id), [2, 3, 4]);
  assert.deepEqual(details[1].constraints, s.constraintList());
  details[1].constraints[1].points[0].face = -1;
  assert.notEqual(s.constraintList()[1].points[0].face, -1);
  s.dispose();
});

test('serialize() round-trips through JSON and deserializeCommand for every command type', async () => {
  const { s } = await withThree();
  await s.setParameter('weight', 1, 40);
  await s.setSetting('gamma', 2);
  await s.setSetting('boundary', 'tangential');
  await s.remove(2);
  await s.replaceDesign({ constraints: [{ type: 'sink', vertex: 9, strength: 3 }] }, 'load design');
  await s.step(false); // one command on the redo stack too
  const json = JSON.parse(JSON.stringify(s.history.serialize()));
  const types = [...json.undo, ...json.redo].map((c) => c.type);
  assert.deepEqual(new Set(types), new Set(['AddConstraint', 'SetParameter', 'SetSetting', 'RemoveConstraint', 'ReplaceDesign']));
  for (const c of [...json.undo, ...json.redo]) assert.deepEqual(deserializeCommand(c).serialize(), c);
  assert.throws(() => deserializeCommand({ type: 'Nope' }), /unknown command "Nope"/);
  assert.throws(() => deserializeCommand(null), /unknown command/);
  s.dispose();
});

test('deserialized commands replayed on another session rebuild the same design, page ids included', async () => {
  const { s } = await withThree();
  await s.setParameter('weight', 3, 5);
  await s.setSetting('gamma', 2);
  await s.remove(2);
  await s.step(false);
  await s.step(true);
  await s.replaceDesign({ constraints: [{ type: 'sink', vertex: 9, strength: 3 }, ...s.design.constraints] }, 'load design');
  await s.remove(pageIds(s)[0]);
  const json = JSON.parse(JSON.stringify(s.history.serialize()));

  const core2 = new FakeCore({ firstId: 5000 });
  const s2 = await open(core2);
  for (const c of json.undo) await s2.execute(() => deserializeCommand(c));
  assert.deepEqual(s2.constraintList(), s.constraintList());
  assert.deepEqual(s2.settings(), s.settings());
  assertMirrorsCore(s2, core2);

  // Its history undoes like the original's.
  while (await s2.step(false));
  assert.deepEqual(s2.constraintList(), []);
  assert.deepEqual(core2.ids, []);
  while (await s2.step(true));
  assert.deepEqual(s2.constraintList(), s.constraintList());

  // A new constraint gets a page id of its own, not one the replayed commands use.
  const used = new Set(json.undo.flatMap((c) => [c.uid, ...(c.before?.uids ?? []), ...(c.after?.uids ?? [])]).filter((x) => x != null));
  const fresh = await s2.addConstraint(pointSpec('vortex', 11, 1));
  assert.ok(!used.has(fresh), `page id ${fresh} is already taken by the replayed history`);
  assert.equal(s2.constraintList().length, s.constraintList().length + 1);
  assertMirrorsCore(s2, core2);
  s.dispose();
  s2.dispose();
});

// ------------------------------------------------------------------------------------------ History alone

const record = (n) => ({ n, label: `c${n}`, serialize: () => ({ n }) });

test('history: a plain record of the steps; labels list the next undo last and the next redo first', () => {
  let changes = 0;
  const h = new History(() => changes++);
  for (const n of [1, 2, 3]) h.push(record(n));
  h.undone();
  h.undone();
  assert.deepEqual(h.labels(), { undo: ['c1'], redo: ['c2', 'c3'] });
  assert.equal(h.peekUndo().n, 1);
  assert.equal(h.peekRedo().n, 2);
  h.redone();
  assert.equal(h.peekUndo().n, 2);
  assert.equal(changes, 6);
  h.push(record(4));
  assert.equal(h.peekRedo(), null, 'a new command drops the redo stack');
  assert.deepEqual(h.serialize(), { undo: [{ n: 1 }, { n: 2 }, { n: 4 }], redo: [] });
  h.clear();
  assert.equal(h.peekUndo(), null);
  assert.equal(h.peekRedo(), null);
});

test('history: the undo stack is bounded and forgets the oldest commands first', () => {
  const h = new History();
  for (let n = 0; n < 520; n++) h.push(record(n));
  assert.equal(h.undoStack.length, 500);
  assert.equal(h.undoStack[0].n, 20);
  assert.equal(h.peekUndo().n, 519);
});

// ------------------------------------------------------------------------------------------ one request a step

test('each edit, undo and redo is one request to the core, the one its command names', async () => {
  const { s, core } = await withThree();
  const ops = async (step) => {
    const from = core.log.length;
    await step();
    return core.log.slice(from).map(([op]) => op);
  };
  assert.deepEqual(await ops(() => s.addConstraint(specs.vector)), ['add']);
  assert.deepEqual(await ops(() => s.step(false)), ['remove']);
  assert.deepEqual(await ops(() => s.step(true)), ['add']);
  assert.deepEqual(await ops(() => s.remove(2)), ['remove']);
  assert.deepEqual(await ops(() => s.setParameter('weight', 1, 3)), ['setWeight']);
  assert.deepEqual(await ops(() => s.setSetting('gamma', 1)), ['setGamma']);
  assert.deepEqual(await ops(() => s.setSetting('symmetry', 1)), [], 'a symmetry that changes nothing asks nothing');
  assert.deepEqual(await ops(() => s.replaceDesign({ constraints: [] }, 'clear')), ['applyDesign']);
  assert.deepEqual(await ops(() => s.step(false)), ['applyDesign']);
  assertMirrorsCore(s, core);
  s.dispose();
});

test('an undo the core refuses leaves the command on the undo stack', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.addConstraint(specs.vector);
  await s.addConstraint(specs.source);
  core.specs.delete(s.table.coreIdOf(2)); // the core lost it: its removal will be refused
  await assert.rejects(s.step(false), /no constraint with id/);
  assert.deepEqual(s.history.labels(), { undo: ['add vector #1', 'add source #2'], redo: [] });
  s.dispose();
});

// ------------------------------------------------------------------------------------------ the table alone

test('constraint table: a change naming a constraint the page never saw is an internal error', () => {
  const t = new ConstraintTable();
  t.apply({ ids: [7], document: { boundary: 'free', gamma: 0, constraints: [{ type: 'sink', vertex: 1, strength: 1 }] } });
  t.adoptUnmapped();
  assert.deepEqual(t.list(), [{ id: 1, type: 'sink', vertex: 1, strength: 1 }]);
  assert.throws(() => t.apply({ ids: [7, 8], changed: [] }), /constraint 8, which the page never saw/);
  t.apply({ ids: [7, 9], changed: [[9, { type: 'source', vertex: 2, strength: 1 }]] });
  t.adoptUnmapped();
  assert.deepEqual(t.uidsInCoreOrder(), [1, 2]);
  t.apply({ ids: [9], changed: [] });
  assert.equal(t.has(1), false, 'a page id whose core constraint went is dropped');
  assert.throws(() => t.coreIdOf(1), /no constraint with id 1/);
});

test('AddConstraint: label and serialize name the page id and spec', () => {
  const c = new AddConstraint(pointSpec('vortex', 3, 1), 12);
  assert.equal(c.label, 'add vortex #12');
  assert.deepEqual(c.serialize(), { type: 'AddConstraint', uid: 12, spec: { type: 'vortex', face: 3, strength: 1 } });
});
