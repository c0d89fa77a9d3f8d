// Replaces the whole design (boundary, γ, constraints) with a document: Load, Clear and autosave restores.
// before/after are {design, uids}: the document and the page ids of its constraints in the core's order.
export class ReplaceDesign {
  static type = 'ReplaceDesign';

  constructor(label, before, after) {
    this.label = label;
    this.before = before;
    this.after = after;
  }

  // ignoreFingerprint: apply a design saved for another mesh anyway (its indices taken as they are).
  static of(table, design, label, { ignoreFingerprint = false } = {}) {
    if (!design || typeof design !== 'object' || Array.isArray(design))
      throw new Error('a design must be a JSON object');
    if (ignoreFingerprint) {
      design = { ...design };
      delete design.mesh;
    }
    const before = { design: structuredClone(table.design), uids: table.uidsInCoreOrder() };
    return new ReplaceDesign(label, before, { design, uids: null });
  }

  get result() {
    return undefined;
  }

  // A new design: what was selected is gone (its page id may be reused).
  get clearsSelection() {
    return true;
  }

  request() {
    return { op: 'applyDesign', args: [this.after.design] };
  }

  applied(reply, table) {
    table.mapDocument(this.after.uids);
    this.after = { design: structuredClone(table.design), uids: table.uidsInCoreOrder() };
  }

  undoRequest() {
    return { op: 'applyDesign', args: [this.before.design] };
  }

  undone(reply, table) {
    table.mapDocument(this.before.uids);
  }

  // The core put the previous design back, under fresh core ids.
  refused(table, forward) {
    table.mapDocument((forward ? this.before : this.after).uids);
  }

  serialize() {
    const { label, before, after } = this;
    return { type: ReplaceDesign.type, label, before: structuredClone(before), after: structuredClone(after) };
  }

  static deserialize({ label, before, after }) {
    return new ReplaceDesign(label, structuredClone(before), structuredClone(after));
  }
}
