// SPDX-License-Identifier: GPL-2.0-or-later
// The field's fill-reducing ordering kept per mesh in IndexedDB (kept-store.js), with the symbolic factor it
// gives (solver/kept_symbolic.h), so that opening a model again skips the whole analysis: METIS on the mesh's
// vertex graph, then the elimination tree, column counts and supernodes (armadillo-sub2 in the page: 2.4-3.9 s
// at its first opening, 0.5 s with the ordering alone kept). An entry is keyed by the mesh's hash and the
// field's symmetry (the core's pendingOrderingKey) and holds the hash of the matrix pattern it was made for.
// The core ignores one whose pattern or size differs (stale), refuses one of the other ordering kind or that is
// not a permutation, and analyzes anew where the symbolic factor does not fit the matrix (foreign, damaged);
// the new analysis then replaces the entry. Entries of the first format (the ordering alone) are taken and
// completed. Owned by load-ops.js.
import { KeptStore } from './kept-store.js';

const FORMAT = 2; // 1: the ordering alone

export class OrderingCache {
  constructor(options) {
    this.store = new KeptStore('tvf-ordering-cache', 'orderings', 4, { blobs: true, ...options });
  }

  // The entry kept for the pending model, read (IndexedDB: ~0.2 s for a big mesh's 40 MB, so started as soon
  // as the model is open, beside what else comes before its factorization; its arrays kept as Blobs, whose bytes
  // the browser reads off this thread). Resolves with {key, entry}.
  async find(designer) {
    try {
      const key = designer.pendingOrderingKey();
      return { key, entry: key ? await this.store.get(key) : null };
    } catch {
      return { key: '', entry: null };
    }
  }

  // Before commitModel: the entry found (find()'s promise) adopted, and the pending model asked to keep its
  // analysis for keep(). Resolves with {key, adopted}; never fails a load (an optimization only).
  async adopt(designer, found) {
    try {
      const { key, entry: e } = await found;
      const usable = (e?.format === 1 || e?.format === FORMAT) && e.perm instanceof Int32Array &&
        typeof e.pattern === 'string';
      const symbolic = usable && e.symbolic instanceof Uint8Array ? e.symbolic : null;
      const adopted = usable && designer.adoptPendingOrdering(e.perm, e.pattern, !!e.metis, !!e.dissection, symbolic);
      designer.keepPendingSymbolic(true);
      return { key, adopted };
    } catch {
      return { key: '', adopted: false };
    }
  }

  // After it: the current model's ordering and symbolic factor stored, where the core made something the entry
  // lacks (keptOrderingJson's n is 0 otherwise). The core's copies go in any case. The promise resolves once
  // stored (or not: a full or refused store costs the next opening only).
  keep(designer, key) {
    try {
      const k = JSON.parse(designer.keptOrderingJson());
      if (!key || !(k.n > 0)) return Promise.resolve();
      const perm = designer.keptOrderingPerm().slice();
      const symbolic = k.symbolic ? designer.keptSymbolicBytes().slice() : null;
      const { pattern, metis, dissection } = k;
      const entry = { key, format: FORMAT, madeAt: Date.now(), perm, pattern, metis, dissection, symbolic };
      return this.store.put(entry);
    } catch {
      return Promise.resolve();
    } finally {
      try {
        designer.releaseKeptOrdering();
      } catch {
        // a designer gone with its worker
      }
    }
  }
}
