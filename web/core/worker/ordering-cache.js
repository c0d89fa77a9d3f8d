// SPDX-License-Identifier: GPL-2.0-or-later
// The field's fill-reducing ordering kept per mesh in IndexedDB (kept-store.js), so that opening a model again
// skips ordering it: METIS on the mesh's vertex graph, most of the analysis before a big model's first field
// (armadillo-sub2 in the page: 2.4-3.9 s). An entry is keyed by the mesh's hash and the field's symmetry (the
// core's pendingOrderingKey) and holds the hash of the matrix pattern it was made for. The core ignores one whose
// pattern or size differs (stale), and refuses one of the other ordering kind or that is not a permutation
// (foreign, damaged); the load then orders as before, and the new ordering replaces the entry. Owned by
// load-ops.js.
import { KeptStore } from './kept-store.js';

const FORMAT = 1;

export class OrderingCache {
  constructor(options) {
    this.store = new KeptStore('tvf-ordering-cache', 'orderings', 4, options);
  }

  // Before commitModel: the ordering kept for the pending model, adopted. Resolves with {key, adopted}; never
  // fails a load (an optimization only).
  async adopt(designer) {
    try {
      const key = designer.pendingOrderingKey();
      const e = key ? await this.store.get(key) : null;
      const usable = e?.format === FORMAT && e.perm instanceof Int32Array && typeof e.pattern === 'string';
      const adopted = usable && designer.adoptPendingOrdering(e.perm, e.pattern, !!e.metis, !!e.dissection);
      return { key, adopted };
    } catch {
      return { key: '', adopted: false };
    }
  }

  // After it: the current model's ordering stored, unless its factorization reused the one adopted. The
  // promise resolves once stored (or not: a full or refused store costs the next opening only).
  keep(designer, key) {
    try {
      if (!key) return Promise.resolve();
      const k = JSON.parse(designer.keptOrderingJson());
      if (k.reused || !(k.n > 0)) return Promise.resolve();
      const perm = designer.keptOrderingPerm().slice();
      const { pattern, metis, dissection } = k;
      return this.store.put({ key, format: FORMAT, madeAt: Date.now(), perm, pattern, metis, dissection });
    } catch {
      return Promise.resolve();
    }
  }
}
