// Page side of the core worker (core-worker.js): request/reply over postMessage. The session serialises its
// mutations itself (session.js), so replies come back in request order; each carries the worker's timing.
// One proxy (one worker) per element; terminate() ends it.
import { CoreError } from './core-client.js';

// A module worker from another origin (a CDN) cannot be started directly; its source can, from a blob: URL
// (CSP: worker-src blob:). The worker is told the asset base, so its own URL does not matter.
async function workerUrl(assetBase) {
  const url = new URL('core-worker.js', assetBase);
  if (url.origin === globalThis.location?.origin) return { href: url.href, revoke: () => {} };
  const res = await fetch(url);
  if (!res.ok) throw new CoreError(`could not fetch the core worker ${url.href}: HTTP ${res.status}`);
  const href = URL.createObjectURL(new Blob([await res.text()], { type: 'text/javascript' }));
  return { href, revoke: () => URL.revokeObjectURL(href) };
}

export class CoreProxy {
  // assetBase: URL of the folder holding core-worker.js and wasm/.
  static async start(assetBase) {
    const proxy = new CoreProxy();
    await proxy.#open(assetBase);
    return proxy;
  }

  constructor() {
    this.worker = null;
    this.pending = new Map();
    this.seq = 0;
    this.failure = null;
  }

  async #open(assetBase) {
    const { href, revoke } = await workerUrl(assetBase);
    if (this.failure) return revoke(); // terminated while the source was fetched
    this.worker = new Worker(href, { type: 'module', name: 'tvf-core' });
    this.worker.onmessage = ({ data }) => {
      revoke();
      this.#settle(data);
    };
    // A worker that fails to start (bad URL, syntax error) reports here, not through messages.
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      this.#failAll(new CoreError(`the core worker failed: ${event.message || 'could not start it'}`));
    };
    this.worker.onmessageerror = () => this.#failAll(new CoreError('the core worker sent an unreadable message'));
    await this.call('init', [new URL('./', assetBase).href]);
  }

  // Resolves with the whole reply ({value, snapshot?, mesh?, workerMs}); rejects with the core's message.
  // A rejection may still carry the state the core is left in: err.reply.snapshot. onEarly receives the new
  // face vectors of an edit as soon as the solve is done, before the rest of the snapshot.
  call(op, args = [], transfer = [], onEarly = null) {
    if (this.failure) return Promise.reject(this.failure);
    const seq = ++this.seq;
    return new Promise((resolve, reject) => {
      this.pending.set(seq, { resolve, reject, onEarly });
      this.worker.postMessage({ seq, op, args }, transfer);
    });
  }

  // Ends the worker (and with it the core's memory); pending calls reject.
  terminate() {
    this.worker?.terminate();
    this.worker = null;
    this.#failAll(new CoreError('the designer was disposed'));
  }

  #settle(reply) {
    const p = this.pending.get(reply.seq);
    if (!p) return;
    if (reply.early) return void p.onEarly?.(reply.early);
    this.pending.delete(reply.seq);
    if (reply.ok) p.resolve(reply);
    else {
      const err = new CoreError(reply.error);
      err.reply = reply;
      p.reject(err);
    }
  }

  #failAll(err) {
    for (const p of this.pending.values()) p.reject(err);
    this.pending.clear();
    this.failure ??= err;
  }
}
