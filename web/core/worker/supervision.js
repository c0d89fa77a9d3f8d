// The worker's half of its supervision (the page's half is core-proxy.js): the lock it holds for its whole
// life, whose release tells the page the moment it ends, and which errors leave it unusable. Imports nothing.

// name: the lock's (the worker's own name, given by the page); no name or no Web Locks: nothing held.
export function holdLifeLock(scope) {
  if (!scope.name || !scope.navigator?.locks) return;
  scope.navigator.locks
    .request(scope.name, () => {
      scope.postMessage({ locked: true });
      return new Promise(() => {});
    })
    .catch(() => {});
}

// A wasm trap or an abort (out of memory, an assertion) leaves the instance unusable: the page must replace
// this worker rather than send it more work.
export function isFatal(err) {
  const text = `${err?.name ?? ''} ${err?.message ?? err}`;
  return err instanceof WebAssembly.RuntimeError ||
    /RuntimeError|Aborted\(|unreachable|memory access out of bounds|table index is out of bounds/.test(text);
}
