// SPDX-License-Identifier: GPL-2.0-or-later
// Field-guided, exemplar-based parallel texture synthesis in a mesh's texture atlas, on the GPU (WebGL2):
// Lefebvre & Hoppe 2005 ("Parallel controllable texture synthesis": coarse-to-fine coordinate upsampling, jitter,
// sub-pass correction; anisometric synthesis through a per-texel Jacobian) with the appearance-space exemplar and
// k-coherence of Lefebvre & Hoppe 2006. The exemplar analysis (Gaussian stack, appearance PCA, neighbourhood PCA,
// k-coherence) comes from the wasm core (core/texture/, ExemplarAnalysis binding); everything per texel runs here
// in float render targets, with no read-back inside the level loop. A run after one with the same atlas, exemplar
// and options makes again only the texels whose field moved (local-update.js).
//
// Usage:
//   const syn = new Synthesizer();                 // its own WebGL2 context (or the view's: gl-guard.js)
//   syn.setExemplar(tables);                       // exemplarTables(analysis) from exemplar.js
//   syn.setAtlas({resolution, positions, triangles, cornerUVs, neighbour?});
//   const stats = syn.synthesize(vertexVectors, {featureScale, magnitudeExponent, seed, ...});
//   syn.displayCopy()                              // the result for the view, on the GPU
//   syn.readCoordinates(), syn.readJacobian(), syn.readColour({magnification, nearest})
import { AtlasRaster } from './atlas-raster.js';
import {
  FloatTarget,
  FULLSCREEN_VS,
  GLError,
  Program,
  animationFrame,
  checkInTurn,
  createContext,
  drawFullscreen,
  requireFloatTargets,
  sync,
} from './gl.js';
import { disposeExemplar, uploadExemplar } from './gpu-exemplar.js';
import { GLGuard } from './gl-guard.js';
import { levelPlan } from './level-plan.js';
import { correctClass, upsampleClass } from './level-passes.js';
import { LocalUpdate } from './local-update.js';
import { warmUpPipelines } from './pipeline-warm-up.js';
import { interleavedRun } from './interleaved-run.js';
import {
  COPY_FS,
  CORRECT_FS,
  JACOBIAN_DOWN_FS,
  JACOBIAN_FS,
  LOCATOR_FS,
  LOCATOR_VS,
  RESOLVE_FS,
  SEAM_RESOLVE_FS,
  UNPACK_FS,
  UPSAMPLE_FS,
} from './shaders.js';
import { SlicePacer, nextTask } from './slice-pacer.js';
import { displayCopy, readColour, readCoordinates, readJacobian } from './synthesis-readout.js';

export const DEFAULTS = Object.freeze({
  featureScale: 1, // 1: one exemplar pixel spans one atlas texel (at the atlas's mean density) on the surface
  magnitudeExponent: 0, // texture scale follows (|field| / mean |field|)^exponent; 0 = direction only (paper Sec. 6)
  jitter: 0.2, // randomness per level in level texels (LH05 r_l); a number or one value per level, coarsest first
  finestJitter: 0.0, // the finest level adds no jitter of its own by default
  passes: 2, // correction passes per level, each of 4 sub-passes
  kappa: 0.25, // extra cost of non-coherent (k-coherence) candidates, LH06's coherence bias
  seed: 1,
  // A run after one with the same atlas, exemplar and options synthesizes again only the texels whose field
  // turned (or scaled) by more than this many degrees since they were made, and two texels round them
  // (local-update.js); 0: every run synthesizes every texel.
  localDegrees: 1,
  gutter: 2, // texels of border around each chart (the atlas's packing; the raster's gutter quads)
  seams: true, // follow the seam indirection across chart boundaries (atlases with seams only)
  timing: 'levels', // 'levels': wait for the GPU after each level (per-level times); 'total': only at the end
  // Faces whose field goes to the GPU per task (atlas-raster.js, an RGBA texel per corner): 4.7 MB, so a model of
  // up to 98k faces sends it in one go (each further slice waits for the GPU: 3 slices were 32 ms of bunny00's
  // update on a real GPU).
  sliceFaces: 3 << 15,
});

export class Synthesizer {
  // gl: a context of its own by default; or the view's, with its three.js `renderer`, whose state each batch of
  // GL calls here leaves as it found it (gl-guard.js).
  constructor(gl = createContext(), { renderer = null } = {}) {
    requireFloatTargets(gl);
    this.gl = gl;
    this.guard = new GLGuard(renderer);
    this.guard.run(() => this.#create(gl));
    this.exemplar = null;
    this.atlas = null; // an AtlasRaster
    this.lastStats = null;
  }

  #create(gl) {
    this.vao = gl.createVertexArray();
    this.programs = {
      locator: new Program(gl, LOCATOR_VS, LOCATOR_FS, 'atlas-locator'),
      jacobian: new Program(gl, FULLSCREEN_VS, JACOBIAN_FS, 'jacobian'),
      jacobianDown: new Program(gl, FULLSCREEN_VS, JACOBIAN_DOWN_FS, 'jacobian-down'),
      upsample: new Program(gl, FULLSCREEN_VS, UPSAMPLE_FS, 'upsample'),
      correct: new Program(gl, FULLSCREEN_VS, CORRECT_FS, 'correct'),
      unpack: new Program(gl, FULLSCREEN_VS, UNPACK_FS, 'unpack'),
      resolve: new Program(gl, FULLSCREEN_VS, RESOLVE_FS, 'resolve'),
      copy: new Program(gl, FULLSCREEN_VS, COPY_FS, 'copy'),
      seamResolve: new Program(gl, FULLSCREEN_VS, SEAM_RESOLVE_FS, 'seam-resolve'),
    };
    this.localUpdate = new LocalUpdate(gl, this.vao);
  }

  // Every program, the local runs' too (pipeline warm-up, checks).
  get allPrograms() {
    return { ...this.programs, ...this.localUpdate.programs };
  }

  // Every program checked (compiled and linked, or a GLError): waits for the driver where it is not done yet.
  checkPrograms() {
    this.guard.run(() => {
      for (const p of Object.values(this.allPrograms)) p.check();
    });
  }

  // Resolves once the driver has compiled and linked every program, looked at once per nextFrame() (the
  // compilation goes on beside the page: KHR_parallel_shader_compile), then checks them. Without that extension
  // (SwiftShader), a fence issued after the link commands says when the GPU process has come to them: asked
  // earlier, the check waited for it on the page's thread (~0.1-0.2 s at the first texture). inTurn: checked
  // a few a frame (checkInTurn), for work ahead of any texture; else in one task, as a texture asked for now.
  // A context lost meanwhile (dispose()) ends the wait unchecked.
  async programsReady(nextFrame = animationFrame, { inTurn = false } = {}) {
    const gl = this.gl, parallel = gl.getExtension('KHR_parallel_shader_compile');
    const fence = parallel || this.programsChecked ? null : gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.flush();
    const done = () =>
      parallel
        ? Object.values(this.allPrograms).every((p) => p.ready(parallel))
        : !fence || gl.getSyncParameter(fence, gl.SYNC_STATUS) === gl.SIGNALED;
    try {
      while (!gl.isContextLost() && !done()) await nextFrame();
    } finally {
      if (fence) gl.deleteSync(fence);
    }
    const lost = () => gl.isContextLost();
    if (inTurn) await checkInTurn(Object.values(this.allPrograms), nextFrame, { run: (f) => this.guard.run(f), lost });
    else if (!lost()) this.checkPrograms();
    this.programsChecked = true;
  }

  // Every program drawn once into a small target (pipeline-warm-up.js), once they are linked: software GL
  // compiles at the first draw. For the time before a first texture.
  async warmUpPipelines(nextFrame = animationFrame) {
    await this.programsReady(nextFrame, { inTurn: true });
    if (!this.gl.isContextLost()) this.guard.run(() => warmUpPipelines(this.gl, this.allPrograms, this.vao));
  }

  // The pyramid levels of the current atlas, finest first.
  get levels() {
    return this.atlas?.levels ?? [];
  }

  // tables: {size, levels: [{appearance, neighbourhood, candidates, projection, projectionOffset}], rgba8}
  setExemplar(tables) {
    if (tables === this.exemplarTables) return; // already on the GPU
    this.exemplarTables = tables;
    this.guard.run(() => {
      const exemplar = uploadExemplar(this.gl, tables);
      this.#disposeExemplar();
      this.exemplar = exemplar;
    });
  }

  // The mesh in the atlas: {resolution, positions, triangles, cornerUVs, neighbour?} (atlas-raster.js).
  setAtlas(spec) {
    for (const _ of this.setAtlasSteps(spec));
  }

  // The same a GPU allocation per step (AtlasRaster.allocate), for a caller that yields to the page between
  // them; the previous atlas stays until the last step.
  *setAtlasSteps(spec) {
    return yield* this.guard.steps(this.#atlasSteps(spec));
  }

  *#atlasSteps(spec) {
    this.programs.locator.check();
    const atlas = new AtlasRaster(this.gl, this.programs.locator, spec);
    let done = false;
    try {
      yield* atlas.allocate();
      done = true;
    } finally {
      if (!done) atlas.dispose();
    }
    this.#disposeAtlas();
    this.atlas = atlas;
  }

  // Runs the whole pyramid for the per-vertex field `vertexVectors` (3 per vertex, the core's vertexVectors), a
  // vector field's {whitney} or {cornerVectors} (9 per face: a line or cross field combed for the atlas; both
  // AtlasRaster.rasterSteps).
  // Returns {levels: [{size, stackLevel, spacing, ms}], jacobianMs, totalMs, ...}.
  synthesize(vertexVectors, options = {}) {
    return this.guard.run(() => {
      const steps = this.#steps(vertexVectors, options);
      for (let r = steps.next(); ; r = steps.next()) if (r.done) return r.value;
    });
  }

  // The same, yielding to the page between slices so that the view keeps rendering and input keeps working
  // while the GPU works through the pyramid (interleaved-run.js; run: its onProgress, cancelled, clock).
  // Resolves to null when cancelled (the previous result stays). Options as synthesize(), plus `finestLevel`
  // (0, or 1 for a quarter-cost preview that stops one level short: the result then lives at half the atlas
  // resolution, see resultLevel). A cancelled run is counted, with the share of its work it had done
  // (`cancelledRuns` in later runs' stats).
  async synthesizeInterleaved(vertexVectors, options = {}, run = {}) {
    this.pacer ??= new SlicePacer(this.gl);
    let done = 0;
    const onProgress = (f) => run.onProgress?.((done = f));
    const makeSteps = () => this.guard.steps(this.#steps(vertexVectors, options));
    const result = await interleavedRun(this.pacer, makeSteps, { ...run, onProgress });
    if (!result) this.cancelledRuns = { count: (this.cancelledRuns?.count ?? 0) + 1, lastAt: done };
    return result;
  }

  // Resolves once the GPU has done everything issued in this context so far (the view's frames included),
  // marking the wait as `phase` on `clock`: before big uploads, which would otherwise wait for it on the page's
  // thread (a 0.55 s texImage2D of the atlas's set-up behind a reopened model's frames).
  async drained(clock, phase) {
    this.pacer ??= new SlicePacer(this.gl);
    await this.pacer.drain(clock, nextTask, () => false, phase);
  }

  // Level L's quarters into its result, its texels made keeping their Jacobian; at the finest level with `seams`,
  // gutter texels next to seams take the coordinates across the seam (for the magnified rendering; m: the
  // exemplar's size). Returns the result.
  #unpack(L, seams, m) {
    const gl = this.gl;
    L.result.bindAsTarget();
    this.programs.unpack
      .use()
      .texture('uS0', L.quarters[0])
      .texture('uS1', L.quarters[1])
      .texture('uS2', L.quarters[2])
      .texture('uS3', L.quarters[3]);
    drawFullscreen(gl, this.vao);
    this.localUpdate.after(L);
    if (!seams) return L.result;
    L.spare2 ??= new FloatTarget(gl, L.size, L.size, null, { check: false }); // as the atlas's (atlas-raster.js)
    L.spare2.bindAsTarget();
    this.programs.seamResolve
      .use()
      .texture('uCoord', L.result)
      .texture('uJac', L.jac)
      .texture('uIndir', L.indirection)
      .float('uM', m);
    drawFullscreen(gl, this.vao);
    [L.result, L.spare2] = [L.spare2, L.result];
    return L.result;
  }

  *#steps(vertexVectors, options) {
    if (!this.exemplar) throw new GLError('no exemplar set');
    if (!this.atlas) throw new GLError('no atlas set');
    this.checkPrograms();
    const o = { ...DEFAULTS, ...options };
    const gl = this.gl;
    const t0 = performance.now();
    const { resolution } = this.atlas;
    const m = this.exemplar.size;
    const stackTop = this.exemplar.levels.length - 1;

    const finestLevel = Math.min(o.finestLevel ?? 0, this.levels.length - 1);
    let done = 0;
    const work = (texels) => ({ texels, progress: Math.min(1, (done += texels) / total) });
    // The field's upload, a slice per task: each slice ends the task (a frame between), progress unchanged.
    const raster = this.atlas.rasterSteps(this.programs, this.vao, vertexVectors, o);
    for (let r = raster.next(); ; r = raster.next()) {
      if (r.done) {
        this.magRef = r.value;
        break;
      }
      yield { texels: Infinity, progress: 0, field: true, phase: r.value };
    }
    // Total shading work: the Jacobian and per level 4 upsample quarters, 4 x passes correction quarters
    // (weighted x8: they read ~90 texels each) and the unpack.
    const jacobianWork = resolution * resolution;
    let total = jacobianWork;
    for (let k = finestLevel; k < this.levels.length; k++) total += this.levels[k].size ** 2 * (2 + 8 * o.passes);
    // The raster's draws (an atlas's map of faces the first time, the Jacobian's full-screen pass, the coarser
    // levels) waited for as a phase of their own: with software GL they take a bunny00 update tens of ms, which
    // the kernel's polls otherwise counted as waits between its slices. The progress shown meanwhile is the
    // Jacobian's share.
    const phase = 'field rasterized into the atlas (GPU)';
    yield { texels: Infinity, progress: jacobianWork / total, field: true, phase };
    // A local run's texels to make again (local-update.js), found on the GPU and waited for as the kernel's first
    // phase: where each level is drawn is read back then.
    const plan = levelPlan(o, this.levels.length, stackTop, finestLevel);
    if (this.localUpdate.begin(this.atlas, this.exemplar, o)) {
      this.localUpdate.find(this.levels, plan);
      yield { texels: Infinity, progress: jacobianWork / total, field: true, phase: 'kernel: texels to make again' };
    }
    this.localUpdate.readBlocks(this.levels, plan);
    yield work(jacobianWork);
    if (o.timing === 'levels') sync(gl, this.levels[0].jac);
    const tJac = performance.now();

    const levelStats = [];
    let parent = null;
    let tLevel = performance.now();
    const levelDone = ({ size }, { stackLevel, spacing, jitter }) => {
      const now = performance.now();
      levelStats.push({ size, stackLevel, spacing, jitter, ms: now - tLevel });
      tLevel = now;
    };
    for (const step of plan) {
      const L = this.levels[step.k];
      const E = this.exemplar.levels[step.stackLevel];
      // The texels to make again (a local run's; every texel otherwise). A level with none keeps its result.
      const redo = this.localUpdate.before(L);
      if (redo.local && redo.rects?.length === 0) {
        parent = L.result;
        levelDone(L, step);
        continue;
      }
      // Upsample (or initialise) each parity class into its quarter.
      for (let c = 0; c < 4; c++) upsampleClass(this, L, parent, step, c, o, redo);
      yield work(L.size * L.size);
      // Correction: passes x 4 sub-passes, one parity class each, in LH05's order (0,0), (1,1), (1,0), (0,1).
      for (let pass = 0; pass < o.passes; pass++) {
        for (const c of [0, 3, 1, 2]) {
          correctClass(this, L, E, step, c, o, redo);
          yield work(2 * L.size * L.size);
        }
      }
      parent = this.#unpack(L, step.k === finestLevel && o.seams, m);
      yield work(L.size * L.size);
      if (o.timing === 'levels') sync(gl, L.result);
      levelDone(L, step);
    }
    // Interleaved, the last slice is waited for like every other, so that the one-texel read that ends a
    // blocking run's timing finds the GPU done here.
    yield { texels: Infinity, progress: 1, gpuIdle: true };
    if (o.timing !== 'levels') sync(gl, parent);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const t1 = performance.now();
    this.result = this.levels[finestLevel].result;
    this.resultLevel = finestLevel;
    this.lastStats = {
      resolution: this.levels[finestLevel].size,
      atlasResolution: resolution,
      preview: finestLevel > 0,
      exemplarSize: m,
      featureScale: o.featureScale,
      magnitudeExponent: o.magnitudeExponent,
      passes: o.passes,
      subpasses: 4,
      seed: o.seed,
      ...this.localUpdate.summary(),
      raster: this.atlas.lastDraw, // {faces drawn again, whole, rects}
      cancelledRuns: this.cancelledRuns ?? { count: 0, lastAt: null },
      levels: levelStats,
      jacobianMs: tJac - t0,
      seams: o.seams ? this.atlas.seams : null,
      totalMs: t1 - t0,
      timing: o.timing,
    };
    return this.lastStats;
  }

  // The result copied for the view, and read back for files and tests (synthesis-readout.js).
  displayCopy() {
    return displayCopy(this);
  }

  readCoordinates() {
    return readCoordinates(this);
  }

  readJacobian(level) {
    return readJacobian(this, level);
  }

  readColour(options) {
    return readColour(this, options);
  }

  #disposeExemplar() {
    if (!this.exemplar) return;
    disposeExemplar(this.gl, this.exemplar);
    this.exemplar = null;
  }

  #disposeAtlas() {
    if (!this.atlas) return;
    this.atlas.dispose();
    this.atlas = null;
    this.result = null;
  }

  // Frees its GL objects; a context of its own is lost with them, the view's is left to the view.
  dispose() {
    this.guard.run(() => {
      this.#disposeExemplar();
      this.#disposeAtlas();
      for (const p of Object.values(this.allPrograms)) p.dispose();
      this.gl.deleteVertexArray(this.vao);
    });
    if (!this.guard.renderer) this.gl.getExtension('WEBGL_lose_context')?.loseContext();
  }
}
