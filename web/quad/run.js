// SPDX-License-Identifier: GPL-2.0-or-later
// One quad remeshing on a worker of its own: a second core-worker.js (the same entry and wasm module the element's
// core runs, started through core/core-proxy.js as the big models' preview worker is), which loads the core, runs
// quad/worker-ops.js's quadRemesh and is ended when the run is over, so that its wasm heap (the parametrization's
// factor) goes with it. The element's core worker is never asked anything: the design stays editable while a
// remesh runs, and cancelling is terminate(), at once, whatever the core is in the middle of. Imports core/.
import { CoreProxy } from '../core/core-proxy.js';

export const CANCELLED = 'the quad remeshing was cancelled';

// assetBase: the folder of core-worker.js and wasm/; input: {positions, triangles, faceDirections} (copies: their
// buffers are transferred to the worker); options: the core's ({edgeLength} | {quads}, symmetry);
// onProgress({stage, fraction}). Returns {promise, cancel()}: the promise resolves with the worker's reply value
// (quad/worker-ops.js) or rejects with an Error: the core's refusal, or CANCELLED once cancel() was called.
export function startQuadRun(assetBase, input, options, onProgress = () => {}) {
  let proxy = null, ended = false, cancel;
  const cancelled = new Promise((_, reject) => {
    cancel = () => reject(new Error(CANCELLED));
  });
  cancelled.catch(() => {});
  const end = () => {
    ended = true;
    proxy?.terminate();
  };
  const run = (async () => {
    const started = await CoreProxy.start(assetBase, { silentMs: 60_000 });
    if (ended) return void started.terminate(); // cancelled while the core was loading
    proxy = started;
    const { positions, triangles, faceDirections } = input;
    const transfer = [positions.buffer, triangles.buffer, faceDirections.buffer];
    try {
      const reply = await proxy.call('quadRemesh', [positions, triangles, faceDirections, options], transfer, {
        onProgress,
      });
      return reply.value;
    } catch (err) {
      // A trap or an out-of-memory abort ends the worker (core-proxy.js would start another: not for this run).
      throw new Error(err.restart ? `the quad remeshing stopped: ${proxy.lastFailure?.detail ?? err.message}` :
        err.message);
    }
  })();
  const promise = Promise.race([run, cancelled]).finally(end);
  return {
    promise,
    cancel() {
      if (ended) return false;
      cancel();
      end();
      return true;
    },
  };
}
