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

// How to take back the edit in flight when the solve after it fails (a factor that does not fit, a field that
// is not finite): the core then holds exactly what it held before the request. Set by each mutating op.
let undoEdit = null;

// The current design, and the entry of one core id in it.
function currentDesign() {
  return JSON.parse(core.designJson());
}
function currentSpec(id) {
  return currentDesign().constraints[core.constraintIds().indexOf(id)];
}

const ops = {
  // assetBase: the folder holding wasm/tvf_core.mjs (the element's asset base; the worker may run from a
  // blob: URL, where its own import.meta.url names nothing useful).
  async init(assetBase) {
    core = await loadCore(assetBase);
    // Held for the worker's whole life: the page notices its release the moment this worker ends.
    if (self.name && self.navigator?.locks) {
      self.navigator.locks
        .request(self.name, () => {
          self.postMessage({ locked: true });
          return new Promise(() => {});
        })
        .catch(() => {});
    }
    coreExport = new CoreExport(core.Module);
    return { crossOriginIsolated: self.crossOriginIsolated === true };
  },

  warmUp(levels, rounds) {
    return core.warmUp(levels, rounds);
  },

  // settings: {boundary, gamma} carried over from the previous model; design: an autosaved document to
  // restore (its failure is reported, not fatal: the mesh still loads with the settings).
  // One transaction in the core: the new mesh is read, checked, configured, factored and solved aside and
  // replaces the current model only when all of that succeeded; a failure leaves the core and the page on the
  // previous model.
  loadMesh(bytes, format, settings, design) {
    // A GLB exported with its design (docs/export.md) reopens with it, unless an autosave is newer.
    const embedded = design ? null : coreExport.embeddedDesign(bytes);
    const { settingsError, restoreError } = core.loadModel(bytes, format, settings, design ?? embedded);
    coreExport.modelLoaded(bytes, format);
    const info = core.info();
    const mesh = core.mesh();
    const edges = core.edges();
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
    const id = core.addConstraintJson(spec);
    undoEdit = () => core.remove(id);
    return id;
  },

  remove(id) {
    core.remove(id);
    return true;
  },

  setWeight(id, w) {
    const before = currentSpec(id)?.weight;
    core.setWeight(id, w);
    if (before !== undefined) undoEdit = () => core.setWeight(id, before);
    return true;
  },

  setStrength(id, s) {
    const before = currentSpec(id)?.strength;
    core.setStrength(id, s);
    if (before !== undefined) undoEdit = () => core.setStrength(id, before);
    return true;
  },

  setBoundary(bc) {
    const before = currentDesign().boundary;
    undoEdit = () => core.setBoundary(before);
    core.setBoundary(bc);
    core.factor();
    return true;
  },

  setGamma(g) {
    const before = core.gamma();
    undoEdit = () => core.setGamma(before);
    core.setGamma(g);
    core.factor();
    return true;
  },

  applyDesign(design) {
    const before = currentDesign();
    undoEdit = () => core.applyDesignJson(JSON.stringify(before));
    core.applyDesignJson(JSON.stringify(design));
    core.factor();
    return true;
  },

  fieldJson() {
    return core.fieldJson();
  },

  // For the supervision tests: what a wasm trap (unreachable, an out-of-bounds access, an abort) looks like
  // to the worker; the core itself has none to offer on purpose.
  trapForTest() {
    throw new WebAssembly.RuntimeError('unreachable executed (test)');
  },

  // 0: the wasm address space left (default); a number: a fixed limit (tests scale it down instead of
  // building a multi-million-edge mesh).
  setFactorMemoryLimit(bytes) {
    core.setFactorMemoryLimit(bytes);
    return true;
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

const NO_MESH_NEEDED = new Set(['init', 'warmUp', 'loadMesh', 'setFactorMemoryLimit', 'trapForTest']);
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

// A wasm trap or an abort (out of memory, an assertion) leaves the instance unusable: the page must replace
// this worker rather than send it more work.
function isFatal(err) {
  const text = `${err?.name ?? ''} ${err?.message ?? err}`;
  return err instanceof WebAssembly.RuntimeError ||
    /RuntimeError|Aborted\(|unreachable|memory access out of bounds|table index is out of bounds/.test(text);
}

self.onmessage = async ({ data }) => {
  if (data.ping) return void self.postMessage({ pong: true });
  // For the supervision tests: a worker that stops answering without a call in flight (an infinite loop in
  // a timer, a deadlock), for `ms` milliseconds.
  if (data.hangForTest) {
    const end = performance.now() + data.hangForTest;
    while (performance.now() < end);
    return;
  }
  const { seq, op, args } = data;
  const t0 = performance.now();
  const timing = {};
  let reply, transfer = [];
  undoEdit = null;
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
    reply = { ok: false, error: err?.message || String(err), fatal: isFatal(err) };
    // An edit whose factor or solve failed is taken back, so the core never keeps a state it cannot solve.
    if (undoEdit && !reply.fatal) {
      try {
        undoEdit();
      } catch {
        // the snapshot below shows whatever the core holds
      }
    }
    // The page mirrors the core: after a failed edit it must still see what the core now holds.
    if (MUTATING.has(op) && core?.hasMesh && !reply.fatal) {
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
