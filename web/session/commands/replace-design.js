// Replaces the whole design (boundary, γ, constraints) with a document: Load, Clear and autosave restores.
// before/after are {design, uids}: the document and the page ids of its constraints in the core's order.
export class ReplaceDesign {
  static type = 'ReplaceDesign';

  constructor(label, before, after) {
    this.label = label;
    this.before = before;
    this.after = after;
  }

  static of(s, design, label) {
    return new ReplaceDesign(label, { design: structuredClone(s.table.design), uids: s.table.uidsInCoreOrder() }, { design, uids: null });
  }

  get result() {
    return undefined;
  }

  async #go(s, target, other) {
    try {
      await s.call('applyDesign', [target.design]);
    } catch (err) {
      s.table.mapDocument(other.uids); // the core put the previous design back, under fresh core ids
      throw err;
    }
    s.table.mapDocument(target.uids);
  }

  async execute(s) {
    await this.#go(s, this.after, this.before);
    s.selected = null;
    this.after = { design: structuredClone(s.table.design), uids: s.table.uidsInCoreOrder() };
  }

  undo(s) {
    return this.#go(s, this.before, this.after);
  }

  serialize() {
    return { type: ReplaceDesign.type, label: this.label, before: structuredClone(this.before), after: structuredClone(this.after) };
  }

  static deserialize({ label, before, after }) {
    return new ReplaceDesign(label, structuredClone(before), structuredClone(after));
  }
}
