// The sharp features: the angle above which an edge is one (degrees; 0: none detected) and the edges added to or
// removed from what the angle finds, with the features they replace. One refactorization each way (a change of
// the system's base); the whole document comes back, as after any setting.
const KEYS = ['angle', 'add', 'remove'];

// [[a, b], ...] as plain arrays (typed arrays would not survive JSON); anything else as it is, for the core to
// refuse by name.
const iterable = (v) => v != null && typeof v === 'object' && typeof v[Symbol.iterator] === 'function';
const plainPairs = (list) => (iterable(list) ? Array.from(list, (p) => (iterable(p) ? Array.from(p) : p)) : list);

export class SetFeatures {
  static type = 'SetFeatures';

  // from, to: {angle, add, remove}.
  constructor(from, to) {
    this.from = from;
    this.to = to;
  }

  // features: any of {angle, add, remove}; the others keep their values. The core checks the values.
  static of(table, features) {
    if (!features || typeof features !== 'object' || Array.isArray(features))
      throw new Error('features must be an object {angle, add, remove}');
    const unknown = Object.keys(features).find((key) => !KEYS.includes(key));
    if (unknown) throw new Error(`features: unknown key "${unknown}" (angle, add, remove)`);
    const from = structuredClone(table.features());
    const to = { ...from };
    if ('angle' in features) to.angle = features.angle;
    for (const key of ['add', 'remove']) {
      if (key in features) to[key] = structuredClone(plainPairs(features[key]));
    }
    return new SetFeatures(from, to);
  }

  get label() {
    return this.to.angle !== this.from.angle ? `feature angle ${this.to.angle}` : 'feature edges';
  }

  get result() {
    return undefined;
  }

  get changes() {
    return JSON.stringify(this.from) !== JSON.stringify(this.to);
  }

  request() {
    return this.changes ? { op: 'setFeatures', args: [this.to] } : null;
  }

  // The features as the core holds them.
  applied(reply, table) {
    if (reply) this.to = structuredClone(table.features());
  }

  undoRequest() {
    return { op: 'setFeatures', args: [this.from] };
  }

  serialize() {
    const { from, to } = this;
    return { type: SetFeatures.type, from: structuredClone(from), to: structuredClone(to) };
  }

  static deserialize({ from, to }) {
    return new SetFeatures(structuredClone(from), structuredClone(to));
  }
}
