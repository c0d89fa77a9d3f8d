// Design documents (web/session/documents.js): the model key autosaves are filed under, what counts as an
// empty design, reading a design file, and the autosave's localStorage copy.
import assert from 'node:assert/strict';
import test from 'node:test';
import { FakeLocalStorage } from './fakes.mjs';
import { baseName, isEmptyDesign, loadAutosave, modelKey, readJsonFile, saveAutosave } from '../../web/session/documents.js';

const bytes = (text) => new TextEncoder().encode(text);

test('modelKey hashes the bytes with 32-bit FNV-1a (the published test vectors)', () => {
  // Test vectors of the FNV reference (Fowler/Noll/Vo): FNV-1a 32 of "" = 811c9dc5, "a" = e40c292c,
  // "foobar" = bf9cf968.
  assert.equal(modelKey('m', bytes('')), 'm|0|811c9dc5');
  assert.equal(modelKey('m', bytes('a')), 'm|1|e40c292c');
  assert.equal(modelKey('m', bytes('foobar')), 'm|6|bf9cf968');
});

test('modelKey tells apart files that share a name and a size, and names that share bytes', () => {
  const a = bytes('OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n');
  const b = bytes('OFF\n3 1 0\n0 0 0\n1 0 0\n0 2 0\n3 0 1 2\n'); // one digit differs
  assert.equal(a.length, b.length);
  assert.notEqual(modelKey('tri.off', a), modelKey('tri.off', b));
  assert.notEqual(modelKey('tri.off', a), modelKey('other.off', a));
  assert.equal(modelKey('tri.off', a), modelKey('tri.off', a.slice()), 'the same file gets the same key');
});

test('isEmptyDesign: no constraints, the free boundary and γ = 0, however written', () => {
  assert.equal(isEmptyDesign({}), true);
  assert.equal(isEmptyDesign({ constraints: [] }), true);
  assert.equal(isEmptyDesign({ boundary: 'free', gamma: 0, constraints: [] }), true);
  assert.equal(isEmptyDesign({ constraints: [{ type: 'source', vertex: 0, strength: 1 }] }), false);
  assert.equal(isEmptyDesign({ boundary: 'tangential', constraints: [] }), false);
  assert.equal(isEmptyDesign({ boundary: { angle: 0 }, constraints: [] }), false);
  assert.equal(isEmptyDesign({ gamma: 0.1, constraints: [] }), false);
});

test('readJsonFile parses a design file and names the file when it is not JSON', async () => {
  const design = { schema: 'tvf-design/1', constraints: [{ type: 'sink', vertex: 3, strength: 1 }] };
  assert.deepEqual(await readJsonFile(new File([JSON.stringify(design)], 'good.json')), design);
  await assert.rejects(readJsonFile(new File(['{"constraints": ['], 'broken-design.json')), (err) => {
    assert.match(err.message, /^broken-design\.json is not valid JSON \(/);
    return true;
  });
});

test('baseName drops one extension', () => {
  assert.equal(baseName('bunny.obj'), 'bunny');
  assert.equal(baseName('scan.v2.PLY'), 'scan.v2');
  assert.equal(baseName('noext'), 'noext');
  assert.equal(baseName(''), 'model');
});

test('localStorage copy: round trip, empty designs removed, separate per autosave name', () => {
  globalThis.localStorage = new FakeLocalStorage();
  const design = { boundary: 'free', gamma: 0, constraints: [{ type: 'vortex', face: 1, strength: 1 }] };
  assert.equal(saveAutosave('', 'k', design, '2024-01-01T00:00:00.000Z'), true);
  assert.deepEqual(loadAutosave('', 'k'), { savedAt: '2024-01-01T00:00:00.000Z', design });
  assert.equal(loadAutosave('other', 'k'), null, 'another designer on the page has its own copies');
  assert.equal(loadAutosave('', 'k2'), null);
  saveAutosave('', 'k', { constraints: [] });
  assert.equal(loadAutosave('', 'k'), null);
  assert.equal(localStorage.length, 0);
});

test('localStorage copy: a full or disabled storage and a corrupt entry are not errors', () => {
  globalThis.localStorage = new FakeLocalStorage({ quota: 50 });
  const big = { constraints: Array.from({ length: 20 }, (_, k) => ({ type: 'sink', vertex: k, strength: 1 })) };
  assert.equal(saveAutosave('', 'k', big), false);
  assert.equal(loadAutosave('', 'k'), null);
  globalThis.localStorage = new FakeLocalStorage();
  const key = [...(saveAutosave('', 'k', big), localStorage.map.keys())][0];
  localStorage.setItem(key, '{not json');
  assert.equal(loadAutosave('', 'k'), null);
  delete globalThis.localStorage; // storage disabled: the name does not even resolve
  assert.equal(saveAutosave('', 'k', big), false);
  assert.equal(loadAutosave('', 'k'), null);
});
