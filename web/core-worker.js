// The core's module worker (one per <tangent-field-designer> element, started by core/core-proxy.js as
// core-worker.js beside the bundle, and as a throwaway reader of model files): an entry point that only
// composes. The wasm core's ops and their protocol are core/worker/ (dispatch.js says how each group's ops
// are served); the CPU halves of texture synthesis are synthesis/worker-ops.js, the
// stripe pattern's stripes/worker-ops.js, the quad remeshing's quad/worker-ops.js (served by a worker of its own:
// quad/run.js starts this entry a second time for it). An entry point may import
// any layer; everything it composes keeps to its own.
import { exportOps } from './core/core-export.js';
import { bytesOps } from './core/model-bytes.js';
import { serve } from './core/worker/dispatch.js';
import { editOps } from './core/worker/edit-ops.js';
import { testHooks } from './core/worker/hooks.js';
import { loadOps } from './core/worker/load-ops.js';
import { previewOps } from './core/worker/preview-ops.js';
import { readOps } from './core/worker/read-ops.js';
import { settingOps } from './core/worker/setting-ops.js';
import { WorkerState } from './core/worker/state.js';
import { quadOps } from './quad/worker-ops.js';
import { stripeOps } from './stripes/worker-ops.js';
import { synthesisOps } from './synthesis/worker-ops.js';

// The worker's whole state is this one WorkerState: one served core per worker, one worker per element.
function serveWorker(scope) {
  const state = new WorkerState(scope);
  serve(scope, state, [
    loadOps(state),
    previewOps(state),
    editOps(state),
    settingOps(state),
    readOps(state),
    exportOps(state),
    bytesOps(),
    synthesisOps(state),
    stripeOps(state),
    quadOps(state),
    testHooks(state),
  ]);
}

serveWorker(self);
