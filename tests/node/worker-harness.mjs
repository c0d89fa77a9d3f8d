// The core worker's entry (web/core-worker.js) served in this thread, for the tests that drive its ops with the
// real wasm core (core-worker.test.mjs, quad-worker.test.mjs). The entry serves `self` as it is imported, so the
// stand-in of the worker's global, which keeps what the worker posts, is set first and the entry imported after.
// Once per process (node --test runs each test file in its own): a second call would find the entry imported.
//
// call(op, ...args) posts a request as the page does and resolves with the reply's data, the transfer list it
// came with and its seq, or rejects with the worker's error; posted: every message the worker posted, progress
// messages included, in order.
export async function serveCoreWorker() {
  const posted = [];
  const scope = { postMessage: (data, list = []) => posted.push({ data, list }) };
  globalThis.self = scope;
  await import('../../web/core-worker.js');

  let seq = 0;
  async function call(op, ...args) {
    const mine = ++seq;
    await scope.onmessage({ data: { seq: mine, op, args } });
    const { data, list } = posted.find((p) => p.data.seq === mine && !p.data.progress);
    if (!data.ok) throw new Error(data.error);
    return { ...data, list, seq: mine };
  }
  return { posted, call };
}
