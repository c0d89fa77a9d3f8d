// Removes one constraint; undo re-adds its spec under the same page id.
export class RemoveConstraint {
  static type = 'RemoveConstraint';

  // spec: the constraint as the core holds it (the session's table), kept for the undo.
  constructor(uid, spec) {
    this.uid = Number(uid);
    this.spec = spec;
  }

  static of(table, uid) {
    return new RemoveConstraint(uid, table.specOf(Number(uid)));
  }

  get label() {
    return `delete ${this.spec.type} #${this.uid}`;
  }

  get result() {
    return true;
  }

  request(table) {
    return { op: 'remove', args: [table.coreIdOf(this.uid)] };
  }

  applied(reply, table) {
    table.uids.delete(this.uid);
  }

  undoRequest() {
    return { op: 'add', args: [this.spec] };
  }

  undone(reply, table) {
    table.uids.set(this.uid, reply.value);
  }

  serialize() {
    return { type: RemoveConstraint.type, uid: this.uid, spec: structuredClone(this.spec) };
  }

  static deserialize({ uid, spec }) {
    return new RemoveConstraint(uid, structuredClone(spec));
  }
}
