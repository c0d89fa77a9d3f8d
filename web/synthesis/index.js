// SPDX-License-Identifier: GPL-2.0-or-later
// Field-guided texture synthesis on the page: exemplar analysis (wasm), GPU synthesis in the model's texture
// atlas (synthesizer.js), the textured model in the view (render.js), exports, and the window.tvf additions
// (docs/js-api.md, "Texture synthesis"). The page hands in a small adapter; see installSynthesis().
import { formatBench, runSynthesisBench } from './bench.js';
import { ExemplarLibrary, PROCEDURAL_SIZE, USER_EXEMPLAR_SIZE, imageToRGBA8 } from './exemplar.js';
import { encodeGlb } from './glb.js';
import { mountSynthesisPanel } from './panel.js';
import { TexturedModel } from './render.js';
import { DEFAULTS, Synthesizer } from './synthesizer.js';

const MAX_RESOLUTION = 2048;
const OPTION_KEYS = ['featureScale', 'magnitudeExponent', 'jitter', 'finestJitter', 'passes', 'kappa', 'seed', 'gutter', 'seams', 'timing'];
const CONTROLLER_KEYS = ['resolution', 'autoUpdate', 'interleave'];
// Field changes closer together than this count as quick edits: the texture follows them with a preview (one
// level short of the finest, a quarter of the work) and is synthesized in full once they stop for this long.
const QUICK_EDIT_MS = 400;
// Default feature size. Stripes read as following the field only where the field (and the surface it lies on)
// turns little over a stripe period; on a curved model the field turns with the surface, so the exemplar tile
// is sized from the model's curvature: tiles across sqrt(area) = TILES_PER_COMPLEXITY x the shape complexity
// (sqrt(area) x the area-mean |mean curvature|: 3.5 for a sphere, ~14 for the bunny, ~18 for homer, ~34 for a thin
// knotted tube), between MIN_TILES and MAX_TILES. Measured on exported GLBs (docs/texture-synthesis.md): on
// homer 6 tiles left 9.6° mean deviation, 12 tiles 5.8°, with the same synthesis.
const TILES_PER_COMPLEXITY = 0.66;
const MIN_TILES = 6;
const MAX_TILES = 16;
// Below this many atlas texels per exemplar pixel the synthesis resolves the exemplar's features with too few
// texels (a 16-pixel stripe period in fewer than 10 texels): the tile count gives way first.
const MIN_FEATURE_SCALE = 0.625;

// The atlas resolution a model gets by default: enough texels per face for the Jacobian to vary smoothly and for
// a stripe period to span ≥ 10 texels at the default feature size (≈ 16 texels per face at ~60 % coverage),
// between 256² and 1024².
export function defaultResolution(numFaces) {
  const want = Math.sqrt((numFaces * 16) / 0.6);
  let r = 256;
  while (r < want && r < 1024) r *= 2;
  return r;
}

// sqrt(area) x the area-mean |mean curvature|, from dihedral angles: sum over interior edges of |theta_e| l_e,
// over 2 x area (1 / radius on a sphere, so a sphere scores sqrt(4 pi) = 3.5). Scale-free.
export function shapeComplexity(positions, triangles) {
  const nF = triangles.length / 3;
  const normals = new Float64Array(3 * nF);
  let area = 0;
  for (let f = 0; f < nF; f++) {
    const a = 3 * triangles[3 * f], b = 3 * triangles[3 * f + 1], c = 3 * triangles[3 * f + 2];
    const e1 = [positions[b] - positions[a], positions[b + 1] - positions[a + 1], positions[b + 2] - positions[a + 2]];
    const e2 = [positions[c] - positions[a], positions[c + 1] - positions[a + 1], positions[c + 2] - positions[a + 2]];
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const l = Math.hypot(n[0], n[1], n[2]);
    area += l / 2;
    if (l > 0) normals.set([n[0] / l, n[1] / l, n[2] / l], 3 * f);
  }
  const nV = positions.length / 3;
  const firstFace = new Map(); // edge (i < j) as i * nV + j -> the first face seen on it
  let bend = 0;
  for (let f = 0; f < nF; f++)
    for (let k = 0; k < 3; k++) {
      const i = triangles[3 * f + k], j = triangles[3 * f + ((k + 1) % 3)];
      const key = i < j ? i * nV + j : j * nV + i;
      const g = firstFace.get(key);
      if (g === undefined) {
        firstFace.set(key, f);
        continue;
      }
      const d = normals[3 * f] * normals[3 * g] + normals[3 * f + 1] * normals[3 * g + 1] + normals[3 * f + 2] * normals[3 * g + 2];
      const len = Math.hypot(positions[3 * i] - positions[3 * j], positions[3 * i + 1] - positions[3 * j + 1], positions[3 * i + 2] - positions[3 * j + 2]);
      bend += Math.acos(Math.min(1, Math.max(-1, d))) * len;
    }
  return area > 0 ? (bend / (2 * area)) * Math.sqrt(area) : 0;
}

// The feature scale (atlas texels per exemplar pixel at the atlas's mean density) that makes one exemplar tile
// span sqrt(area) / tiles on the surface, tiles from the shape complexity (above): tile length
// m * featureScale * texelLength, with texelLength = sqrt(area / coverage) / R.
export function defaultFeatureScale(resolution, coverage, exemplarSize, complexity = MIN_TILES / TILES_PER_COMPLEXITY) {
  const tiles = Math.min(MAX_TILES, Math.max(MIN_TILES, TILES_PER_COMPLEXITY * complexity));
  const fs = (resolution * Math.sqrt(Math.max(coverage, 0.05))) / (tiles * exemplarSize);
  return Math.min(8, Math.max(MIN_FEATURE_SCALE, fs));
}

// RGBA8 (row 0 = bottom, as read from WebGL) to a PNG Blob, rows flipped so that v = 1 is the image's top row
// (the glTF convention: UV (u, v) shows pixel (u W, (1 - v) H)).
async function rgbaToPngBlob(pixels, width, height) {
  const flipped = new Uint8ClampedArray(pixels.length);
  const row = 4 * width;
  for (let y = 0; y < height; y++) flipped.set(pixels.subarray((height - 1 - y) * row, (height - y) * row), y * row);
  const image = new ImageData(flipped, width, height);
  if (typeof OffscreenCanvas !== 'undefined') {
    const c = new OffscreenCanvas(width, height);
    c.getContext('2d').putImageData(image, 0, 0);
    return c.convertToBlob({ type: 'image/png' });
  }
  const c = Object.assign(document.createElement('canvas'), { width, height });
  c.getContext('2d').putImageData(image, 0, 0);
  return new Promise((resolve) => c.toBlob(resolve, 'image/png'));
}

export class SynthesisController {
  // viewer: the page's Viewer (scene, surfaceMesh, requestRender).
  // getModel(): {key, name, positions, triangles, cornerUVs | null, vertexVectors} of the current model and field.
  // computeAtlas(model, {resolution, gutter}) and analyzeExemplar(spec): chooseAtlas (atlas.js) and
  // analyzeExemplar (exemplar.js) off the page's thread (the element's core worker), resolving with their results.
  constructor({ viewer, getModel, computeAtlas, analyzeExemplar, onChange = () => {}, onError = () => {} }) {
    this.computeAtlas = computeAtlas;
    this.viewer = viewer;
    this.getModel = getModel;
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
    this.stale = false; // the field changed since the texture was made (autoUpdate off)
    this.runToken = 0;
    this.lastFieldChange = -Infinity;
    this.settleTimer = null;
    this.active = false; // a texture is shown and follows field changes
    this.stats = null;
    this.queue = Promise.resolve();
    this.pendingField = false;
  }

  #exclusive(fn) {
    const run = this.queue.then(fn);
    this.queue = run.catch(() => {});
    return run;
  }

  #ensureSynth() {
    if (!this.synth) this.synth = new Synthesizer();
    return this.synth;
  }

  proceduralNames() {
    return ['stripes', 'scales', 'weave'];
  }

  // src: a procedural name ('stripes' | 'scales' | 'weave'), {procedural, size, seed}, a URL (string or URL),
  // a Blob/File (PNG or JPEG), ImageData or an ImageBitmap. Options: {size} for images (power of two, default 128).
  setExemplar(src, { size } = {}) {
    return this.#exclusive(async () => {
      const t0 = performance.now();
      let result, label;
      const spec = typeof src === 'string' && this.proceduralNames().includes(src) ? { procedural: src } : src;
      if (spec && typeof spec === 'object' && typeof spec.procedural === 'string') {
        const n = spec.size ?? PROCEDURAL_SIZE;
        result = await this.library.procedural(spec.procedural, n, spec.seed ?? 1);
        label = spec.procedural;
      } else {
        const n = size ?? USER_EXEMPLAR_SIZE;
        if (!Number.isInteger(n) || n < 16 || n > 256 || (n & (n - 1))) throw new Error(`exemplar size must be a power of two in [16, 256] (got ${n})`);
        const img = await imageToRGBA8(spec, n);
        result = await this.library.image(img.rgba, img.size, img.label);
        label = img.label;
      }
      this.exemplar = { tables: result.tables, label, cached: result.cached, analysisMs: performance.now() - t0 };
      this.#ensureSynth().setExemplar(result.tables);
      this.onChange();
      if (this.active) await this.#run();
      return this.exemplarInfo();
    });
  }

  exemplarInfo() {
    if (!this.exemplar) return null;
    const { tables, label, cached, analysisMs } = this.exemplar;
    return { label, size: tables.size, levels: tables.levels.length, cached, analysisMs, analysis: tables.stats };
  }

  // The atlas for the current model at `resolution` (cached per model and resolution).
  async #atlasFor(model, resolution) {
    const gutter = this.options.gutter ?? DEFAULTS.gutter;
    if (this.atlas && this.atlas.key === model.key && this.atlas.resolution === resolution && this.atlas.gutter === gutter) return this.atlas;
    // Generating an atlas takes up to seconds on a big model: the element's core worker does it, so the page
    // keeps drawing and taking input.
    const chosen = await this.computeAtlas(model, { resolution, gutter });
    this.atlas = { key: model.key, resolution, gutter, ...chosen };
    this.#ensureSynth().setAtlas({ resolution, positions: model.positions, triangles: model.triangles, cornerUVs: this.atlas.cornerUVs });
    if (!this.render) this.render = new TexturedModel(this.viewer);
    this.render.setGeometry(model.positions, model.triangles, this.atlas.cornerUVs);
    return this.atlas;
  }

  // Synthesizes for the current field and shows the result; later field changes resynthesize with the same
  // options until clearTexture(). Options: resolution (power of two, default 256) and the synthesizer's
  // (featureScale, magnitudeExponent, jitter, passes, kappa, seed, gutter, timing).
  synthesize(options = {}) {
    return this.#exclusive(async () => {
      if (options.resolution !== undefined && options.resolution !== 'auto') {
        const r = options.resolution;
        if (!Number.isInteger(r) || r < 16 || r > MAX_RESOLUTION || (r & (r - 1))) throw new Error(`resolution must be 'auto' or a power of two in [16, ${MAX_RESOLUTION}] (got ${r})`);
      }
      for (const k of Object.keys(options)) {
        if (!CONTROLLER_KEYS.includes(k) && !OPTION_KEYS.includes(k)) throw new Error(`unknown synthesis option '${k}'`);
      }
      if (options.featureScale !== undefined && options.featureScale !== 'auto' && !(options.featureScale > 0)) throw new Error("featureScale must be 'auto' or > 0");
      this.options = { ...this.options, ...options };
      if (!this.exemplar) {
        const r = await this.library.procedural('stripes', PROCEDURAL_SIZE, 1);
        this.exemplar = { tables: r.tables, label: 'stripes', cached: r.cached, analysisMs: 0 };
        this.#ensureSynth().setExemplar(r.tables);
      }
      this.active = true;
      return this.#run();
    });
  }

  // One synthesis for the current model and field. preview: stop one level short of the finest (quick edits).
  async #run({ preview = false } = {}) {
    const model = this.getModel();
    if (!model) throw new Error('no model loaded');
    const token = ++this.runToken;
    const t0 = performance.now();
    const resolution = this.options.resolution === 'auto' ? defaultResolution(model.triangles.length / 3) : this.options.resolution;
    const atlas = await this.#atlasFor(model, resolution);
    const tAtlas = performance.now() - t0;
    const synthOptions = {};
    for (const k of OPTION_KEYS) if (this.options[k] !== undefined) synthOptions[k] = this.options[k];
    const coverage = atlas.stats.coverage ?? atlas.stats.check?.coverage ?? 0.5;
    if (synthOptions.featureScale === 'auto') {
      atlas.complexity ??= shapeComplexity(model.positions, model.triangles);
      synthOptions.featureScale = defaultFeatureScale(atlas.resolution, coverage, this.exemplar.tables.size, atlas.complexity);
    }
    if (preview) synthOptions.finestLevel = 1;
    let s;
    if (this.options.interleave) {
      let shown = -1;
      this.progress = { fraction: 0, preview };
      this.onChange();
      s = await this.synth.synthesizeInterleaved(model.vertexVectors, { ...synthOptions, timing: 'total' }, {
        cancelled: () => token !== this.runToken,
        onProgress: (f) => {
          this.progress = { fraction: f, preview };
          if (Math.floor(100 * f) !== shown) (shown = Math.floor(100 * f)), this.onChange();
        },
      });
      this.progress = null;
      if (!s) return this.synthesisStats(); // superseded by a newer field change
    } else {
      s = this.synth.synthesize(model.vertexVectors, synthOptions);
    }
    const t1 = performance.now();
    const coords = this.synth.readCoordinates();
    const jacobian = this.synth.readJacobian();
    this.render.setTexture({ resolution: s.resolution, coords, jacobian, exemplar: this.exemplar.tables.rgba8, exemplarSize: this.exemplar.tables.size });
    this.viewer.requestRender?.();
    this.stale = false;
    this.stats = {
      ...s,
      autoFeatureScale: this.options.featureScale === 'auto',
      shapeComplexity: atlas.complexity ?? null,
      autoResolution: this.options.resolution === 'auto',
      exemplar: this.exemplarInfo(),
      atlas: { source: atlas.source, reason: atlas.reason, resolution: atlas.resolution, ...atlas.stats, ms: tAtlas },
      readbackMs: performance.now() - t1,
      wallMs: performance.now() - t0,
      fieldVersion: model.fieldVersion,
    };
    this.lastFieldVersion = model.fieldVersion;
    this.onChange();
    return structuredClone(this.stats);
  }

  // The field changed: resynthesize while a texture is shown (autoUpdate), coalescing bursts of changes into
  // one run and cancelling a run the change makes stale. Changes that come quickly (or with interactive: true,
  // e.g. while a stroke is dragged) get a preview, and a full synthesis once they stop.
  fieldChanged({ interactive = false } = {}) {
    if (!this.active) return;
    const model = this.getModel();
    if (model && this.atlas && model.fieldVersion !== undefined && model.fieldVersion === this.lastFieldVersion) return;
    if (!this.options.autoUpdate) {
      this.stale = true;
      this.onChange();
      return;
    }
    const now = performance.now();
    const quick = interactive || now - this.lastFieldChange < QUICK_EDIT_MS;
    this.lastFieldChange = now;
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

  #schedule(preview) {
    if (this.pendingField) {
      this.pendingPreview &&= preview;
      return;
    }
    this.pendingField = true;
    this.pendingPreview = preview;
    setTimeout(() => {
      this.pendingField = false;
      const p = this.pendingPreview;
      this.#exclusive(() => (this.active ? this.#run({ preview: p }) : null)).catch((err) => this.onError(err));
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
  async whenIdle() {
    for (;;) {
      await this.queue;
      if (!this.pendingField && !this.settleTimer) return this.synthesisStats();
      await new Promise((r) => setTimeout(r, 5));
    }
  }

  clearTexture() {
    return this.#exclusive(() => {
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

  #requireResult() {
    if (!this.stats || !this.synth?.result) throw new Error('nothing synthesized yet: call synthesize() first');
  }

  // Output pixels per atlas texel for an export: {resolution} (output size, a power of two in [16, 8192]) or
  // {magnification} (1..8).
  #exportMagnification({ magnification, resolution }, fallback) {
    if (resolution !== undefined) {
      if (!Number.isInteger(resolution) || resolution < 16 || resolution > 8192 || (resolution & (resolution - 1))) throw new Error(`export resolution must be a power of two in [16, 8192] (got ${resolution})`);
      return resolution / this.stats.resolution;
    }
    const m = magnification ?? fallback;
    if (!(m >= 1 && m <= 8)) throw new Error(`magnification must be in [1, 8] (got ${m})`);
    return m;
  }

  // The synthesized texture as a PNG Blob, rendered as the page renders it (magnification: the four nearest
  // texels' patches blended) at {resolution} pixels per side or {magnification} pixels per atlas texel.
  exportTexturePNG(options = {}) {
    return this.#exclusive(async () => {
      this.#requireResult();
      const magnification = this.#exportMagnification(options, 1);
      const { width, height, pixels } = this.synth.readColour({ magnification, nearest: false });
      return rgbaToPngBlob(pixels, width, height);
    });
  }

  // The model with the atlas UVs and the synthesized texture embedded (binary glTF), as a Blob; the image at
  // {resolution} or {magnification} (default 2 pixels per atlas texel), rendered as exportTexturePNG.
  exportGLB(options = {}) {
    return this.#exclusive(async () => {
      this.#requireResult();
      const model = this.getModel();
      const magnification = this.#exportMagnification(options, 2);
      const { width, height, pixels } = this.synth.readColour({ magnification, nearest: false });
      const png = new Uint8Array(await (await rgbaToPngBlob(pixels, width, height)).arrayBuffer());
      const nF = model.triangles.length / 3;
      const positions = new Float32Array(9 * nF), uvs = new Float32Array(6 * nF), indices = new Uint32Array(3 * nF);
      const uv = this.atlas.cornerUVs;
      for (let f = 0; f < nF; f++)
        for (let k = 0; k < 3; k++) {
          const v = model.triangles[3 * f + k];
          for (let c = 0; c < 3; c++) positions[9 * f + 3 * k + c] = model.positions[3 * v + c];
          uvs[6 * f + 2 * k] = uv[6 * f + 2 * k];
          uvs[6 * f + 2 * k + 1] = 1 - uv[6 * f + 2 * k + 1]; // glTF: v down the image
          indices[3 * f + k] = 3 * f + k;
        }
      const glb = encodeGlb({ positions, uvs, indices, png, name: model.name || 'model', generator: 'tangent-field-designer texture synthesis' });
      return new Blob([glb], { type: 'model/gltf-binary' });
    });
  }

  // For tests and tools: the raw result (copies). coords/jacobian: RGBA32F per atlas texel; colour: RGBA8
  // (nearest exemplar pixel); exemplar: RGBA8; rows start at v = 0.
  readback() {
    return this.#exclusive(async () => {
      this.#requireResult();
      const r = this.stats.resolution;
      return {
        resolution: r,
        coords: this.synth.readCoordinates(),
        jacobian: this.synth.readJacobian(),
        colour: this.synth.readColour({ nearest: true }).pixels,
        exemplar: this.exemplar.tables.rgba8.slice(),
        exemplarSize: this.exemplar.tables.size,
        cornerUVs: this.atlas.cornerUVs.slice(),
      };
    });
  }

  // The synthesis benchmark (bench.js) on a synthesizer of its own.
  bench(options = {}) {
    return this.#exclusive(async () => {
      return runSynthesisBench(this.library, options);
    });
  }

  // The element left the page: free the synthesis WebGL context and the textured mesh now.
  dispose() {
    this.active = false;
    this.render?.dispose();
    this.render = null;
    this.synth?.dispose();
    this.synth = null;
  }

  // Milliseconds of one plain full-screen pass at size^2 on the synthesis context (the bench's unit).
  plainPassMs(size, repeats) {
    return this.#ensureSynth().plainPassMs(size, repeats);
  }
}

// Adds the texture-synthesis calls to window.tvf (docs/js-api.md). `deps` as for SynthesisController.
export function installSynthesis(tvf, deps) {
  const c = new SynthesisController(deps);
  Object.assign(tvf, {
    setExemplar: (src, opts) => c.setExemplar(src, opts),
    synthesize: (opts) => c.synthesize(opts),
    exportTexturePNG: (opts) => c.exportTexturePNG(opts),
    exportGLB: (opts) => c.exportGLB(opts),
    synthesisStats: () => c.synthesisStats(),
    clearTexture: () => c.clearTexture(),
    exemplarInfo: () => c.exemplarInfo(),
    synthesisReadback: () => c.readback(),
    synthesisIdle: () => c.whenIdle(),
    synthesisProgress: () => (c.progress ? { ...c.progress } : null),
    setTextureAutoUpdate: (on) => c.setAutoUpdate(on),
    synthesisBench: (opts) => c.bench(opts),
  });
  return c;
}

// ?bench=1[&sizes=256,512] on the app page: once it is ready, runs the benchmark, shows it over the view and
// leaves the result in window.tvfBench (scripts/bench-web.mjs reads it from there).
function scheduleBench(tvf, controller, viewport) {
  const params = new URLSearchParams(globalThis.location?.search ?? '');
  if (params.get('bench') !== '1') return;
  const sizes = (params.get('sizes') || '256,512,1024').split(',').map(Number).filter((n) => n > 0);
  // A microtask: tvf.ready is assigned once the page's start-up code returns.
  Promise.resolve()
    .then(() => tvf.ready)
    .then(() => controller.bench({ sizes }))
    .then((result) => {
      window.tvfBench = result;
      const pre = document.createElement('pre');
      pre.id = 'synthesis-bench';
      pre.style.cssText = 'position:absolute;left:220px;bottom:40px;z-index:10;background:#000c;color:#dfe;padding:8px;font:12px monospace;white-space:pre-wrap;max-width:70vw';
      pre.textContent = formatBench(result);
      viewport?.append(pre);
      console.log(pre.textContent);
    })
    .catch((err) => {
      window.tvfBench = { error: err?.message || String(err) };
    });
}

// Everything a designer needs in one call: the texture calls added to `api` (the element forwards its texture
// methods there), plus the "Texture" panel in `panel` (e.g. the side panel) when given, and the benchmark when
// `bench` (the app page; `ready` is the element). Returns the controller (fieldChanged(), modelChanged(), dispose()).
export function setupSynthesis(api, { panel = null, bench = null, ...deps }) {
  const controller = installSynthesis(api, deps);
  if (bench) scheduleBench(bench, controller, panel?.parentElement);
  if (panel) {
    const view = mountSynthesisPanel(controller, panel, { onError: deps.onError, modelName: () => (deps.getModel()?.name ?? 'model').replace(/\.[^.]*$/, '') });
    const notify = controller.onChange;
    controller.onChange = () => (notify(), view.refresh());
  }
  return controller;
}
