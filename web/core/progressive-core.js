// Page side of a big model's two cores (docs/architecture.md, "Big meshes"): the exact core (core-proxy.js, the
// session's worker) and, while a model at least `previewEdges` edges large is open, a preview core in a second
// worker that solves the same design on a coarse stand-in (preview/). The session talks to this class as it
// would to the exact proxy:
// * a load opens the model in the exact worker, which sends the mesh and design ahead of its factorization;
//   the preview worker simplifies, solves and answers first, and the page shows that field (stats.preview)
//   while the exact factorization goes on;
// * each edit goes to both, in order: the preview's reply answers the session at once, the exact worker
//   queues the edit behind the factorization (or the previous exact solve) and replays it; when the exact
//   core has caught up with every edit sent, its field replaces the preview (onExact), never earlier, so the
//   page only ever shows the field of the design it holds;
// * reads (exports, read-outs, the design file) go to the exact core, behind the edits.
// An edit the preview refuses, or a preview worker that fails, ends the preview: that edit and the next ones
// wait for the exact core, as on a small mesh.
//
// Owns the preview worker. Imports core-proxy.js.
import { CoreProxy } from './core-proxy.js';

// Above this many edges a model opens with a preview (measured: README, "Big meshes"). bunny00's 100k edges
// factor in ~0.5 s and take no preview.
export const PREVIEW_EDGES = 300_000;

// Ops that change the design or the field: the preview takes them too.
const EDITS = ['add', 'remove', 'setWeight', 'setStrength', 'setBoundary', 'setGamma', 'setSymmetry',
  'setCurvatureAlignment', 'applyDesign', 'addSingularity', 'moveSingularity', 'setFeatures', 'addSingularities',
  'removeConstraints', 'setExactSingularities'];
const isEdit = (op) => EDITS.includes(op);

export class ProgressiveCore {
  // exact: the session's CoreProxy. onExact(snapshot, reply): the exact field has caught up with the design;
  // onExactError(err, op): an exact op failed after the preview had answered for it; onPhase({phase, ...}): load
  // progress.
  constructor(exact, { assetBase, onExact, onExactError }) {
    this.exact = exact;
    this.assetBase = assetBase;
    this.onExact = onExact;
    this.onExactError = onExactError;
    this.preview = null;
    this.outstanding = 0; // exact calls sent since the preview led, not yet answered
    this.waiters = [];
  }

  // Resolves when the field shown is the exact core's (at once when no preview leads).
  settled() {
    return this.outstanding === 0 ? Promise.resolve() : new Promise((resolve) => this.waiters.push(resolve));
  }

  // Field arrays the page is done with go back to the worker that made them (core-proxy.js recycle()).
  recycle(arrays, fromPreview) {
    (fromPreview && this.preview ? this.preview : this.exact).recycle(arrays);
  }

  dropPreview() {
    this.preview?.terminate();
    this.preview = null;
  }

  // args: loadMesh's [bytes, format, settings, design]. Resolves with {reply, progressive}: the exact reply
  // (a small model, or no preview possible) or one shaped like it whose snapshot is the preview's.
  // delayForTestMs: the exact worker waits this long before factoring (tests of the preview's lead).
  async load(args, transfer, { previewEdges = PREVIEW_EDGES, delayForTestMs = 0, onPhase = () => {} } = {}) {
    this.dropPreview();
    let opened, surfaced;
    const ahead = new Promise((resolve) => (opened = resolve));
    const surfaceSent = new Promise((resolve) => (surfaced = resolve));
    // A file this large may well be past the threshold (binary formats take ≥ 8 bytes per edge, OFF and OBJ
    // text over 20): the preview worker starts now, beside the exact worker's reading, rather than after it. It
    // warms up while the exact worker reads (preview/warm-up.js), and simplifies the mesh as soon as it is read
    // (open-steps.js). A smaller model would only have its load share the cores with that warm-up (bunny00's
    // 2.6 MB OFF, 113k edges).
    const bytesPerEdge = ['off', 'obj'].includes(args[1]) ? 12 : 4;
    const big = previewEdges > 0 && args[0].byteLength >= bytesPerEdge * previewEdges;
    const early = big ? this.#startPreview(true) : null;
    let meshed = null;
    const prepare = (mesh) =>
      (meshed ??= (async () => {
        const proxy = await (early ?? this.#startPreview());
        const { positions, triangles } = mesh;
        const reply = await proxy.call('previewMesh', [{ positions, triangles }], [positions.buffer, triangles.buffer]);
        // The mesh's preview parts were kept from an earlier opening (worker/preview-cache.js): what is left of
        // the preview, its coarse solve, is short beside the exact worker's own work before its factorization
        // (the picking parts, the analysis, the matrix), which then need not wait for it.
        if (reply.value?.kept) this.exact.notify({ previewMade: true });
        return proxy;
      })());
    const endWorkers = () => [early, meshed].forEach((p) => p?.then((proxy) => proxy.terminate(), () => {}));
    const exactLoad = this.exact.call('loadMesh', [...args, { previewEdges, delayForTestMs }], transfer, {
      onProgress: (p) => {
        onPhase(p);
        if (p.phase === 'read') prepare(p.mesh).catch(() => {});
        if (p.phase === 'opened') opened(p);
        if (p.phase === 'surface') surfaced(p.surface);
      },
    });
    // The surface comes before the factorization; a load that fails first sends none.
    const surface = Promise.race([surfaceSent, exactLoad.then(() => surfaceSent)]);
    surface.catch(() => {}); // a failed load is reported by exactLoad itself
    const first = await Promise.race([ahead, exactLoad.then((reply) => ({ reply }), () => ({}))]);
    if (!first.info) {
      endWorkers();
      return { reply: await exactLoad, progressive: false };
    }
    let preview = null;
    try {
      onPhase({ phase: 'preview', info: first.info });
      const { mesh, design } = first;
      preview = await prepare(mesh);
      onPhase({ phase: 'previewStarted' });
      let exactDone = null, exactFailed = null;
      exactLoad.then((r) => (exactDone = r), (err) => (exactFailed = err));
      const reply = await preview.call('openPreview', [design, args[2]]);
      this.exact.notify({ previewMade: true }); // the exact worker factors from here on (worker/load-ops.js)
      // The exact core refused the model while the preview was made (too large to factor, say): the load fails
      // as any other, and the previous model stays.
      if (exactFailed) throw Object.assign(exactFailed, { exactLoad: true });
      this.preview = preview; // kept for the strokes' previews, even when the exact field came first
      onPhase({ phase: 'previewSolved' });
      const value = {
        info: first.info,
        settingsError: first.settingsError,
        restoreError: first.restoreError,
        embeddedDesign: first.embeddedDesign,
        cornerUVs: first.cornerUVs,
        surface: await surface,
        previewTimings: reply.value.timings,
      };
      if (exactDone) return { reply: { ...exactDone, value }, progressive: false };
      this.#track(exactLoad, 'loadMesh');
      return { reply: { ...reply, value }, progressive: true };
    } catch (err) {
      this.exact.notify({ previewMade: true });
      endWorkers();
      if (err.exactLoad) throw err;
      console.warn(`tangent-field-designer: no preview (${err.message}); waiting for the exact field`);
      const reply = await exactLoad;
      reply.value.surface = await surface;
      return { reply, progressive: false };
    }
  }

  async #startPreview(warm = false) {
    const proxy = await CoreProxy.start(this.assetBase, { silentMs: 60_000 });
    if (warm) proxy.call('warmUpPreview').catch(() => {});
    return proxy;
  }

  // The session's request: an edit goes to both cores while the preview leads; everything else to the exact one.
  async call(op, args = [], transfer = [], options = {}) {
    if (!this.preview || !isEdit(op)) return this.exact.call(op, args, transfer, options);
    const exactReply = this.exact.call(op, args, transfer, { ...options, wholeDesign: true });
    const previewReply = this.preview.call(op, args);
    // Whichever answers first answers the session: the exact core may beat the preview on a mesh just past the
    // threshold, and a later preview reply must then not cover the exact field. The claims run in the order the
    // replies arrive, and the exact one before #track's own handler, so that the exact snapshot is applied
    // exactly once: as this reply, or by onExact.
    let by = null;
    const entry = { answered: false };
    previewReply.then(
      () => (by ??= 'preview'),
      (err) => {
        by ??= 'preview failed';
        console.warn(`tangent-field-designer: the preview ends (${err.message}); the exact core answers alone`);
      },
    );
    const claimExact = () => {
      by ??= 'exact';
      if (by !== 'preview') entry.answered = true;
    };
    exactReply.then(claimExact, claimExact);
    this.#track(exactReply, op, entry);
    await Promise.race([previewReply, exactReply].map((p) => p.catch(() => {})));
    if (by === 'preview') return previewReply;
    // The exact core answered first, or the preview refused what the exact core may take, or its worker failed
    // (from here on the exact core answers alone, this edit included).
    if (by === 'preview failed') this.dropPreview();
    return exactReply;
  }

  // entry.answered: the reply answered the session itself (call()), and must not be applied again.
  #track(promise, op, entry = { answered: false }) {
    this.outstanding++;
    const done = () => {
      this.outstanding--;
      if (this.outstanding === 0) for (const w of this.waiters.splice(0)) w();
    };
    promise.then(
      (reply) => {
        const caughtUp = this.outstanding === 1;
        done();
        if (caughtUp && !entry.answered && reply.snapshot) this.onExact(reply.snapshot, reply);
      },
      (err) => {
        done();
        if (!entry.answered && !err.restart) this.onExactError(err, op, this.outstanding === 0);
      },
    );
  }

  terminate() {
    this.dropPreview();
    for (const w of this.waiters.splice(0)) w();
  }
}
