// The core worker's protocol (the page's side is core-proxy.js): one request at a time, {seq, op, args}, and
// one reply {seq, ok, value | error, fatal, snapshot?, workerMs, timing}. Every op that may change the field
// ends with a solve and replies with a snapshot of what changed (snapshot.js); an edit whose solve fails is
// taken back. Messages outside the sequence: `ping` (the page's heartbeat) and each group's notes.
//
// The ops come in groups (edit-ops.js, load-ops.js, preview-ops.js, read-ops.js, hooks.js, setting-ops.js,
// core-export.js, model-bytes.js, synthesis/worker-ops.js), composed by the worker's entry (web/core-worker.js).
// A group files each op under what the dispatch does around it:
//   edits    need a mesh; the core solves after them and the reply carries a snapshot
//   opens    make a model current, solved by the op itself (one transaction); the reply carries a snapshot
//   onMesh   need a mesh; the reply carries the op's value only
//   anytime  need no mesh
//   notes    {key: fn(value)}: a message {key: value} outside the request sequence
// and may give `afterEdit()`: run once an edit has replied, when no foreground request waits, before the edit's
// update goes into the factor (what the page will ask for next about the new field, made ahead: the stripes).
// Imports the worker's state's parts it drives.
import { CoreError } from '../core-error.js';
import { snapshot } from './snapshot.js';
import { isFatal } from './supervision.js';
import { Transfer } from './transfer.js';

const KINDS = ['edits', 'opens', 'onMesh', 'anytime'];

// groups: op groups as above. Returns {ops: Map name -> {run, kind}, notes: Map key -> fn, afterEdit: [fn]}; an
// op or a note that two groups define is an error (one would silently shadow the other).
export function composeOps(groups) {
  const ops = new Map();
  const notes = new Map();
  const afterEdit = groups.map((group) => group.afterEdit).filter(Boolean);
  const claim = (table, name, entry) => {
    if (table.has(name)) throw new Error(`the worker's op ${name} is defined twice`);
    table.set(name, entry);
  };
  for (const group of groups) {
    for (const kind of KINDS)
      for (const [name, run] of Object.entries(group[kind] ?? {})) claim(ops, name, { run, kind });
    for (const [key, fn] of Object.entries(group.notes ?? {})) claim(notes, key, fn);
  }
  return { ops, notes, afterEdit };
}

// Serves the composed groups on scope (the worker's global, or a stand-in with postMessage in tests).
export function serve(scope, state, groups) {
  const { ops, notes, afterEdit } = composeOps(groups);
  // Requests received and not yet begun, and those of them that rank above a background one (core-proxy.js):
  // what the page will ask for next is made ahead only when no such request waits (a background read that
  // waits, such as the page's request for the stripes of a big model's preview field, which this worker does
  // not make, is served after it).
  let waiting = 0, foreground = 0;
  const idle = () => waiting === 0;
  const noForeground = () => foreground === 0;
  // Requests run one after another, in the order they came, each once the one before has replied: an op that
  // waits (a big model's load for the page's word that its preview is made, the ordering cache for IndexedDB)
  // is not overtaken by the edits the page sends behind it, which would change the model it is replacing and
  // be lost with it. Notes and pings are not requests: they are taken at once (the word the load waits for).
  let queue = Promise.resolve();
  scope.onmessage = ({ data }) => {
    if (data.ping) return void scope.postMessage({ pong: true });
    for (const [key, note] of notes) if (data[key]) return void note(data[key]);
    waiting++;
    if (!data.background) foreground++;
    queue = queue.then(() => {
      waiting--;
      if (!data.background) foreground--;
      return serveRequest(scope, state, ops, data, { idle, noForeground, afterEdit });
    }).catch((err) => console.error(err));
    return queue; // resolves once this request is served (a stand-in scope in tests awaits it)
  };
}

// A task's turn: the messages that came while the thread was busy are received (and counted as waiting).
const nextTask = () => new Promise((resolve) => setTimeout(resolve, 0));

// One request: its op answered and replied; then, after an edit and while no foreground request waits, the
// groups' afterEdit() (the stripes the page will ask for next); then, once no request waits, the update the
// solves went through put into the factor (Designer::setDeferredUpdates). A read the page sent meanwhile (its
// request for those stripes) goes first; an edit puts the update in itself before its own (every other change
// of the factor does), the next idle moment after it the edit's.
async function serveRequest(scope, state, ops, data, { idle, noForeground, afterEdit }) {
  const entry = ops.get(data.op);
  const mutating = entry?.kind === 'edits' || entry?.kind === 'opens';
  const t0 = performance.now();
  const { reply, transfer } = await answer(state, data, entry, mutating);
  if (reply.snapshot) delete reply.snapshot.transfer;
  reply.seq = data.seq;
  reply.workerMs = performance.now() - t0;
  scope.postMessage(reply, transfer);
  if (!state.core?.hasMesh) return;
  if (mutating) state.deferredFor = data.seq;
  if (entry?.kind === 'edits' && reply.ok && afterEdit.length) {
    await nextTask();
    if (noForeground()) afterEdit.forEach((hook) => runHook(hook));
  }
  if (state.deferredFor === null) return;
  await nextTask();
  if (!idle()) return;
  const t = performance.now();
  state.core.applyDeferredUpdates();
  scope.postMessage({ deferredUpdate: { seq: state.deferredFor, ms: performance.now() - t } });
  state.deferredFor = null;
}

function runHook(hook) {
  try {
    hook();
  } catch (err) {
    console.error(err); // made ahead only: the page's own request reports what fails
  }
}

async function answer(state, data, entry, mutating) {
  const { seq, op } = data;
  state.beginRequest(seq, data.mark);
  state.spares.take(data.spare);
  const t0 = performance.now();
  const timing = {};
  try {
    if (!entry) throw new CoreError(`unknown operation ${op}`);
    if (entry.kind === 'edits' || entry.kind === 'onMesh') state.requireMesh();
    // A preview worker takes each edit posed on its coarse mesh (preview/preview.js), and keeps the fine specs.
    const args = state.preview && mutating ? state.preview.argsOnCoarse(op, data.args) : data.args;
    let value = await entry.run(...args);
    let transfer = [];
    if (state.preview && mutating)
      state.preview.afterOp(op, data.args, value instanceof Transfer ? value.value : value);
    if (value instanceof Transfer) {
      transfer = value.list;
      value = value.value;
    }
    const t1 = performance.now();
    timing.opMs = t1 - t0;
    if (entry.kind === 'edits') state.core.solve();
    timing.solveMs = performance.now() - t1;
    const reply = { ok: true, value, timing };
    if (mutating) {
      reply.snapshot = snapshot(state, data.wholeDesign ? null : state.changedIds, timing);
      transfer = [...transfer, ...reply.snapshot.transfer];
    }
    return { reply, transfer };
  } catch (err) {
    return failed(state, err, entry, mutating, timing);
  }
}

// An edit whose factor or solve failed is taken back, so the core never keeps a state it cannot solve; and the
// page mirrors the core: after a failed edit it must still see what the core now holds (the whole design,
// whatever the edit had got to).
function failed(state, err, entry, mutating, timing) {
  const reply = { ok: false, error: err?.message || String(err), fatal: isFatal(err), timing };
  if (reply.fatal) return { reply, transfer: [] };
  if (state.undoEdit) {
    try {
      state.undoEdit();
    } catch {
      // the snapshot below shows whatever the core holds
    }
  }
  if (!mutating || !state.core?.hasMesh) return { reply, transfer: [] };
  try {
    if (entry.kind === 'edits') state.core.solve(); // an open is one transaction: the model it leaves is solved
    reply.snapshot = snapshot(state, null, timing);
    return { reply, transfer: reply.snapshot.transfer };
  } catch {
    return { reply, transfer: [] }; // no field to show; the page keeps its previous copies
  }
}
