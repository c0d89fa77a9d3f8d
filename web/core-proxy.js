// Page side of the core worker (core-worker.js): request/reply over postMessage. The page serialises its
// mutations itself (main.js), so replies come back in request order; each carries the worker's timing.
import { CoreError } from './core-client.js';

export class CoreProxy {
  constructor(workerUrl) {
    this.worker = new Worker(workerUrl, { type: 'module', name: 'tvf-core' });
    this.pending = new Map();
    this.seq = 0;
    this.worker.onmessage = ({ data }) => this.#settle(data);
    // A worker that fails to start (bad URL, syntax error) reports here, not through messages.
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      this.#failAll(new CoreError(`the core worker failed: ${event.message || 'could not start it'}`));
    };
    this.worker.onmessageerror = () => this.#failAll(new CoreError('the core worker sent an unreadable message'));
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
    this.failure = err;
  }
}
