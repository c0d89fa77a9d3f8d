// The core worker's entry (web/core-worker.js) served in this thread, for the tests that drive its ops with the
// real wasm core (core-worker.test.mjs, quad-worker.test.mjs). The entry serves `self` as it is imported, so the
// stand-in of the worker's global, which keeps what the worker posts, is set first and the entry imported after.
// Once per process (node --test runs each test file in its own): a second call would find the entry imported.
//
// call(op, ...args) posts a request as the page does and resolves with the reply's data, the transfer list it
// came with and its seq, or rejects with the worker's error (callMarked(mark, op, ...args): with the page's
// interrupt count it was sent at); posted: every message the worker posted, progress messages included, in
// order.
export async function serveCoreWorker() {
  const posted = [];
  const scope = { postMessage: (data, list = []) => posted.push({ data, list }) };
  globalThis.self = scope;
  await import('../../web/core-worker.js');

  let seq = 0;
  // mark: the page's interrupt count the request is sent at (core-proxy.js), or undefined.
  async function callMarked(mark, op, ...args) {
    const mine = ++seq;
    await scope.onmessage({ data: { seq: mine, op, args, mark } });
    const { data, list } = posted.find((p) => p.data.seq === mine && !p.data.progress);
    if (!data.ok) throw new Error(data.error);
    return { ...data, list, seq: mine };
  }
  const call = (op, ...args) => callMarked(undefined, op, ...args);
  return { posted, call, callMarked };
}
