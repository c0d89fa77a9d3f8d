// One designer's model: its core (a worker, core/), the page's copies of what the core holds (mesh, field,
// design mirror with page ids), the history of edits, the autosave and the model files. A
// <tangent-field-designer> element owns one Session; nothing here is shared between elements.
//
// The session imports nothing of the element, its panels, views or tools: it emits change signals
// (emitter.js) and the element subscribes them. Every edit is a command object (commands/) run by execute(),
// one at a time in call order: the session sends the one request the command names to the worker, which solves
// and replies with a snapshot of what changed (field arrays, stats, the touched constraints); that becomes the
// session's state (the field a DerivedField, derived-field.js), so reads stay synchronous, and the command,
// once it took, goes onto the history as a record.
//
// Signals: 'change' (new field or design: redraw), 'model' (a new mesh: before its 'change'), 'surface' {surface,
// ready} (a big model's Surface, ahead of its 'model': the views may take it on, setting `ready` to a promise
// the adoption waits for; the load may yet fail), 'selection',
// 'history', 'settings' (after a refused edit), 'busy' {op, done} or {op, phase} (a label naming the op's phase
// now), 'flash' {text, ms}, 'banner' {message, action}, 'banner-clear', and the element's public events: 'error'
// {code, message}, 'load', 'fieldchange', 'constraintschange', 'corerestart', 'autosaveconflict'.
import {
  AddConstraint,
  RemoveConstraint,
  ReplaceDesign,
  SetParameter,
  SetSetting,
  SetSymmetry,
} from './commands/index.js';
import { Autosave } from './autosave.js';
import { ConstraintTable, sameConstraints } from './constraint-table.js';
import { DerivedField } from './derived-field.js';
import { Emitter } from './emitter.js';
import { FieldTopology } from './field-topology.js';
import { History } from './history.js';
import { ModelLoader } from './model-loader.js';
import { CoreProxy } from '../core/core-proxy.js';
import { ProgressiveCore } from '../core/progressive-core.js';
import { awaitExact, exactFailed, exactLanded, revive } from './core-follow.js';

// Weight 1e4 keeps strokes within ~0.4% of the drawn direction (paper, Sec. 6.1) while the rank-1 updates
// stay well conditioned.
export const DEFAULT_WEIGHT = 1e4;
const NOTICE_MS = 6000; // a command's notice (what a new symmetry took with it) stays that long

export class Session extends Emitter {
  #coreStartSettled;
  #core = null;

  // assetBase: URL of the folder with core-worker.js and wasm/; autosave: storage key or null (off).
  constructor({ assetBase, autosave = null }) {
    super();
    this.assetBase = assetBase;
    this.readonly = false;
    this.proxy = null;
    // Settles when start() has finished, whether the core came up or not (then `proxy` stays null).
    this.coreStarted = new Promise((resolve) => (this.#coreStartSettled = resolve));
    this.modelName = '';
    this.modelKey = '';
    this.modelSource = null; // {bytes, format}: what a restarted core reloads
    this.info = null;
    this.surface = null;
    this.cornerUVs = null;
    this.meshSerial = 0;
    // The field of the last completed change, with what is derived from it (derived-field.js).
    this.field = null;
    this.fieldVersion = 0;
    this.retired = []; // fields replaced since the last 'change', whose arrays go back to the worker
    this.table = new ConstraintTable();
    this.selected = null;
    this.history = new History(() => this.emit('history'));
    this.autosave = new Autosave(this, autosave);
    this.models = new ModelLoader(this);
    this.topology = new FieldTopology(this); // prescribed singularities and sharp features
    this.perf = {};
    this.disposed = false;
    // Every mutation runs alone and in call order: the worker's state and the session's copies move together.
    this.queue = Promise.resolve();
    this.lastConstraints = []; // the constraints as the last constraintschange had them (table.views())
    this.savedDesignJson = null; // the design as last saved, loaded or found with the model
  }

  // The proxy, with a preview core beside it on big models (core/progressive-core.js); null before start().
  get core() {
    if (this.proxy && this.#core?.exact !== this.proxy) {
      this.#core = new ProgressiveCore(this.proxy, {
        assetBase: this.assetBase,
        onExact: (snapshot, reply) => exactLanded(this, snapshot, reply),
        onExactError: (err, op, caughtUp) => exactFailed(this, err, op, caughtUp),
      });
    }
    return this.#core;
  }

  get design() {
    return this.table.design;
  }

  // Before the first model, settings wait in the design and go in with the mesh.
  set design(design) {
    this.table.design = design;
  }

  // Starts the worker and the core. Rejects (and signals `error`, code 'core') when either fails.
  async start() {
    try {
      const proxy = await CoreProxy.start(this.assetBase, {
        onRestart: (reason) => revive(this, reason),
        onStatus: (text) => this.flash(text, 4000),
        onDeferredUpdate: (update) => (this.perf.deferredUpdate = update), // the factor's, after an edit's field
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

  // Ends the worker; the session is dead afterwards.
  dispose() {
    if (this.disposed) return;
    this.disposed = true;
    this.#core?.terminate();
    this.proxy?.terminate();
    this.autosave.close();
    this.clearListeners();
  }

  // ------------------------------------------------------------------------------------------ signals

  flash(text, ms) {
    this.emit('flash', { text, ms });
  }

  // A failure the user did not ask to handle (a model, design, texture or core start): `error` signal (the
  // element's event and banner). Returns the Error.
  fail(code, err) {
    const error = err instanceof Error ? err : new Error(String(err));
    this.emit('error', { code, message: error.message });
    return error;
  }

  emitChanges() {
    this.emit('fieldchange', { version: this.fieldVersion, stats: structuredClone(this.field.stats) });
    const views = this.table.views();
    if (sameConstraints(views, this.lastConstraints)) return;
    this.lastConstraints = views;
    let copies = null; // made for a listener that reads them, of the list as it was here
    this.emit('constraintschange', { get constraints() { return (copies ??= structuredClone(views)); } });
  }

  // The field and design changed (or must be shown again): listeners redraw synchronously; afterwards the
  // replaced fields' arrays go back to the worker, which refills them instead of allocating (the views keep
  // nothing of a field but what they made of it; the read API hands out copies).
  // The exact field landing behind its preview is drawn at once too: a draw issued while the GPU process still
  // rasterizes the preview's frame does not wait for it (the strokes' long tasks in a profile of a million
  // triangles in software GL were garbage collections, not this draw), and waiting for the next frame held the
  // exact field back by a whole frame of that rasterization (1.96 s against 0.38–0.52 s to its draw,
  // bench:web).
  changed() {
    this.emit('change');
    for (const field of this.retired) {
      if (field.autosavePending) this.autosave.checkFinite(field);
      this.core?.recycle([field.faceVectors, field.vertexVectors, field.oneForm], field.stats?.preview);
    }
    this.retired = [];
  }

  // ------------------------------------------------------------------------------------------ core link

  exclusive(fn) {
    const run = this.queue.then(fn);
    this.queue = run.catch(() => {});
    return run;
  }

  requireProxy() {
    if (!this.proxy) throw new Error(this.disposed ? 'the designer was disposed' : 'the core is not running');
    return this.proxy;
  }

  requireReady() {
    if (this.disposed) throw new Error('the designer was disposed');
    if (!this.proxy || !this.info || !this.field)
      throw new Error('the designer is not ready yet; await its ready promise first');
  }

  // One request to the worker; the snapshot it returns (also with a failure) becomes the session's state. On a
  // big model the reply may be the preview core's (core/progressive-core.js): the exact field follows through
  // core-follow.js exactLanded. load: loadMesh's options for ProgressiveCore.load ({previewEdges, onPhase}).
  async call(op, args = [], transfer = [], load = null) {
    this.requireProxy();
    this.emit('busy', { op, done: false });
    const t0 = performance.now();
    try {
      let reply, progressive = false;
      if (load) ({ reply, progressive } = await this.core.load(args, transfer, load));
      else reply = await this.core.call(op, args, transfer);
      const t1 = performance.now();
      const preview = !!reply.snapshot?.stats?.preview;
      const { workerMs, timing: workerParts } = reply;
      this.perf.lastOp = { op, workerMs, workerParts, roundTripMs: t1 - t0, sentAt: t0, receivedAt: t1, preview };
      if (reply.snapshot) this.applySnapshot(reply.snapshot);
      this.perf.lastOp.applyMs = performance.now() - t1;
      if (progressive) awaitExact(this);
      return reply;
    } catch (err) {
      if (err.reply?.snapshot) this.applySnapshot(err.reply.snapshot);
      throw err;
    } finally {
      this.emit('busy', { op, done: true });
    }
  }

  // Resolves when the field shown is the exact core's (after a preview on a big model: docs/js-api.md).
  settled() {
    return this.core ? this.core.settled() : Promise.resolve();
  }

  // A call that changes nothing the session mirrors (exports, the texture's analyses): in the queue when
  // `exclusive`, else in the background beside the edits.
  async request(op, args = [], { exclusive = false, transfer = [] } = {}) {
    if (exclusive) {
      return this.exclusive(async () => {
        this.requireReady();
        return (await this.call(op, args, transfer)).value;
      });
    }
    return (await this.requireProxy().call(op, args, transfer, { background: true })).value;
  }

  // The snapshot's field arrays (and its magnitude scale, geometry/magnitudes.js, made by the worker) start a new
  // DerivedField; its design changes go to the table.
  applySnapshot(snapshot) {
    if (this.field) this.retired.push(this.field);
    this.field = new DerivedField(snapshot, () => this.surface);
    this.fieldVersion++;
    this.table.apply(snapshot.design);
    if (this.selected != null && !this.table.has(this.selected)) this.selected = null;
  }

  // ------------------------------------------------------------------------------------------ reads

  constraintList() {
    return this.table.list();
  }

  settings() {
    return this.table.settings();
  }

  // Derived on first read, once per field: no edit waits for them. [{vertex, index, prescribed, id?}].
  currentSingularities() {
    return this.topology.singularities();
  }

  // The current field's 'faceVectors', 'oneForm' or 'vertexVectors' (a preview's first two derived on first read).
  fieldArray(name) {
    if (name === 'faceVectors') return this.field.requireFaceVectors();
    if (name === 'oneForm') return this.field.requireOneForm();
    return this.field.requireVertexVectors();
  }

  select(uid) {
    this.selected = uid != null && this.table.has(uid) ? Number(uid) : null;
    this.emit('selection', this.selected);
  }

  // ------------------------------------------------------------------------------------------ edits

  // Runs the command made by makeCommand(table) (inside the queue, once the session is ready) and records it
  // unless it changed nothing (command.changes === false).
  execute(makeCommand) {
    return this.exclusive(async () => {
      this.requireReady();
      const command = makeCommand(this.table);
      try {
        await this.#perform(command, true);
      } catch (err) {
        this.emit('settings', this.settings()); // what the core holds, also after a refusal
        throw err;
      }
      if (command.changes !== false) this.history.push(command);
      this.afterEdit();
      return command.result;
    });
  }

  // One step of a command, forward (do, redo) or back (undo): the one request it names, the reply's snapshot
  // taken on (call), then the command's own bookkeeping of page ids, and its notice if it has one.
  async #perform(command, forward) {
    const table = this.table;
    const request = forward ? command.request(table) : command.undoRequest(table);
    let reply = null;
    if (request) {
      try {
        reply = await this.call(request.op, request.args);
      } catch (err) {
        command.refused?.(table, forward);
        throw err;
      }
    }
    const notice = forward ? command.applied?.(reply, table) : command.undone?.(reply, table);
    if (forward && command.clearsSelection) this.selected = null;
    if (notice) this.flash(notice, NOTICE_MS);
  }

  // spec: a design-format constraint; meshSerial: the model the edit was made on (tool input), dropped when
  // the model changed before it reached the core; undefined for API calls.
  addConstraint(spec, meshSerial = undefined) {
    return this.execute(() => {
      if (meshSerial !== undefined && meshSerial !== this.meshSerial)
        throw new Error('the model changed before this edit reached the core; it was not applied');
      return new AddConstraint(spec);
    });
  }

  remove(uid) {
    return this.execute((table) => RemoveConstraint.of(table, uid));
  }

  // kind: 'weight' | 'strength'.
  setParameter(kind, uid, value) {
    return this.execute((table) => SetParameter.of(table, kind, uid, value));
  }

  // kind: 'boundary' | 'gamma' | 'symmetry' | 'curvatureAlignment' | 'exactSingularities'; the core checks the
  // value. A new symmetry takes the constraints it cannot keep with it, in the same step, and resolves with them
  // ({id, ...spec}).
  setSetting(kind, value) {
    return this.execute((table) =>
      kind === 'symmetry' ? SetSymmetry.of(table, value) : SetSetting.of(table, kind, value),
    );
  }

  // ignoreFingerprint: apply a design saved for another mesh anyway (its indices taken as they are).
  replaceDesign(design, label, { ignoreFingerprint = false } = {}) {
    return this.execute((table) => ReplaceDesign.of(table, design, label, { ignoreFingerprint }));
  }

  step(forward) {
    return this.exclusive(async () => {
      this.requireReady();
      const command = forward ? this.history.peekRedo() : this.history.peekUndo();
      if (!command) return false;
      try {
        await this.#perform(command, forward);
      } finally {
        if (this.selected != null && !this.table.has(this.selected)) this.selected = null;
      }
      if (forward) this.history.redone();
      else this.history.undone();
      this.afterEdit();
      return true;
    });
  }

  // After every completed change: redraw, keep the autosave (when on) in step with the core, tell listeners.
  afterEdit() {
    this.table.adoptUnmapped();
    this.emit('banner-clear');
    this.changed();
    this.autosave.saveNow();
    this.emitChanges();
  }

  exportField() {
    return this.request('fieldJson', [], { exclusive: true });
  }

  // ------------------------------------------------------------------------------------------ unsaved edits

  markSaved() {
    this.savedDesignJson = this.table.key();
  }

  // Edits since the design was last saved, loaded or opened with its model (undoing back to it counts as none).
  hasUnsavedEdits() {
    return !!this.field && this.savedDesignJson !== this.table.key();
  }

  // ------------------------------------------------------------------------------------------ models

  // opts: {name, format, companions, restore}. The autosaved design is restored only when autosave is on.
  loadModel(src, opts = {}) {
    return this.models.load(src, opts);
  }

  // ------------------------------------------------------------------------------------------ supervision

  cancel() {
    return this.proxy?.cancel() ?? false;
  }

  supervision() {
    return { restarts: this.proxy?.restarts ?? 0, lastFailure: structuredClone(this.proxy?.lastFailure ?? null) };
  }
}
