// The boundary condition or γ (each a refactorization), with the value it replaces.
export class SetSetting {
  static type = 'SetSetting';

  // kind: 'boundary' | 'gamma'; the values as the design format writes them.
  constructor(kind, from, to) {
    this.kind = kind;
    this.from = from;
    this.to = to;
  }

  static of(s, kind, to) {
    return new SetSetting(kind, structuredClone(s.table.settings()[kind]), to);
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

  #op() {
    return this.kind === 'boundary' ? 'setBoundary' : 'setGamma';
  }

  async execute(s) {
    await s.call(this.#op(), [this.to]);
    this.to = structuredClone(s.table.settings()[this.kind]); // as the core holds it
  }

  undo(s) {
    return s.call(this.#op(), [this.from]);
  }

  serialize() {
    return { type: SetSetting.type, kind: this.kind, from: structuredClone(this.from), to: structuredClone(this.to) };
  }

  static deserialize({ kind, from, to }) {
    return new SetSetting(kind, structuredClone(from), structuredClone(to));
  }
}
