// SPDX-License-Identifier: GPL-2.0-or-later
// A few entries kept in an IndexedDB object store of the worker's origin, the most recently made ones: the
// caches that let a model opened again skip work that depends on its mesh alone (the texture's atlas,
// synthesis/atlas-cache.js; the field's ordering, ordering-cache.js). Each entry is an object with `key` and
// `madeAt`. Without IndexedDB (node, a page that refuses it) every call does nothing. Imports nothing.
function request(req) {
  return new Promise((resolve, reject) => {
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error ?? new Error('IndexedDB request failed'));
  });
}

export class KeptStore {
  // dbName: the database (version 1, one object store `storeName` keyed by `key`); kept: how many entries.
  constructor(dbName, storeName, kept, { persistent = !!globalThis.indexedDB } = {}) {
    this.dbName = dbName;
    this.storeName = storeName;
    this.kept = kept;
    this.persistent = persistent;
    this.db = null;
  }

  // The entry under `key`, or null (none, or IndexedDB unavailable or failing).
  async get(key) {
    const db = await this.#open().catch(() => null);
    if (!db) return null;
    return request(db.transaction(this.storeName).objectStore(this.storeName).get(key)).catch(() => null);
  }

  // Stores `entry` (with its `key` and `madeAt`), dropping the least recently made past `kept`. Never throws: a
  // full or refused store costs the next opening only.
  async put(entry) {
    try {
      const db = await this.#open();
      if (!db) return;
      const store = db.transaction(this.storeName, 'readwrite').objectStore(this.storeName);
      await request(store.put(entry));
      // Reading every entry to find the oldest (tens of MB each for a big mesh's analysis) only when there is
      // one too many.
      if ((await request(store.count())) <= this.kept) return;
      const all = await request(store.getAll());
      all.sort((x, y) => y.madeAt - x.madeAt);
      for (const old of all.slice(this.kept)) await request(store.delete(old.key));
    } catch {
      // nothing kept
    }
  }

  async #open() {
    if (!this.persistent) return null;
    if (this.db) return this.db;
    const open = indexedDB.open(this.dbName, 1);
    open.onupgradeneeded = () => open.result.createObjectStore(this.storeName, { keyPath: 'key' });
    this.db = await request(open);
    this.db.onversionchange = () => {
      this.db.close();
      this.db = null;
    };
    return this.db;
  }
}
