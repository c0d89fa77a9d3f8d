// The wasm core's client: loads the module (dist/wasm/tvf_core.mjs, or the threaded build) and wraps its embind
// Designer in one class whose calls come in groups by concern (client/): a model's opening, the solver, the
// settings, the constraints, the read-outs, the stripe pattern. Each call goes through client/checks.js, so that a
// failure, in whatever form the core reports it, reaches the page as one CoreError (core-error.js) naming the
// operation.
// Owns the loaded module and its Designer; imports client/ and core-error.js.
import { editCalls } from './client/edit-calls.js';
import { describe } from './client/checks.js';
import { modelCalls } from './client/model-calls.js';
import { readOuts } from './client/read-outs.js';
import { settingCalls } from './client/setting-calls.js';
import { solveCalls } from './client/solve-calls.js';
import { stripeCalls } from './client/stripe-calls.js';
import { CoreError } from './core-error.js';

// The core with a helper thread for each solve's backward substitution (tvf_core_threads.mjs) needs shared
// memory, which a page has only when it is cross-origin isolated (COOP/COEP, as `npm start` serves the app);
// any other page, and an isolated one where the threaded core fails to start (its worker script on another
// origin, say), runs the plain core: the same results, bit for bit, one thread.
export async function loadCore(baseUrl) {
  if (globalThis.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function') {
    try {
      return await loadModule(baseUrl, 'tvf_core_threads');
    } catch (err) {
      const fallback = await loadModule(baseUrl, 'tvf_core');
      fallback.threadsUnavailable = describe(err);
      return fallback;
    }
  }
  return loadModule(baseUrl, 'tvf_core');
}

async function loadModule(baseUrl, name) {
  const moduleUrl = new URL(`wasm/${name}.mjs`, baseUrl).href;
  let factory;
  try {
    // A computed specifier keeps the bundler from trying to inline the emscripten module.
    factory = (await import(moduleUrl)).default;
  } catch (err) {
    throw new CoreError(
      `could not load the field-design core from ${moduleUrl} (${describe(err)}); ` +
        'build it with `npm run build:wasm && npm run build:web`',
    );
  }
  const Module = await factory({ locateFile: (path) => new URL(path, moduleUrl).href });
  return new CoreClient(Module);
}

// What every group of calls works on: the module and its Designer.
class LoadedCore {
  constructor(Module) {
    this.Module = Module;
    this.threadsUnavailable = null; // why an isolated page runs the plain core, if it does
    this.designer = new Module.Designer();
    this.hasMesh = false;
  }

  // V8 first runs wasm on its baseline tier (2-3x slower); the core's warmUp() exercises the factor/update/solve
  // paths on a small sphere so the user's first real factorization runs optimized code. Returns ms, or -1.
  warmUp(levels = 3, rounds = 2) {
    try {
      return this.Module.warmUp(levels, rounds);
    } catch {
      return -1; // an optimization only: never fail start-up over it
    }
  }
}

// The groups extend one another in turn (no two define the same call: tests/node/core-client.test.mjs).
export class CoreClient extends stripeCalls(readOuts(editCalls(settingCalls(solveCalls(modelCalls(LoadedCore)))))) {}
