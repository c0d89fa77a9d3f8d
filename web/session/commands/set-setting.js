// The boundary condition, γ or the curvature alignment, with the value it replaces (each a refactorization or a
// new right-hand side). The symmetry N has a command of its own (set-symmetry.js): it may take constraints with it.
const OPS = { boundary: 'setBoundary', gamma: 'setGamma', curvatureAlignment: 'setCurvatureAlignment' };
const LABELS = { boundary: 'boundary condition', gamma: 'γ', curvatureAlignment: 'curvature alignment' };

export class SetSetting {
  static type = 'SetSetting';

  // kind: 'boundary' | 'gamma' | 'curvatureAlignment'; the values as the design format writes them.
  constructor(kind, from, to) {
    this.kind = kind;
    this.from = from;
    this.to = to;
  }

  static of(s, kind, to) {
    if (!OPS[kind]) throw new Error(`unknown setting ${JSON.stringify(kind)} (settings: ${Object.keys(OPS).join(', ')}, symmetry)`);
    return new SetSetting(kind, structuredClone(s.table.settings()[kind]), to);
  }

  get label() {
    return LABELS[this.kind];
  }

  get result() {
    return undefined;
  }

  get changes() {
    return true;
  }

  async execute(s) {
    await s.call(OPS[this.kind], [this.to]);
    this.to = structuredClone(s.table.settings()[this.kind]); // as the core holds it
  }

  undo(s) {
    return s.call(OPS[this.kind], [this.from]);
  }

  serialize() {
    return { type: SetSetting.type, kind: this.kind, from: structuredClone(this.from), to: structuredClone(this.to) };
  }

  static deserialize({ kind, from, to }) {
    return new SetSetting(kind, structuredClone(from), structuredClone(to));
  }
}
