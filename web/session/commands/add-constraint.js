// Adds one constraint (a design-format spec, docs/design-format.md, passed through as it is: the core
// validates it). The first execute records the spec as the core stored it, so that a redo (or the undo of a
// later delete) re-adds exactly that. Page ids ("uids") survive a delete and its undo, although the core
// hands out a fresh id whenever it re-adds the constraint.
export class AddConstraint {
  static type = 'AddConstraint';

  constructor(spec, uid = null) {
    this.spec = spec;
    this.uid = uid;
  }

  get label() {
    return `add ${this.spec.type} #${this.uid}`;
  }

  get result() {
    return this.uid;
  }

  async execute(s) {
    const reply = await s.call('add', [this.spec]);
    this.uid ??= s.table.nextUid++;
    s.table.uids.set(this.uid, reply.value);
    s.table.nextUid = Math.max(s.table.nextUid, this.uid + 1); // a deserialized command brings its own page id
    this.spec = s.table.specOf(this.uid);
  }

  async undo(s) {
    await s.call('remove', [s.table.coreIdOf(this.uid)]);
    s.table.uids.delete(this.uid);
  }

  serialize() {
    return { type: AddConstraint.type, uid: this.uid, spec: structuredClone(this.spec) };
  }

  static deserialize({ spec, uid }) {
    return new AddConstraint(structuredClone(spec), uid);
  }
}
