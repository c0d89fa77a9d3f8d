// The symmetry N of the field (1 vector, 2 line, 4 cross: symmetry.js) as one step. What the new N cannot
// keep goes in the same step, and the user is told what: the sources, sinks, vortices and edge constraints a
// line or cross field has no notion of (the core refuses N ≥ 2 while they are there), the prescribed
// singularities whose index is no multiple of 1/N, and the curvature alignment an odd N has none of. Strokes
// and vectors carry over. Undo brings back N, the alignment and the removed constraints, under their page ids
// and with the specs the core held.
import { alignsToCurvature, countedTypes, fieldTitle, keepsSpec, symmetryName } from '../symmetry.js';

export class SetSymmetry {
  static type = 'SetSymmetry';
  #uids = null; // the page ids in the core's order when the request went: a refusal puts them back

  // from, to: {symmetry, curvatureAlignment}; removed: [{uid, spec}] in page-id order.
  constructor(from, to, removed) {
    this.from = from;
    this.to = to;
    this.removed = removed;
  }

  static of(table, n) {
    const { symmetry, curvatureAlignment } = table.settings();
    const removed = table
      .entries()
      .filter(({ spec }) => !keepsSpec(spec, n))
      .sort((a, b) => a.uid - b.uid)
      .map(({ uid, spec }) => ({ uid, spec: structuredClone(spec) }));
    const to = { symmetry: n, curvatureAlignment: alignsToCurvature(n) ? curvatureAlignment : 0 };
    return new SetSymmetry({ symmetry, curvatureAlignment }, to, removed);
  }

  get label() {
    return `symmetry: ${symmetryName(this.to.symmetry)}`;
  }

  // The constraints the step removed, each with its page id (as constraints() lists them).
  get result() {
    return this.removed.map(({ uid, spec }) => ({ id: uid, ...structuredClone(spec) }));
  }

  get changes() {
    const { from, to } = this;
    const settingMoves = to.symmetry !== from.symmetry || to.curvatureAlignment !== from.curvatureAlignment;
    return settingMoves || this.removed.length > 0;
  }

  // One worker request (the worker's setSymmetry); the reply's whole document drops the page ids of the
  // removed constraints. Should the core refuse, it puts the whole design back under fresh core ids, which get
  // the page ids they had (refused).
  #go(table, target, plan) {
    this.#uids = table.uidsInCoreOrder();
    return { op: 'setSymmetry', args: [target.symmetry, { curvatureAlignment: target.curvatureAlignment, ...plan }] };
  }

  // Nothing to refactor for when nothing changes: no request.
  request(table) {
    if (!this.changes) return null;
    return this.#go(table, this.to, { remove: this.removed.map(({ uid }) => table.coreIdOf(uid)) });
  }

  // Returns the notice the user is shown, if any.
  applied(reply, table) {
    if (!reply) return undefined;
    const { symmetry, curvatureAlignment } = table.settings(); // as the core holds them
    this.to = { symmetry, curvatureAlignment };
    return this.#notice();
  }

  undoRequest(table) {
    return this.#go(table, this.from, { add: this.removed.map(({ spec }) => spec) });
  }

  undone(reply, table) {
    this.removed.forEach(({ uid }, k) => table.uids.set(uid, reply.value[k]));
    if (this.removed.length) return `Undo: restored ${countedTypes(this.removed.map(({ spec }) => spec))}`;
    return undefined;
  }

  refused(table) {
    table.mapDocument(this.#uids);
  }

  // 'Line field: removed 2 sources and 1 vortex (undo restores them)'; null when nothing went.
  #notice() {
    const parts = [];
    if (this.removed.length) parts.push(`removed ${countedTypes(this.removed.map(({ spec }) => spec))}`);
    const alignmentOff = this.from.curvatureAlignment > 0 && !(this.to.curvatureAlignment > 0);
    if (alignmentOff) parts.push('turned curvature alignment off');
    if (!parts.length) return null;
    const several = this.removed.length + (alignmentOff ? 1 : 0) > 1;
    return `${fieldTitle(this.to.symmetry)}: ${parts.join(' and ')} (undo restores ${several ? 'them' : 'it'})`;
  }

  serialize() {
    const { from, to, removed } = this;
    return { type: SetSymmetry.type, from: { ...from }, to: { ...to }, removed: structuredClone(removed) };
  }

  static deserialize({ from, to, removed }) {
    return new SetSymmetry({ ...from }, { ...to }, structuredClone(removed));
  }
}
