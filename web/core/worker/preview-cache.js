// SPDX-License-Identifier: GPL-2.0-or-later
// A big model's preview parts kept per mesh in IndexedDB (kept-store.js), so that opening it again skips what
// depends on its mesh alone: the simplification and the map's search (preview/preview.js keptParts; armadillo-sub2
// in the page: about 0.9 s of the preview worker, which the exact worker waits for before it factors). An entry
// is keyed by the fine mesh's hash (mesh-key.js: an edited or another mesh has another key); one whose arrays do
// not fit the mesh or index out of range (foreign, damaged) is ignored, the preview made as before and the entry
// replaced. Owned by preview-ops.js.
import { KeptStore } from './kept-store.js';
import { meshKey } from './mesh-key.js';

const FORMAT = 1;

// Whether `entry` holds preview parts for a mesh of nV vertices: every array of its type and size, every index
// in range.
export function usablePreviewParts(entry, nV) {
  if (entry?.format !== FORMAT) return false;
  const { coarseTriangles: T, fineVertex, vertexFace, vertexBary, nearest } = entry;
  const ints = [T, fineVertex, vertexFace, nearest].every((a) => a instanceof Int32Array);
  if (!ints || !(vertexBary instanceof Float64Array)) return false;
  const nC = fineVertex.length, nCF = T.length / 3;
  if (!nC || T.length % 3 || vertexFace.length !== nV || nearest.length !== nV || vertexBary.length !== 3 * nV)
    return false;
  const within = (a, n) => a.every((x) => x >= 0 && x < n);
  return within(fineVertex, nV) && within(T, nC) && within(vertexFace, nCF) && within(nearest, nC) &&
    vertexBary.every(Number.isFinite);
}

export class PreviewCache {
  constructor(options) {
    this.store = new KeptStore('tvf-preview-cache', 'previews', 2, { blobs: true, ...options });
  }

  // fine: {positions, triangles}. Resolves with {key, kept}: kept is the parts kept for this mesh, or null.
  // Never fails (an optimization only).
  async find({ positions, triangles }) {
    try {
      const key = meshKey(positions, triangles);
      const entry = await this.store.get(key);
      return { key, kept: usablePreviewParts(entry, positions.length / 3) ? entry : null };
    } catch {
      return { key: '', kept: null };
    }
  }

  // parts: Preview.keptParts(). Resolves once stored (or not).
  keep(key, parts) {
    if (!key) return Promise.resolve();
    return this.store.put({ key, format: FORMAT, madeAt: Date.now(), ...parts });
  }
}
