// A Directional .sing file opened on the page (web/session/field-topology.js addSingFile, the command
// AddSingularities) and the setting "only prescribed singularities" (SetSetting exactSingularities): each one
// request and one history step, undo and redo, refusals that change nothing and name the file. Driven through a
// real Session over the fake core of fakes.mjs; the truth each test checks against is what the fake core holds.
import assert from 'node:assert/strict';
import test from 'node:test';
import { icosphereOff } from '../icosphere.mjs';
import { FakeCore } from './fakes.mjs';
import { Session } from '../../web/session/session.js';
import { deserializeCommand } from '../../web/session/commands/index.js';

const MODEL = new TextEncoder().encode(icosphereOff(1)); // 42 vertices

async function open(core = new FakeCore()) {
  const s = new Session({ assetBase: 'http://localhost/' });
  s.proxy = core;
  await s.loadModel(MODEL, { name: 'ico.off' });
  return s;
}

const coreSingularities = (core) =>
  core.ids
    .map((id) => core.specs.get(id))
    .filter((spec) => spec.type === 'singularity')
    .map(({ vertex, index }) => [vertex, index]);
const requests = (core, from) => core.log.slice(from).map(([op]) => op).filter((op) => op !== 'warmUp');

test('a .sing file adds all its singularities in one request and one step; one undo removes them all', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 4);
  const before = s.history.labels().undo.length;
  const from = core.log.length;
  const ids = await s.topology.addSingFile('4 3\n5 1\n17 -1\n30 2\n', 'model.sing');
  assert.deepEqual(requests(core, from), ['readSing', 'addSingularities']);
  assert.deepEqual(coreSingularities(core), [[5, 0.25], [17, -0.25], [30, 0.5]]);
  assert.equal(ids.length, 3);
  assert.deepEqual(
    ids.map((id) => s.constraintList().find((c) => c.id === id).vertex),
    [5, 17, 30],
    'each has a page id of its own',
  );
  assert.equal(s.history.labels().undo.length, before + 1, 'one step');
  assert.match(s.history.labels().undo.at(-1), /3 singularities from model\.sing/);
  await s.step(false);
  assert.deepEqual(coreSingularities(core), [], 'one undo removes them all');
  await s.step(true);
  assert.deepEqual(coreSingularities(core), [[5, 0.25], [17, -0.25], [30, 0.5]]);
  assert.deepEqual(
    s.constraintList().filter((c) => c.type === 'singularity').map((c) => c.id),
    ids,
    'redo keeps the page ids',
  );
  const replay = deserializeCommand(JSON.parse(JSON.stringify(s.history.undoStack.at(-1).serialize())));
  assert.deepEqual(replay.list, [[5, 0.25], [17, -0.25], [30, 0.5]]);
  s.dispose();
});

test('a .sing the design cannot take is refused naming the file and its N; nothing changes', async () => {
  const core = new FakeCore();
  const s = await open(core);
  await s.setSetting('symmetry', 4);
  await s.topology.addSingularity(9, 0.25);
  const steps = s.history.labels().undo.length;
  // The second entry lands on the vertex that has one: all or none.
  await assert.rejects(s.topology.addSingFile('4 2\n3 1\n9 -1\n', 'pair.sing'), /^Error: pair\.sing: .*9/);
  assert.deepEqual(coreSingularities(core), [[9, 0.25]], 'the first of the file was taken back');
  // k / N of a file of N = 3 is not a multiple of 1/4.
  await assert.rejects(s.topology.addSingFile('3 1\n4 1\n', 'third.sing'), /third\.sing: .*the file's N is 3/);
  await assert.rejects(s.topology.addSingFile('x\n', 'bad.sing'), /bad\.sing: line 1/);
  await assert.rejects(s.topology.addSingFile('4 0\n', 'empty.sing'), /empty\.sing holds no singularity/);
  assert.equal(s.history.labels().undo.length, steps, 'no step recorded');
  assert.deepEqual(coreSingularities(core), [[9, 0.25]]);
  s.dispose();
});

test('only prescribed singularities: a setting with undo, in the design, the summary and the next model', async () => {
  const core = new FakeCore();
  const s = await open(core);
  assert.equal(s.settings().exactSingularities, false);
  assert.equal(s.topology.summary().exact, false);
  const from = core.log.length;
  await s.topology.setExactSingularities(true);
  assert.deepEqual(requests(core, from), ['setExactSingularities']);
  assert.equal(core.exactSingularities, true);
  assert.equal(s.design.exactSingularities, true, 'the saved design carries it');
  assert.equal(s.topology.summary().exact, true);
  assert.equal(s.history.labels().undo.at(-1), 'only prescribed singularities');
  await s.step(false);
  assert.equal(core.exactSingularities, false);
  assert.equal('exactSingularities' in s.design, false, 'written only when true');
  await s.step(true);
  assert.equal(core.exactSingularities, true);
  const steps = s.history.labels().undo.length;
  await assert.rejects(s.topology.setExactSingularities('yes'), /true or false/);
  assert.equal(core.exactSingularities, true);
  assert.equal(s.history.labels().undo.length, steps);
  await s.loadModel(MODEL, { name: 'again.off' });
  const [, [, , settings]] = core.log.findLast(([op]) => op === 'loadMesh');
  assert.equal(settings.exactSingularities, true, 'the next model takes it, as the other settings');
  s.dispose();
});
