// SPDX-License-Identifier: GPL-2.0-or-later
// Exemplars for synthesis: the procedural ones of the core (stripes, scales, weave) and user images, analysed
// by the wasm core's ExemplarAnalysis (core/texture/) and cached per exemplar, as the flat tables the GPU
// synthesizer uploads.
//
// The analysis (~0.1-0.5 s for a 128^2 exemplar) runs in the element's core worker (analyzeExemplar there), so
// the page keeps drawing and taking input; the page keeps the cache.
import { scratchCanvas } from '../dom.js';

export const USER_EXEMPLAR_SIZE = 128;
export const PROCEDURAL_SIZE = 64;

// Copies everything out of wasm memory (the views die at the next call).
function tablesOf(analysis) {
  const levels = [];
  for (let s = 0; s < analysis.numLevels(); s++) {
    levels.push({
      colour: Float32Array.from(analysis.colour(s)),
      appearance: Float32Array.from(analysis.appearance(s)),
      neighbourhood: Float32Array.from(analysis.neighbourhood(s)),
      candidates: Float32Array.from(analysis.candidates(s)),
      projection: Float32Array.from(analysis.projection(s)),
      projectionOffset: Float32Array.from(analysis.projectionOffset(s)),
    });
  }
  return {
    size: analysis.size(),
    levels,
    rgba8: Uint8Array.from(analysis.rgba8()),
    stats: JSON.parse(analysis.statsJson()),
  };
}

// spec: {procedural, size, seed} or {rgba (Uint8Array of size*size*4), size}. Returns the tables: {size,
// levels, rgba8, stats}.
export function analyzeExemplar(Module, spec) {
  if (typeof Module?.ExemplarAnalysis !== 'function')
    throw new Error('this build of the core has no ExemplarAnalysis; rebuild it (npm run build:wasm)');
  const a = new Module.ExemplarAnalysis();
  try {
    const err =
      typeof spec.procedural === 'string'
        ? a.analyzeProcedural(spec.procedural, spec.size, spec.seed ?? 1)
        : a.analyzeRGBA8(spec.rgba, spec.size);
    if (err) throw new Error(`exemplar analysis: ${err}`);
    return tablesOf(a);
  } finally {
    a.delete();
  }
}

// The buffers of the tables, to transfer them between threads.
export function exemplarBuffers(tables) {
  return [tables.rgba8.buffer, ...tables.levels.flatMap((l) => Object.values(l).map((a) => a.buffer))];
}

export class ExemplarLibrary {
  // analyze(spec): resolves with the tables of analyzeExemplar (above), wherever it runs.
  constructor(analyze, { capacity = 6 } = {}) {
    this.analyze = analyze;
    this.cache = new Map(); // key -> tables, most recently used last
    this.pending = new Map(); // key -> the analysis under way: asked again meanwhile, it is awaited, not redone
    this.capacity = capacity;
  }

  async #cached(key, label, spec) {
    if (this.pending.has(key)) await this.pending.get(key).catch(() => {});
    if (this.cache.has(key)) {
      const t = this.cache.get(key);
      this.cache.delete(key);
      this.cache.set(key, t);
      return { tables: t, cached: true };
    }
    const analysis = Promise.resolve(this.analyze(spec));
    this.pending.set(key, analysis);
    try {
      const tables = { key, source: label, ...(await analysis) };
      this.cache.set(key, tables);
      while (this.cache.size > this.capacity) this.cache.delete(this.cache.keys().next().value);
      return { tables, cached: false };
    } finally {
      this.pending.delete(key);
    }
  }

  procedural(name, size = PROCEDURAL_SIZE, seed = 1) {
    if (name === 'brushed')
      return this.#cached(`procedural:${name}:${size}:${seed}`, name, { rgba: brushedRGBA8(size, seed), size });
    return this.#cached(`procedural:${name}:${size}:${seed}`, name, { procedural: name, size, seed });
  }

  // rgba: Uint8Array of size*size*4.
  image(rgba, size, label = 'image') {
    return this.#cached(`image:${size}:${contentHash(rgba)}`, label, { rgba, size });
  }
}

// FNV-1a over the bytes (sampled for large images): the cache key of user images.
export function contentHash(bytes) {
  let h = 0x811c9dc5;
  const step = Math.max(1, Math.floor(bytes.length / 65536));
  for (let i = 0; i < bytes.length; i += step) {
    h ^= bytes[i];
    h = Math.imul(h, 0x01000193);
  }
  return `${bytes.length}:${(h >>> 0).toString(16)}`;
}

function canvas2d(size) {
  return scratchCanvas(size, size).getContext('2d', { willReadFrequently: true });
}

// Any image source (URL string/URL, Blob/File, ImageData, ImageBitmap, HTMLImageElement/Canvas) as RGBA8 of
// size x size: the central square, resampled by the browser's smooth scaling. Returns {rgba, size, label}.
export async function imageToRGBA8(source, size = USER_EXEMPLAR_SIZE) {
  let bitmap, label = 'image';
  if (typeof source === 'string' || source instanceof URL) {
    const url = String(source);
    label = url.split('/').pop() || url;
    const res = await fetch(url);
    if (!res.ok) throw new Error(`could not fetch the exemplar ${url}: HTTP ${res.status}`);
    bitmap = await createImageBitmap(await res.blob());
  } else if (typeof Blob !== 'undefined' && source instanceof Blob) {
    label = source.name || 'image';
    try {
      bitmap = await createImageBitmap(source);
    } catch {
      throw new Error(`could not decode ${label} as an image (PNG or JPEG expected)`);
    }
  } else if (typeof ImageData !== 'undefined' && source instanceof ImageData) {
    bitmap = await createImageBitmap(source);
    label = 'ImageData';
  } else if (source && typeof source === 'object' && 'width' in source && 'height' in source) {
    bitmap = source;
  } else {
    throw new Error('setExemplar: expected a procedural name, a URL, a Blob/File, or ImageData');
  }
  const side = Math.min(bitmap.width, bitmap.height);
  if (!(side >= 4)) throw new Error(`the exemplar image is too small (${bitmap.width}x${bitmap.height})`);
  const ctx = canvas2d(size);
  ctx.imageSmoothingEnabled = true;
  ctx.imageSmoothingQuality = 'high';
  ctx.drawImage(bitmap, (bitmap.width - side) / 2, (bitmap.height - side) / 2, side, side, 0, 0, size, size);
  const rgba = new Uint8Array(ctx.getImageData(0, 0, size, size).data.buffer);
  return { rgba, size, label };
}

// 'brushed': brushed metal, fine streaks along the exemplar's x axis (the field's direction), for line fields
// (hair, grain, anisotropic metal), made here rather than in the core. Each row's brightness varies slowly along x
// (a few harmonics of the tile, so it tiles seamlessly) with its own random amplitudes and phases, rows mixed
// lightly with their neighbours; deterministic in seed. RGBA8, size × size.
export function brushedRGBA8(size, seed = 1) {
  let state = (seed * 2654435761) >>> 0 || 1;
  const rand = () => ((state = (Math.imul(state, 1664525) + 1013904223) >>> 0) / 4294967296);
  const H = 4;
  const rows = Array.from({ length: size }, () => ({
    base: rand() - 0.5,
    a: Array.from({ length: H }, () => rand() / (1 + rand())),
    p: Array.from({ length: H }, () => 2 * Math.PI * rand()),
  }));
  const raw = new Float64Array(size * size);
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++) {
      const r = rows[y];
      let v = r.base;
      for (let h = 0; h < H; h++) v += 0.35 * r.a[h] * Math.cos((2 * Math.PI * (h + 1) * x) / size + r.p[h]);
      raw[y * size + x] = v;
    }
  const out = new Uint8Array(4 * size * size);
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++) {
      const at = (dy) => raw[((y + dy + size) % size) * size + x];
      const v = Math.max(0, Math.min(1, 0.55 + 0.5 * (0.25 * at(-1) + 0.5 * at(0) + 0.25 * at(1))));
      out.set([Math.round(255 * v * 0.92), Math.round(255 * v * 0.95), Math.round(255 * v), 255], 4 * (y * size + x));
    }
  return out;
}
