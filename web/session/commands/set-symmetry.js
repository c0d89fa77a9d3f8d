// The symmetry N of the field (1 vector, 2 line, 4 cross: core/symmetry.js) as one step. What the new N cannot
// keep goes in the same step, and the user is told what: the sources, sinks, vortices and edge constraints a
// line or cross field has no notion of (the core refuses N ≥ 2 while they are there), and the curvature
// alignment an odd N has none of. Strokes and vectors carry over. Undo brings back N, the alignment and the
// removed constraints, under their page ids and with the specs the core held.
import { alignsToCurvature, countedTypes, fieldTitle, keepsConstraint, symmetryName } from '../../core/symmetry.js';

const FLASH_MS = 6000;

export class SetSymmetry {
  static type = 'SetSymmetry';

  // from, to: {symmetry, curvatureAlignment}; removed: [{uid, spec}] in page-id order.
  constructor(from, to, removed) {
    this.from = from;
    this.to = to;
    this.removed = removed;
  }

  static of(s, n) {
    const { symmetry, curvatureAlignment } = s.table.settings();
    const removed = s.table
      .entries()
      .filter(({ spec }) => !keepsConstraint(spec.type, n))
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
    return this.to.symmetry !== this.from.symmetry || this.to.curvatureAlignment !== this.from.curvatureAlignment || this.removed.length > 0;
  }

  // One worker request (core/setting-ops.js setSymmetry); the reply's whole document drops the page ids of the
  // removed constraints. Should the core refuse, it puts the whole design back under fresh core ids, which get
  // the page ids they had.
  async #go(s, target, plan) {
    const uids = s.table.uidsInCoreOrder();
    try {
      return await s.call('setSymmetry', [target.symmetry, { curvatureAlignment: target.curvatureAlignment, ...plan }]);
    } catch (err) {
      s.table.mapDocument(uids);
      throw err;
    }
  }

  async execute(s) {
    if (!this.changes) return; // nothing to refactor for
    await this.#go(s, this.to, { remove: this.removed.map(({ uid }) => s.table.coreIdOf(uid)) });
    const { symmetry, curvatureAlignment } = s.table.settings(); // as the core holds them
    this.to = { symmetry, curvatureAlignment };
    const notice = this.#notice();
    if (notice) s.flash(notice, FLASH_MS);
  }

  async undo(s) {
    const reply = await this.#go(s, this.from, { add: this.removed.map(({ spec }) => spec) });
    this.removed.forEach(({ uid }, k) => s.table.uids.set(uid, reply.value[k]));
    if (this.removed.length) s.flash(`Undo: restored ${countedTypes(this.removed.map(({ spec }) => spec))}`, FLASH_MS);
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
    return { type: SetSymmetry.type, from: { ...this.from }, to: { ...this.to }, removed: structuredClone(this.removed) };
  }

  static deserialize({ from, to, removed }) {
    return new SetSymmetry({ ...from }, { ...to }, structuredClone(removed));
  }
}
