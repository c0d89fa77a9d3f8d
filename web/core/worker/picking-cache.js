// SPDX-License-Identifier: GPL-2.0-or-later
// A big model's bounds tree (the page's picking BVH, geometry/mesh-bvh-transfer.js) kept per mesh in IndexedDB
// (kept-store.js), so that opening it again skips building it (armadillo-sub2: about 0.27 s, which the
// exact worker spends after the preview and before it factors). Keyed by the core's mesh hash; an
// entry whose tree does not fit the mesh (another count, a node or leaf out of range: foreign, damaged) is
// ignored, the tree built as before and the entry replaced. Owned by load-ops.js.
import { SERIALIZED_MESH_BVH_VERSION } from '../../geometry/mesh-bvh-transfer.js';
import { KeptStore } from './kept-store.js';

const FORMAT = 1;
const UINT32_PER_NODE = 8; // three-mesh-bvh's packed node: 6 float bounds, then offset / right child, count
const LEAF = 0xffff;

// Whether the packed nodes of one root are a tree over `faces` faces: each inner node's right child inside the
// buffer after its left one, each leaf's range inside the faces, every bound finite.
function validRoot(buffer, faces) {
  if (!(buffer instanceof ArrayBuffer) || !buffer.byteLength || buffer.byteLength % (4 * UINT32_PER_NODE)) return false;
  const u32 = new Uint32Array(buffer), u16 = new Uint16Array(buffer), f32 = new Float32Array(buffer);
  for (let n = 0; n < u32.length; n += UINT32_PER_NODE) {
    for (let k = 0; k < 6; k++) if (!Number.isFinite(f32[n + k])) return false;
    if (u16[2 * n + 15] === LEAF) {
      if (u32[n + 6] + u16[2 * n + 14] > faces) return false;
    } else {
      const right = n + u32[n + 6] * UINT32_PER_NODE;
      if (u32[n + 6] < 2 || right >= u32.length || u32[n + 7] > 2) return false;
    }
  }
  return true;
}

// Whether `entry` holds a bounds tree of a mesh of nV vertices and nF faces.
export function usableBVH(entry, nV, nF) {
  const bvh = entry?.format === FORMAT ? entry.bvh : null;
  if (bvh?.format !== SERIALIZED_MESH_BVH_VERSION || bvh.faces !== nF || bvh.vertices !== nV) return false;
  const indirect = bvh.indirectBuffer;
  if (!(indirect instanceof Uint32Array || indirect instanceof Uint16Array) || indirect.length !== nF) return false;
  if (!indirect.every((f) => f < nF) || !Array.isArray(bvh.roots) || !bvh.roots.length) return false;
  return bvh.roots.every((r) => validRoot(r, nF)) && bvh.boundingSphere?.length === 4;
}

export class PickingCache {
  constructor(options) {
    this.store = new KeptStore('tvf-picking-cache', 'trees', 2, { blobs: true, ...options });
  }

  // hash: the core's mesh hash (the float positions' bits and the triangles: what the tree is built on); nV, nF
  // the mesh's counts. Resolves with {key, bvh}: the tree kept for this mesh, or null. Never fails (an
  // optimization only).
  async find(hash, nV, nF) {
    try {
      const key = hash ? `${hash}-v${nV}-f${nF}` : '';
      const entry = key ? await this.store.get(key) : null;
      return { key, bvh: usableBVH(entry, nV, nF) ? entry.bvh : null };
    } catch {
      return { key: '', bvh: null };
    }
  }

  // bvh: pickingParts()'s, copied now (the page is sent the original's buffers). Resolves once stored (or not).
  keep(key, bvh) {
    if (!key) return Promise.resolve();
    const copy = { ...bvh, roots: bvh.roots.map((r) => r.slice(0)), indirectBuffer: bvh.indirectBuffer.slice() };
    return this.store.put({ key, format: FORMAT, madeAt: Date.now(), bvh: copy });
  }
}
