// The durable autosave (web/session/autosave-store.js: versions in IndexedDB, a localStorage mirror, a
// BroadcastChannel between tabs) on an in-memory IndexedDB and localStorage (fakes.mjs) and node's own
// BroadcastChannel; then the session's autosave (autosave.js) end to end with the fake core.
import assert from 'node:assert/strict';
import test from 'node:test';
import { icosphereOff } from '../icosphere.mjs';
import { FakeCore, FakeIndexedDB, FakeLocalStorage } from './fakes.mjs';
import { AutosaveStore, OTHER_VERSIONS_KEPT, VERSIONS_KEPT, finiteDesign } from '../../web/session/autosave-store.js';
import { loadAutosave, modelKey, saveAutosave } from '../../web/session/documents.js';
import { Session } from '../../web/session/session.js';

// A fresh browser profile for each test.
function freshStorage() {
  globalThis.indexedDB = new FakeIndexedDB();
  globalThis.localStorage = new FakeLocalStorage();
}

const design = (n, extra = {}) => ({
  schema: 'tvf-design/1',
  boundary: 'free',
  gamma: 0,
  constraints: Array.from({ length: n }, (_, k) => ({ type: 'source', vertex: k, strength: k + 1 })),
  ...extra,
});
// The constraint counts of the `count` newest of versions 1..last.
const newest = (last, count) => Array.from({ length: count }, (_, k) => last - k);
const EMPTY = { boundary: 'free', gamma: 0, constraints: [] };

async function until(condition, ms = 5000) {
  const end = Date.now() + ms;
  while (!condition() && Date.now() < end) await new Promise((resolve) => setTimeout(resolve, 5));
}

// Stores made by a test, closed at its end (each holds a BroadcastChannel, which would keep node running).
function stores(t) {
  const made = [];
  t.after(() => made.forEach((s) => s.close()));
  return (...args) => {
    const store = new AutosaveStore(...args);
    made.push(store);
    return store;
  };
}

test(`saving seven versions keeps the newest ${VERSIONS_KEPT}, newest first, each with its design`, async (t) => {
  freshStorage();
  const store = stores(t)('');
  for (let n = 1; n <= 7; n++) await store.save('bunny', design(n));
  const versions = await store.versions('bunny');
  assert.equal(versions.length, VERSIONS_KEPT);
  assert.deepEqual(
    versions.map((v) => v.constraints),
    newest(7, VERSIONS_KEPT),
  );
  const ids = versions.map((v) => v.id);
  assert.deepEqual(ids, [...ids].sort((a, b) => b - a), 'newest (highest id) first');
  assert.ok(versions.every((v) => v.mine && v.tab === store.tab));
  for (const v of versions) assert.deepEqual((await store.version(v.id)).design, design(v.constraints));
  assert.equal(await store.version(ids.at(-1) - 1), null, 'a trimmed version is gone');
  assert.deepEqual((await store.load('bunny')).design, design(7));
});

test('versions of one model never leak to another model or another autosave name', async (t) => {
  freshStorage();
  const make = stores(t);
  const a = make(''), b = make('second-designer');
  await a.save('bunny', design(1));
  await a.save('knot', design(2));
  await b.save('bunny', design(3));
  assert.deepEqual((await a.versions('bunny')).map((v) => v.constraints), [1]);
  assert.deepEqual((await a.versions('knot')).map((v) => v.constraints), [2]);
  assert.deepEqual((await b.versions('bunny')).map((v) => v.constraints), [3]);
  assert.deepEqual(await b.versions('knot'), []);
  assert.equal(await a.load('teapot'), null);
  assert.deepEqual((await b.load('bunny')).design, design(3));
  assert.deepEqual((await a.load('bunny')).design, design(1));
});

test('an empty design is not a version while nothing preceded it; after a non-empty one it is kept', async (t) => {
  freshStorage();
  const make = stores(t);
  const store = make('');
  await store.save('bunny', EMPTY);
  assert.deepEqual(await store.versions('bunny'), []);
  assert.equal(await store.load('bunny'), null);
  await store.save('bunny', design(2));
  await store.save('bunny', EMPTY); // cleared: must stay cleared after a reload
  assert.deepEqual((await store.versions('bunny')).map((v) => v.constraints), [0, 2]);
  assert.deepEqual((await store.load('bunny')).design, EMPTY);
  assert.equal(loadAutosave('', 'bunny'), null, 'the localStorage mirror of an empty design is removed');
  // Settings alone are not empty.
  await store.save('knot', { ...EMPTY, gamma: 0.5 });
  assert.equal((await store.versions('knot')).length, 1);
  // A later page load (a store with a tab id of its own) that clears a restored design: kept too.
  await store.save('teapot', design(3));
  const reloaded = make('');
  await reloaded.save('teapot', EMPTY);
  assert.deepEqual((await reloaded.load('teapot')).design, EMPTY);
  assert.deepEqual((await reloaded.versions('teapot')).map((v) => [v.constraints, v.mine]), [[0, true], [3, false]]);
});

test('two tabs keep their own versions; each hears of the other saving the same model', async (t) => {
  freshStorage();
  const make = stores(t);
  const heard = { a: [], b: [], other: [] };
  const a = make('', { onOtherTab: (key) => heard.a.push(key) });
  const b = make('', { onOtherTab: (key) => heard.b.push(key) });
  make('elsewhere', { onOtherTab: (key) => heard.other.push(key) });
  assert.notEqual(a.tab, b.tab);
  for (let n = 1; n <= 7; n++) await a.save('bunny', design(n));
  await b.save('bunny', design(10));
  await b.save('bunny', design(11));
  await until(() => heard.a.length >= 2 && heard.b.length >= 7);
  await new Promise((resolve) => setTimeout(resolve, 20)); // and nothing more arrives
  assert.deepEqual(heard.a, ['bunny', 'bunny']);
  assert.equal(heard.b.length, 7, "b hears each of a's saves");
  assert.deepEqual(heard.other, [], 'another autosave name hears nothing');
  const versions = await a.versions('bunny');
  assert.deepEqual(versions.map((v) => v.constraints), [11, 10, ...newest(7, VERSIONS_KEPT)]);
  assert.deepEqual(versions.map((v) => v.mine), [false, false, ...Array(VERSIONS_KEPT).fill(true)]);
  assert.deepEqual((await b.versions('bunny')).map((v) => v.mine), [true, true, ...Array(VERSIONS_KEPT).fill(false)]);
  // b's trimming never touches a's versions.
  for (let n = 20; n < 30; n++) await b.save('bunny', design(n));
  assert.equal((await a.versions('bunny')).filter((v) => v.mine).length, VERSIONS_KEPT);
  assert.equal((await a.versions('bunny')).filter((v) => !v.mine).length, VERSIONS_KEPT);
});

test(`earlier page loads' versions: the newest ${OTHER_VERSIONS_KEPT} kept, and a save reads none`, async (t) => {
  freshStorage();
  const make = stores(t);
  // Six page loads of the app, one after the other, each a tab of its own saving seven versions of the bunny.
  for (let load = 0; load < 6; load++) {
    const store = make('');
    for (let n = 1; n <= 7; n++) await store.save('bunny', design(10 * load + n));
    store.close();
  }
  // And one of the knot, which the bunny's trimming must leave alone.
  const knot = make('');
  await knot.save('knot', design(99));
  const now = make('');
  const before = globalThis.indexedDB.valuesRead;
  await now.save('bunny', design(100));
  assert.equal(globalThis.indexedDB.valuesRead, before, 'a save reads ids, not the versions kept');
  const versions = await now.versions('bunny');
  // Each earlier load kept its newest five; the newest twenty of those 30 stay, with the new one.
  const earlier = Array.from({ length: 6 }, (_, load) => newest(10 * load + 7, VERSIONS_KEPT).reverse()).flat();
  assert.deepEqual(versions.map((v) => v.constraints), [100, ...earlier.slice(-OTHER_VERSIONS_KEPT).reverse()]);
  assert.deepEqual(versions.map((v) => v.mine), [true, ...Array(OTHER_VERSIONS_KEPT).fill(false)]);
  assert.deepEqual((await now.versions('knot')).map((v) => v.constraints), [99]);
  // This tab's own versions are trimmed to five as before, the others' twenty untouched by it.
  for (let n = 101; n <= 107; n++) await now.save('bunny', design(n));
  const after = await now.versions('bunny');
  assert.deepEqual(after.filter((v) => v.mine).map((v) => v.constraints), newest(107, VERSIONS_KEPT));
  assert.equal(after.filter((v) => !v.mine).length, OTHER_VERSIONS_KEPT);
  assert.deepEqual((await now.load('bunny')).design, design(107));
});

test('a design with a non-finite number is refused and nothing is stored', async (t) => {
  freshStorage();
  const store = stores(t)('');
  await store.save('bunny', design(1));
  const bad = design(2);
  bad.constraints[1].strength = NaN;
  await assert.rejects(store.save('bunny', bad), /non-finite/);
  await assert.rejects(store.save('bunny', design(1, { gamma: Infinity })), /non-finite/);
  assert.deepEqual((await store.versions('bunny')).map((v) => v.constraints), [1]);
  assert.deepEqual(loadAutosave('', 'bunny').design, design(1));
  assert.equal(finiteDesign(design(3)), true);
  assert.equal(finiteDesign({ constraints: [{ vector: [0, -Infinity, 0] }] }), false);
});

test('load() returns the newer of IndexedDB and the localStorage mirror', async (t) => {
  freshStorage();
  const store = stores(t)('');
  await store.save('bunny', design(2));
  // A write that reached localStorage but not IndexedDB (the tab closed first): newer, so it wins.
  saveAutosave('', 'bunny', design(5), new Date(Date.now() + 60_000).toISOString());
  assert.deepEqual((await store.load('bunny')).design, design(5));
  // An older mirror (an earlier build's) loses to the IndexedDB version.
  saveAutosave('', 'bunny', design(9), '2001-01-01T00:00:00.000Z');
  assert.deepEqual((await store.load('bunny')).design, design(2));
  // Only a mirror (what earlier builds saved): it is what there is.
  saveAutosave('', 'knot', design(4));
  assert.deepEqual((await store.load('knot')).design, design(4));
});

test('without IndexedDB a save rejects, but the synchronous mirror still restores the design', async (t) => {
  freshStorage();
  delete globalThis.indexedDB;
  const store = stores(t)('');
  await assert.rejects(store.save('bunny', design(3)), /IndexedDB is not available/);
  assert.deepEqual((await store.load('bunny')).design, design(3));
});

test('overlapping saves each read and trim in their own single transaction', async (t) => {
  // As in browsers, the fake IndexedDB runs overlapping readwrite transactions one after the other, and
  // commits a transaction once a task ends with none of its requests pending (a later request then fails).
  // A save that read its versions in one transaction and wrote in another, or awaited anything else in
  // between, would lose versions or fail here.
  freshStorage();
  const store = stores(t)('');
  const saves = [];
  for (let n = 1; n <= 6; n++) saves.push(store.save('bunny', design(n)));
  await Promise.all(saves);
  assert.equal((await store.versions('bunny')).length, VERSIONS_KEPT);
});

// ------------------------------------------------------------------------------------------ the session's autosave

const MODEL = new TextEncoder().encode(icosphereOff(1));

async function openSession(t, core = new FakeCore(), bytes = MODEL, name = 'ico.off') {
  const s = new Session({ assetBase: 'http://localhost/', autosave: 'unit' });
  t.after(() => s.dispose());
  s.proxy = core;
  await s.loadModel(bytes, { name });
  return s;
}

test('session: every edit is autosaved; reopening the model restores the design with page ids', async (t) => {
  freshStorage();
  const s = await openSession(t);
  await s.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  await s.addConstraint({ type: 'vortex', face: 2, strength: -1 });
  await s.setSetting('gamma', 0.25);
  await s.autosave.idle();
  const versions = await s.autosave.versions();
  assert.deepEqual(versions.map((v) => v.constraints), [2, 2, 1]);
  assert.equal(s.modelKey, modelKey('ico.off', MODEL));

  const core2 = new FakeCore();
  const s2 = await openSession(t, core2);
  const [, [, , , restored]] = core2.log.find(([op]) => op === 'loadMesh');
  assert.deepEqual(restored.constraints, s.design.constraints, 'the core received the saved design with the mesh');
  assert.equal(restored.gamma, 0.25);
  assert.deepEqual(s2.constraintList(), s.constraintList());
});

test('session: a cleared design stays cleared after reloads, also when the design came from an earlier page load', async (t) => {
  freshStorage();
  const first = await openSession(t);
  await first.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  await first.autosave.idle();
  first.dispose();
  // A reload: a new page (a new store, a new tab id) restores the design; the user clears it.
  const second = await openSession(t);
  assert.equal(second.constraintList().length, 1);
  await second.replaceDesign({ constraints: [] }, 'clear');
  await second.autosave.idle();
  second.dispose();
  const third = await openSession(t);
  assert.deepEqual(third.constraintList(), [], 'the cleared design came back');
});

test('session: another model with the same name gets nothing of the first one’s autosave', async (t) => {
  freshStorage();
  const s = await openSession(t);
  await s.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  await s.autosave.idle();
  const other = new TextEncoder().encode(icosphereOff(2));
  const core2 = new FakeCore();
  const s2 = await openSession(t, core2, other, 'ico.off');
  const [, [, , , restored]] = core2.log.find(([op]) => op === 'loadMesh');
  assert.equal(restored, null);
  assert.deepEqual(s2.constraintList(), []);
  assert.deepEqual(await s2.autosave.versions(), []);
});

test('session: a non-finite field is never autosaved, and the user is told', async (t) => {
  freshStorage();
  const core = new FakeCore();
  const s = await openSession(t, core);
  const banners = [];
  s.on('banner', ({ message }) => banners.push(message));
  await s.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  core.nonFinite = true;
  await s.addConstraint({ type: 'sink', vertex: 2, strength: 1 });
  await s.autosave.idle();
  assert.deepEqual((await s.autosave.versions()).map((v) => v.constraints), [1]);
  assert.equal(banners.length, 1);
  assert.match(banners[0], /not finite/);
});

test('session: a failed save is reported as an error until a save works again', async (t) => {
  freshStorage();
  const s = await openSession(t);
  const errors = [], flashes = [];
  s.on('error', (e) => errors.push(e));
  s.on('flash', ({ text }) => flashes.push(text));
  globalThis.indexedDB.failWrites = true; // a full disk
  await s.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  await s.autosave.idle();
  assert.equal(errors.length, 1);
  assert.equal(errors[0].code, 'autosave');
  assert.match(errors[0].message, /^Autosave failed \(the quota has been exceeded\)/);
  assert.deepEqual(await s.autosave.versions(), [], 'the failed transaction stored nothing');
  globalThis.indexedDB.failWrites = false;
  await s.addConstraint({ type: 'sink', vertex: 2, strength: 1 });
  await s.autosave.idle();
  assert.equal(errors.length, 1);
  assert.ok(flashes.some((f) => /Autosave works again/.test(f)));
  assert.equal(s.autosave.error, null);
});

test('session: restoring a version replaces the design (undoably); another model’s version is refused', async (t) => {
  freshStorage();
  const s = await openSession(t);
  await s.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  await s.addConstraint({ type: 'sink', vertex: 3, strength: 2 });
  await s.autosave.idle();
  const [, older] = await s.autosave.versions();
  await s.autosave.restore(older.id);
  assert.deepEqual(s.constraintList().map(({ id, ...spec }) => spec), [{ type: 'source', vertex: 1, strength: 1 }]);
  await s.step(false);
  assert.equal(s.constraintList().length, 2);

  const other = new AutosaveStore('unit');
  t.after(() => other.close());
  await other.save('some other model', design(1));
  const [foreign] = await other.versions('some other model');
  await assert.rejects(s.autosave.restore(foreign.id), new RegExp(`no autosaved version ${foreign.id} of this model`));
});

test('session: autosave off (no name) touches no storage', async (t) => {
  freshStorage();
  const s = new Session({ assetBase: 'http://localhost/' });
  t.after(() => s.dispose());
  s.proxy = new FakeCore();
  await s.loadModel(MODEL, { name: 'ico.off' });
  await s.addConstraint({ type: 'source', vertex: 1, strength: 1 });
  await s.autosave.idle();
  assert.equal(globalThis.indexedDB.opened, 0);
  assert.equal(globalThis.localStorage.length, 0);
  assert.deepEqual(await s.autosave.versions(), []);
});
