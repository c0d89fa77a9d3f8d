// Several prescribed singularities as one step (a Directional .sing file opened on the page; the Singularity
// tool's +/- pair, add-singularity-pair.js): one request each way, the worker's addSingularities (which adds all
// or, on a refusal, none) and its removeConstraints for the undo. Each singularity gets a page id of its own,
// kept across undo and redo, and is listed, moved and removed as any prescribed one.
export class AddSingularities {
  static type = 'AddSingularities';

  // list: [[vertex, index], ...]; uids: their page ids once the first execution gave them. what: the label's
  // words (the file they came from).
  constructor(list, uids = list.map(() => null), what = '') {
    this.list = list;
    this.uids = uids;
    this.what = what;
  }

  get label() {
    const n = this.list.length;
    return `add ${n} singularit${n === 1 ? 'y' : 'ies'}${this.what ? ` from ${this.what}` : ''}`;
  }

  get result() {
    return [...this.uids];
  }

  get changes() {
    return this.list.length > 0;
  }

  request() {
    return { op: 'addSingularities', args: [this.list] };
  }

  applied(reply, table) {
    this.uids = this.uids.map((uid, k) => {
      uid ??= table.nextUid++;
      table.uids.set(uid, reply.value[k]);
      table.nextUid = Math.max(table.nextUid, uid + 1); // a deserialized command brings its own page ids
      return uid;
    });
  }

  undoRequest(table) {
    return { op: 'removeConstraints', args: [this.uids.map((uid) => table.coreIdOf(uid))] };
  }

  undone(reply, table) {
    for (const uid of this.uids) table.uids.delete(uid);
  }

  serialize() {
    const { list, uids, what } = this;
    return { type: AddSingularities.type, list: structuredClone(list), uids: [...uids], what };
  }

  static deserialize({ list, uids, what = '' }) {
    return new AddSingularities(structuredClone(list), [...uids], what);
  }
}
