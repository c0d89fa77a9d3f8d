// Module worker that owns the wasm core, so factorizations never block the page. The page (core-proxy.js)
// sends one request at a time: {seq, op, args}; every mutating op ends with a solve and replies with what
// changed: the field arrays (transferred, not copied), the stats, and the design as a change to the page's
// copy (the constraints the op touched and the id order) rather than the whole document. Everything else is
// derived when it is read or shown: the singularities on the page (web/singularities.js), the streamlines
// here on request (`streamlines`), the whole design document on request (`read`).
//
// One worker per <tangent-field-designer> element: its globals are that element's core and nothing else.
import { CoreError, loadCore } from './core-client.js';
import { CoreExport, exportOps } from './core-export.js';
import { readOps } from './model-bytes.js';
import { FieldParts } from './field-parts.js';
import { settingOps } from './setting-ops.js';
import { SpareArrays } from './spare-arrays.js';
import { Preview } from './preview/preview.js';
import { warmUpPreview } from './preview/warm-up.js';
import { openModelInSteps } from './open-steps.js';
import { traceStreamlines } from '../geometry/streamlines.js';
import { preparedAtlas, preparedBuffers } from '../synthesis/atlas-prepared.js';
import { analyzeExemplar, exemplarBuffers } from '../synthesis/exemplar.js';
import { Surface } from '../geometry/surface.js';
import { pageSurface, pickingParts } from '../geometry/mesh-bvh-transfer.js';
import { magnitudeScale } from '../geometry/magnitudes.js';

// The worker's whole state lives in this closure: one served core per worker, one worker per element.
function serve(scope) {
  let core = null;
  let coreExport = null;
  // The field's version: one more after every solve the page is told about. Requests for derived read-outs
  // name the version they are for, so a reply never pairs one field with another field's read-outs.
  let version = 0;
  // For the streamlines: the mesh's surface (built on first use), and the last trace.
  let tracing = { surface: null, key: '', lines: null };
  // The current field's Hodge decomposition and its parts' vectors, made on request and kept until the next solve.
  const parts = new FieldParts(() => core);
  // In a preview worker (progressive-core.js): the coarse stand-in of the page's big mesh, else null.
  let preview = null;
  let warming = null;
  let prepared = null; // the big model's coarse stand-in and map, until its preview opens
  let previewMade = () => {}; // what a big model's load waits for before factoring
  // The request in flight, whose `progress` messages the page routes to its caller (core-proxy.js).
  let seqNow = 0;
  const progress = (value, list = []) => scope.postMessage({ seq: seqNow, progress: value }, list);

  function surfaceOf() {
    if (!tracing.surface) {
      const mesh = core.mesh();
      tracing.surface = new Surface(mesh.positions, mesh.triangles, core.edges());
    }
    return tracing.surface;
  }

  function requireMesh() { if (!core?.hasMesh) throw new CoreError('no mesh loaded'); }

  // A result that carries its own transfer list.
  class Transfer {
    constructor(value, list) {
      Object.assign(this, { value, list });
    }
  }
  const transferOf = ({ value, list }) => new Transfer(value, list);

  const spares = new SpareArrays(); // earlier field arrays the page handed back, refilled rather than allocated

  // What the exports read of the field: a vector field's one-form, or a line or cross field's directions.
  function exportedField() {
    const symmetry = core.symmetry();
    return symmetry > 1 ? { symmetry, faceDirections: core.faceVectors() } : { symmetry, oneForm: core.oneForm() };
  }

  // After a solve: the field arrays the views need, copied out of the wasm heap (a memcpy each, into spares where
  // the page has handed some back) and transferred; the vertex vectors are derived here because the default
  // arrow view interpolates them.
  // `changed`: core ids whose design entry the op set (null: the whole document, after a load, a setting, a
  // design, or an edit taken back). timing (optional) receives where the time goes. `symmetry`: the field's N
  // (faceVectors and vertexVectors are then unit representatives, one of the N directions: web/views/).
  function snapshot(changed, timing = {}) {
    let t = performance.now();
    const lap = (key) => {
      const now = performance.now();
      timing[key] = now - t;
      t = now;
    };
    version++;
    parts.drop();
    const counts = { reused: 0 };
    const copy = (view) => spares.copyOut(view, counts);
    const faceVectors = core.faceVectors(copy);
    const oneForm = core.oneForm(copy);
    lap('copyMs');
    const vertexVectors = core.vertexVectors(copy);
    lap('deriveMs');
    timing.reusedArrays = counts.reused;
    const ids = core.constraintIds();
    const design = changed
      ? { ids, changed: changed.filter((id) => ids.includes(id)).map((id) => [id, core.constraint(id)]) }
      : { ids, document: JSON.parse(core.designJson()) };
    lap('designMs');
    // heapBytes: the wasm memory, which never shrinks: the peak so far.
    const stats = { ...core.stats(), preview: false, heapBytes: core.Module.HEAP8.buffer.byteLength };
    lap('statsMs');
    const transfer = [faceVectors.buffer, vertexVectors.buffer, oneForm.buffer];
    // The magnitude scale here rather than on the page's thread.
    return { version, symmetry: core.symmetry(), faceVectors, vertexVectors, oneForm, scale: magnitudeScale(vertexVectors), stats, design, transfer };
  }

  // How to take back the edit in flight when the solve after it fails (a factor that does not fit, a field that
  // is not finite): the core then holds exactly what it held before the request. Set by each mutating op.
  let undoEdit = null;
  // The core ids whose entry in the design the op in flight changed; null: the whole document.
  let changedIds = null;
  const settingEdits = settingOps(() => core, (undo) => (undoEdit = undo));

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
      coreExport = new CoreExport(core);
      core.setDeferredUpdates(true); // an edit's field is replied before the factor takes its update (below)
      if (core.threadsUnavailable)
        console.warn(`tangent-field-designer: the core with threads did not start (${core.threadsUnavailable}); solving on one thread`);
      return { crossOriginIsolated: self.crossOriginIsolated === true };
    },

    warmUp: (levels, rounds) => core.warmUp(levels, rounds),

    // settings: {boundary, gamma, symmetry, curvatureAlignment} carried over from the previous model; design: an
    // autosaved document to restore (its failure is reported, not fatal: the mesh still loads with the settings).
    // One transaction in the core: the new mesh is read, checked, configured, factored and solved aside and
    // replaces the current model only when all of that succeeded, or the core and page keep the previous one.
    // options.previewEdges: a mesh this big sends its mesh and design ahead as `progress` 'read' and 'opened'
    // (open-steps.js) for a preview core (progressive-core.js), then the page's surface ('surface'), and once
    // the preview is made its adjacency and BVH ('picking': the first field needs neither), then factors.
    async loadMesh(bytes, format, settings, design, options = {}) {
      preview = null;
      // A GLB exported with its design (docs/export.md) reopens with it, unless an autosave is newer.
      const embedded = design ? null : coreExport.embeddedDesign(bytes);
      const steps = { bytes, format, settings, design: design ?? embedded, embedded: embedded != null, previewEdges: options.previewEdges };
      const { opened, info: pendingInfo, ahead } = openModelInSteps(core, steps, progress);
      if (ahead) {
        const m = core.pendingMesh();
        const { arrays, list } = pageSurface(new Surface(m.positions, m.triangles, m.edges), true, { picking: false });
        progress({ phase: 'surface', surface: arrays }, list);
        // The picking parts and the factorization's two threads would take the cores from the preview: they
        // wait for the page's word that it is made (or failed), 20 s at most.
        await new Promise((resolve) => {
          previewMade = resolve;
          setTimeout(resolve, 20_000);
        });
        const picking = pickingParts(core.designer.pendingPositions(), core.designer.pendingTriangles());
        progress({ phase: 'picking', picking: picking.value }, picking.list);
      }
      progress({ phase: 'factoring', info: pendingInfo });
      // Tests: an exact factorization that takes at least this long, so the preview surely leads.
      for (const end = performance.now() + (options.delayForTestMs ?? 0); performance.now() < end; );
      const committed = core.commitModel();
      coreExport.modelLoaded(bytes, format);
      const info = core.info();
      spares.reset([3 * info.faces, 3 * info.vertices, info.edges]);
      tracing = { surface: null, key: '', lines: null };
      // Texture synthesis (web/synthesis/) needs the model's per-corner UVs (6 per face; empty without TEXCOORD_0).
      const cornerUVs = core.designer.cornerUVs().slice();
      const value = { info, settingsError: opened.settingsError, restoreError: opened.restoreError ?? committed.restoreError, embeddedDesign: embedded != null, cornerUVs };
      if (ahead) return new Transfer(value, [cornerUVs.buffer]);
      // The mesh's geometry and adjacency, built once here (off the page's thread): the worker traces on it, and
      // the page takes a copy of its arrays instead of deriving them again.
      const { arrays, list } = pageSurface(surfaceOf());
      return new Transfer({ ...value, surface: arrays }, [...list, cornerUVs.buffer]);
    },

    // A preview worker's steps (preview/): a warm-up (warm-up.js; a failed one costs time), the mesh's part from
    // the exact worker's `read` (or `opened`) progress, the rest from `opened` (replying with the preview field).
    warmUpPreview() {
      return (warming = warmUpPreview(core).then(() => true, () => false));
    },
    async previewMesh(mesh) {
      await warming;
      prepared = await Preview.prepare(mesh);
      return true;
    },
    openPreview(fineDoc, settings) {
      preview = Preview.open(core, prepared, fineDoc, settings);
      const { fine } = preview.map;
      spares.reset([fine.triangles.length, fine.positions.length]);
      return { timings: preview.timings };
    },

    // One constraint in the design format: new ones and re-added ones (undo of a delete) alike go through the
    // core's own design-file parser.
    add(spec) {
      const id = core.addConstraintJson(spec);
      undoEdit = () => core.remove(id);
      changedIds = [id];
      return id;
    },

    remove(id) {
      core.remove(id);
      changedIds = [];
      return true;
    },

    setWeight(id, w) {
      const before = core.constraint(id)?.weight;
      core.setWeight(id, w);
      if (before !== undefined) undoEdit = () => core.setWeight(id, before);
      changedIds = [id];
      return true;
    },

    setStrength(id, s) {
      const before = core.constraint(id)?.strength;
      core.setStrength(id, s);
      if (before !== undefined) undoEdit = () => core.setStrength(id, before);
      changedIds = [id];
      return true;
    },

    // setBoundary, setGamma, setSymmetry, setCurvatureAlignment, applyDesign (setting-ops.js).
    ...settingEdits,

    fieldJson() {
      return core.fieldJson();
    },

    // The streamlines of field `forVersion` at `spacing` (web/streamlines.js, off the page's thread): Float32Array
    // polylines, transferred; null when the field has changed since the page asked (it asks again for the new one).
    // component: 'whole' (the field) or a part of its Hodge decomposition ('exact' | 'coexact' | 'harmonic'; see
    // `component`), whose vertex vectors are traced instead.
    streamlines(forVersion, spacing, lift, component = 'whole') {
      if (forVersion !== version) return null;
      const key = `${version} ${spacing} ${lift} ${component}`;
      if (tracing.key !== key) {
        const field = component === 'whole' ? { vertexVectors: core.vertexVectors(), faceVectors: core.faceVectors() } : parts.component(version, component);
        // An N-field's corners are matched to its face representatives before they are interpolated.
        const options = { spacing, lift, symmetry: core.symmetry(), faceVectors: field.faceVectors };
        tracing.lines = traceStreamlines(surfaceOf(), field.vertexVectors, options);
        tracing.key = key;
      }
      // Copies: the cached lines stay here for the next request at the same spacing.
      const lines = tracing.lines.map((l) => l.slice());
      return new Transfer(lines, lines.map((l) => l.buffer));
    },

    // The Hodge decomposition (Eq. 3) of field `forVersion` (field-parts.js): all of it, transferred; only the
    // shares ({energyShares, decomposeMs}: the Views panel's line); one part ('whole' | 'exact' | 'coexact' |
    // 'harmonic') as {oneForm, faceVectors, vertexVectors}, transferred. Each null when the field has changed.
    hodge(forVersion) {
      return forVersion === version ? transferOf(parts.hodgeReply(version)) : null;
    },

    hodgeShares(forVersion) {
      return forVersion === version ? parts.sharesReply(version) : null;
    },

    component(forVersion, name) {
      return forVersion === version ? transferOf(parts.componentReply(version, name)) : null;
    },

    // The texture atlas of a model (web/synthesis/atlas.js): its TEXCOORD_0 when usable, else one generated by
    // the core (LSCM charts, packing: up to seconds on a big model, so here rather than on the page's thread),
    // with its raster's corner data and seams (atlas-prepared.js). The model's arrays come from the page.
    textureAtlas(positions, triangles, cornerUVs, options) {
      const atlas = preparedAtlas(core.Module, { positions, triangles, cornerUVs }, options);
      return new Transfer(atlas, preparedBuffers(atlas));
    },

    // An exemplar's analysis for synthesis (spec as for analyzeExemplar): 0.1-0.5 s that the page does not wait on.
    analyzeExemplar(spec) {
      const tables = analyzeExemplar(core.Module, spec);
      return new Transfer(tables, exemplarBuffers(tables));
    },

    // What the core itself holds now, each read-out derived by the core (not the page's copies): the tests'
    // reference for the page's lazily derived and incrementally kept read-outs.
    read() {
      const value = {
        version,
        oneForm: core.oneForm(),
        faceVectors: core.faceVectors(),
        vertexVectors: core.vertexVectors(),
        singularities: core.singularities(),
        design: JSON.parse(core.designJson()),
      };
      return new Transfer(value, [value.oneForm.buffer, value.faceVectors.buffer, value.vertexVectors.buffer]);
    },

    // For the supervision tests: what a wasm trap (unreachable, an out-of-bounds access, an abort) looks like
    // to the worker; the core itself has none to offer on purpose.
    trapForTest() {
      throw new WebAssembly.RuntimeError('unreachable executed (test)');
    },

    // 0: the wasm address space left (default); a number: a fixed limit (tests scale it down instead of
    // building a multi-million-edge mesh).
    setFactorMemoryLimit: (bytes) => (core.setFactorMemoryLimit(bytes), true),

    // exportAtlasNote, exportFlowMap, exportGlb, exportRawField (core-export.js); readBytes (model-bytes.js).
    ...exportOps(() => coreExport, () => exportedField(), () => JSON.parse(core.designJson())),
    ...readOps(Transfer),
  };

  const NO_MESH_NEEDED = new Set(['init', 'warmUp', 'warmUpPreview', 'previewMesh', 'loadMesh', 'openPreview', 'setFactorMemoryLimit', 'trapForTest', 'textureAtlas', 'analyzeExemplar', 'readBytes']);
  // Ops after which the field may have changed: they solve and send a snapshot back.
  const MUTATING = new Set(['loadMesh', 'openPreview', 'add', 'remove', 'setWeight', 'setStrength', ...Object.keys(settingEdits)]);

  // A wasm trap or an abort (out of memory, an assertion) leaves the instance unusable: the page must replace
  // this worker rather than send it more work.
  function isFatal(err) {
    const text = `${err?.name ?? ''} ${err?.message ?? err}`;
    return err instanceof WebAssembly.RuntimeError ||
      /RuntimeError|Aborted\(|unreachable|memory access out of bounds|table index is out of bounds/.test(text);
  }

  scope.onmessage = async ({ data }) => {
    if (data.ping) return void scope.postMessage({ pong: true });
    if (data.previewMade) return void previewMade();
    // For the supervision tests: a worker that stops answering without a call in flight (an infinite loop in
    // a timer, a deadlock), for `ms` milliseconds.
    if (data.hangForTest) {
      const end = performance.now() + data.hangForTest;
      while (performance.now() < end);
      return;
    }
    const { seq, op } = data;
    let { args } = data;
    seqNow = seq;
    spares.take(data.spare);
    const t0 = performance.now();
    const timing = {};
    let reply, transfer = [];
    undoEdit = null;
    changedIds = null;
    try {
      if (!ops[op]) throw new CoreError(`unknown operation ${op}`);
      if (!NO_MESH_NEEDED.has(op)) requireMesh();
      const fineArgs = args;
      if (preview && MUTATING.has(op)) args = preview.argsOnCoarse(op, args);
      let out = await ops[op](...args);
      if (preview && MUTATING.has(op)) preview.afterOp(op, fineArgs, out instanceof Transfer ? out.value : out);
      if (out instanceof Transfer) {
        transfer = out.list;
        out = out.value;
      }
      const t1 = performance.now();
      timing.opMs = t1 - t0;
      if (MUTATING.has(op) && op !== 'loadMesh' && op !== 'openPreview') core.solve();
      timing.solveMs = performance.now() - t1;
      reply = { ok: true, value: out };
      if (MUTATING.has(op)) {
        reply.snapshot = preview ? preview.snapshot(spares, timing, data.wholeDesign ? null : changedIds) : snapshot(data.wholeDesign ? null : changedIds, timing);
        transfer = [...transfer, ...reply.snapshot.transfer];
      }
    } catch (err) {
      reply = { ok: false, error: err?.message || String(err), fatal: isFatal(err) };
      transfer = [];
      // An edit whose factor or solve failed is taken back, so the core never keeps a state it cannot solve.
      if (undoEdit && !reply.fatal) {
        try {
          undoEdit();
        } catch {
          // the snapshot below shows whatever the core holds
        }
      }
      // The page mirrors the core: after a failed edit it must still see what the core now holds (the whole
      // design, whatever the edit had got to).
      if (MUTATING.has(op) && core?.hasMesh && !reply.fatal) {
        try {
          if (op !== 'loadMesh') core.solve(); // a load is one transaction: the model it leaves is solved
          reply.snapshot = preview ? preview.snapshot(spares, timing) : snapshot(null);
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
    scope.postMessage(reply, transfer);
    // The update the solve went through (Designer::setDeferredUpdates) goes into the factor once the field has gone.
    if (!MUTATING.has(op) || !core?.hasMesh) return;
    const t = performance.now();
    core.applyDeferredUpdates();
    scope.postMessage({ deferredUpdate: { seq, ms: performance.now() - t } });
  };
}

serve(self);
