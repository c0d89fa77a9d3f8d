// Durable autosave: designs kept in IndexedDB (no 5 MB localStorage cap), the last few versions per model and
// per tab, so that a full localStorage never loses an edit and two tabs editing one model both keep their
// designs. Every page load is a tab of its own, so the versions other tabs and earlier page loads left are kept
// up to a number per model (the newest), or a model edited over many days would gather versions without end,
// and each save would have to read them. A save reads the model's version ids only, never a design, so it costs
// the same however many are kept. A BroadcastChannel tells the other tabs of the same origin when a model's
// design was saved, so each tab can say that another one is editing the same model. One store per element (its
// autosave name).
//
// Records: {id, key, tab, savedAt, design}; key = element's autosave name + the model key (documents.js); ids
// grow with every save, so a model's ids in ascending order are its versions from the oldest.
import { isEmptyDesign, loadAutosave as loadMirror, saveAutosave as saveMirror } from './documents.js';

const DB_NAME = 'tvf-autosave';
const STORE = 'versions';
const CHANNEL = 'tvf-autosave';
export const VERSIONS_KEPT = 5; // per model and tab
// Per model, of the other tabs and earlier page loads: four other tabs' whole histories.
export const OTHER_VERSIONS_KEPT = 4 * VERSIONS_KEPT;

function request(req) {
  return new Promise((resolve, reject) => {
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error ?? new Error('IndexedDB request failed'));
  });
}

function done(tx) {
  return new Promise((resolve, reject) => {
    tx.oncomplete = () => resolve();
    tx.onabort = tx.onerror = () => reject(tx.error ?? new Error('IndexedDB transaction failed'));
  });
}

// A design whose numbers are all finite (JSON would turn NaN and Infinity into null and lose them). A walk over
// its values (JSON.stringify with a replacer took a 200-stroke design 11 ms under node). known: a WeakSet of
// the items of its lists (constraints, singularities) found finite before, which are not walked again and are
// added to it: an edit replaces the items it changes, so a save walks those alone.
export function finiteDesign(design, known = null) {
  for (const value of Object.values(design ?? {})) {
    if (!known || !Array.isArray(value)) {
      if (!finiteValue(value)) return false;
      continue;
    }
    for (const item of value) {
      if (known.has(item)) continue;
      if (!finiteValue(item)) return false;
      if (item !== null && typeof item === 'object') known.add(item);
    }
  }
  return true;
}

function finiteValue(value) {
  const stack = [value];
  while (stack.length) {
    const v = stack.pop();
    if (typeof v === 'number') {
      if (!Number.isFinite(v)) return false;
    } else if (Array.isArray(v)) {
      for (let i = 0; i < v.length; i++) stack.push(v[i]);
    } else if (v !== null && typeof v === 'object') {
      for (const x of Object.values(v)) stack.push(x);
    }
  }
  return true;
}

export class AutosaveStore {
  // name: the element's autosave attribute ('' on the app page); onOtherTab(key): another tab saved a design
  // of the same model.
  constructor(name, { onOtherTab = () => {} } = {}) {
    this.name = name ?? '';
    this.tab = `${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 8)}`;
    this.onOtherTab = onOtherTab;
    this.db = null;
    this.mine = new Map(); // record key → the ids this tab added, ascending
    this.finiteItems = new WeakSet(); // the designs' list items found finite (finiteDesign)
    this.channel = typeof BroadcastChannel === 'function' ? new BroadcastChannel(CHANNEL) : null;
    if (this.channel)
      this.channel.onmessage = ({ data }) => {
        if (data?.store === this.name && data.tab !== this.tab) this.onOtherTab(data.key);
      };
  }

  close() {
    this.channel?.close();
    this.db?.close();
  }

  async #open() {
    if (this.db) return this.db;
    if (!globalThis.indexedDB) throw new Error('IndexedDB is not available in this browser');
    const open = indexedDB.open(DB_NAME, 1);
    open.onupgradeneeded = () => {
      const store = open.result.createObjectStore(STORE, { keyPath: 'id', autoIncrement: true });
      store.createIndex('byKey', 'key');
    };
    this.db = await request(open);
    this.db.onversionchange = () => {
      this.db.close();
      this.db = null;
    };
    return this.db;
  }

  #key(modelKey) {
    return `${this.name}|${modelKey}`;
  }

  // Every version of a model, newest first: [{id, tab, savedAt, constraints, mine}].
  async versions(modelKey) {
    const records = await this.#records(modelKey);
    return records.map((r) => ({
      id: r.id,
      savedAt: r.savedAt,
      tab: r.tab,
      mine: r.tab === this.tab,
      constraints: r.design.constraints?.length ?? 0,
    }));
  }

  async #records(modelKey) {
    const db = await this.#open();
    const tx = db.transaction(STORE, 'readonly');
    const all = await request(tx.objectStore(STORE).index('byKey').getAll(this.#key(modelKey)));
    return all.sort((a, b) => b.id - a.id);
  }

  async version(id) {
    const db = await this.#open();
    const record = await request(db.transaction(STORE, 'readonly').objectStore(STORE).get(Number(id)));
    return record ?? null;
  }

  // The newest version ({design, savedAt, tab}) or null: the newer of IndexedDB's latest and the localStorage
  // mirror (written synchronously, so an edit made just before a reload is there even if the asynchronous
  // IndexedDB write was cut short; also what earlier builds saved).
  async load(modelKey) {
    let latest = null;
    try {
      [latest] = await this.#records(modelKey);
    } catch {
      // no IndexedDB: what localStorage holds is all there is
    }
    const mirror = loadMirror(this.name, modelKey);
    if (!latest) return mirror;
    return mirror && mirror.savedAt > latest.savedAt ? mirror : latest;
  }

  // Appends a version; trims this tab's versions of the model to VERSIONS_KEPT and the other tabs' to the newest
  // OTHER_VERSIONS_KEPT. Rejects (with the browser's reason) when the design could not be stored.
  async save(modelKey, design) {
    if (!finiteDesign(design, this.finiteItems))
      throw new Error('the design holds non-finite numbers and was not saved');
    const savedAt = new Date().toISOString();
    // The quick copy: fails quietly when localStorage is full (IndexedDB below is the durable one).
    saveMirror(this.name, modelKey, design, savedAt);
    const db = await this.#open();
    const key = this.#key(modelKey);
    const tx = db.transaction(STORE, 'readwrite');
    const store = tx.objectStore(STORE);
    const ids = await request(store.index('byKey').getAllKeys(key));
    // An empty design is saved too once the model has a version, whichever tab or page load saved it (a cleared
    // design must stay cleared, also when the design it cleared was restored from an earlier page load).
    if (!(isEmptyDesign(design) && !ids.length)) {
      const present = new Set(ids);
      const mine = (this.mine.get(key) ?? []).filter((id) => present.has(id));
      const own = new Set(mine);
      const others = ids.filter((id) => !own.has(id));
      const dropped = [...mine.slice(0, -(VERSIONS_KEPT - 1)), ...others.slice(0, -OTHER_VERSIONS_KEPT)];
      for (const id of dropped) store.delete(id);
      const kept = mine.slice(-(VERSIONS_KEPT - 1));
      // add() stores a structured clone of the record, made in the call: the design needs no copy of its own.
      request(store.add({ key, tab: this.tab, savedAt, design })).then(
        (id) => this.mine.set(key, [...kept, id]),
        () => {}, // the transaction fails with it (the deletions undone): done() reports it
      );
    }
    await done(tx);
    this.channel?.postMessage({ store: this.name, key: modelKey, tab: this.tab });
    return true;
  }
}
