// The weight or the strength of one constraint, with the value it replaces (each a rank-1 update).
export class SetParameter {
  static type = 'SetParameter';

  // kind: 'weight' | 'strength'.
  constructor(kind, uid, from, to) {
    this.kind = kind;
    this.uid = Number(uid);
    this.from = from;
    this.to = to;
  }

  static of(table, kind, uid, to) {
    const spec = table.specOf(Number(uid));
    if (spec[kind] === undefined) throw new Error(`a ${spec.type} has no ${kind}`);
    return new SetParameter(kind, uid, spec[kind], to);
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

  #set(table, value) {
    return { op: this.kind === 'weight' ? 'setWeight' : 'setStrength', args: [table.coreIdOf(this.uid), value] };
  }

  request(table) {
    return this.#set(table, this.to);
  }

  undoRequest(table) {
    return this.#set(table, this.from);
  }

  serialize() {
    return { type: SetParameter.type, kind: this.kind, uid: this.uid, from: this.from, to: this.to };
  }

  static deserialize({ kind, uid, from, to }) {
    return new SetParameter(kind, uid, from, to);
  }
}
