// SPDX-License-Identifier: GPL-2.0-or-later
// One designer's texture synthesis: which exemplar, which atlas (per model and resolution), when to
// (re)synthesize as the field changes (quick edits get a preview, bursts coalesce, stale runs are cancelled),
// the textured model in the view, and the texture handed to the exports. Everything runs in order through one
// queue, so an export never reads a half-made texture. The GPU work is synthesizer.js's; the settings chosen
// for the user are auto-settings.js's; which options synthesize() takes, options.js's; what a run hands the
// synthesizer (its options, the field it follows), run-inputs.js's; the texture read out, texture-exports.js's.
import { runSynthesisBench } from './bench.js';
import { ExemplarLibrary, PROCEDURAL_SIZE, USER_EXEMPLAR_SIZE, imageToRGBA8 } from './exemplar.js';
import { setUpAtlas } from './atlas-setup.js';
import { PhaseClock } from './phase-clock.js';
import { QUICK_EDIT_MS, followsWithin, isQuickEdit } from './quick-edits.js';
import { DEFAULTS, Synthesizer } from './synthesizer.js';
import { glbTexture, texturePng, textureReadback } from './texture-exports.js';
import { TEXTURE_SYMMETRIES, textureRefusal } from '../session/symmetry.js';
import { checkSynthesisOptions } from './options.js';
import { fieldInputSteps, runOptions, stepped } from './run-inputs.js';
import { BAR_DELAY_MS, progressFollower } from './progress-follower.js';
import { watchContext } from './context-loss.js';

export class SynthesisController {
  // viewer: the page's Viewer (scene, surfaceMesh, requestRender).
  // getModel(): {key, name, positions, triangles, surface, cornerUVs | null, symmetry, oneForm (N = 1; a big
  // model's preview: vertexVectors) or vertexVectors and faceVectors (N ≥ 2), fieldVersion} of the current model
  // and field (surface: geometry/surface.js, with normals and the half-edge map).
  // computeAtlas(model, {resolution, gutter}) and analyzeExemplar(spec): preparedAtlas (atlas-prepared.js) and
  // analyzeExemplar (exemplar.js) off the page's thread (the element's core worker), resolving with their results.
  // getFieldVersion(): the model's fieldVersion without the copies getModel() makes (tens of ms at 400k
  // vertices, at every field change). isPreviewField(): the current field is a big model's preview, which its
  // exact field replaces when it lands.
  constructor({
    viewer,
    getModel,
    getFieldVersion = () => getModel()?.fieldVersion,
    isPreviewField = () => false,
    computeAtlas,
    analyzeExemplar,
    onChange = () => {},
    onError = () => {},
  }) {
    this.computeAtlas = computeAtlas;
    this.viewer = viewer;
    this.getModel = getModel;
    this.getFieldVersion = getFieldVersion;
    this.isPreviewField = isPreviewField;
    this.onChange = onChange;
    this.onError = onError;
    this.library = new ExemplarLibrary(analyzeExemplar);
    this.synth = null;
    this.render = null;
    this.exemplar = null; // {tables, label, analysisMs, cached}
    this.atlas = null; // {key, resolution, cornerUVs, source, reason, stats}
    // resolution / featureScale 'auto': chosen from the model and the exemplar (defaultResolution,
    // defaultFeatureScale). autoUpdate: resynthesize on field changes. interleave: yield to the page between draws.
    this.options = { ...DEFAULTS, resolution: 'auto', featureScale: 'auto', autoUpdate: true, interleave: true };
    this.progress = null; // {fraction, preview} while a synthesis runs
    this.progressShown = null; // the progress the panel shows (none for a run's first BAR_DELAY_MS)
    this.stale = false; // the field changed since the texture was made (autoUpdate off)
    this.runToken = 0;
    this.lastFieldChange = -Infinity;
    this.settleTimer = null;
    this.active = false; // a texture is shown and follows field changes
    this.stats = null;
    this.queue = Promise.resolve();
    this.pendingField = false;
    this.runVersion = undefined; // the field version the run scheduled or under way is for
    this.changedAt = null; // the first field change the next run answers
    this.previewFieldShown = false; // the last field change was a big model's preview field
    this.runsQueued = 0; // field changes' runs queued or running (quick-edits.js)
    this.previewRuns = 0; // runs made as previews of quick edits (synthesisStats().previewRuns)
    watchContext(this);
  }

  // Runs fn after everything queued before it (texture-exports.js reads through this too).
  exclusive(fn) {
    const run = this.queue.then(fn);
    this.queue = run.catch(() => {});
    return run;
  }

  // The synthesizer draws in the view's own WebGL context (its result shown where it is made: gl-guard.js).
  ensureSynth() {
    if (this.synth) return this.synth;
    const renderer = this.viewer.renderer;
    if (renderer.getContext().isContextLost()) throw new Error('the view\'s WebGL context is lost: no texture yet');
    this.synth = new Synthesizer(renderer.getContext(), { renderer });
    if (this.exemplar) this.synth.setExemplar(this.exemplar.tables); // a context lost and restored
    return this.synth;
  }

  // A new one in a task of its own (its programs are created there); null if disposed meanwhile.
  async #synthesizer() {
    if (!this.synth) {
      this.ensureSynth();
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
    return this.synth;
  }

  // 'brushed' (exemplar.js) reads as lines: for line fields, as stripes do.
  proceduralNames() {
    return ['stripes', 'scales', 'weave', 'brushed'];
  }

  // src: a procedural name ('stripes' | 'scales' | 'weave' | 'brushed'), {procedural, size, seed}, a URL (string or
  // URL), a Blob/File (PNG or JPEG), ImageData or an ImageBitmap. Options: {size} for images (power of two, default
  // 128).
  setExemplar(src, { size } = {}) {
    return this.exclusive(async () => {
      const t0 = performance.now();
      let result, label;
      const spec = typeof src === 'string' && this.proceduralNames().includes(src) ? { procedural: src } : src;
      if (spec && typeof spec === 'object' && typeof spec.procedural === 'string') {
        const n = spec.size ?? PROCEDURAL_SIZE;
        result = await this.library.procedural(spec.procedural, n, spec.seed ?? 1);
        label = spec.procedural;
      } else {
        const n = size ?? USER_EXEMPLAR_SIZE;
        if (!Number.isInteger(n) || n < 16 || n > 256 || n & (n - 1))
          throw new Error(`exemplar size must be a power of two in [16, 256] (got ${n})`);
        const img = await imageToRGBA8(spec, n);
        result = await this.library.image(img.rgba, img.size, img.label);
        label = img.label;
      }
      this.exemplar = { tables: result.tables, label, cached: result.cached, analysisMs: performance.now() - t0 };
      (await this.#synthesizer())?.setExemplar(result.tables);
      this.onChange();
      if (this.active) await this.#run();
      return this.exemplarInfo();
    });
  }

  // The exemplar the next synthesis uses when none was chosen (its tables, from the library's cache after the
  // first call): for the panel's thumbnail before any texture is made.
  async defaultExemplar() {
    return (await this.library.procedural('stripes', PROCEDURAL_SIZE, 1)).tables;
  }

  exemplarInfo() {
    if (!this.exemplar) return null;
    const { tables, label, cached, analysisMs } = this.exemplar;
    return { label, size: tables.size, levels: tables.levels.length, cached, analysisMs, analysis: tables.stats };
  }

  // Synthesizes for the current field and shows the result; later field changes resynthesize with the same
  // options until clearTexture(). Options: resolution (power of two, default 256) and the synthesizer's
  // (featureScale, magnitudeExponent, jitter, passes, kappa, seed, gutter, timing).
  synthesize(options = {}) {
    const clock = new PhaseClock();
    this.changedAt = null;
    return this.exclusive(async () => {
      clock.mark('queued behind earlier texture work');
      checkSynthesisOptions(options);
      this.options = { ...this.options, ...options };
      if (!this.exemplar) {
        const r = await this.library.procedural('stripes', PROCEDURAL_SIZE, 1);
        this.exemplar = { tables: r.tables, label: 'stripes', cached: r.cached, analysisMs: 0 };
        clock.mark('exemplar analysis (worker)');
        (await this.#synthesizer())?.setExemplar(r.tables);
        clock.mark('synthesizer, exemplar to the GPU');
      }
      this.active = true;
      return this.#run({ clock });
    });
  }

  // One synthesis for the current model and field. preview: stop one level short of the finest (quick edits).
  // clock: the phases since the call or the field change this run answers (phase-clock.js).
  async #run({ preview = false, clock = new PhaseClock() } = {}) {
    const model = this.getModel();
    if (!model) throw new Error('no model loaded');
    // A line or cross field's vectors are each one of its N directions, chosen arbitrarily: it is combed for the
    // atlas below. Other N are refused, and a texture shown stops following the field.
    const symmetry = model.symmetry ?? 1;
    if (!TEXTURE_SYMMETRIES.includes(symmetry)) {
      this.active = false;
      this.render?.setVisible(false);
      this.onChange();
      throw new Error(textureRefusal(symmetry));
    }
    const token = ++this.runToken;
    const t0 = performance.now(), frames0 = this.viewer.renderCount;
    this.ensureSynth();
    clock.mark('field from the page');
    const atlas = await setUpAtlas(this, model, clock);
    const tAtlas = performance.now() - t0;
    const synthOptions = runOptions(this.options, model, atlas, this.exemplar.tables.size, preview);
    const field = await stepped(fieldInputSteps(model, atlas), this.options.interleave, () => token !== this.runToken);
    if (!field) return this.synthesisStats(); // superseded by a newer field change
    clock.mark(field.symmetry > 1 ? 'field combed for the atlas' : 'field per corner (Whitney)');
    let s;
    if (this.options.interleave) {
      this.progress = { fraction: 0, preview };
      const follow = progressFollower(() => this.progress, () => {
        this.progressShown = this.progress;
        this.onChange();
      }, { delayMs: BAR_DELAY_MS });
      s = await this.synth.synthesizeInterleaved(field.input, { ...synthOptions, timing: 'total' }, {
        clock,
        cancelled: () => token !== this.runToken,
        onProgress: (f) => {
          this.progress = { fraction: f, preview };
          follow();
        },
      });
      follow.stop();
      this.progress = this.progressShown = null;
      if (!s) return this.synthesisStats(); // superseded by a newer field change
    } else {
      s = this.synth.synthesize(field.input, synthOptions);
      clock.mark('kernel (blocking run)');
    }
    if (token !== this.runToken || !this.render) return this.synthesisStats(); // superseded meanwhile
    // The result stays on the GPU: copied (exact) into targets the view draws from, which later runs do not touch.
    const t2 = performance.now();
    const { rgba8: exemplar, size: exemplarSize } = this.exemplar.tables;
    if (!this.render.setTexture({ ...this.synth.displayCopy(), exemplar, exemplarSize })) return this.synthesisStats();
    this.viewer.drawDeferred?.(); // the field's frame, if it waited for this texture (followsWithin)
    clock.mark('to the view (copied on the GPU)');
    this.stale = false;
    this.stats = {
      ...s,
      autoFeatureScale: this.options.featureScale === 'auto',
      shapeComplexity: atlas.complexity ?? null,
      shapeFoldDegrees: atlas.foldDegrees ?? null,
      autoResolution: this.options.resolution === 'auto',
      exemplar: this.exemplarInfo(),
      atlas: { source: atlas.source, reason: atlas.reason, resolution: atlas.resolution, ...atlas.stats, ms: tAtlas,
        workerSteps: atlas.workerSteps, cache: atlas.cache },
      uploadMs: performance.now() - t2,
      ...clock.summary(), // phases and wallMs
      startedAt: clock.t0,
      shownAt: clock.last,
      fieldVersion: model.fieldVersion,
      previewRuns: this.previewRuns,
      viewFrames: this.viewer.renderCount - frames0, // the view's frames drawn during the run (beside it on the GPU)
      fieldFrameWaited: this.frameWaited ?? 0, // ms the field's frame could wait for this texture (0: drawn first)
      symmetry: field.symmetry,
      ...(field.symmetry > 1 ? { combMs: field.ms, combCutEdges: field.cutEdges } : {}),
    };
    this.lastFieldVersion = model.fieldVersion;
    this.onChange();
    return structuredClone(this.stats);
  }

  // The field changed: resynthesize while a texture is shown (autoUpdate), cancelling a run the change makes
  // stale. A change on its own (a released stroke, an edit, a big model's exact field landing after its preview)
  // starts a full synthesis at once. Quick edits (quick-edits.js: changes that come faster than the texture
  // follows, or while something is dragged) get a preview, and a full synthesis once they stop.
  fieldChanged({ interactive = false } = {}) {
    if (!this.active) return;
    const version = this.getFieldVersion();
    if (this.atlas && version !== undefined && (version === this.lastFieldVersion || version === this.runVersion))
      return;
    if (!this.options.autoUpdate) {
      this.stale = true;
      this.onChange();
      return;
    }
    const now = performance.now();
    const previewField = this.isPreviewField();
    const landing = this.previewFieldShown && !previewField; // the exact field of what the preview stood for
    this.previewFieldShown = previewField;
    const quick = isQuickEdit(this, { interactive, landing, now });
    if (!landing) this.lastFieldChange = now;
    this.changedAt ??= now;
    this.runVersion = version;
    this.runToken++; // cancels a run in progress
    clearTimeout(this.settleTimer);
    this.settleTimer = null;
    if (quick) {
      this.settleTimer = setTimeout(() => {
        this.settleTimer = null;
        this.#schedule(false);
      }, QUICK_EDIT_MS);
    }
    this.#schedule(quick && this.stats !== null);
  }

  // The milliseconds the view's frame of a field change may wait for this texture to be shown with it in one
  // frame (0: drawn at once): asked before the change is drawn (quick-edits.js followsWithin).
  followsWithin() {
    return (this.frameWaited = followsWithin(this));
  }

  #schedule(preview) {
    if (this.pendingField) {
      this.pendingPreview &&= preview;
      return;
    }
    this.pendingField = true;
    this.pendingPreview = preview;
    // A task of its own: the page draws the changed field first.
    setTimeout(() => {
      this.pendingField = false;
      const p = this.pendingPreview;
      const run = () => {
        // The phases of an update start at the field change it answers.
        const clock = new PhaseClock(this.changedAt ?? performance.now());
        this.changedAt = null;
        clock.mark(p ? 'settle, queue (preview)' : 'queue (behind the page\'s tasks)');
        if (p) this.previewRuns++;
        // With the view's context lost, its restore starts the run (#watchContext).
        const lost = this.viewer.renderer?.getContext().isContextLost();
        return this.active && !lost ? this.#run({ preview: p, clock }) : null;
      };
      this.runsQueued++;
      this.exclusive(run)
        .catch((err) => this.onError(err))
        .finally(() => this.runsQueued--);
    }, 0);
  }

  // Sets autoUpdate (and brings the texture up to date when switched on).
  setAutoUpdate(on) {
    this.options.autoUpdate = !!on;
    if (on && this.stale) this.fieldChanged();
    this.onChange();
  }

  // A new model: the atlas and the textured mesh belong to the old one.
  modelChanged() {
    this.atlas = null;
    this.render?.dispose();
    this.render = null;
    this.stats = null;
    this.lastFieldVersion = undefined;
    if (this.active) this.fieldChanged();
    this.onChange(); // the status line must stop showing the old model's numbers
  }

  // Resolves (with the latest stats) once no synthesis is queued or pending.
  // A run queued while it waited (this.queue moved on) is waited for too.
  async whenIdle() {
    for (;;) {
      const queue = this.queue;
      await queue;
      if (queue !== this.queue) continue;
      if (!this.pendingField && !this.settleTimer) return this.synthesisStats();
      await new Promise((r) => setTimeout(r, 5));
    }
  }

  clearTexture() {
    return this.exclusive(() => {
      this.active = false;
      this.render?.setVisible(false);
      this.onChange();
    });
  }

  setTextureVisible(visible) {
    this.render?.setVisible(!!visible);
  }

  synthesisStats() {
    return this.stats ? structuredClone(this.stats) : null;
  }

  // The texture read out for files and tests (texture-exports.js): a PNG as the page renders it, the texture a
  // GLB export embeds (or null), the raw result.
  exportTexturePNG(options = {}) {
    return texturePng(this, options);
  }

  exportTexture(options = {}) {
    return glbTexture(this, options);
  }

  readback() {
    return textureReadback(this);
  }

  // The synthesis benchmark (bench.js) on a synthesizer of its own.
  bench(options = {}) {
    return this.exclusive(async () => {
      return runSynthesisBench(this.library, options);
    });
  }

  // The element left the page: free the synthesis WebGL context and the textured mesh now.
  dispose() {
    const canvas = this.viewer?.renderer?.domElement;
    canvas?.removeEventListener?.('webglcontextlost', this.onContextLost);
    canvas?.removeEventListener?.('webglcontextrestored', this.onContextRestored);
    this.active = false;
    this.render?.dispose();
    this.render = null;
    this.synth?.dispose();
    this.synth = null;
  }
}
