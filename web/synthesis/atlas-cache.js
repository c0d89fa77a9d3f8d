// SPDX-License-Identifier: GPL-2.0-or-later
// Prepared atlases (atlas-prepared.js) kept per mesh in the core's worker: the last one in memory, and every
// recent one in IndexedDB, so that a texture on the same mesh again (another resolution and back, the model
// opened again, the page reloaded) skips the charts and packing (seconds on a big model). An entry is keyed by
// a 64-bit hash of the exact input (positions, triangles, the model's own UVs, resolution, gutter) and holds
// that input's sizes and a format version: an entry whose sizes or version differ is stale or foreign and is
// ignored (and replaced once the atlas is made again).
import { KeptStore } from '../core/worker/kept-store.js';

const DB_NAME = 'tvf-atlas-cache';
const STORE = 'atlases';
const FORMAT = 3; // 2: the corners carry the gutter's quads; 3: UVs and frames per face, not corner data
const KEPT = 4; // entries in IndexedDB, the least recently made dropped first

// Two 32-bit multiplicative hashes over the bytes of each array (as 32-bit words, the tail byte by byte).
export function inputHash(arrays) {
  let a = 0x811c9dc5, b = 0x9e3779b9;
  const step = (w) => {
    a = Math.imul(a ^ w, 0x01000193);
    b = Math.imul(b ^ w, 0x85ebca6b) ^ (b >>> 13);
  };
  for (const arr of arrays) {
    if (!arr) {
      step(0x7fffffff);
      continue;
    }
    const bytes = new Uint8Array(arr.buffer, arr.byteOffset, arr.byteLength);
    const words = new Uint32Array(arr.buffer, arr.byteOffset, arr.byteOffset % 4 ? 0 : bytes.length >> 2);
    for (let i = 0; i < words.length; i++) step(words[i]);
    for (let i = 4 * words.length; i < bytes.length; i++) step(bytes[i]);
    step(bytes.length);
  }
  return (a >>> 0).toString(16).padStart(8, '0') + (b >>> 0).toString(16).padStart(8, '0');
}

// A prepared atlas's typed arrays copied (what the cache keeps while the caller transfers its own away).
function copied(atlas) {
  return {
    ...atlas,
    cornerUVs: atlas.cornerUVs.slice(),
    faceCharts: atlas.faceCharts?.slice(),
    corners: {
      ...atlas.corners,
      uv: atlas.corners.uv.slice(),
      frames: atlas.corners.frames.slice(),
      faceArea: atlas.corners.faceArea.slice(),
      gutter: copiedGutter(atlas.corners.gutter),
    },
    seams: { ...atlas.seams, map: atlas.seams.map.slice() },
  };
}

function copiedGutter({ uv, source, indices, ...rest }) {
  return { ...rest, uv: uv.slice(), source: source.slice(), indices: indices.slice() };
}

export class AtlasCache {
  constructor({ persistent = !!globalThis.indexedDB } = {}) {
    this.store = new KeptStore(DB_NAME, STORE, KEPT, { persistent, blobs: true });
    this.memory = null; // {key, sizes, atlas}
  }

  // The input's identity: {key, sizes}.
  static identify({ positions, triangles, cornerUVs }, { resolution, gutter }) {
    const sizes = [positions.length, triangles.length, cornerUVs?.length ?? -1, resolution, gutter, FORMAT];
    return { key: inputHash([positions, triangles, cornerUVs, Int32Array.from(sizes)]), sizes };
  }

  // The atlas kept for the input (a copy the caller may transfer), or null.
  async get(id) {
    return (await this.has(id)) ? copied(this.memory.atlas) : null;
  }

  // Whether an atlas is kept for the input, in memory or in IndexedDB (then brought into memory), copying
  // nothing: what an atlas prepared ahead looks up before making one.
  async has({ key, sizes }) {
    const same = (e) =>
      e && e.key === key && e.sizes?.length === sizes.length && e.sizes.every((n, i) => n === sizes[i]);
    if (same(this.memory)) return true;
    const entry = await this.store.get(key);
    if (!same(entry)) return false;
    this.memory = { ...entry, persisted: true };
    return true;
  }

  // Keeps a copy of `atlas`, made for the input identified by {key, sizes}: in memory at once, in IndexedDB
  // behind the caller (the promise returned; a full or refused store costs the next opening only) unless
  // `persist` is false (an atlas prepared ahead, which nobody asked for yet: persist() stores it once used).
  put({ key, sizes }, atlas, { persist = true } = {}) {
    const entry = { key, sizes, madeAt: Date.now(), atlas: copied(atlas) };
    this.memory = { ...entry, persisted: persist };
    return persist ? this.store.put(entry) : Promise.resolve();
  }

  // The atlas in memory stored in IndexedDB too, where it is not yet.
  persist() {
    const m = this.memory;
    if (!m || m.persisted) return Promise.resolve();
    m.persisted = true;
    const { persisted, ...entry } = m;
    return this.store.put(entry);
  }
}
