// Opening a model: read the file (model-files.js), find its autosave, hand it to the core in one transaction
// (loaded, checked, factored and solved aside; a failure keeps the previous model), then adopt the new mesh.
// Tool input made meanwhile is refused (loadsPending), and one made on the previous model is dropped. A big model
// (opts.previewEdges, default core/progressive-core.js PREVIEW_EDGES) is adopted with its preview field, the
// exact one following (session/core-follow.js exactLanded); should the exact load then fail, the previous model
// comes back.
import { grouped } from '../dom.js';
import { featureAngleForNextModel } from './constraint-table.js';
import { modelKey } from './documents.js';
import { readModel } from './model-files.js';
import { Surface } from '../geometry/surface.js';
import { PREVIEW_EDGES } from '../core/progressive-core.js';
import { readBytesOffThread } from '../core/core-proxy.js';

// The progress label through a load's phases (core/worker/load-ops.js loadMesh's progress, progressive-core.js): a big
// model is read, previewed while the exact factorization starts, then factored; a small one read and factored.
const LOAD_PHASE_LABELS = {
  opened: (p) => `Reading done; a preview of ${grouped(p.info.faces)} faces on a coarse mesh…`,
  factoring: 'Factoring…',
  previewSolved: 'Drawing the preview…',
};

export class ModelLoader {
  constructor(session) {
    this.session = session;
    this.loadsPending = 0; // model loads asked for and not finished
    this.warmedUp = false;
    this.staged = null; // {arrays, surface, ready}: the Surface of a big model's mesh sent ahead (#phase)
    this.adopting = null; // while a reply waits for its mesh's uploads: the promise it waits on
    this.picking = null; // the Surface sent ahead whose adjacency and BVH are still to come
  }

  load(src, opts = {}) {
    const s = this.session;
    this.loadsPending++;
    // The file is read at once, beside whatever the core is still doing (the previous model's warm-up, an
    // edit); only handing it to the core waits its turn. A read that fails is reported in that turn.
    const t0 = performance.now();
    const reading = readModel(src, opts, (source) => readBytesOffThread(s.assetBase, source));
    reading.then((model) => (s.perf.modelRead = { thread: model.thread, ms: performance.now() - t0 }), () => {});
    return s
      .exclusive(async () => {
        s.requireProxy();
        let model;
        try {
          model = await reading;
        } catch (err) {
          throw s.fail('model', new Error(`Could not load model: ${err.message}`));
        }
        const key = modelKey(model.name, model.bytes, model.digest);
        const saved = opts.restore === false ? null : await s.autosave.load(key);
        const bytes = model.copy ?? model.bytes.slice(); // its own buffer, transferred to the worker
        model.copy = null;
        let reply;
        const previous = this.#current();
        s.perf.loadPhases = { start: performance.now() };
        const previewEdges = opts.previewEdges ?? PREVIEW_EDGES;
        const load = { previewEdges, delayForTestMs: s.debugExactDelayMs ?? 0, onPhase: (p) => this.#phase(p) };
        // The design's feature angle goes with the settings where the user chose it; else the model's own.
        const angle = featureAngleForNextModel(s.table.features().angle, s.info?.folds?.suggestedFeatureAngle);
        const settings = { ...s.settings(), featureAngle: angle };
        const args = [bytes, model.format, settings, saved?.design ?? null];
        try {
          reply = await s.call('loadMesh', args, [bytes.buffer], load);
        } catch (err) {
          // The core kept its previous mesh and everything on it.
          if (s.info) s.changed();
          throw s.fail('model', new Error(`Could not load ${model.name}: ${err.message.replace(/^load: /, '')}`));
        }
        const { info, settingsError, restoreError, embeddedDesign, cornerUVs } = reply.value;
        let staged = this.staged;
        this.staged = null;
        if (staged?.arrays !== reply.value.surface) staged = null;
        // The mesh's buffers reach the GPU in tasks of their own, not in the adoption's (at 832k faces ~150 ms
        // of uploads in one task; the field waits for them instead).
        if (staged?.ready) {
          this.adopting = staged.ready;
          await staged.ready;
          this.adopting = null;
        }
        const surface = staged?.surface ?? Surface.fromArrays(reply.value.surface);
        this.previous = reply.snapshot?.stats?.preview ? previous : null;
        this.#adopt({ model, key, source: { bytes: model.bytes, format: model.format }, info, surface, cornerUVs });
        s.perf.loadPhases.adopted = performance.now();
        s.perf.previewTimings = reply.value.previewTimings ?? null;
        this.#tellRestored(model, saved, restoreError, embeddedDesign, settingsError);
        this.#announce();
        this.#warmUpLater();
        return structuredClone(info);
      })
      .finally(() => this.loadsPending--);
  }

  // A model the core has just taken on: the session's copies, then the signals.
  #adopt({ model, key, source, info, surface, cornerUVs }) {
    const s = this.session;
    s.surface = surface;
    s.info = info;
    s.modelName = model.name;
    s.modelKey = key;
    s.modelSource = source;
    s.selected = null;
    s.table.restart();
    s.markSaved();
    s.history.clear();
    s.cornerUVs = cornerUVs.length ? cornerUVs : null;
    s.meshSerial++;
    s.emit('banner-clear');
    const t0 = performance.now();
    s.emit('model', { info, surface });
    s.changed();
    // Main-thread cost of taking a new mesh on (adjacency, BVH, buffers, first draw): the one pause left.
    s.perf.meshSetupMs = performance.now() - t0;
  }

  #announce() {
    const s = this.session;
    s.emit('load', { info: structuredClone(s.info) });
    s.emitChanges();
  }

  // What #adopt needs to bring the current model back, and its design.
  #current() {
    const s = this.session;
    if (!s.info) return null;
    const { modelKey: key, modelSource: source, info, surface, design } = s;
    const cornerUVs = s.cornerUVs ?? new Float32Array(0);
    return { model: { name: s.modelName }, key, source, info, surface, cornerUVs, design };
  }

  #phase(p) {
    const s = this.session;
    (s.perf.loadPhases ??= {})[p.phase] = performance.now();
    // A big model's mesh comes ahead of its field: the views take it on in tasks of their own ('surface': a
    // listener may set `ready`, a promise its adoption waits for), and its adoption uses the same Surface.
    if (p.phase === 'surface') {
      this.staged = { arrays: p.surface, surface: Surface.fromArrays(p.surface), ready: null };
      this.picking = this.staged.surface;
      s.emit('surface', this.staged);
    }
    // Its adjacency and BVH follow, before or after its first field (the viewer picks nothing until then); the
    // BVH kept from an earlier opening of the same mesh when there was one (perf().pickingTreeKept).
    if (p.phase === 'picking') {
      this.picking?.adoptPicking(p.picking);
      this.picking = null;
      s.perf.pickingTreeKept = p.treeKept;
    }
    if (p.phase === 'opened') {
      const faces = grouped(p.info.faces);
      s.flash(`Opening a big mesh (${faces} faces): a preview first, the exact field follows.`, 4000);
    }
    // While a preview is made, the exact worker's factoring is not what the page waits for.
    const label = p.phase === 'factoring' && s.perf.loadPhases?.opened ? null : LOAD_PHASE_LABELS[p.phase];
    if (label) s.emit('busy', { op: 'loadMesh', phase: typeof label === 'function' ? label(p) : label });
  }

  // The exact core could not take the big model whose preview is shown (too large to factor, say): it still
  // holds the previous model, which comes back on the page with its design; the preview's edits are gone.
  exactLoadFailed(err) {
    const s = this.session;
    const name = s.modelName;
    s.fail('model', new Error(`Could not load ${name}: ${err.message.replace(/^load: /, '')}`));
    const previous = this.previous;
    this.previous = null;
    if (!previous) return;
    s.exclusive(async () => {
      this.#adopt(previous);
      await s.call('applyDesign', [previous.design]);
      s.changed();
      this.#announce();
    }).catch((e) => s.fail('model', e));
  }

  #tellRestored(model, saved, restoreError, embeddedDesign, settingsError) {
    const s = this.session;
    const restored = saved?.design ? 'autosaved' : 'embedded';
    if (restoreError) s.flash(`The ${restored} design could not be restored: ${restoreError}`, 6000);
    else if ((saved?.design || embeddedDesign) && s.table.size)
      s.flash(`Restored the ${restored} design (${s.table.size} constraints).`);
    if (settingsError) {
      const settings = 'The field settings (boundary, γ, symmetry, curvature alignment)';
      s.emit('banner', { message: `${settings} did not apply to ${model.name}: ${settingsError}` });
    }
  }

  // After the first frame, not before: on the small default model warming up costs more than it saves
  // (measured: ~0.3 s to save ~35 ms), but the next, larger model the user opens gets optimized code.
  #warmUpLater() {
    if (this.warmedUp) return;
    this.warmedUp = true;
    const s = this.session;
    setTimeout(() => s.exclusive(() => s.proxy?.call('warmUp', [3, 2])).catch(() => {}), 0);
  }

  // Tool input is bound to the model it was made on: while a load is pending it is refused (null).
  boundSerial() {
    if (this.loadsPending > 0) {
      this.session.flash('A model is loading: the edit was not applied.', 3000);
      return null;
    }
    return this.session.meshSerial;
  }
}
