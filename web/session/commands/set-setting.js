// The boundary condition, γ, the curvature alignment or whether the field has only the prescribed
// singularities, with the value it replaces (each a refactorization or a new right-hand side). The symmetry N
// has a command of its own (set-symmetry.js): it may take constraints with it.
const OPS = {
  boundary: 'setBoundary',
  gamma: 'setGamma',
  curvatureAlignment: 'setCurvatureAlignment',
  exactSingularities: 'setExactSingularities',
};
const LABELS = {
  boundary: 'boundary condition',
  gamma: 'γ',
  curvatureAlignment: 'curvature alignment',
  exactSingularities: 'only prescribed singularities',
};

export class SetSetting {
  static type = 'SetSetting';

  // kind: 'boundary' | 'gamma' | 'curvatureAlignment' | 'exactSingularities'; the values as the design format
  // writes them.
  constructor(kind, from, to) {
    this.kind = kind;
    this.from = from;
    this.to = to;
  }

  static of(table, kind, to) {
    if (!OPS[kind]) {
      const known = Object.keys(OPS).join(', ');
      throw new Error(`unknown setting ${JSON.stringify(kind)} (settings: ${known}, symmetry)`);
    }
    return new SetSetting(kind, structuredClone(table.settings()[kind]), to);
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

  request() {
    return { op: OPS[this.kind], args: [this.to] };
  }

  applied(reply, table) {
    this.to = structuredClone(table.settings()[this.kind]); // as the core holds it
  }

  undoRequest() {
    return { op: OPS[this.kind], args: [this.from] };
  }

  serialize() {
    const { kind, from, to } = this;
    return { type: SetSetting.type, kind, from: structuredClone(from), to: structuredClone(to) };
  }

  static deserialize({ kind, from, to }) {
    return new SetSetting(kind, structuredClone(from), structuredClone(to));
  }
}
