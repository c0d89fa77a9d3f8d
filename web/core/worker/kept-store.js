// SPDX-License-Identifier: GPL-2.0-or-later
// A few entries kept in an IndexedDB object store of the worker's origin, the most recently made ones: the
// caches that let a model opened again skip work that depends on its mesh alone (the texture's atlas,
// synthesis/atlas-cache.js; the field's ordering, ordering-cache.js). Each entry is an object with `key` and
// `madeAt`. Without IndexedDB (node, a page that refuses it) every call does nothing. Imports nothing.

// With `blobs`, an entry's typed arrays of at least BLOB_BYTES go in as Blobs: IndexedDB serializes a value on
// the calling thread when it is put (a bunny00 atlas, 25 MB: 443 ms of the core worker's; as Blobs, 185 ms); a
// Blob is a handle whose bytes the browser stores on its own.
const BLOB_BYTES = 1 << 16;

const isPlain = (x) => x !== null && typeof x === 'object' && Object.getPrototypeOf(x) === Object.prototype;

// The entry as stored: its big typed arrays and ArrayBuffers (in plain objects and arrays, at any depth) as
// {keptBlob, type}.
export function storedForm(x) {
  if (ArrayBuffer.isView(x) && x.byteLength >= BLOB_BYTES) return { keptBlob: new Blob([x]), type: x.constructor.name };
  if (x instanceof ArrayBuffer && x.byteLength >= BLOB_BYTES) return { keptBlob: new Blob([x]), type: 'ArrayBuffer' };
  if (Array.isArray(x)) return x.map(storedForm);
  if (isPlain(x)) return Object.fromEntries(Object.entries(x).map(([k, v]) => [k, storedForm(v)]));
  return x;
}

// The entry as it was put: storedForm undone (the Blobs read back as typed arrays of their type).
export async function restoredForm(x) {
  if (isPlain(x) && x.keptBlob instanceof Blob) {
    const bytes = await x.keptBlob.arrayBuffer();
    return x.type === 'ArrayBuffer' ? bytes : new globalThis[x.type](bytes);
  }
  if (Array.isArray(x)) return Promise.all(x.map(restoredForm));
  if (!isPlain(x)) return x;
  const out = {};
  for (const [k, v] of Object.entries(x)) out[k] = await restoredForm(v);
  return out;
}

function request(req) {
  return new Promise((resolve, reject) => {
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error ?? new Error('IndexedDB request failed'));
  });
}

export class KeptStore {
  // dbName: the database (version 1, one object store `storeName` keyed by `key`); kept: how many entries;
  // blobs: big typed arrays stored as Blobs (storedForm).
  constructor(dbName, storeName, kept, { persistent = !!globalThis.indexedDB, blobs = false } = {}) {
    this.dbName = dbName;
    this.storeName = storeName;
    this.kept = kept;
    this.persistent = persistent;
    this.blobs = blobs;
    this.db = null;
  }

  // The entry under `key`, or null (none, or IndexedDB unavailable or failing).
  async get(key) {
    const db = await this.#open().catch(() => null);
    if (!db) return null;
    const entry = await request(db.transaction(this.storeName).objectStore(this.storeName).get(key)).catch(() => null);
    if (!entry || !this.blobs) return entry;
    return restoredForm(entry).catch(() => null); // a Blob's bytes gone (the site's data cleared): nothing kept
  }

  // Stores `entry` (with its `key` and `madeAt`), dropping the least recently made past `kept`. Never throws: a
  // full or refused store costs the next opening only.
  async put(entry) {
    // In a task of its own: IndexedDB serializes the value on this thread when it is put, and a caller's reply
    // (the op that made the entry, posted in this task's microtasks) goes first.
    await new Promise((resolve) => setTimeout(resolve, 0));
    try {
      const db = await this.#open();
      if (!db) return;
      const value = this.blobs ? storedForm(entry) : entry;
      const store = db.transaction(this.storeName, 'readwrite').objectStore(this.storeName);
      await request(store.put(value));
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
