// The autosave of one session (opt-in: `name` null keeps it off): after every completed change the design
// goes to the durable store (autosave-store.js, IndexedDB), in edit order, in the next task so that an edit's
// promise resolves with the new field drawn without waiting for it. A non-finite field is never saved (the
// core refuses to make one; this is the last guard). A failed save is shown, and stays shown until a save
// succeeds, so nobody believes unsaved work is safe.
import { AutosaveStore } from './autosave-store.js';

const nextTask = () => new Promise((resolve) => setTimeout(resolve, 0));

function allFinite(values) {
  for (let i = 0; i < values.length; i++) if (!Number.isFinite(values[i])) return false;
  return true;
}

export class Autosave {
  constructor(session, name) {
    this.session = session;
    this.name = name;
    this.store = null; // made on first use, for the current name
    this.chain = Promise.resolve(); // saves run one after the other, in edit order
    this.error = null; // the last save's failure, shown until a save succeeds
    this.otherTabNoticed = null;
  }

  // Computed once per field, before its arrays may go back to the worker (a preview's face vectors and
  // one-form, derived from its vertex vectors, may never have been made).
  checkFinite(field) {
    const arrays = field.oneForm ? [field.oneForm, field.faceVectors] : [field.vertexVectors, field.faceVectors];
    field.finite ??= arrays.every((a) => !a || allFinite(a));
    return field.finite;
  }

  #store() {
    if (this.name == null) return null;
    if (this.store?.name !== this.name) {
      this.store?.close();
      this.store = new AutosaveStore(this.name, { onOtherTab: (key) => this.#otherTab(key) });
    }
    return this.store;
  }

  // The saved design of a model, or null (autosave off, or nothing saved).
  load(modelKey) {
    return this.#store()?.load(modelKey) ?? null;
  }

  // Saves still queued (the last edit's starts in the next task) are written before the store closes.
  close() {
    const store = this.store;
    if (store) this.chain.then(() => store.close());
  }

  saveNow() {
    const s = this.session;
    const store = this.#store();
    if (!store || !s.modelKey) return;
    // The design as it is now, not a copy (a 200-stroke design's took 8–11 ms an edit): an edit replaces the
    // session's design and its specs (constraint-table.js), it never changes them in place.
    const key = s.modelKey, design = s.design, field = s.field;
    field.autosavePending = true;
    this.chain = this.chain.then(nextTask).then(() => {
      field.autosavePending = false;
      if (!this.checkFinite(field)) {
        if (!s.disposed) s.emit('banner', { message: 'The field is not finite; this state was not autosaved.' });
        return undefined;
      }
      return store.save(key, design).then(
        () => {
          s.perf.lastAutosave = { savedAt: Date.now(), constraints: design.constraints.length };
          if (this.error && !s.disposed) s.flash('Autosave works again; the design is saved.', 4000);
          this.error = null;
        },
        (err) => {
          this.error = err.message || String(err);
          const advice = 'the latest edits are not saved in this browser; use Save to download the design.';
          s.fail('autosave', new Error(`Autosave failed (${this.error}): ${advice}`));
        },
      );
    });
  }

  #otherTab(key) {
    const s = this.session;
    if (key !== s.modelKey || this.otherTabNoticed === key) return;
    this.otherTabNoticed = key;
    s.flash('This model is being edited in another tab too: both designs are kept as autosave versions.', 8000);
    s.emit('autosaveconflict', { model: s.modelName });
  }

  // Resolves when every autosave asked for so far has been written (or has failed and been reported).
  idle() {
    return this.chain;
  }

  async versions() {
    const store = this.#store();
    if (!store || !this.session.modelKey) return [];
    return store.versions(this.session.modelKey);
  }

  // Replaces the design with an autosaved version (undoable like loading a design).
  async restore(id) {
    const s = this.session;
    const record = await this.#store()?.version(id);
    if (!record || !record.key.endsWith(`|${s.modelKey}`)) throw new Error(`no autosaved version ${id} of this model`);
    return s.replaceDesign(record.design, 'restore autosave');
  }
}
