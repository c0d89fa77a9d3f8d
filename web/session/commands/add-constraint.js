// Adds one constraint (a design-format spec, docs/design-format.md, passed through as it is: the core
// validates it). The first execution records the spec as the core stored it, so that a redo (or the undo of a
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

  request() {
    return { op: 'add', args: [this.spec] };
  }

  // The reply's design is the table's now: the core's new id gets the page id.
  applied(reply, table) {
    this.uid ??= table.nextUid++;
    table.uids.set(this.uid, reply.value);
    table.nextUid = Math.max(table.nextUid, this.uid + 1); // a deserialized command brings its own page id
    this.spec = table.specOf(this.uid);
  }

  undoRequest(table) {
    return { op: 'remove', args: [table.coreIdOf(this.uid)] };
  }

  undone(reply, table) {
    table.uids.delete(this.uid);
  }

  serialize() {
    return { type: AddConstraint.type, uid: this.uid, spec: structuredClone(this.spec) };
  }

  static deserialize({ spec, uid }) {
    return new AddConstraint(structuredClone(spec), uid);
  }
}
