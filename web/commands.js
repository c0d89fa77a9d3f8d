// Design edits as command objects: apply() makes the change in the core (and the session's id mapping),
// revert() makes the inverse factor update. The history (history.js) stacks them. Both run inside the
// session's queue, one at a time; a failure leaves the session mirroring whatever the core then holds.
//
// Constraints carry page ids ("uids") that survive a delete and its undo, although the core hands out a
// fresh id whenever it re-adds the constraint.

const clone = (x) => structuredClone(x);

// Adds one constraint (a design-format spec). The first apply records the spec as the core stored it, so
// that a redo (or the undo of a later delete) re-adds exactly that.
export class AddConstraint {
  constructor(spec) {
    this.spec = spec;
    this.uid = null;
  }

  get label() {
    return `add ${this.spec.type} #${this.uid}`;
  }

  get result() {
    return this.uid;
  }

  async apply(s) {
    const reply = await s.call('add', [this.spec]);
    this.uid ??= s.nextUid++;
    s.constraints.set(this.uid, reply.value);
    this.spec = clone(s.specOf(this.uid));
  }

  async revert(s) {
    await s.call('remove', [s.coreIdOf(this.uid)]);
    s.constraints.delete(this.uid);
  }
}

export class RemoveConstraint {
  constructor(s, uid) {
    this.uid = Number(uid);
    this.spec = clone(s.specOf(this.uid));
  }

  get label() {
    return `delete ${this.spec.type} #${this.uid}`;
  }

  get result() {
    return true;
  }

  async apply(s) {
    await s.call('remove', [s.coreIdOf(this.uid)]);
    s.constraints.delete(this.uid);
  }

  async revert(s) {
    const reply = await s.call('add', [this.spec]);
    s.constraints.set(this.uid, reply.value);
  }
}

// Weight or strength of one constraint, with the value it replaces.
export class SetParameter {
  constructor(s, kind, uid, to) {
    this.kind = kind;
    this.uid = Number(uid);
    const spec = s.specOf(this.uid);
    if (spec[kind] === undefined) throw new Error(`a ${spec.type} has no ${kind}`);
    this.from = spec[kind];
    this.to = to;
  }

  get label() {
    return `${this.kind} of #${this.uid}`;
  }

  get result() {
    return true;
  }

  get changes() {
    return this.from !== this.to;
  }

  #set(s, value) {
    return s.call(this.kind === 'weight' ? 'setWeight' : 'setStrength', [s.coreIdOf(this.uid), value]);
  }

  apply(s) {
    return this.#set(s, this.to);
  }

  revert(s) {
    return this.#set(s, this.from);
  }
}

// Boundary condition or γ (each a refactorisation).
export class SetSetting {
  constructor(s, kind, to) {
    this.kind = kind; // 'boundary' | 'gamma'
    this.from = clone(s.settings()[kind]);
    this.to = to;
  }

  get label() {
    return this.kind === 'boundary' ? 'boundary condition' : 'γ';
  }

  get result() {
    return undefined;
  }

  get changes() {
    return true;
  }

  async apply(s) {
    await s.call(this.kind === 'boundary' ? 'setBoundary' : 'setGamma', [this.to]);
    this.to = clone(s.settings()[this.kind]); // as the core holds it
  }

  revert(s) {
    return s.call(this.kind === 'boundary' ? 'setBoundary' : 'setGamma', [this.from]);
  }
}

// Replaces the whole design (boundary, γ, constraints) with a document: Load and Clear. before/after are
// {design, uids}: the document and the page ids of its constraints in the core's order.
export class ReplaceDesign {
  constructor(s, design, label) {
    this.label = label;
    this.before = { design: clone(s.design), uids: s.uidsInCoreOrder() };
    this.after = { design, uids: null };
  }

  get result() {
    return undefined;
  }

  async #go(s, target, other) {
    try {
      await s.call('applyDesign', [target.design]);
    } catch (err) {
      s.mapDocument(other.uids); // the core put the previous design back, under fresh core ids
      throw err;
    }
    s.mapDocument(target.uids);
  }

  async apply(s) {
    await this.#go(s, this.after, this.before);
    s.selected = null;
    this.after = { design: clone(s.design), uids: s.uidsInCoreOrder() };
  }

  revert(s) {
    return this.#go(s, this.before, this.after);
  }
}
