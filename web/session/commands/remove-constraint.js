// Removes one constraint; undo re-adds its spec under the same page id.
export class RemoveConstraint {
  static type = 'RemoveConstraint';

  // spec: the constraint as the core holds it (the session's table), kept for the undo.
  constructor(uid, spec) {
    this.uid = Number(uid);
    this.spec = spec;
  }

  static of(s, uid) {
    return new RemoveConstraint(uid, s.table.specOf(Number(uid)));
  }

  get label() {
    return `delete ${this.spec.type} #${this.uid}`;
  }

  get result() {
    return true;
  }

  async execute(s) {
    await s.call('remove', [s.table.coreIdOf(this.uid)]);
    s.table.uids.delete(this.uid);
  }

  async undo(s) {
    const reply = await s.call('add', [this.spec]);
    s.table.uids.set(this.uid, reply.value);
  }

  serialize() {
    return { type: RemoveConstraint.type, uid: this.uid, spec: structuredClone(this.spec) };
  }

  static deserialize({ uid, spec }) {
    return new RemoveConstraint(uid, structuredClone(spec));
  }
}
