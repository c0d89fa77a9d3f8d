// The core worker's dispatch and derived-field object without a browser or the wasm core (web/core/worker/):
// op groups composed, each op served as its group files it (an edit solved and snapshotted, a failed edit
// taken back, a read-out without either, notes outside the sequence), and one version's derived data made once
// and dropped with the version. The real core behind the real entry: core-worker.test.mjs.
import assert from 'node:assert/strict';
import test from 'node:test';
import { composeOps, serve } from '../../web/core/worker/dispatch.js';
import { WorkerState } from '../../web/core/worker/state.js';
import { editOps } from '../../web/core/worker/edit-ops.js';
import { readOps } from '../../web/core/worker/read-ops.js';
import { testHooks } from '../../web/core/worker/hooks.js';
import { stripeOps } from '../../web/stripes/worker-ops.js';
import { icosphere } from './fakes.mjs';

// A core of one constraint (id 1) over a fixed field; its solve fails while any weight is negative, as a
// factorization that does not fit would.
class TinyCore {
  constructor(mesh) {
    this.hasMesh = true;
    this.calls = [];
    this.weights = new Map([[1, 1]]);
    this.Module = { HEAP8: { buffer: { byteLength: 1 << 20 } } };
    this.meshArrays = mesh;
    const nV = mesh.positions.length / 3;
    // A rotation field about z: tangent to the sphere off the poles.
    this.vertex = new Float64Array(3 * nV);
    for (let v = 0; v < nV; v++) this.vertex.set([-mesh.positions[3 * v + 1], mesh.positions[3 * v], 0], 3 * v);
  }
  faceVectors(copy = (a) => a.slice()) {
    this.calls.push('faceVectors');
    return copy(new Float64Array(this.meshArrays.triangles.length));
  }
  oneForm(copy = (a) => a.slice()) {
    return copy(new Float64Array(this.meshArrays.edges.length / 2));
  }
  vertexVectors(copy = (a) => a.slice()) {
    this.calls.push('vertexVectors');
    return copy(this.vertex);
  }
  symmetry() {
    return 1;
  }
  constraintIds() {
    return [...this.weights.keys()];
  }
  constraint(id) {
    return this.weights.has(id) ? { type: 'vortex', weight: this.weights.get(id) } : undefined;
  }
  constraintSpecs() {
    return this.constraintIds().map((id) => this.constraint(id));
  }
  designJson() {
    return JSON.stringify({ constraints: this.constraintSpecs() });
  }
  stats() {
    return { solves: this.calls.filter((c) => c === 'solve').length };
  }
  setWeight(id, w) {
    this.weights.set(id, w);
  }
  solve() {
    this.calls.push('solve');
    if ([...this.weights.values()].some((w) => w < 0)) throw new Error('solve: the field is not finite');
  }
  applyDeferredUpdates() {
    this.calls.push('deferred');
  }
  computeStripes(vectors, options) {
    this.calls.push(`stripes ${JSON.stringify(options)}`);
    return { families: 1, localUpdate: options.localUpdate !== false };
  }
  stripeArrays() {
    const nF = this.meshArrays.triangles.length / 3;
    return { families: 1, cornerPhase: new Float32Array(3 * nF), branchIndex: new Int8Array(nF) };
  }
  hodge() {
    this.calls.push('hodge');
    const n = this.meshArrays.edges.length / 2;
    const arrays = ['exact', 'coexact', 'harmonic', 'metric', 'potential0', 'potential2'];
    return { ...Object.fromEntries(arrays.map((k) => [k, new Float64Array(n)])), energyShares: { exact: 1 }, metricName: 'M' };
  }
  reconstruct(oneForm) {
    this.calls.push('reconstruct');
    return { faceVectors: new Float64Array(this.meshArrays.triangles.length), vertexVectors: this.vertex.slice() };
  }
  mesh() {
    return { positions: this.meshArrays.positions, triangles: this.meshArrays.triangles };
  }
  edges() {
    return this.meshArrays.edges;
  }
}

// A worker stand-in: the entry's composition over TinyCore, and the messages it posts.
function worker() {
  const posted = [];
  const scope = { postMessage: (data, list = []) => posted.push({ data, list }) };
  const state = new WorkerState(scope);
  state.core = new TinyCore(icosphere(2));
  serve(scope, state, [editOps(state), readOps(state), stripeOps(state), testHooks(state)]);
  let seq = 0;
  const call = async (op, args = [], extra = {}) => {
    const mine = ++seq;
    await scope.onmessage({ data: { seq: mine, op, args, ...extra } });
    return posted.find((p) => p.data.seq === mine && !p.data.progress);
  };
  return { scope, state, posted, call };
}

test('composing op groups: every op filed under one kind, a name defined twice refused', () => {
  const { ops, notes } = composeOps([{ edits: { a() {} }, onMesh: { b() {} } }, { anytime: { c() {} }, notes: { d() {} } }]);
  assert.deepEqual([...ops].map(([name, { kind }]) => [name, kind]), [['a', 'edits'], ['b', 'onMesh'], ['c', 'anytime']]);
  assert.deepEqual([...notes.keys()], ['d']);
  assert.throws(() => composeOps([{ edits: { a() {} } }, { onMesh: { a() {} } }]), /op a is defined twice/);
  assert.throws(() => composeOps([{ notes: { hang() {} } }, { notes: { hang() {} } }]), /hang is defined twice/);
});

test('an edit is solved and answered with a snapshot of what it changed, then the factor takes its update', async () => {
  const { state, posted, call } = worker();
  const reply = await call('setWeight', [1, 5]);
  assert.equal(reply.data.ok, true);
  assert.deepEqual(state.core.calls.filter((c) => c === 'solve' || c === 'deferred'), ['solve', 'deferred']);
  const snap = reply.data.snapshot;
  assert.equal(snap.version, 1);
  assert.equal(snap.transfer, undefined, 'the transfer list travels beside the reply, not in it');
  assert.deepEqual(snap.design, { ids: [1], changed: [[1, { type: 'vortex', weight: 5 }]] });
  assert.deepEqual(reply.list, [snap.faceVectors.buffer, snap.vertexVectors.buffer, snap.oneForm.buffer]);
  assert.ok(snap.scale.max > 0 && snap.scale.top <= snap.scale.max);
  assert.deepEqual(posted.at(-1).data.deferredUpdate.seq, reply.data.seq);
  // wholeDesign: the whole document instead of the change (the progressive core's exact replies).
  const whole = await call('setWeight', [1, 6], { wholeDesign: true });
  assert.deepEqual(whole.data.snapshot.design.document, { constraints: [{ type: 'vortex', weight: 6 }] });
  assert.equal(whole.data.snapshot.version, 2);
});

test('an edit whose solve fails is taken back, and the reply shows the whole design the core holds', async () => {
  const { state, call } = worker();
  const reply = await call('setWeight', [1, -1]);
  assert.equal(reply.data.ok, false);
  assert.match(reply.data.error, /not finite/);
  assert.equal(reply.data.fatal, false);
  assert.equal(state.core.weights.get(1), 1, 'the weight before the edit');
  assert.deepEqual(reply.data.snapshot.design.document, { constraints: [{ type: 'vortex', weight: 1 }] });
  assert.deepEqual(state.core.calls.filter((c) => c === 'solve' || c === 'deferred'), ['solve', 'solve', 'deferred']);
});

test('read-outs, unknown ops, a missing mesh, a trap, notes and the heartbeat', async () => {
  const { state, posted, scope, call } = worker();
  const json = await call('hodgeShares', [0]);
  assert.deepEqual(json.data.value, { energyShares: { exact: 1 }, decomposeMs: json.data.value.decomposeMs });
  assert.equal(json.data.snapshot, undefined, 'a read-out changes no field');
  assert.ok(!state.core.calls.includes('solve'));
  assert.equal((await call('hodgeShares', [7])).data.value, null, "another version's read-out: null");
  assert.match((await call('nonsense')).data.error, /unknown operation nonsense/);
  const trap = await call('trapForTest');
  assert.equal(trap.data.fatal, true);
  assert.equal(trap.data.snapshot, undefined);
  state.core.hasMesh = false;
  assert.match((await call('setWeight', [1, 2])).data.error, /no mesh loaded/);
  assert.match((await call('streamlines', [0, 0.1, 0])).data.error, /no mesh loaded/);
  const before = posted.length;
  const t0 = performance.now();
  await scope.onmessage({ data: { hangForTest: 30 } });
  assert.ok(performance.now() - t0 >= 30, 'the hang holds the thread');
  assert.equal(posted.length, before, 'a note is not answered');
  await scope.onmessage({ data: { ping: true } });
  assert.deepEqual(posted.at(-1).data, { pong: true });
});

test("one derived-field object per field version: each read-out made on first request, gone with the version", async () => {
  const { state, call } = worker();
  await call('setWeight', [1, 2]);
  const field = state.field;
  assert.equal(field.version, 1);
  const calls = () => state.core.calls.filter((c) => c === 'hodge' || c === 'reconstruct' || c === 'vertexVectors');
  const baseline = calls().length;
  const first = await call('streamlines', [1, 0.3, 0]);
  assert.ok(first.data.value.length > 0, 'the rotation field has streamlines');
  const again = await call('streamlines', [1, 0.3, 0]);
  assert.deepEqual(again.data.value, first.data.value);
  assert.equal(calls().length, baseline + 1, 'traced once: one read of the vertex vectors');
  assert.notEqual(first.data.value[0].buffer, field.traces.get('0.3 0 whole')[0].buffer, 'the kept lines are not handed over');

  await call('hodge', [1]);
  await call('hodgeShares', [1]);
  await call('component', [1, 'exact']);
  await call('component', [1, 'exact']);
  await call('streamlines', [1, 0.3, 0, 'exact']);
  assert.deepEqual(calls().slice(baseline + 1), ['hodge', 'reconstruct'], 'one decomposition, one reconstruction');
  assert.match((await call('component', [1, 'curl'])).data.error, /unknown component "curl"/);

  // Four sets of options are kept; a fifth pushes out the oldest.
  for (const spacing of [0.31, 0.32, 0.33]) await call('streamlines', [1, spacing, 0]);
  assert.deepEqual([...field.traces.keys()], ['0.3 0 exact', '0.31 0 whole', '0.32 0 whole', '0.33 0 whole']);

  await call('setWeight', [1, 3]);
  assert.notEqual(state.field, field, 'a new version, a new object');
  assert.equal(state.field.version, 2);
  assert.equal((await call('hodge', [1])).data.value, null);
  assert.equal((await call('streamlines', [1, 0.3, 0])).data.value, null);
  const hodgeBefore = state.core.calls.filter((c) => c === 'hodge').length;
  await call('hodgeShares', [2]);
  assert.equal(state.core.calls.filter((c) => c === 'hodge').length, hodgeBefore + 1, 'the new version decomposes anew');
});

// Requests are served one after another: an op that waits (a big model's load for the page's word that its
// preview is made, the ordering cache for IndexedDB) is not overtaken by the request the page sent behind it,
// which would otherwise change the model being replaced and be lost with it; a note is still taken at once.
test('an op that waits is not overtaken by the request behind it; notes are taken meanwhile', async () => {
  const posted = [];
  const scope = { postMessage: (data) => posted.push(data) };
  const state = new WorkerState(scope);
  const order = [];
  let release;
  const waiting = new Promise((resolve) => (release = resolve));
  serve(scope, state, [{
    anytime: {
      async slow() {
        order.push('slow begins');
        await waiting;
        order.push('slow ends');
        return 1;
      },
      fast() {
        order.push('fast');
        return 2;
      },
    },
    notes: { word: () => (order.push('note'), release()) },
  }]);
  const first = scope.onmessage({ data: { seq: 1, op: 'slow', args: [] } });
  const second = scope.onmessage({ data: { seq: 2, op: 'fast', args: [] } });
  await new Promise((resolve) => setTimeout(resolve, 20));
  assert.deepEqual(order, ['slow begins'], 'the second request waits for the first');
  scope.onmessage({ data: { word: true } });
  await Promise.all([first, second]);
  assert.deepEqual(order, ['slow begins', 'note', 'slow ends', 'fast']);
  assert.deepEqual(posted.filter((p) => p.seq).map((p) => [p.seq, p.value]), [[1, 1], [2, 2]]);
});

// What the page will ask for next, made ahead (stripes/worker-ops.js): once the page has asked for the whole
// field's stripes, each edit's pattern is made after the edit's reply and its factor update, with the options of
// that last request, and served when the page asks for it; not while another request waits behind the edit, not
// for a settling request's whole pattern, not after the page says it no longer shows them, not on another mesh.
test("an edit's stripes are made ahead for the page's next request, and only then", async () => {
  const { state, call, scope } = worker();
  const stripeCalls = () => state.core.calls.filter((c) => c.startsWith('stripes'));
  await call('setWeight', [1, 2]);
  assert.deepEqual(stripeCalls(), [], 'none before the page asks');
  const options = { frequency: 3, profile: 'stripes' };
  const first = await call('stripes', [1, 'whole', options]);
  assert.equal(first.data.value.stats.madeAhead, undefined);
  assert.equal(first.list.length, 2, 'the arrays are transferred');
  await call('setWeight', [1, 3]);
  const asked = 'stripes {"frequency":3,"profile":"stripes"}';
  assert.deepEqual(stripeCalls(), [asked, asked]);
  const afterSolve = state.core.calls.slice(state.core.calls.lastIndexOf('solve'));
  assert.deepEqual(afterSolve.filter((c) => c === 'deferred' || c.startsWith('stripes')).map((c) => c.slice(0, 7)),
    ['stripes', 'deferre'], 'after the reply, before the factor takes the update');
  const ahead = await call('stripes', [2, 'whole', options]);
  assert.equal(ahead.data.value.stats.madeAhead, true);
  assert.equal(ahead.list.length, 2);
  assert.equal(stripeCalls().length, 2, 'served as made');
  // A settling request (the whole pattern) is made when asked; the next edit's is a local update again.
  await call('stripes', [2, 'whole', { ...options, localUpdate: false }]);
  assert.match(stripeCalls().at(-1), /"localUpdate":false/);
  await call('setWeight', [1, 4]);
  assert.equal(stripeCalls().at(-1), asked);
  // Other options than those made ahead: made as asked.
  const other = await call('stripes', [3, 'whole', { frequency: 5, profile: 'stripes' }]);
  assert.equal(other.data.value.stats.madeAhead, undefined);
  // An edit with another request behind it: none made ahead.
  const before = stripeCalls().length;
  const edit = scope.onmessage({ data: { seq: 100, op: 'setWeight', args: [1, 5] } });
  const read = scope.onmessage({ data: { seq: 101, op: 'hodgeShares', args: [4] } });
  await Promise.all([edit, read]);
  assert.equal(stripeCalls().length, before, 'the request waiting behind the edit goes first');
  const tail = state.core.calls.slice(state.core.calls.lastIndexOf('solve'));
  assert.deepEqual(tail.filter((c) => c === 'deferred' || c === 'hodge'), ['hodge', 'deferred'],
    'a read waiting behind an edit goes before its factor update, which follows once nothing waits');
  // A background read waiting (the page's request for a big model's preview field's stripes, of a version this
  // worker does not have): made ahead all the same, the read served after it.
  await call('stripes', [4, 'whole', options]);
  const edited = scope.onmessage({ data: { seq: 200, op: 'setWeight', args: [1, 5.5] } });
  const stale = scope.onmessage({ data: { seq: 201, op: 'stripes', args: [4, 'whole', options], background: true } });
  await Promise.all([edited, stale]);
  assert.equal(stripeCalls().length, before + 2, 'made ahead');
  assert.equal((await call('stripes', [5, 'whole', options])).data.value.stats.madeAhead, true);
  // Hidden (or another model): none.
  scope.onmessage({ data: { stripesUnfollow: true } });
  await call('setWeight', [1, 6]);
  assert.equal(stripeCalls().length, before + 2);
  await call('stripes', [6, 'whole', options]);
  state.meshChanged();
  await call('setWeight', [1, 7]);
  assert.equal(stripeCalls().length, before + 3);
  // A Hodge part's stripes are not made ahead.
  await call('stripes', [7, 'exact', options]);
  await call('setWeight', [1, 8]);
  assert.equal(stripeCalls().length, before + 4);
});
