// One designer instance's state and behaviour: its core worker, the page's copies of what the core holds
// (mesh, field, design) and the page↔core constraint id mapping, the history of edits, the view, the tools
// and the panels. A <tangent-field-designer> element owns one Session; nothing here is shared between
// elements.
//
// The core runs in a module worker (core-worker.js); every edit is one request that ends with a solve and a
// snapshot of what changed (the field arrays, the stats, the touched constraints), which the session keeps
// so that reads stay synchronous. What no edit needs is derived when read or shown, once per field: the
// singularities on the page, the streamlines in the worker (on the page when read before the worker's arrive).
import { AddConstraint, RemoveConstraint, ReplaceDesign, SetParameter, SetSetting } from './commands.js';
import { CoreProxy } from './core-proxy.js';
import { AutosaveStore } from './autosave-store.js';
import { baseName, downloadBlob, downloadJson, modelKey, readJsonFile } from './documents.js';
import { setupExport } from './export/index.js';
import { captureScreenshot } from './screenshot.js';
import { History } from './history.js';
import { ACCEPT, readModel } from './model-files.js';
import { findSingularities } from './singularities.js';
import { traceStreamlines } from './streamlines.js';
import { magnitudeScale } from './colormap.js';
import { boundarySpec, gammaSpec, pointSpec, strokeSpec, vectorSpec } from './specs.js';
import { Surface } from './surface.js';
import { setupSynthesis } from './synthesis/index.js';
import { ToolController } from './tools.js';
import { setPivotAt } from './camera.js';
import { bindUi } from './ui.js';
import { Viewer } from './viewer.js';

// Weight 1e4 keeps strokes within ~0.4% of the drawn direction (paper, Sec. 6.1) while the rank-1 updates
// stay well conditioned.
export const DEFAULT_WEIGHT = 1e4;

const PROGRESS_LABELS = {
  loadMesh: 'Loading and factoring…',
  setBoundary: 'Refactoring…',
  setGamma: 'Refactoring…',
  applyDesign: 'Applying the design…',
  fieldJson: 'Exporting…',
  exportFlowMap: 'Exporting the flow map…',
  exportGlb: 'Exporting the GLB…',
};

function allFinite(values) {
  for (let i = 0; i < values.length; i++) if (!Number.isFinite(values[i])) return false;
  return true;
}

// Computed once per field (the autosave's last guard), before its arrays may go back to the worker.
function fieldIsFinite(field) {
  field.finite ??= allFinite(field.oneForm) && allFinite(field.faceVectors);
  return field.finite;
}

const nextTask = () => new Promise((resolve) => setTimeout(resolve, 0));

export class Session {
  #coreStartSettled;

  // host: the element (events are dispatched on it); root: its shadow root (markup already in place);
  // assetBase: URL of the folder with core-worker.js and wasm/; autosave: storage key or null (off);
  // bench: run the synthesis benchmark when the page asks for it (the app page only); onTool(name): the user
  // picked a tool.
  constructor({ host, root, assetBase, autosave = null, bench = false, onTool = () => {} }) {
    this.host = host;
    this.onTool = onTool;
    this.textureView = false; // the `texture` view is on: synthesize after every model load
    this.root = root;
    this.assetBase = assetBase;
    this.autosave = autosave;
    this.autosaveStore = null; // made on first use, for the current autosave name
    this.autosaveChain = Promise.resolve(); // saves run one after the other, in edit order
    this.autosaveError = null; // the last save's failure, shown until a save succeeds
    this.readonly = false;
    this.proxy = null;
    // Settles when start() has finished, whether the core came up or not (then `proxy` stays null).
    this.coreStarted = new Promise((resolve) => (this.#coreStartSettled = resolve));
    this.modelName = '';
    this.modelKey = '';
    this.modelSource = null; // {bytes, format}: what a restarted core reloads
    this.loadsPending = 0; // model loads asked for and not finished: tool input meanwhile is refused
    this.info = null;
    this.surface = null;
    // {version (the worker's), faceVectors, vertexVectors, oneForm, stats, singularities (null until derived)}
    // of the last completed change.
    this.field = null;
    this.retired = []; // fields replaced since the last refresh(), whose arrays go back to the worker
    // The core's document, kept in step from the constraints each edit touched (core-worker.js snapshot()).
    this.design = { boundary: 'free', gamma: 0, constraints: [] };
    this.specByCore = new Map(); // core id → spec (design format)
    this.coreOrder = []; // core ids in the core's order (that of design.constraints)
    this.constraints = new Map(); // uid → core id
    this.nextUid = 1;
    this.selected = null;
    this.fieldVersion = 0;
    this.streamlineCache = null; // {version, spacing, surface, lines, source: 'worker' | 'page'}
    this.shown = { singularities: -1, vertexField: -1 }; // the field versions those views were last given
    this.perf = {};
    this.meshSerial = 0;
    this.cornerUVs = null;
    this.disposed = false;
    // Every mutation runs alone and in call order: the worker's state and the session's copies move together.
    this.queue = Promise.resolve();
    this.lastConstraintsJson = '[]';
    this.savedDesignJson = null; // the design as last saved, loaded or found with the model (unsaved edits differ)

    const $ = (sel) => root.querySelector(sel);
    const container = $('#viewport');
    this.viewer = new Viewer(container);
    this.history = new History(() => this.ui && this.refreshHistory());
    this.ui = bindUi(root, host, this.#uiActions());
    this.tools = new ToolController(this, container, this.#toolActions());
    // Double-click (double-tap) on the model: orbit around that point from now on.
    this.viewer.canvas.addEventListener('dblclick', (e) => setPivotAt(this.viewer, e.clientX, e.clientY));
    this.views = this.ui.views();
    this.applyViews(this.views);
    // Texture synthesis (web/synthesis/, docs/texture-synthesis.md): its calls go onto the element.
    this.textureApi = {};
    this.synthesis = setupSynthesis(this.textureApi, {
      viewer: this.viewer,
      panel: $('#side-panel'),
      bench: bench ? host : null,
      onError: (err) => this.fail('texture', err),
      computeAtlas: async ({ positions, triangles, cornerUVs }, options) => {
        if (!this.proxy) throw new Error(this.disposed ? 'the designer was disposed' : 'the core is not running');
        const reply = await this.proxy.call('textureAtlas', [positions, triangles, cornerUVs ?? null, options], [], { background: true });
        return reply.value;
      },
      // An exemplar may be chosen before the core has started: the analysis waits for it.
      analyzeExemplar: async (spec) => {
        await this.coreStarted;
        if (!this.proxy) throw new Error(this.disposed ? 'the designer was disposed' : 'the core is not running');
        return (await this.proxy.call('analyzeExemplar', [spec], [], { background: true })).value;
      },
      getModel: () =>
        this.surface && this.field
          ? {
              key: `${this.modelKey}#${this.meshSerial}`,
              name: this.modelName,
              positions: this.surface.positions,
              triangles: this.surface.triangles,
              cornerUVs: this.cornerUVs,
              // A copy: synthesis and exports hold it across awaits, and the session's own array goes back to the
              // worker once a newer field replaces it (#recycleRetired).
              vertexVectors: this.field.vertexVectors.slice(),
              fieldVersion: this.fieldVersion,
            }
          : null,
    });
    // Flow map / GLB exports and the material preview (web/export/, docs/export.md).
    this.exports = setupExport({
      viewer: this.viewer,
      panel: $('#side-panel'),
      call: (op, args) =>
        this.exclusive(async () => {
          this.requireReady();
          return (await this.call(op, args)).value;
        }),
      modelName: () => baseName(this.modelName),
      onError: (err) => !this.disposed && this.ui.showError(err.message),
    });
  }

  // Starts the worker and the core. Rejects (and fires `error`, code 'core') when either fails.
  async start() {
    try {
      const proxy = await CoreProxy.start(this.assetBase, {
        onRestart: (reason) => this.#revive(reason),
        onStatus: (text) => this.ui.flash(text, 4000),
      });
      if (this.disposed) return proxy.terminate();
      this.proxy = proxy;
    } catch (err) {
      this.fail('core', err);
      throw err;
    } finally {
      this.#coreStartSettled();
    }
  }

  // Ends the worker and frees the WebGL contexts; the element is dead afterwards.
  dispose() {
    if (this.disposed) return;
    this.disposed = true;
    this.proxy?.terminate();
    // Saves still queued (the last edit's starts in the next task) are written before the store closes.
    const store = this.autosaveStore;
    if (store) this.autosaveChain.then(() => store.close());
    this.synthesis.dispose();
    this.exports.dispose();
    this.tools.dispose();
    this.ui.dispose();
    this.viewer.dispose();
  }

  // ------------------------------------------------------------------------------------------ events

  emit(type, detail) {
    if (this.disposed) return;
    this.host.dispatchEvent(new CustomEvent(type, { detail, bubbles: true, composed: true }));
  }

  // A failure the user did not ask to handle (a model, design, texture or core start): `error` event and
  // the banner. Returns the Error.
  fail(code, err) {
    const error = err instanceof Error ? err : new Error(String(err));
    this.emit('error', { code, message: error.message });
    this.ui.showError(error.message);
    return error;
  }

  #emitChanges() {
    this.emit('fieldchange', { version: this.fieldVersion, stats: structuredClone(this.field.stats) });
    const constraints = this.constraintList();
    const json = JSON.stringify(constraints);
    if (json !== this.lastConstraintsJson) {
      this.lastConstraintsJson = json;
      this.emit('constraintschange', { constraints });
    }
  }

  // ------------------------------------------------------------------------------------------ core calls

  exclusive(fn) {
    const run = this.queue.then(fn);
    this.queue = run.catch(() => {});
    return run;
  }

  requireReady() {
    if (this.disposed) throw new Error('the designer was disposed');
    if (!this.proxy || !this.info || !this.field) throw new Error('the designer is not ready yet; await its ready promise first');
  }

  // One request to the worker; the snapshot it returns (also with a failure) becomes the session's state.
  async call(op, args = [], transfer = []) {
    if (!this.proxy) throw new Error(this.disposed ? 'the designer was disposed' : 'the core is not running');
    const phase = PROGRESS_LABELS[op] ?? 'Updating…';
    const end = this.ui.startProgress(phase);
    this.emit('progress', { phase: op, fraction: 0 });
    const t0 = performance.now();
    const renders0 = this.viewer.renderCount;
    try {
      const reply = await this.proxy.call(op, args, transfer);
      const t1 = performance.now();
      // Frames the page drew while the worker computed: the page never waits for the core.
      this.perf.lastOp = {
        op,
        workerMs: reply.workerMs,
        workerParts: reply.timing,
        roundTripMs: t1 - t0,
        sentAt: t0,
        receivedAt: t1,
        framesDrawnMeanwhile: this.viewer.renderCount - renders0,
      };
      if (reply.snapshot) this.#applySnapshot(reply.snapshot);
      this.perf.lastOp.applyMs = performance.now() - t1;
      return reply;
    } catch (err) {
      if (err.reply?.snapshot) this.#applySnapshot(err.reply.snapshot);
      throw err;
    } finally {
      end();
      this.emit('progress', { phase: op, fraction: 1 });
    }
  }

  #applySnapshot(snap) {
    const { version, faceVectors, vertexVectors, oneForm, stats, design } = snap;
    if (this.field) this.retired.push(this.field);
    this.field = { version, faceVectors, vertexVectors, oneForm, stats, singularities: null };
    this.fieldVersion++;
    this.#applyDesign(design);
    for (const [uid, coreId] of this.constraints) if (!this.specByCore.has(coreId)) this.constraints.delete(uid);
    if (this.selected != null && !this.constraints.has(this.selected)) this.selected = null;
  }

  // The worker sends the whole document after loads, settings, designs and failed edits; after a constraint
  // edit only the entries it touched and the id order.
  #applyDesign({ ids, document, changed }) {
    if (document) {
      this.design = document;
      this.specByCore = new Map(ids.map((id, k) => [id, document.constraints[k]]));
    } else {
      for (const [id, spec] of changed) this.specByCore.set(id, spec);
      const missing = ids.find((id) => !this.specByCore.has(id));
      if (missing !== undefined) throw new Error(`internal error: the core has constraint ${missing}, which the page never saw`);
      this.specByCore = new Map(ids.map((id) => [id, this.specByCore.get(id)]));
      this.design = { ...this.design, constraints: ids.map((id) => this.specByCore.get(id)) };
    }
    this.coreOrder = ids;
  }

  // ------------------------------------------------------------------------------------------ id mapping

  // Core constraints no page id points at (a loaded design, an autosave) get fresh ids in the core's order.
  adoptUnmapped() {
    const mapped = new Set(this.constraints.values());
    for (const coreId of this.coreOrder) if (!mapped.has(coreId)) this.constraints.set(this.nextUid++, coreId);
  }

  // After a document replaced the core's list: give its constraints the page ids `uids` (same order).
  mapDocument(uids) {
    this.constraints.clear();
    const ids = this.coreOrder;
    if (uids && uids.length === ids.length) uids.forEach((uid, k) => this.constraints.set(uid, ids[k]));
    this.adoptUnmapped();
  }

  uidsInCoreOrder() {
    const byCore = new Map([...this.constraints].map(([uid, coreId]) => [coreId, uid]));
    return this.coreOrder.map((id) => byCore.get(id));
  }

  coreIdOf(uid) {
    const coreId = this.constraints.get(Number(uid));
    if (coreId === undefined) throw new Error(`no constraint with id ${uid}`);
    return coreId;
  }

  specOf(uid) {
    return this.specByCore.get(this.coreIdOf(uid));
  }

  constraintList() {
    return [...this.constraints.keys()].sort((a, b) => a - b).map((uid) => ({ id: uid, ...structuredClone(this.specOf(uid)) }));
  }

  settings() {
    return { boundary: this.design.boundary ?? 'free', gamma: this.design.gamma ?? 0 };
  }

  // ------------------------------------------------------------------------------------------ drawing

  #streamlineSpacing() {
    return this.surface.radius * (0.01 + 0.008 * (this.views?.streamlineSpacing ?? 5));
  }

  #streamlineLift() {
    return 0.03 * this.surface.meanEdge;
  }

  // Cached per field version and spacing; the view and streamlines() share them. The view has them traced in
  // the worker (#scheduleStreamlines); a read before those arrive traces here, with the same code and field.
  currentStreamlines() {
    const spacing = this.#streamlineSpacing();
    const c = this.streamlineCache;
    if (c && c.version === this.fieldVersion && c.spacing === spacing && c.surface === this.surface) return c.lines;
    const lines = this.traceStreamlinesHere();
    this.streamlineCache = { version: this.fieldVersion, spacing, surface: this.surface, lines, source: 'page' };
    return lines;
  }

  // Traces on the page, now, whatever the cache holds.
  traceStreamlinesHere() {
    const t0 = performance.now();
    const lines = traceStreamlines(this.surface, this.field.vertexVectors, { spacing: this.#streamlineSpacing(), lift: this.#streamlineLift() });
    this.perf.streamlines = { ms: performance.now() - t0, source: 'page', fieldVersion: this.fieldVersion };
    return lines;
  }

  // The streamlines view asks the worker for the lines of the field it shows; they are drawn when they come
  // (after the frame with the arrows), unless the field, the spacing or the view changed meanwhile.
  #scheduleStreamlines() {
    if (!this.views.streamlines) {
      this.viewer.streamlines.setLines([]);
      return;
    }
    const spacing = this.#streamlineSpacing(), surface = this.surface, fieldVersion = this.fieldVersion;
    const c = this.streamlineCache;
    const current = () =>
      !this.disposed && this.views.streamlines && this.fieldVersion === fieldVersion && this.surface === surface && this.#streamlineSpacing() === spacing;
    if (c && c.version === fieldVersion && c.spacing === spacing && c.surface === surface) {
      this.viewer.streamlines.setLines(c.lines);
      return;
    }
    const t0 = performance.now();
    this.proxy
      ?.call('streamlines', [this.field.version, spacing, this.#streamlineLift()], [], { background: true })
      .then(({ value: lines, workerMs }) => {
        if (!lines || !current()) return;
        this.streamlineCache = { version: fieldVersion, spacing, surface, lines, source: 'worker' };
        this.perf.streamlines = { ms: performance.now() - t0, workerMs, source: 'worker', fieldVersion };
        this.viewer.streamlines.setLines(lines);
        this.viewer.requestRender();
      })
      .catch(() => {}); // a restarted worker: the refresh after the restart asks again
  }

  // Derived on first read, once per field: no edit waits for them.
  currentSingularities() {
    this.field.singularities ??= findSingularities(this.surface, this.field.faceVectors);
    return this.field.singularities;
  }

  // One magnitude scale per field for the arrows, the surface colours and the legend.
  #fieldScale() {
    this.field.scale ??= magnitudeScale(this.field.vertexVectors);
    return this.field.scale;
  }

  // The views that are on get the current field, once per field version; the others get nothing.
  #showDerived() {
    const { viewer, views, shown } = this;
    if (views.singularities && shown.singularities !== this.fieldVersion) {
      viewer.singularities.setSingularities(this.currentSingularities());
      shown.singularities = this.fieldVersion;
    }
    if ((views.colorMap || views.lic) && shown.vertexField !== this.fieldVersion) {
      viewer.setVertexField(this.field.vertexVectors, this.#fieldScale());
      shown.vertexField = this.fieldVersion;
    }
    this.ui.setLegend(this.#legendShown() ? this.#fieldScale().top : null);
  }

  // Pushes the current field, constraints and settings to the view and the panels; draws synchronously.
  refresh() {
    const { viewer, ui, field } = this;
    const t0 = performance.now();
    viewer.arrows.setField(field.faceVectors, field.vertexVectors, this.#fieldScale());
    this.#showDerived();
    viewer.handles.setConstraints([...this.constraints.keys()].map((uid) => ({ uid, spec: this.specOf(uid) })));
    viewer.handles.setSelected(this.selected);
    ui.setConstraints(this.constraintList(), this.selected);
    ui.setSettings(this.settings());
    ui.setStatus({ name: this.modelName, info: this.info, stats: field.stats });
    this.refreshHistory();
    const t1 = performance.now();
    viewer.renderNow();
    this.perf.refresh = { updateViewsMs: t1 - t0, renderMs: performance.now() - t1 };
    this.#scheduleStreamlines();
    this.synthesis.fieldChanged(); // texture synthesis: resynthesize when the field changed (no-op otherwise)
    this.#recycleRetired();
  }

  // The arrays of fields a newer one replaced go back to the worker, which refills them for the next field
  // instead of allocating (core-worker.js). Only the session holds them by then: the views were handed the
  // current field's arrays above and keep nothing else of a field but what they made of it (GPU buffers,
  // samples), the read API and getModel() hand out copies, and an autosave still to run has its finiteness
  // check done here first.
  #recycleRetired() {
    for (const field of this.retired) {
      if (field.autosavePending) fieldIsFinite(field);
      this.proxy?.recycle([field.faceVectors, field.vertexVectors, field.oneForm]);
    }
    this.retired = [];
  }

  refreshHistory() {
    const h = this.history;
    this.ui.setHistory({
      canUndo: !!h.peekUndo(),
      canRedo: !!h.peekRedo(),
      undoLabel: h.peekUndo()?.label ?? '',
      redoLabel: h.peekRedo()?.label ?? '',
    });
  }

  applyViews(views) {
    this.views = { ...this.views, ...views };
    const v = this.views, viewer = this.viewer;
    viewer.arrows.setOptions({ visible: v.arrows, density: v.arrowDensity, scaled: v.arrowsScaled });
    // The views turned on get the current field first (the markers are built when the view shows).
    if (this.field) this.#showDerived();
    viewer.setColorMap(v.colorMap);
    viewer.singularities.setVisible(v.singularities);
    viewer.lic.setVisible(v.lic);
    if (this.field) this.#scheduleStreamlines();
    viewer.requestRender();
  }

  // Arrows and the surface map share one magnitude scale (viridis, top at the 98th percentile): one legend.
  #legendShown() {
    return this.views.colorMap || this.views.arrows;
  }

  setViews(views) {
    this.ui.setViews(views);
    this.applyViews(this.ui.views());
    return { ...this.views };
  }

  select(uid) {
    this.selected = uid != null && this.constraints.has(Number(uid)) ? Number(uid) : null;
    this.viewer.handles.setSelected(this.selected);
    this.ui.setConstraints(this.constraintList(), this.selected);
    this.viewer.requestRender();
  }

  // After every completed change: redraw, keep the autosave (when on) in step with the core, tell listeners.
  #afterEdit() {
    this.adoptUnmapped();
    this.ui.clearError();
    this.refresh();
    this.#autosaveNow();
    this.#emitChanges();
    this.exports.fieldChanged();
  }

  // ------------------------------------------------------------------------------------------ autosave

  #store() {
    if (this.autosave == null) return null;
    if (this.autosaveStore?.name !== this.autosave) {
      this.autosaveStore?.close();
      this.autosaveStore = new AutosaveStore(this.autosave, { onOtherTab: (key) => this.#otherTab(key) });
    }
    return this.autosaveStore;
  }

  // A non-finite field is never saved (the core refuses to make one; this is the last guard). A failed save
  // is shown, and stays shown until a save succeeds, so nobody believes unsaved work is safe.
  // The save's own work (the finiteness scan, the localStorage mirror, IndexedDB) starts in the next task, so an
  // edit's promise resolves with the new field drawn without waiting for it; the state saved is this edit's.
  #autosaveNow() {
    const store = this.#store();
    if (!store || !this.modelKey) return;
    const key = this.modelKey, design = structuredClone(this.design), field = this.field;
    field.autosavePending = true;
    this.autosaveChain = this.autosaveChain.then(nextTask).then(() => {
      field.autosavePending = false;
      if (!fieldIsFinite(field)) {
        if (!this.disposed) this.ui.showError('The field is not finite; this state was not autosaved.');
        return undefined;
      }
      return store.save(key, design).then(
        () => {
          this.perf.lastAutosave = { savedAt: Date.now(), constraints: design.constraints.length };
          if (this.autosaveError && !this.disposed) this.ui.flash('Autosave works again; the design is saved.', 4000);
          this.autosaveError = null;
        },
        (err) => {
          this.autosaveError = err.message || String(err);
          this.fail('autosave', new Error(`Autosave failed (${this.autosaveError}): the latest edits are not saved in this browser; use Save to download the design.`));
        },
      );
    });
  }

  #otherTab(key) {
    if (key !== this.modelKey || this.otherTabNoticed === key) return;
    this.otherTabNoticed = key;
    this.ui.flash('This model is being edited in another tab too: both designs are kept as autosave versions.', 8000);
    this.emit('autosaveconflict', { model: this.modelName });
  }

  // Resolves when every autosave asked for so far has been written (or has failed and been reported).
  autosaveIdle() {
    return this.autosaveChain;
  }

  async autosaveVersions() {
    const store = this.#store();
    if (!store || !this.modelKey) return [];
    return store.versions(this.modelKey);
  }

  // Replaces the design with an autosaved version (undoable like loading a design).
  async restoreAutosave(id) {
    const record = await this.#store()?.version(id);
    if (!record || !record.key.endsWith(`|${this.modelKey}`)) throw new Error(`no autosaved version ${id} of this model`);
    return this.replaceDesign(record.design, 'restore autosave');
  }

  // ------------------------------------------------------------------------------------------ models

  // opts: {name, format, companions, restore}. The autosaved design is restored only when autosave is on.
  loadModel(src, opts = {}) {
    this.loadsPending++;
    return this.exclusive(async () => {
      if (!this.proxy) throw new Error(this.disposed ? 'the designer was disposed' : 'the core is not running');
      let model;
      try {
        model = await readModel(src, opts);
      } catch (err) {
        throw this.fail('model', new Error(`Could not load model: ${err.message}`));
      }
      const key = modelKey(model.name, model.bytes);
      const store = opts.restore === false ? null : this.#store();
      const saved = store ? await store.load(key) : null;
      const bytes = model.bytes.slice(); // its own buffer, transferred to the worker
      const source = { bytes: model.bytes, format: model.format };
      let reply;
      try {
        reply = await this.call('loadMesh', [bytes, model.format, this.settings(), saved?.design ?? null], [bytes.buffer]);
      } catch (err) {
        // The core kept its previous mesh and everything on it.
        if (this.info) this.refresh();
        throw this.fail('model', new Error(`Could not load ${model.name}: ${err.message.replace(/^load: /, '')}`));
      }
      const tApply = performance.now();
      this.ui.clearError();
      const { info, settingsError, restoreError, embeddedDesign } = reply.value;
      const { positions, triangles, edges, cornerUVs } = reply.value.mesh;
      this.surface = new Surface(positions, triangles, edges);
      this.info = info;
      this.modelName = model.name;
      this.modelKey = key;
      this.modelSource = source;
      this.selected = null;
      this.streamlineCache = null;
      this.constraints.clear();
      this.nextUid = 1; // constraint numbers restart with every model
      this.mapDocument(null);
      this.markSaved();
      this.history.clear();
      this.viewer.setMesh(this.surface);
      // Texture synthesis: the model's UVs (6 per face, or none) and a fresh atlas for the new mesh.
      this.cornerUVs = cornerUVs.length ? cornerUVs : null;
      this.meshSerial++;
      this.synthesis.modelChanged();
      this.ui.setHasBoundary(info.boundaryLoops > 0);
      this.refresh();
      // Main-thread cost of taking a new mesh on (adjacency, BVH, buffers, first draw): the one pause left.
      this.perf.meshSetupMs = performance.now() - tApply;
      const restored = saved?.design ? 'autosaved' : 'embedded';
      if (restoreError) this.ui.flash(`The ${restored} design could not be restored: ${restoreError}`, 6000);
      else if ((saved?.design || embeddedDesign) && this.constraints.size) {
        this.ui.flash(`Restored the ${restored} design (${this.constraints.size} constraints).`);
      }
      if (settingsError) this.ui.showError(`The boundary/γ settings did not apply to ${model.name}: ${settingsError}`);
      this.emit('load', { info: structuredClone(info) });
      this.#emitChanges();
      this.exports.fieldChanged();
      if (!this.warmedUp) {
        this.warmedUp = true;
        // After the first frame, not before: on the small default model warming up costs more than it saves
        // (measured: ~0.3 s to save ~35 ms), but the next, larger model the user opens gets optimized code.
        setTimeout(() => this.exclusive(() => this.proxy?.call('warmUp', [3, 2])).catch(() => {}), 0);
      }
      return structuredClone(info);
    }).finally(() => this.loadsPending--);
  }

  // ------------------------------------------------------------------------------------------ supervision

  // The proxy replaced a dead, trapped or cancelled worker: the current model and design go to the new one,
  // the page ids are mapped onto the new core ids (the history stays valid), and the user is told.
  async #revive({ kind, detail, call }) {
    const t0 = performance.now();
    if (!this.modelSource || this.disposed) return;
    const uids = this.uidsInCoreOrder();
    const bytes = this.modelSource.bytes.slice();
    const reply = await call('loadMesh', [bytes, this.modelSource.format, this.settings(), this.design], [bytes.buffer]);
    this.#applySnapshot(reply.snapshot);
    this.mapDocument(uids);
    this.refresh();
    this.perf.lastRestart = { kind, detail, restoreMs: performance.now() - t0, constraints: this.constraints.size };
    this.emit('corerestart', { kind, detail });
    this.ui.flash(
      kind === 'cancelled'
        ? 'Cancelled. The design is as it was before.'
        : `The core stopped (${detail}) and was restarted; your model and design are back.`,
      6000,
    );
  }

  cancel() {
    return this.proxy?.cancel() ?? false;
  }

  supervision() {
    return { restarts: this.proxy?.restarts ?? 0, lastFailure: structuredClone(this.proxy?.lastFailure ?? null) };
  }

  // Tool input is bound to the model it was made on: while a load is pending it is refused, and an edit that
  // reaches the core after the model changed is dropped rather than applied to the new model.
  #boundToModel() {
    if (this.loadsPending > 0) {
      this.ui.flash('A model is loading: the edit was not applied.', 3000);
      return null;
    }
    return this.meshSerial;
  }

  // ------------------------------------------------------------------------------------------ edits

  // Runs the command made by makeCommand() (inside the queue, once the session is ready) and records it.
  run(makeCommand) {
    return this.exclusive(async () => {
      this.requireReady();
      const command = makeCommand();
      try {
        await this.history.execute(command, this);
      } catch (err) {
        this.ui.setSettings(this.settings()); // shows what the core holds, also after a refusal
        throw err;
      }
      this.#afterEdit();
      return command.result;
    });
  }

  // meshSerial: the model the edit was made on (tool input); undefined for API calls.
  addConstraint(makeSpec, meshSerial = undefined) {
    return this.run(() => {
      if (meshSerial !== undefined && meshSerial !== this.meshSerial)
        throw new Error('the model changed before this edit reached the core; it was not applied');
      return new AddConstraint(makeSpec());
    });
  }

  remove(uid) {
    return this.run(() => new RemoveConstraint(this, uid));
  }

  setParameter(kind, uid, value) {
    return this.run(() => new SetParameter(this, kind, uid, value));
  }

  // kind: 'boundary' | 'gamma'.
  setSetting(kind, value) {
    return this.run(() => new SetSetting(this, kind, kind === 'boundary' ? boundarySpec(value) : gammaSpec(value)));
  }

  // ignoreFingerprint: apply a design saved for another mesh anyway (its indices taken as they are).
  replaceDesign(design, label, { ignoreFingerprint = false } = {}) {
    return this.run(() => {
      if (!design || typeof design !== 'object' || Array.isArray(design)) throw new Error('a design must be a JSON object');
      if (ignoreFingerprint) {
        design = { ...design };
        delete design.mesh;
      }
      return new ReplaceDesign(this, design, label);
    });
  }

  // ------------------------------------------------------------------------------------------ unsaved edits

  #designKey() {
    const { boundary, gamma, constraints } = this.design;
    return JSON.stringify({ boundary, gamma, constraints });
  }

  markSaved() {
    this.savedDesignJson = this.#designKey();
  }

  // Edits since the design was last saved, loaded or opened with its model (undoing back to it counts as none).
  hasUnsavedEdits() {
    return !!this.field && this.savedDesignJson !== this.#designKey();
  }

  // Asks before a UI action would discard unsaved edits; true to go ahead.
  async #mayDiscard(what) {
    if (!this.hasUnsavedEdits()) return true;
    const n = this.constraints.size;
    return this.ui.confirm(
      `${what} replaces the current design (${n} constraint${n === 1 ? '' : 's'}), which has unsaved edits. Save it first with Save (Ctrl+S), or go ahead.`,
      `${what} anyway`,
    );
  }

  // A design file picked or dropped by the user: refused with the reason (the design untouched); a design
  // for another mesh can be applied after an explicit choice, undoably.
  async #loadDesignFile(file) {
    let design;
    try {
      design = await readJsonFile(file);
    } catch (err) {
      throw this.fail('design', new Error(`Could not load ${file.name}: ${err.message}`));
    }
    const apply = (ignoreFingerprint) =>
      this.replaceDesign(design, 'load design', { ignoreFingerprint }).then(() => {
        this.markSaved();
        this.ui.flash(`Loaded ${file.name} (${this.constraints.size} constraints). Undo (Ctrl+Z) brings the previous design back.`, 5000);
      });
    try {
      await apply(false);
    } catch (err) {
      const message = `Could not load ${file.name}: ${err.message}`;
      this.emit('error', { code: 'design', message });
      if (!/another mesh/.test(err.message)) return this.ui.showError(message);
      this.ui.showError(message, { label: 'Apply anyway', run: () => this.#report(apply(true)) });
    }
  }

  step(forward) {
    return this.exclusive(async () => {
      this.requireReady();
      let done;
      try {
        done = forward ? await this.history.redo(this) : await this.history.undo(this);
      } finally {
        if (this.selected != null && !this.constraints.has(this.selected)) this.selected = null;
      }
      if (done) this.#afterEdit();
      return done;
    });
  }

  exportField() {
    return this.exclusive(async () => {
      this.requireReady();
      return (await this.call('fieldJson')).value;
    });
  }

  // ------------------------------------------------------------------------------------------ UI wiring

  // Surfaces any failure of a UI-started action in the banner; the API variants reject instead. The panels
  // are redrawn from the state so an input the core refused shows the value in force again.
  #report(promise) {
    return promise.catch((err) => {
      if (this.disposed) return;
      this.ui.showError(err.message);
      if (this.field && this.surface) this.refresh();
    });
  }

  // Time from a user action to the frame that shows its result (reported through perf()).
  async #timed(name, t0, promise) {
    const result = await promise;
    // refresh() has drawn synchronously; the next animation frame puts it on screen.
    const shown = await new Promise((resolve) => requestAnimationFrame(() => resolve(performance.now())));
    const op = this.perf.lastOp ?? {};
    this.perf[name] = {
      toFrameMs: shown - t0,
      workerMs: op.workerMs,
      workerParts: op.workerParts,
      roundTripMs: op.roundTripMs,
      refresh: this.perf.refresh,
    };
    return result;
  }

  #edit(name, promise) {
    return this.#report(this.#timed(name, performance.now(), promise));
  }

  // The tool options, or null (with the reason in the banner) when a box holds an invalid number.
  #toolOptions() {
    try {
      return this.ui.toolOptions();
    } catch (err) {
      this.ui.showError(err.message);
      return null;
    }
  }

  // The mouse tools' results, as constraints (never in readonly mode: the tools stay on orbit/select).
  #toolActions() {
    return {
      flash: (text, ms) => this.ui.flash(text, ms),
      onStroke: (points) => {
        const serial = this.#boundToModel();
        if (serial === null) return void this.viewer.clearStroke();
        const options = this.#toolOptions();
        if (!options) return this.viewer.clearStroke();
        const { strength, weight } = options;
        this.#edit('stroke', this.addConstraint(() => strokeSpec(this, points, { strength, weight }), serial)).finally(() => {
          if (!this.tools.tools.stroke.drawing) this.viewer.clearStroke();
        });
      },
      onVector: (face, vector) => {
        const serial = this.#boundToModel();
        if (serial === null) return;
        const options = this.#toolOptions();
        if (options) this.#edit('vector', this.addConstraint(() => vectorSpec(this, face, vector, { weight: options.weight }), serial));
      },
      onPlace: (kind, hit) => {
        const serial = this.#boundToModel();
        if (serial === null) return;
        const options = this.#toolOptions();
        if (!options) return;
        const { strength, orientation } = options;
        const spec =
          kind === 'vortex'
            ? () => pointSpec(this, 'vortex', hit.face, orientation === 'cw' ? -strength : strength)
            : () => pointSpec(this, kind, this.surface.nearestCorner(hit.face, hit.point), strength);
        this.#edit(kind, this.addConstraint(spec, serial));
      },
      onSelect: (uid) => this.select(uid),
    };
  }

  #uiActions() {
    const editable = (fn) => (...args) => (this.readonly ? undefined : fn(...args));
    return {
      accept: ACCEPT,
      onOpen: async (file, companions) => {
        if (await this.#mayDiscard('Opening a model')) this.#report(this.loadModel(file, { companions }));
      },
      onLoadDesign: editable(async (file) => {
        if (await this.#mayDiscard('Loading a design')) this.#report(this.#loadDesignFile(file));
      }),
      onSaveDesign: () => {
        try {
          this.requireReady();
          const name = `${baseName(this.modelName)}.design.json`;
          downloadJson(name, JSON.stringify(this.design, null, 1));
          this.markSaved();
          this.ui.flash(`Saved ${name} (${this.constraints.size} constraint${this.constraints.size === 1 ? '' : 's'}).`, 4000);
        } catch (err) {
          this.ui.showError(err.message);
        }
      },
      onExportField: () => this.#report(this.exportField().then((text) => downloadJson(`${baseName(this.modelName)}.field.json`, text))),
      onTool: (tool) => {
        this.tools?.setTool(tool); // bindUi selects orbit before the tools exist
        this.onTool(tool);
      },
      onUndo: editable(() => this.#edit('undo', this.step(false))),
      onRedo: editable(() => this.#edit('redo', this.step(true))),
      onBoundary: editable((bc) => this.#report(this.setSetting('boundary', bc))),
      onGamma: editable((g) => this.#report(this.setSetting('gamma', g))),
      onViews: (views) => {
        this.applyViews(views);
      },
      onSelect: (uid) => this.select(uid),
      onFrame: (view) => this.viewer.frame(view),
      onScreenshot: () => {
        const c = this.viewer.canvas;
        const size = { width: Math.min(8192, 2 * c.clientWidth), height: Math.min(8192, 2 * c.clientHeight) };
        this.#report(captureScreenshot(this.viewer, size).then((blob) => downloadBlob(`${baseName(this.modelName)}.png`, blob)));
      },
      // The first-run hint is remembered with the autosave (the app page), shown every time elsewhere.
      hintKey: this.autosave != null ? 'tvf-hint-seen' : null,
      onRemove: editable((uid) => this.#edit('delete', this.remove(uid))),
      onEditWeight: editable((uid, w) => this.#report(this.setParameter('weight', uid, w))),
      onEditStrength: editable((uid, s) => this.#report(this.setParameter('strength', uid, s))),
      onCancel: () => this.cancel(),
      onClear: editable(() => this.constraints.size && this.#report(this.replaceDesign({ ...this.settings(), constraints: [] }, 'clear'))),
    };
  }
}
