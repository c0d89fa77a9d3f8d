// The client's calls that run the solver (core-client.js composes them): the factorization, the solve, the held
// update of an added constraint, and the factor's memory limit. Owns nothing; imports client/checks.js.
import { check, guard } from './checks.js';

// Base: a class whose instances hold the embind Designer as `designer` (core-client.js).
export const solveCalls = (Base) =>
  class SolveCalls extends Base {
    // bytes: a fixed limit for the factor's memory; 0: what is left of the wasm address space (default).
    setFactorMemoryLimit(bytes) {
      check('memory limit', guard('memory limit', () => this.designer.setFactorMemoryLimit(bytes)));
    }

    factor() {
      check('factor', guard('factor', () => this.designer.factor()));
    }

    solve() {
      check('solve', guard('solve', () => this.designer.solve()));
    }

    // An added constraint's update held beside the factor, the solve applying it (Designer::setDeferredUpdates),
    // until applyDeferredUpdates() puts it into the factor: the worker does that after its reply has gone.
    setDeferredUpdates(defer) {
      check('deferred updates', guard('deferred updates', () => this.designer.setDeferredUpdates(!!defer)));
    }

    applyDeferredUpdates() {
      check('update', guard('update', () => this.designer.applyDeferredUpdates()));
    }
  };
