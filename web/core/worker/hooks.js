// The worker's hooks for the tests (tests/e2e/robust.spec.mjs and others): failures the core itself has none
// of on purpose, and a factorization limit small enough to reach without a multi-million-edge mesh. Imports
// nothing.

export function testHooks(state) {
  const anytime = {
    // What a wasm trap (unreachable, an out-of-bounds access, an abort) looks like to the worker.
    trapForTest() {
      throw new WebAssembly.RuntimeError('unreachable executed (test)');
    },

    // 0: the wasm address space left (default); a number: a fixed limit.
    setFactorMemoryLimit(bytes) {
      state.core.setFactorMemoryLimit(bytes);
      return true;
    },
  };

  const notes = {
    // A worker that stops answering without a call in flight (an infinite loop in a timer, a deadlock), for
    // `ms` milliseconds.
    hangForTest(ms) {
      const end = performance.now() + ms;
      while (performance.now() < end);
    },
  };

  return { anytime, notes };
}
