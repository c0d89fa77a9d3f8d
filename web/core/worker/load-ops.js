// The worker's start and a model's load (dispatch.js files `loadMesh` as an open: one transaction that leaves
// its model solved). A big model opens in steps beside a preview worker (open-steps.js here, preview-ops.js
// there, progressive-core.js on the page). Imports geometry/ for the Surface and BVH parts the page takes over.
import { pageSurface, pickingParts } from '../../geometry/mesh-bvh-transfer.js';
import { Surface } from '../../geometry/surface.js';
import { loadCore } from '../core-client.js';
import { CoreExport } from '../core-export.js';
import { openModelInSteps } from '../open-steps.js';
import { OrderingCache } from './ordering-cache.js';
import { PickingCache } from './picking-cache.js';
import { holdLifeLock } from './supervision.js';
import { Transfer } from './transfer.js';

// The picking parts and the factorization's two threads wait this long at most for the page's word that the
// preview is made.
const PREVIEW_WAIT_MS = 20_000;

export function loadOps(state) {
  const orderings = new OrderingCache();
  const trees = new PickingCache();
  const anytime = {
    // assetBase: the folder holding wasm/tvf_core.mjs (the element's asset base; the worker may run from a
    // blob: URL, where its own import.meta.url names nothing useful). interrupts: the page's count of the
    // requests that rank above a background one (an Int32Array on shared memory), or null.
    async init(assetBase, interrupts = null) {
      if (interrupts instanceof Int32Array && interrupts.buffer instanceof SharedArrayBuffer)
        state.interrupts = interrupts;
      const core = (state.core = await loadCore(assetBase));
      // Held for the worker's whole life: the page notices its release the moment this worker ends.
      holdLifeLock(state.scope);
      state.coreExport = new CoreExport(core);
      core.setDeferredUpdates(true); // an edit's field is replied before the factor takes its update (dispatch.js)
      if (core.threadsUnavailable) {
        const why = core.threadsUnavailable;
        console.warn(`tangent-field-designer: the core with threads did not start (${why}); solving on one thread`);
      }
      return { crossOriginIsolated: state.scope.crossOriginIsolated === true };
    },
  };

  const onMesh = {
    warmUp: (levels, rounds) => state.core.warmUp(levels, rounds),
  };

  const opens = {
    // settings: {boundary, gamma, symmetry, curvatureAlignment} carried over from the previous model; design: an
    // autosaved document to restore (its failure is reported, not fatal: the mesh still loads with the settings).
    // One transaction in the core: the new mesh is read, checked, configured, factored and solved aside and
    // replaces the current model only when all of that succeeded, or the core and page keep the previous one.
    // options.previewEdges: a mesh this big sends its mesh and design ahead as `progress` 'read' and 'opened'
    // (open-steps.js) for a preview core (progressive-core.js), then the page's surface ('surface'), and once
    // the preview is made its adjacency and BVH ('picking': the first field needs neither), then factors.
    async loadMesh(bytes, format, settings, design, options = {}) {
      const { core, coreExport } = state;
      state.preview = null;
      // A GLB exported with its design (docs/export.md) reopens with it, unless an autosave is newer.
      const embedded = design ? null : coreExport.embeddedDesign(bytes);
      const steps = {
        bytes,
        format,
        settings,
        design: design ?? embedded,
        embedded: embedded != null,
        previewEdges: options.previewEdges,
      };
      const progress = (value, list) => state.progress(value, list);
      const { opened, info: pendingInfo, ahead } = openModelInSteps(core, steps, progress);
      const found = orderings.find(core.designer);
      if (ahead) await sendAhead(state, trees);
      // The ordering and analysis this mesh had when it was last opened (ordering-cache.js): none is made.
      const ordering = await orderings.adopt(core.designer, found);
      state.progress({ phase: 'factoring', info: pendingInfo });
      // Tests: an exact factorization that takes at least this long, so the preview surely leads.
      for (const end = performance.now() + (options.delayForTestMs ?? 0); performance.now() < end; );
      const committed = core.commitModel();
      // Factored and solved: what the page does with the field after this is its own time (loadPhases).
      state.progress({ phase: 'committed' });
      orderings.keep(core.designer, ordering.key); // behind the reply
      coreExport.modelLoaded(bytes, format);
      state.meshChanged();
      const info = core.info();
      state.spares.reset([3 * info.faces, 3 * info.vertices, info.edges]);
      // Texture synthesis (web/synthesis/) needs the model's per-corner UVs (6 per face; empty without TEXCOORD_0).
      const cornerUVs = core.designer.cornerUVs().slice();
      const restoreError = opened.restoreError ?? committed.restoreError;
      const { settingsError } = opened;
      const value = { info, settingsError, restoreError, embeddedDesign: embedded != null, cornerUVs };
      if (ahead) return new Transfer(value, [cornerUVs.buffer]);
      // The mesh's geometry and adjacency, built once here (off the page's thread): the worker traces on it, and
      // the page takes a copy of its arrays instead of deriving them again.
      const { arrays, list } = pageSurface(state.surface());
      return new Transfer({ ...value, surface: arrays }, [...list, cornerUVs.buffer]);
    },
  };

  // The page's word that the big model's preview is made (or failed): the load factors from here on.
  const notes = {
    previewMade: () => state.previewMade(),
  };

  return { anytime, onMesh, opens, notes };
}

// A big model, opened: the page's surface goes now, and the picking parts and the factorization's two threads,
// which would take the cores from the preview, wait for the page's word that it is made; the matrix is then
// assembled while the bounds tree and the ordering kept for the mesh are read (IndexedDB: 0.1-0.3 s for a big
// mesh, and their copies into the worker wait for it to be free). trees: the bounds trees kept per mesh
// (picking-cache.js).
async function sendAhead(state, trees) {
  const m = state.core.pendingMesh();
  const { arrays, list } = pageSurface(new Surface(m.positions, m.triangles, m.edges), true, { picking: false });
  state.progress({ phase: 'surface', surface: arrays }, list);
  const { designer } = state.core;
  const { vertices, faces } = state.core.pendingInfo();
  const keptTree = trees.find(designer.pendingMeshHash(), vertices, faces); // read while waiting
  await new Promise((resolve) => {
    state.previewMade = resolve;
    setTimeout(resolve, PREVIEW_WAIT_MS);
  });
  state.progress({ phase: 'previewWord' });
  designer.preparePendingSystem();
  state.progress({ phase: 'assembled' });
  const kept = await keptTree;
  // Views of the wasm heap, taken after the waits (the heap may have grown while the cache was read).
  const adjacency = designer.pendingFaceAdjacency();
  const picking = pickingParts(designer.pendingPositions(), designer.pendingTriangles(), kept.bvh, adjacency);
  if (!kept.bvh) trees.keep(kept.key, picking.value.bvh);
  state.progress({ phase: 'picking', picking: picking.value, treeKept: !!kept.bvh }, picking.list);
}
