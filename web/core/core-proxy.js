// Page side of the core worker (core/worker/dispatch.js): request/reply over postMessage, and supervision of the
// worker. The session serialises its mutations itself (session.js), so replies come back in request order; each
// carries the worker's timing. One proxy (one worker at a time) per element; terminate() ends it for good.
//
// Supervision: a worker that dies or can no longer be trusted is replaced, never waited on forever.
// * death, even in the middle of a long factorization: the worker holds a Web Lock for its whole life; the
//   lock is released when the worker ends (terminate, close, crash), which this side is waiting for;
// * an uncaught error in the worker (error event) or an unreadable message;
// * a wasm trap or an out-of-memory abort inside the core: the worker replies with `fatal`, since the wasm
//   instance is unusable afterwards;
// * a worker that is alive but silent: when no call is in flight it must answer a heartbeat within
//   `silentMs` (a call in flight is the user's to cancel: cancel()).
// Then every pending call rejects with a readable CoreError, a fresh worker starts, and `onRestart(reason)`
// (supplied by the session) reloads the current model and replays the current design before new calls go out.
import { CoreError } from './core-error.js';

// A module worker from another origin (a CDN) cannot be started directly; its source can, from a blob: URL
// (CSP: worker-src blob:). The worker is told the asset base, so its own URL does not matter.
export async function workerUrl(assetBase) {
  const url = new URL('core-worker.js', assetBase);
  if (url.origin === globalThis.location?.origin) return { href: url.href, revoke: () => {} };
  const res = await fetch(url);
  if (!res.ok) throw new CoreError(`could not fetch the core worker ${url.href}: HTTP ${res.status}`);
  const href = URL.createObjectURL(new Blob([await res.text()], { type: 'text/javascript' }));
  return { href, revoke: () => URL.revokeObjectURL(href) };
}

// A model file's bytes read on a worker thread (model-bytes.js says why). source: an absolute URL string or a
// Blob; assetBase: the folder of core-worker.js. Resolves with {bytes, copy (Uint8Arrays: the same bytes
// twice), digest (model-bytes.js fnv1a)}, or null when no worker could be started (the caller reads on its
// own thread then); a read that fails rejects with the worker's message.
export async function readBytesOffThread(assetBase, source) {
  let worker, revoke = () => {};
  try {
    ({ href: worker, revoke } = await workerUrl(assetBase));
    worker = new Worker(worker, { type: 'module' });
  } catch {
    revoke();
    return null;
  }
  try {
    const reply = await new Promise((resolve) => {
      worker.onmessage = ({ data }) => data.seq === 1 && resolve(data);
      worker.onerror = (event) => (event.preventDefault?.(), resolve(null));
      worker.postMessage({ seq: 1, op: 'readBytes', args: [source] });
    });
    if (!reply) return null;
    if (!reply.ok) throw new Error(reply.error);
    const { bytes, copy, digest } = reply.value;
    return { bytes: new Uint8Array(bytes), copy: new Uint8Array(copy), digest };
  } finally {
    worker.terminate();
    revoke();
  }
}

export class CoreProxy {
  // assetBase: URL of the folder holding core-worker.js and wasm/.
  // options: {onRestart({kind, detail, call}) → Promise, onStatus(text), onDeferredUpdate, heartbeatMs, silentMs}
  static async start(assetBase, options = {}) {
    const proxy = new CoreProxy(options);
    proxy.assetBase = assetBase;
    await proxy.#open();
    return proxy;
  }

  constructor(options = {}) {
    this.worker = null;
    this.pending = new Map();
    this.seq = 0;
    this.failure = null; // set by terminate(): the proxy is done for good
    this.interrupts = null; // the count of requests that rank above a background one (#open), where shared
    this.onRestart = options.onRestart ?? null;
    this.onStatus = options.onStatus ?? (() => {});
    this.onDeferredUpdate = options.onDeferredUpdate ?? null; // ({seq, ms, at}): the worker's update after a reply
    this.heartbeatMs = options.heartbeatMs ?? 2000;
    this.silentMs = options.silentMs ?? 10_000;
    this.restarts = 0;
    this.lastFailure = null;
    this.ready = Promise.resolve();
    this.spare = []; // buffers of field arrays the page is done with, for the worker's next copies
  }

  // Field arrays the page no longer uses (a field replaced by a newer one): their buffers go back to the worker
  // with the next request, to be refilled instead of allocated (worker/snapshot.js). They are detached here then.
  recycle(arrays) {
    for (const a of arrays) if (a?.buffer?.byteLength > 0 && !this.spare.includes(a.buffer)) this.spare.push(a.buffer);
  }

  async #open() {
    this.spare = []; // a new worker starts without spares; these stay with the page's garbage
    const { href, revoke } = await workerUrl(this.assetBase);
    if (this.failure) return revoke(); // terminated while the source was fetched
    const lockName = `tvf-core-${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;
    const worker = new Worker(href, { type: 'module', name: lockName });
    this.worker = worker;
    this.lastPong = performance.now();
    const mine = () => this.worker === worker;
    worker.onmessage = ({ data }) => {
      revoke();
      if (mine()) this.#receive(data, worker, lockName);
    };
    // A worker that fails to start (bad URL, syntax error) or throws outside a request reports here.
    worker.onerror = (event) => {
      event.preventDefault?.();
      if (mine()) this.#fail('error', event.message || 'the worker could not start');
    };
    worker.onmessageerror = () => mine() && this.#fail('error', 'the worker sent an unreadable message');
    clearInterval(this.heartbeat);
    this.heartbeat = setInterval(() => mine() && this.#beat(), this.heartbeatMs);
    // How many requests that rank above a background one (an edit above a stripe pattern of the field before
    // it) this side has sent, counted where the worker can read it while it runs (shared memory: a
    // cross-origin isolated page only); each request carries the count it was sent at (dispatch.js).
    const shared = globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function';
    this.interrupts = shared ? new Int32Array(new SharedArrayBuffer(4)) : null;
    await this.#send('init', [new URL('./', this.assetBase).href, this.interrupts]);
  }

  // Resolves with the whole reply ({value, snapshot?, workerMs, timing}); rejects with the core's message.
  // A rejection may still carry the state the core is left in: err.reply.snapshot. background: a read-out the
  // page can do without (the streamlines view), which cancel() does not count as an operation in flight.
  // onProgress(progress): the worker's word on a long op before its reply (worker/state.js `progress`).
  // wholeDesign: the reply's snapshot carries the whole design document, not the change (progressive-core.js).
  async call(op, args = [], transfer = [], { background = false, onProgress = null, wholeDesign = false } = {}) {
    await this.ready; // a restart in progress finishes (model and design back) first
    return this.#send(op, args, transfer, background, onProgress, wholeDesign);
  }

  #send(op, args = [], transfer = [], background = false, onProgress = null, wholeDesign = false) {
    if (this.failure) return Promise.reject(this.failure);
    if (!this.worker) return Promise.reject(new CoreError(`${op}: the core is restarting`));
    const seq = ++this.seq;
    const spare = this.spare.filter((b) => b.byteLength > 0 && !transfer.includes(b));
    this.spare = [];
    const counted = this.interrupts;
    const mark = !counted ? undefined : background ? Atomics.load(counted, 0) : Atomics.add(counted, 0, 1) + 1;
    return new Promise((resolve, reject) => {
      this.pending.set(seq, { resolve, reject, op, background, onProgress });
      try {
        this.worker.postMessage({ seq, op, args, spare, wholeDesign, mark, background }, [...transfer, ...spare]);
      } catch (err) {
        this.pending.delete(seq);
        reject(new CoreError(`could not send ${op} to the core: ${err.message}`));
      }
    });
  }

  // A word for the worker outside the request sequence (worker/dispatch.js: a group's notes).
  notify(message) {
    this.worker?.postMessage(message);
  }

  // Stops whatever the worker is doing (a huge stroke, a factorization) by replacing it: the pending calls
  // reject with "cancelled", and the model and the design as they were before the cancelled call come back.
  cancel() {
    if (this.failure || ![...this.pending.values()].some((p) => !p.background)) return false;
    this.#fail('cancelled', 'cancelled by the user');
    return true;
  }

  // Ends the worker (and with it the core's memory) for good; pending calls reject.
  terminate() {
    clearInterval(this.heartbeat);
    this.failure ??= new CoreError('the designer was disposed');
    this.worker?.terminate();
    this.worker = null;
    for (const p of this.pending.values()) p.reject(this.failure);
    this.pending.clear();
  }

  // For tests: what a crash of the worker does, without one; a worker that stops answering for `ms`.
  terminateForTest() {
    this.worker?.terminate();
  }

  hangForTest(ms) {
    this.worker?.postMessage({ hangForTest: ms });
  }

  // From the worker's init on, its end is noticed at once.
  #watchLock(worker, lockName) {
    if (!globalThis.navigator?.locks) return;
    navigator.locks
      .request(lockName, () => {
        if (this.worker === worker && !this.failing) this.#fail('ended', 'the core worker ended unexpectedly');
      })
      .catch(() => {});
  }

  #beat() {
    if (this.failing || this.failure) return;
    if (this.pending.size) {
      this.lastPong = performance.now(); // a long call is not silence
      return;
    }
    if (performance.now() - this.lastPong > this.silentMs) {
      this.#fail('silent', `the core did not answer for ${Math.round(this.silentMs / 1000)} s`);
      return;
    }
    try {
      this.worker?.postMessage({ ping: true });
    } catch {
      this.#fail('ended', 'the core worker cannot be reached');
    }
  }

  #receive(reply, worker, lockName) {
    this.lastPong = performance.now();
    if (reply.pong) return;
    if (reply.locked) return void this.#watchLock(worker, lockName);
    if (reply.deferredUpdate) return void this.onDeferredUpdate?.({ ...reply.deferredUpdate, at: this.lastPong });
    const p = this.pending.get(reply.seq);
    if (!p) return;
    if (reply.progress) return void p.onProgress?.(reply.progress);
    this.pending.delete(reply.seq);
    if (reply.ok) p.resolve(reply);
    else {
      const err = new CoreError(reply.error);
      err.reply = reply;
      err.fatal = !!reply.fatal;
      p.reject(err);
    }
    // A trap leaves the wasm instance unusable: this reply was the last one it may give.
    if (reply.fatal) this.#fail('trap', reply.error);
  }

  #fail(kind, detail) {
    if (this.failing || this.failure) return;
    this.failing = true;
    this.lastFailure = { kind, detail, at: Date.now() };
    const worker = this.worker;
    this.worker = null;
    try {
      worker?.terminate();
    } catch {
      // already gone
    }
    const message =
      kind === 'cancelled'
        ? 'cancelled: the operation was stopped; the model and design are back as they were before it'
        : `the core stopped (${detail}); it is being restarted with the current model and design`;
    for (const p of this.pending.values()) {
      const err = new CoreError(message);
      err.restart = kind;
      p.reject(err);
    }
    this.pending.clear();
    this.onStatus(kind === 'cancelled'
      ? 'Cancelled; restoring the design…'
      : `The core stopped (${detail}); restarting…`);
    this.ready = this.#restart(kind, detail);
    this.ready.catch(() => {});
  }

  async #restart(kind, detail) {
    try {
      await this.#open();
    } finally {
      this.failing = false;
    }
    this.restarts++;
    // The session's replay goes straight to the new worker; everyone else waits for it to finish.
    const call = (op, args, transfer) => this.#send(op, args, transfer);
    if (this.onRestart) await this.onRestart({ kind, detail, call });
  }
}
