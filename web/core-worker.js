// Module worker that owns the wasm core, so factorizations never block the page. The page (core-proxy.js)
// sends one request at a time: {seq, op, args}; every mutating op ends with a solve and replies with a
// snapshot of everything the page reads synchronously (field arrays are transferred, not copied).
//
// One worker per <tangent-field-designer> element: its globals are that element's core and nothing else.
import { CoreError, loadCore } from './core-client.js';
import { CoreExport } from './export/core-export.js';

let core = null;
let coreExport = null;

function requireMesh() {
  if (!core?.hasMesh) throw new CoreError('no mesh loaded');
}

// timing (optional) receives where the time goes: vertex vectors and singularities are derived by the core
// on first read, the design document is serialised.
function snapshot(timing = {}) {
  let t = performance.now();
  const lap = (key) => {
    const now = performance.now();
    timing[key] = now - t;
    t = now;
  };
  const faceVectors = core.faceVectors();
  const oneForm = core.oneForm();
  lap('copyMs');
  const vertexVectors = core.vertexVectors();
  const singularities = core.singularities();
  lap('deriveMs');
  const design = JSON.parse(core.designJson());
  lap('designMs');
  return {
    faceVectors,
    vertexVectors,
    oneForm,
    singularities,
    stats: core.stats(),
    design,
    ids: core.constraintIds(), // in the order of design.constraints
    transfer: [faceVectors.buffer, vertexVectors.buffer, oneForm.buffer],
  };
}

function refactorAndSolve() {
  core.factor();
  core.solve();
}

const ops = {
  // assetBase: the folder holding wasm/tvf_core.mjs (the element's asset base; the worker may run from a
  // blob: URL, where its own import.meta.url names nothing useful).
  async init(assetBase) {
    core = await loadCore(assetBase);
    coreExport = new CoreExport(core.Module);
    return { crossOriginIsolated: self.crossOriginIsolated === true };
  },

  warmUp(levels, rounds) {
    return core.warmUp(levels, rounds);
  },

  // settings: {boundary, gamma} carried over from the previous model; design: an autosaved document to
  // restore (its failure is reported, not fatal: the mesh still loads with the settings).
  loadMesh(bytes, format, settings, design) {
    core.loadMesh(bytes, format);
    coreExport.modelLoaded(bytes, format);
    // A GLB exported with its design (docs/export.md) reopens with it, unless an autosave is newer.
    const embedded = design ? null : coreExport.embeddedDesign(bytes);
    design ??= embedded;
    const info = core.info();
    const mesh = core.mesh();
    const edges = core.edges();
    let settingsError = null, restoreError = null;
    try {
      if (settings.boundary !== 'free') core.setBoundary(settings.boundary);
      if (settings.gamma !== 0) core.setGamma(settings.gamma);
    } catch (err) {
      settingsError = err.message;
      core.setBoundary('free');
      core.setGamma(0);
    }
    if (design) {
      try {
        core.applyDesignJson(JSON.stringify(design));
      } catch (err) {
        restoreError = err.message;
      }
    }
    refactorAndSolve();
    // Texture synthesis (web/synthesis/) needs the model's per-corner UVs (6 per face; empty without TEXCOORD_0).
    const cornerUVs = Float32Array.from(core.designer.cornerUVs());
    return {
      value: { info, settingsError, restoreError, embeddedDesign: embedded != null },
      mesh: { positions: mesh.positions, triangles: mesh.triangles, edges, cornerUVs },
      transfer: [mesh.positions.buffer, mesh.triangles.buffer, edges.buffer, cornerUVs.buffer],
    };
  },

  // One constraint in the design format: new ones and re-added ones (undo of a delete) alike go through the
  // core's own design-file parser.
  add(spec) {
    return core.addConstraintJson(spec);
  },

  remove(id) {
    core.remove(id);
    return true;
  },

  setWeight(id, w) {
    core.setWeight(id, w);
    return true;
  },

  setStrength(id, s) {
    core.setStrength(id, s);
    return true;
  },

  setBoundary(bc) {
    core.setBoundary(bc);
    core.factor();
    return true;
  },

  setGamma(g) {
    core.setGamma(g);
    core.factor();
    return true;
  },

  applyDesign(design) {
    core.applyDesignJson(JSON.stringify(design));
    core.factor();
    return true;
  },

  fieldJson() {
    return core.fieldJson();
  },

  // Exports of the current field (docs/export.md): the same bytes as `tvf export` for this model file.
  exportAtlasNote() {
    return coreExport.atlasNote();
  },

  exportFlowMap(options) {
    return coreExport.flowMapPng(core.oneForm(), options);
  },

  exportGlb(options, baseColorPng) {
    return coreExport.glb(core.oneForm(), JSON.parse(core.designJson()), options, baseColorPng);
  },
};

const NO_MESH_NEEDED = new Set(['init', 'warmUp', 'loadMesh']);
// Ops after which the field may have changed: they solve and send a snapshot back.
const MUTATING = new Set([
  'loadMesh',
  'add',
  'remove',
  'setWeight',
  'setStrength',
  'setBoundary',
  'setGamma',
  'applyDesign',
]);

self.onmessage = async ({ data: { seq, op, args } }) => {
  const t0 = performance.now();
  const timing = {};
  let reply, transfer = [];
  try {
    if (!ops[op]) throw new CoreError(`unknown operation ${op}`);
    if (!NO_MESH_NEEDED.has(op)) requireMesh();
    const out = await ops[op](...args);
    const t1 = performance.now();
    timing.opMs = t1 - t0;
    if (MUTATING.has(op) && op !== 'loadMesh') {
      core.solve();
      // The arrows need only the face vectors: send them at once, before the derived read-outs.
      const early = core.faceVectors();
      self.postMessage({ seq, early: { faceVectors: early } }, [early.buffer]);
    }
    timing.solveMs = performance.now() - t1;
    const snap = MUTATING.has(op) ? snapshot(timing) : null;
    if (op === 'loadMesh') {
      reply = { ok: true, value: out.value, mesh: out.mesh, snapshot: snap };
      transfer = [...out.transfer, ...snap.transfer];
    } else {
      reply = { ok: true, value: out, snapshot: snap };
      if (snap) transfer = snap.transfer;
    }
  } catch (err) {
    reply = { ok: false, error: err?.message || String(err) };
    // The page mirrors the core: after a failed edit it must still see what the core now holds.
    if (MUTATING.has(op) && core?.hasMesh) {
      try {
        core.solve();
        reply.snapshot = snapshot();
        transfer = reply.snapshot.transfer;
      } catch {
        // no field to show; the page keeps its previous copies
      }
    }
  }
  if (reply.snapshot) delete reply.snapshot.transfer;
  reply.seq = seq;
  reply.workerMs = performance.now() - t0;
  reply.timing = timing;
  self.postMessage(reply, transfer);
};
